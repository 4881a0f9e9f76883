"""Pounding spectra (issue 18): the isolated mass under records, with bumpers and without."""

from __future__ import annotations

import numpy as np
import pytest

import pounding as pd_
from pounding.records import el_centro

PERIODS = np.array([0.5, 1.0, 2.0, 3.0])
GAPS = np.array([0.01, 0.03, 0.45])


@pytest.fixture(scope="module")
def quakes():
    ec = el_centro()
    short = pd_.Record(ec.t[:600], ec.accel[:600], name="El Centro 12 s", meta=ec.meta)
    return [short, short.scaled(pga_g=0.5).negated()]


@pytest.fixture(scope="module")
def spectrum(quakes):
    return pd_.pounding_spectrum(quakes, PERIODS, gaps_m=GAPS, damping_ratio=0.05)


def test_without_bumpers_it_is_the_elastic_response_spectrum(quakes, spectrum):
    # two independent exact computations: the engine's event-driven runs and the spectrum kernel
    elastic = pd_.response_spectrum(quakes, PERIODS, damping_ratio=0.05)
    ds = spectrum.data
    np.testing.assert_allclose(ds["acc_max_free_g"].values, elastic["sa_g"].values, rtol=1e-9)
    np.testing.assert_allclose(ds["disp_max_free_m"].values, elastic["sd_m"].values, rtol=1e-9)
    # bumpers 0.45 m away are never reached in these 12 s: the same run, amplification 1
    far = ds.sel(gap_m=0.45)
    assert (far["impacts"] == 0).all() and np.allclose(far["amplification"], 1.0, rtol=1e-12)
    assert (ds["status"] == 0).all() and ds.attrs["complete"] == 1


def test_each_entry_is_one_run_of_the_engine(quakes, spectrum):
    rec, period, gap = quakes[1], 2.0, 0.03
    k = 500.0 * (2.0 * np.pi / period) ** 2
    iso = pd_.Isolator((k,), (), "elastic", 2.0 * 0.05 * np.sqrt(k * 500.0))
    law = pd_.presets.paper_damped().bumpers.law
    run = pd_.simulate(pd_.Oscillator(500.0, iso, pd_.Bumpers(gap, gap, law)), rec, rec.t[-1],
                       sample_rate_hz=0)
    got = spectrum.data.isel(record=1).sel(period_s=period, gap_m=gap)
    assert int(got["impacts"]) == len(run.contacts) > 0
    assert float(got["acc_max_g"]) == pytest.approx(run.abs_acceleration_max / rec.g, rel=1e-12)
    assert float(got["disp_max_m"]) == pytest.approx(max(run.displacement_max, -run.displacement_min),
                                                     rel=1e-12)
    assert float(got["impact_force_max_n"]) == pytest.approx(run.contacts["peak_force_n"].max(), rel=1e-12)
    assert float(got["impact_speed_max_m_s"]) == pytest.approx(run.contacts["v_in_m_s"].abs().max(),
                                                               rel=1e-12)
    # pounding: the displacement bounded near the gap, the acceleration amplified
    assert float(got["disp_ratio"]) < 1.0 < float(got["amplification"])


