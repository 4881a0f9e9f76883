"""The paper's campaign: the printed system against the reference, tables, netCDF, threads."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr
from reference_sweep import reference_sweep

import pounding as pd_

FREQS_HZ = [1.0, 1.6, 2.2]
CYCLES, MEASURED = 8, 3


@pytest.fixture(scope="module")
def printed_campaign():
    ybs = pd_.presets.paper_printed()
    return pd_.campaign(ybs.without_bumpers(), ybs, freqs_hz=FREQS_HZ, steady="fixed", cycles=CYCLES,
                        measure_cycles=MEASURED, workers=2)


def test_printed_campaign_agrees_with_the_reference(printed_campaign):
    ds = printed_campaign.data
    assert len(printed_campaign.sweeps) == 14 and printed_campaign.complete
    for (conf, a_g, direction), sw in printed_campaign.sweeps.items():
        ref = reference_sweep(sw.system, a_g, sw.freqs_hz, CYCLES, MEASURED)
        got = ds.sel(configuration=conf, a_g=a_g, direction=direction)
        for row in ref:
            step = got.sel(freq_hz=row["freq_hz"])
            where = f"{conf} a_G={a_g} {direction} {row['freq_hz']} Hz"
            # the reference samples |a_abs| every 20 us: it can only be below the exact peak
            assert step["alpha"] == pytest.approx(row["alpha"], rel=2e-7), where
            assert step["alpha"] >= row["alpha"] * (1 - 1e-12), where
            assert step["excursion_m"] == pytest.approx(row["excursion_m"], rel=1e-8), where
            assert step["contacts_per_cycle"] * MEASURED == row["contacts"], where
            if row["contacts"]:
                assert step["restitution"] == pytest.approx(row["restitution"], rel=1e-7), where
                assert step["contact_time_s"] == pytest.approx(row["contact_time_s"], abs=1e-9), where


def test_dataset_layout_and_netcdf_round_trip(printed_campaign, tmp_path):
    ds = printed_campaign.data
    assert ds["alpha"].dims == ("configuration", "a_g", "direction", "freq_hz")
    assert list(ds["configuration"].values) == ["NBs", "YBs"]
    assert list(ds["a_g"].values) == [0.03, 0.05, 0.075, 0.1]
    assert list(ds["direction"].values) == ["up", "down"]
    # NBs were not run at 0.075 g: NaN and ran False there
    nbs_075 = ds.sel(configuration="NBs", a_g=0.075)
    assert nbs_075["alpha"].isnull().all() and not nbs_075["ran"].any()
    assert ds.sel(configuration="YBs")["ran"].all()
    assert ds.sel(configuration="NBs")["eta"].isnull().all()
    path = printed_campaign.to_netcdf(tmp_path / "campaign.nc")
    back = xr.open_dataset(path)
    xr.testing.assert_allclose(back["alpha"], ds["alpha"])
    assert back["contact"].dtype == bool
    ybs = pd_.Oscillator.from_toml_text(back.attrs["system_YBs"])
    assert ybs == printed_campaign.sweep("YBs", 0.05, "up").system


def test_tables_2_3_4(printed_campaign):
    t2 = printed_campaign.table2()
    assert len(t2) == 14 and list(t2.columns[:4]) == ["configuration", "a_g", "direction", "nu_r"]
    sw = printed_campaign.sweep("YBs", 0.1, "up")
    row = t2.query("configuration == 'YBs' and a_g == 0.1 and direction == 'up'").iloc[0]
    assert row["alpha"] == sw.alpha_max and row["nu_r"] == sw.nu_r
    assert t2.query("configuration == 'NBs'")["eta"].isna().all()
    t3, t4 = printed_campaign.table3(), printed_campaign.table4()
    assert len(t3) == len(t4) == 8
    step = sw.to_dataframe().set_index("freq_hz").loc[sw.resonance_hz]
    r3 = t3.query("a_g == 0.1 and direction == 'up'").iloc[0]
    assert r3["mean_force_over_mg"] == pytest.approx(step["mean_force_n"] / (500 * 9.81))
    assert r3["contact_time_ms"] == pytest.approx(step["contact_time_s"] * 1e3)
    r4 = t4.query("a_g == 0.1 and direction == 'up'").iloc[0]
    assert r4["dissipated_energy_per_mass"] == pytest.approx(step["dissipated_energy_j"] / 500)
    assert r4["restitution"] == step["restitution"]


def test_threads_change_nothing():
    ybs = pd_.presets.paper_printed()
    kw = dict(nbs_a_g=(0.05,), ybs_a_g=(0.05, 0.1), freqs_hz=[1.2, 2.0], steady="fixed", cycles=5,
              measure_cycles=2)
    one = pd_.campaign(ybs.without_bumpers(), ybs, workers=1, **kw).data
    two = pd_.campaign(ybs.without_bumpers(), ybs, workers=2, **kw).data
    xr.testing.assert_identical(one, two)


def test_campaign_interruption_keeps_finished_steps():
    ybs = pd_.presets.paper_printed()
    calls = []

    def progress(n):
        calls.append(n)
        if len(calls) == 2:
            raise KeyboardInterrupt

    with pytest.raises(pd_.Interrupted) as info:
        pd_.campaign(None, ybs, ybs_a_g=(0.05,), directions=("up",), freqs_hz=[1.0, 1.5, 2.0, 2.5],
                     steady="fixed", cycles=4, measure_cycles=2, workers=1, progress=progress)
    part = info.value.partial
    assert not part.complete and part.data.attrs["complete"] == 0
    assert int(part.data["ran"].sum()) == 2 and info.value.total == 4


@pytest.mark.parametrize("args, kwargs, field", [
    ((None, None), {}, "nbs_system, ybs_system"),
    ((pd_.presets.paper_printed(), None), {}, "nbs_system"),
    ((None, pd_.presets.paper_printed(bumpers=False)), {}, "ybs_system"),
    ((None, pd_.presets.paper_printed()), {"ybs_a_g": (0.05, math.nan)}, "ybs_a_g[1]"),
    ((None, pd_.presets.paper_printed()), {"directions": ("up", "up")}, "directions"),
    ((None, pd_.presets.paper_printed()), {"workers": 0}, "workers"),
    ((None, pd_.presets.paper_printed()), {"cycle": 30}, "cycle"),
    ((None, pd_.presets.paper_printed()), {"steady": "fixed", "cycles": 0}, "cycles"),
    ((None, pd_.presets.paper_printed()), {"ybs_a_g": []}, "ybs_a_g"),
    ((pd_.presets.paper_printed(bumpers=False), None), {"nbs_a_g": ()}, "nbs_a_g"),
])
def test_bad_campaign_arguments(args, kwargs, field):
    with pytest.raises(pd_.InputError) as info:
        pd_.campaign(*args, **kwargs)
    assert info.value.field == field


def test_campaign_plot_returns_artists():
    import matplotlib

    matplotlib.use("Agg")
    ybs = pd_.presets.paper_printed()
    res = pd_.campaign(ybs.without_bumpers(), ybs, nbs_a_g=(0.05,), ybs_a_g=(0.05,), freqs_hz=[1.0, 2.0],
                       steady="fixed", cycles=3, measure_cycles=2)
    artists = pd_.plots.plot_campaign(res)
    assert len(artists) >= 8
    assert np.isfinite(res.data["alpha"].sel(configuration="YBs").values).all()


def test_tables_keep_their_columns_without_a_ybs_step():
    # an NBs-only campaign (or one interrupted before a YBs step finished) has no Table 3 or 4
    # rows; the CLI then writes the tables with a 'complete' column, which needs the key columns
    nbs = pd_.presets.paper_printed(bumpers=False)
    res = pd_.campaign(nbs, None, nbs_a_g=(0.05,), directions=("up",), freqs_hz=[1.0], steady="fixed",
                       cycles=3, measure_cycles=2)
    assert len(res.table2()) == 1
    for table, quantities in ((res.table3(), ["mean_force_over_mg", "contact_time_ms", "peak_force_over_mg"]),
                              (res.table4(), ["dissipated_energy_per_mass", "restitution"])):
        assert table.empty
        assert list(table.columns) == ["configuration", "a_g", "direction", "nu_r", *quantities]


def test_a_ctrl_c_after_the_last_step_loses_nothing(monkeypatch):
    """Ctrl-C while the pool winds up or while the dataset is built, after every step finished:
    the result is whole and complete (it was "interrupted: nothing was written", or complete = 0)."""
    import concurrent.futures as cf
    import importlib

    campaign_module = importlib.import_module("pounding.protocols.campaign")

    osc = pd_.presets.paper_damped()
    kwargs = dict(nbs_a_g=(), ybs_a_g=(0.05,), freqs_hz=[1.5, 1.6], directions=("up",), steady="fixed",
                  cycles=5)
    whole = pd_.campaign(None, osc, **kwargs)
    for target, name in ((cf.ThreadPoolExecutor, "shutdown"), (campaign_module, "_dataset")):
        original = getattr(target, name)
        calls = []

        def once(*args, original=original, calls=calls, **kw):
            if not calls:
                calls.append(1)
                if name == "shutdown":
                    original(*args, **kw)  # (the steps finish, then the Ctrl-C)
                raise KeyboardInterrupt
            return original(*args, **kw)

        monkeypatch.setattr(target, name, once)
        result = pd_.campaign(None, osc, **kwargs)
        monkeypatch.setattr(target, name, original)
        assert calls and result.complete and result.data.attrs["complete"] == 1
        assert result.data.equals(whole.data)
