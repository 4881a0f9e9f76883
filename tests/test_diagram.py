"""pounding.bifurcation_diagram: the stroboscopic samples of a stepped sine against the periodic
orbits and branches of continuation, its period test, and what users meet (bad input, Ctrl-C,
files, the command line)."""

from __future__ import annotations

import numpy as np
import pytest
from typer.testing import CliRunner

import pounding as pd_
from pounding.cli import app
from pounding.protocols.bifurcation_diagram import periods

# the paper's damped system with an elastic isolator: no memory, so one orbit per frequency and
# branch (a kinematic isolator's slips shift the orbit each sweep ends on)
ELASTIC = pd_.presets.paper_damped(hysteresis="elastic")
FREQS = np.round(np.arange(1.3, 2.6, 0.02), 2)


@pytest.fixture(scope="module")
def diagram():
    return pd_.bifurcation_diagram(ELASTIC, 0.05, FREQS)


@pytest.fixture(scope="module")
def branch():
    return pd_.continuation(ELASTIC, 0.05, (1.3, 2.6))


def test_period_one_samples_are_the_periodic_orbit_at_the_section(diagram, branch):
    """Where the branch is stable and single, every recorded sample is the orbit's state at table
    phase 0 (periodic_orbit, exact), to 1e-6; the branch's own section agrees as well."""
    assert diagram.success and diagram.message.endswith("every response is periodic (period 1).")
    ds = diagram.data
    for f in (1.3, 1.5, 2.4, 2.58):
        orbit = pd_.periodic_orbit(ELASTIC, pd_.Harmonic(0.05, f))
        exact = np.array([orbit.state.displacement_m, orbit.state.velocity_m_s])
        for d in ("up", "down"):
            got = np.stack([ds.strobe_displacement_m.sel(direction=d, freq_hz=f).values,
                            ds.strobe_velocity_m_s.sel(direction=d, freq_hz=f).values], axis=-1)
            np.testing.assert_allclose(got, np.broadcast_to(exact, got.shape), rtol=1e-6, atol=1e-9)
    sec = branch.section(0.0)
    near = sec.iloc[(sec.freq_hz - 2.4).abs().argsort()[:1]]
    f = float(near.freq_hz.iloc[0])
    orbit = pd_.periodic_orbit(ELASTIC, pd_.Harmonic(0.05, f))
    assert near.displacement_m.iloc[0] == pytest.approx(orbit.state.displacement_m, rel=1e-6)


def test_up_and_down_differ_only_between_the_folds_and_jump_at_them(diagram, branch):
    f_low, f_high = sorted(b.freq_hz for b in branch.folds())
    alpha = diagram.to_dataframe(cycles=False).pivot(index="freq_hz", columns="direction", values="alpha")
    differ = alpha.index[(alpha["up"] - alpha["down"]).abs() > 1e-6].to_numpy()
    assert differ.size > 10 and f_low <= differ.min() and differ.max() <= f_high
    step = 0.02 + 1e-9
    assert differ.max() > f_high - step and differ.min() < f_low + step  # (the jumps: at the folds)
    up, down = diagram.sweeps
    assert up.jumps()["kind"].tolist()[-1] == "down" and down.jumps()["kind"].tolist()[-1] == "up"


def test_the_period_test_on_samples_of_known_period():
    rng = np.random.default_rng(1)
    cycles = np.arange(24)
    base = {1: np.zeros(24), 2: (-1.0) ** cycles, 3: np.cos(2 * np.pi * cycles / 3)}
    strobes = np.zeros((5, 24, 2))
    for i, k in enumerate((1, 2, 3)):
        strobes[i, :, 0] = 0.01 + 0.004 * base[k] + 1e-12 * rng.standard_normal(24)
        strobes[i, :, 1] = 0.02 * base[k]
    strobes[3] = 0.01 * rng.standard_normal((24, 2))  # a cloud
    strobes[4, :, 0] = 0.01 * np.exp(-0.1 * cycles)  # still settling
    got = periods(strobes, np.full(5, 0.01), np.full(5, 2 * np.pi), 8, 1e-6)
    assert got.tolist() == [1, 2, 3, 0, 0]
    assert periods(strobes[:1], np.full(1, 0.01), np.full(1, 2 * np.pi), 8, 1e-14).tolist() == [0]


@pytest.mark.parametrize("kwargs, field", [
    ({"direction": "sideways"}, "direction"), ({"record_cycles": 8}, "record_cycles"),
    ({"transient_cycles": -1}, "transient_cycles"), ({"max_period": 0}, "max_period"),
    ({"freqs_hz": [1.0, 1.0]}, "freqs_hz"), ({"a_g": -0.05}, "a_g"), ({"steady_rtol": 0.0}, "steady_rtol"),
])
def test_bad_arguments_are_named(kwargs, field):
    args = {"freqs_hz": [1.0, 1.5], "a_g": 0.05, **kwargs}
    with pytest.raises(pd_.InputError, match=field):
        pd_.bifurcation_diagram(ELASTIC, args.pop("a_g"), args.pop("freqs_hz"), **args)


def test_ctrl_c_keeps_the_finished_steps_and_files_round_trip(tmp_path):
    calls = []

    def stop_after_five(n):
        calls.append(n)
        if len(calls) == 5:
            raise KeyboardInterrupt

    with pytest.raises(pd_.Interrupted) as info:
        pd_.bifurcation_diagram(ELASTIC, 0.05, FREQS[:10], transient_cycles=20, record_cycles=10,
                                progress=stop_after_five)
    part = info.value.partial
    assert part.status == pd_.Status.INTERRUPTED and "Interrupted after 5 of 20" in part.message
    assert (part.data.period.sel(direction="up").values >= 0).sum() == 5
    assert (part.data.period.sel(direction="down").values == -1).all()
    path = part.to_netcdf(tmp_path / "part.nc")
    import xarray as xr

    with xr.open_dataset(path) as back:
        np.testing.assert_array_equal(back.strobe_displacement_m.values,
                                      part.data.strobe_displacement_m.values)


def test_cli_bifurcation_writes_samples_dataset_and_figure(tmp_path):
    out, nc, png = tmp_path / "d.csv", tmp_path / "d.nc", tmp_path / "d.png"
    res = CliRunner().invoke(app, ["bifurcation", "--preset", "paper-damped", "--a-g", "0.05",
                                   "--fmin", "1.5", "--fmax", "2.1", "--fstep", "0.1",
                                   "--transient-cycles", "20", "--record-cycles", "10", "--out", str(out),
                                   "--netcdf", str(nc),
                                   "--plot", str(png), "--branch"])
    assert res.exit_code == 0, res.output
    import pandas as pd

    table = pd.read_csv(out)
    assert {"direction", "freq_hz", "cycle", "displacement_m", "velocity_m_s", "period"} <= set(table.columns)
    assert len(table) == 2 * 7 * 10 and nc.stat().st_size > 0 and png.stat().st_size > 0
    assert "jumps up" in res.output
    bad = CliRunner().invoke(app, ["bifurcation", "--preset", "paper-damped", "--a-g", "0.05",
                                   "--record-cycles", "3"])
    assert bad.exit_code == 2 and "record_cycles" in bad.output