def test_summary_table_plots_and_file(spectrum, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import xarray as xr

    stats = spectrum.summary()
    median = stats["amplification"].sel(percentile=50.0)
    both = spectrum.data["amplification"]
    # (two records: the median is their mean)
    np.testing.assert_allclose(median, both.mean("record"), rtol=1e-12)
    assert (stats["amplification"].sel(percentile=16.0) <= median).all()
    df = spectrum.to_dataframe()
    assert len(df) == 2 * PERIODS.size * GAPS.size and {"record", "period_s", "gap_m",
                                                        "impacts"} <= set(df.columns)
    path = spectrum.to_netcdf(tmp_path / "spectrum.nc")
    back = xr.open_dataset(path)
    np.testing.assert_allclose(back["amplification"], spectrum.data["amplification"])
    back.close()
    curves = pd_.plots.plot_pounding_spectrum(spectrum)
    assert len(curves) >= 2 * GAPS.size  # (a line and a band per gap, and the line at 1)
    _, ax = plt.subplots()
    mesh = pd_.plots.plot_pounding_spectrum(spectrum, ax=ax, kind="map", quantity="impacts")
    assert spectrum.plot(ax=ax, kind="map", quantity="impacts") is ax.figure
    assert len(mesh) == 1
    # one band per gap computed, labelled with it (not bands around uneven gaps' midpoints)
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert labels == [f"{g * 1e3:g}" for g in GAPS]
    np.testing.assert_allclose(ax.get_yticks(), np.arange(GAPS.size))
    edges = mesh[0].get_coordinates()[:, 0, 1]
    np.testing.assert_allclose(np.diff(edges), 1.0)
    with pytest.raises(pd_.InputError) as info:
        spectrum.plot(quantity="acc_max_free_g")
    assert info.value.field == "quantity"
    plt.close("all")


def test_arguments_are_checked(quakes):
    for kwargs, field in (({"periods_s": [0.0, 1.0]}, "periods_s"), ({"gaps_m": [0.02, 0.01]}, "gaps_m"),
                          ({"gaps_m": [-0.01]}, "gaps_m"), ({"damping_ratio": 1.2}, "damping_ratio"),
                          ({"mass_kg": 0.0}, "mass_kg"), ({"records": []}, "record"),
                          ({"isolator": "rubber"}, "isolator"),
                          ({"workers": 0}, "workers")):
        with pytest.raises(pd_.InputError) as info:
            pd_.pounding_spectrum(**{"records": quakes[0], "periods_s": [1.0], "gaps_m": [0.02], **kwargs})
        assert info.value.field == field, (kwargs, info.value.field)


def test_a_nonlinear_isolator_is_scaled_to_each_period(quakes):
    shape = pd_.Isolator((38e3, 18e3, 2e3), (0.015, 0.04), "kinematic", 0.0)
    ps = pd_.pounding_spectrum(quakes[0], [1.0, 2.0], gaps_m=[0.05], isolator=shape)
    k1 = 500.0 * (2.0 * np.pi) ** 2
    iso = pd_.Isolator((k1, k1 * 18 / 38, k1 * 2 / 38), (0.015, 0.04), "kinematic",
                       2.0 * 0.05 * np.sqrt(k1 * 500.0))
    run = pd_.simulate(pd_.Oscillator(500.0, iso), quakes[0], quakes[0].t[-1], sample_rate_hz=0)
    assert float(ps.data["acc_max_free_g"].sel(period_s=1.0)[0]) == pytest.approx(
        run.abs_acceleration_max / 9.81, rel=1e-12)
    assert "kinematic" in ps.data.attrs["isolator"]


def test_a_bouc_wen_isolator_is_scaled_to_each_period(quakes):
    # every force of the law times one factor (the backbone's slopes and the spring's stiffness, its yield
    # displacement kept): the initial stiffness, slope plus a k, is m (2 pi / T)^2
    shape = pd_.Isolator((2e3,), (), "elastic", 0.0, bouc_wen=pd_.BoucWen(3e4, 0.01, a=0.8))
    ps = pd_.pounding_spectrum(quakes[0], [1.0, 2.0], gaps_m=[0.05], isolator=shape)
    for period in (1.0, 2.0):
        k = 500.0 * (2.0 * np.pi / period) ** 2
        factor = k / (2e3 + 0.8 * 3e4)
        iso = pd_.Isolator((2e3 * factor,), (), "elastic", 2.0 * 0.05 * np.sqrt(k * 500.0),
                           bouc_wen=pd_.BoucWen(3e4 * factor, 0.01, a=0.8))
        run = pd_.simulate(pd_.Oscillator(500.0, iso), quakes[0], quakes[0].t[-1], sample_rate_hz=0)
        assert float(ps.data["acc_max_free_g"].sel(period_s=period)[0]) == pytest.approx(
            run.abs_acceleration_max / 9.81, rel=1e-12)
        assert float(ps.data["disp_max_free_m"].sel(period_s=period)[0]) == pytest.approx(
            run.quantities()["disp_max_m"], rel=1e-12)


def test_an_interrupt_keeps_what_finished(quakes):
    calls = []

    def stop_after_five(n):
        calls.append(n)
        if len(calls) == 5:
            raise KeyboardInterrupt

    with pytest.raises(pd_.Interrupted) as info:
        pd_.pounding_spectrum(quakes[0], PERIODS, gaps_m=GAPS, progress=stop_after_five, workers=1)
    part = info.value.partial.data
    assert part.attrs["complete"] == 0
    assert np.isfinite(part["acc_max_free_g"].values).sum() == 2
    assert np.isfinite(part["acc_max_g"].values).sum() == 3
    assert np.isnan(part["acc_max_g"].values[0, 2:]).all()


def test_cli_spectrum_writes_tables_figures_and_netcdf(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    rec = el_centro()
    text = tmp_path / "ec.csv"
    text.write_text("t,a\n" + "".join(f"{t:.2f},{a / rec.g}\n" for t, a in zip(rec.t[:400], rec.accel[:400])))
    out = tmp_path / "spec"
    runner = CliRunner()
    result = runner.invoke(app, ["spectrum", "--record", str(text), "--periods", "0.5:2:0.5", "--gaps",
                                 "0.01,0.05", "--out", str(out)])
    assert result.exit_code == 0, result.output
    for name in ("pounding_spectrum.nc", "pounding_spectrum.csv", "pounding_summary.csv",
                 "elastic_spectrum.csv",
                 "amplification.png", "amplification_map.png", "displacement.png", "elastic_spectrum.png"):
        assert (out / name).is_file(), name
    import pandas as pd

    df = pd.read_csv(out / "pounding_spectrum.csv")
    assert len(df) == 4 * 2 and sorted(df["period_s"].unique()) == [0.5, 1.0, 1.5, 2.0]
    for args, words in ((["--periods", "0.5:2"], "start:stop:step"),
                        (["--gaps", "0.01,x"], "'x' is not a number"),
                        (["--set", "fema-p695-far-field"], "one of them"),
                        (["--periods", "2:0.5:0.1"], "stop >= start")):
        bad = runner.invoke(app, ["spectrum", "--record", str(text), "--out", str(tmp_path / "x"), *args])
        assert bad.exit_code == 2 and words in bad.output, bad.output
    assert not (tmp_path / "x").exists()


def test_a_run_over_its_budget_is_marked_not_lost(quakes):
    ps = pd_.pounding_spectrum(quakes[0], [1.0, 2.0], gaps_m=[0.02], max_steps=10)
    ds = ps.data
    assert (ds["status"] == int(pd_.Status.BUDGET)).all()
    assert (ds["status_free"] == int(pd_.Status.BUDGET)).all()
    assert np.isnan(ds["acc_max_g"]).all() and np.isnan(ps.summary()["amplification"]).all()
