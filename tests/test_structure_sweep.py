"""Sweeps of structures (``pounding.sweep`` with a Structure or Adjacent): one level equals the single
oscillator's sweep, a linear building's steady steps equal its frequency response on every floor, a fixed
schedule equals simulating it step by step, a pair names its structures and links, and bad input is named."""

from __future__ import annotations

import dataclasses
import importlib
import math

import matplotlib
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pandas

import pounding as pd_
from pounding.engine.assembly import kernel_structure

matplotlib.use("Agg")


def linear_isolator(k: float, c: float) -> pd_.Isolator:
    return pd_.Isolator(slopes_n_m=[k], breakpoints_m=[], damping_n_s_m=c)


@pytest.mark.parametrize("preset, schedule", [("paper_damped", {}), ("nbs", {}), (
    "paper_damped", {"steady": "fixed", "cycles": 20, "measure_cycles": 1})])
def test_one_level_sweeps_as_the_oscillator_and_its_window_measured_again_as_the_step_measured_it(
        preset, schedule):
    # a one-level structure is the single mass: the same sweep, to the bit
    osc = pd_.presets.paper_printed(bumpers=False) if preset == "nbs" else pd_.presets.paper_damped()
    freqs = [1.2, 1.5, 2.0, 2.6] if not schedule else np.round(np.arange(1.0, 3.01, 0.1), 1)
    ro = pd_.sweep(osc, 0.05, freqs, **schedule)
    rs = pd_.sweep(pd_.Structure.from_oscillator(osc), 0.05, freqs, **schedule)
    assert rs.message == ro.message and rs.success
    pandas.testing.assert_frame_equal(rs.to_dataframe(), ro.to_dataframe())
    pandas.testing.assert_frame_equal(rs.contacts_dataframe(), ro.contacts_dataframe())
    # what a structure of several levels measures, its window run once more in one piece from its exact
    # start (the same motion, cut elsewhere: to rounding), is what the core's step summed cycle by cycle
    # (a one-cycle window: its contacts may begin before it, timed from their true start as the step's are)
    from pounding.engine.assembly import assemble
    from pounding.engine.control import new_control
    from pounding.engine.kernels import run_window
    from pounding.metrics.impacts import S_COUNT, S_N_RESTITUTION
    from pounding.protocols.sweep_window import measure, slot_masses

    asm = assemble(osc)
    for i, f in enumerate(ro.freqs_hz):
        start, m = ro.window_states[i], int(ro.window_cycles[i])
        exc = pd_.Harmonic(0.05, f, phase=-(2 * np.pi * f * start[0]))
        out = run_window(asm.system, exc.peak_m_s2, exc.omega_rad_s, exc.phase, start, start[0] + m / f,
                         1 / f, 1e-10, 10**6, new_control(10**9))
        level, drift = np.zeros((1, 3)), np.zeros((0, 2))
        sums = np.zeros_like(ro.contact_sums[i])
        measure(out, [0], exc.peak_m_s2, slot_masses(asm), level, drift, sums, 1)
        np.testing.assert_allclose(level, ro.level_metrics[i], rtol=1e-9)
        np.testing.assert_array_equal(sums[:, [S_COUNT, S_N_RESTITUTION]],
                                      ro.contact_sums[i][:, [S_COUNT, S_N_RESTITUTION]])
        # (measured on these sweeps: 8.5e-13 relative at most on the extrema, 1.2e-11 on the sums; 1e-9 is
        # the bound the two paths' comparison asserted before they were one)
        np.testing.assert_allclose(sums, ro.contact_sums[i], rtol=1e-9)
    assert osc.bumpers is None or ro.contact_sums[:, :, S_COUNT].sum() > 0
    # the step's own window measures a system of one mass with one wall; anything more (a stand's mass, a
    # storey) is measured on the window run again
    from pounding.protocols.sweep_window import step_measures_all

    assert step_measures_all(asm) and step_measures_all(assemble(pd_.Structure.from_oscillator(osc)))
    one = pd_.Structure.from_oscillator(pd_.presets.paper_damped())
    wall = one.walls[0]
    on_a_stand = dataclasses.replace(wall, stand=pd_.Stand(30.0, 3e6, 100.0))
    for more in (dataclasses.replace(one, walls=(on_a_stand,)),
                 dataclasses.replace(one, storeys=(pd_.Storey(100.0, 1e6, 10.0),))):
        assert not step_measures_all(assemble(more))
    # one result for every system: the names before still answer, with a warning naming the new one
    assert type(rs) is type(ro) is pd_.SweepResult
    with pytest.warns(FutureWarning, match="pounding.SweepResult"):
        assert pd_.StructureSweepResult is pd_.SweepResult
    for old in ("oscillator", "structure"):
        with pytest.warns(FutureWarning, match="SweepResult.system"):
            assert getattr(ro, old) is osc


@pytest.mark.parametrize("n_storeys", [1, 3])
def test_a_linear_building_sweeps_to_its_frequency_response(n_storeys):
    rng = np.random.default_rng(7 + n_storeys)
    storeys = [pd_.Storey(m, k, c) for m, k, c in zip(rng.uniform(200.0, 1000.0, n_storeys),
                                                        rng.uniform(5e5, 2e6, n_storeys),
                                                        rng.uniform(2e3, 5e3, n_storeys))]
    k_iso, c_iso = 2e4 * (n_storeys + 1), 2e3
    b = pd_.Structure(600.0, linear_isolator(k_iso, c_iso), storeys)
    freqs = np.array([0.8, 1.3, 2.5])
    res = pd_.sweep(b, 0.15, freqs, steady_rtol=1e-10, max_cycles=3000)
    assert res.success and np.all(res.period_multiple == 1), res.message
    k, c = b.stiffness_matrix.copy(), b.damping_matrix.copy()
    k[0, 0] += k_iso
    c[0, 0] += c_iso
    m = b.masses_kg
    a_g = 0.15 * res.g
    for i, f in enumerate(freqs):
        w = 2 * math.pi * f
        x = np.linalg.solve(k - w**2 * np.diag(m) + 1j * w * c, -m * a_g)
        np.testing.assert_allclose(res.level_metrics[i, :, 0], np.abs(x), rtol=1e-7)
        np.testing.assert_allclose(res.level_metrics[i, :, 1], -np.abs(x), rtol=1e-7)
        np.testing.assert_allclose(res.alpha[i], np.abs(a_g - w**2 * x) / a_g, rtol=1e-7)
        np.testing.assert_allclose(res.peak_drift[i], np.abs(np.diff(x)), rtol=1e-7)
    # the base's resonance among the steps: where its closed-form amplification is largest
    amplification = [abs(a_g - (2 * math.pi * f) ** 2 * np.linalg.solve(
        k - (2 * math.pi * f) ** 2 * np.diag(m) + 2j * math.pi * f * c, -m * a_g)[0]) for f in freqs]
    assert res.resonance_of(0) == freqs[int(np.argmax(amplification))]


@st.composite
def walled(draw):
    n = draw(st.integers(2, 4))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    mass = rng.uniform(200.0, 1500.0, n)
    storeys = [pd_.Storey(m, k, c) for m, k, c in zip(mass[1:], rng.uniform(3e5, 3e6, n - 1),
                                                        rng.uniform(100.0, 2e3, n - 1))]
    wall = pd_.Wall(draw(st.integers(0, n - 1)), draw(st.floats(0.002, 0.02)), draw(st.floats(0.002, 0.02)),
                    pd_.KelvinVoigt(draw(st.floats(1e6, 2e7)), draw(st.floats(1e2, 5e3))))
    if draw(st.booleans()):
        return pd_.Structure(mass[0], linear_isolator(rng.uniform(5e3, 5e4) * n, rng.uniform(0.0, 1e3)),
                             storeys, [wall])
    return pd_.Structure.fixed_base(
        [pd_.Storey(mass[0], rng.uniform(1e5, 1e6), 500.0)] + storeys,
        [pd_.Wall(max(wall.level, 1), wall.gap_left_m, wall.gap_right_m, wall.law)])


def motion(b: pd_.Structure, vector: np.ndarray) -> np.ndarray:
    """A state vector's levels' displacements and velocities, its contacts' and elements' states (not the
    time, nor the energy integrals, which a sweep's steps do not keep)."""
    lay = kernel_structure(b).layout
    return np.concatenate([vector[lay["x"]:lay["acc"]], vector[lay["z"]:]])


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(b=walled(), a_g=st.floats(0.1, 0.4))
def test_a_fixed_schedule_equals_simulating_it_step_by_step(b, a_g):
    freqs, cycles, window = [0.9, 1.6, 2.4], 5, 2
    res = pd_.sweep(b, a_g, freqs, steady="fixed", cycles=cycles, measure_cycles=window)
    assert res.success and res.steps_done == 3
    state = pd_.State.at_rest(b)
    for i, f in enumerate(freqs):
        w = 2 * math.pi * f
        exc = pd_.Harmonic(a_g, f, phase=-w * state.time_s)
        # cycle by cycle, as a step runs (a chain cut elsewhere differs by rounding, which the impacts
        # amplify: 6e-9 m/s after three steps of a drawn building, where this chain agrees to 3e-13)
        for _ in range(cycles - window):
            state = pd_.simulate(b, exc, 1.0 / f, state, sample_rate_hz=0).final_state
        run = pd_.simulate(b, exc, window / f, state, sample_rate_hz=0)
        vec = motion(b, state.vector)
        np.testing.assert_allclose(motion(b, res.window_states[i]), vec, rtol=0,
                                   atol=1e-10 * np.abs(vec).max())
        for _ in range(window):
            state = pd_.simulate(b, exc, 1.0 / f, state, sample_rate_hz=0).final_state
        scale = np.max(np.abs(run.displacement_max)) + np.max(np.abs(run.displacement_min))
        extrema = res.level_metrics[i]
        np.testing.assert_allclose(extrema[:, 0], run.displacement_max, rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(extrema[:, 1], run.displacement_min, rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(res.level_metrics[i, :, 2], run.abs_acceleration_max, rtol=1e-9)
        np.testing.assert_allclose(res.drift_metrics[i, :, 0], run.drift_max, rtol=0, atol=1e-9 * scale)
        ended = run.contacts.dropna(subset=["t_end_s"])
        for c, side in enumerate(("left", "right")):
            assert res.contacts_per_cycle[i, c] * window == np.sum(ended["side"] == side)
    vec = motion(b, state.vector)
    np.testing.assert_allclose(motion(b, res.final_state.vector), vec, rtol=0, atol=1e-10 * np.abs(vec).max())


def test_a_pair_names_its_structures_and_links():
    iso = pd_.Isolator(slopes_n_m=[4.0e5, 1.0e5], breakpoints_m=[0.02], damping_n_s_m=2.0e3)
    isolated = pd_.Structure(3.0e3, iso, [pd_.Storey(2.0e3, 4.0e6, 4.0e3)] * 2)
    old = pd_.Structure.fixed_base([pd_.Storey(2.5e3, 3.0e6, 5.0e3)] * 2)
    pair = pd_.Adjacent(isolated, old, [pd_.Link(2, 2, 0.02, pd_.KelvinVoigt(5.0e7, 2.0e4))])
    res = pd_.sweep(pair, 0.3, [0.8, 1.2], steady="fixed", cycles=8, measure_cycles=3)
    assert res.success
    df = res.to_dataframe()
    assert list(df["structure"][:6]) == ["first"] * 3 + ["second"] * 3
    # (the second's base is the ground)
    assert df.loc[df["structure"] == "second", "alpha"].iloc[0] == pytest.approx(1.0)
    links = res.contacts_dataframe()
    assert list(links["kind"]) == ["link", "link"] and links["contacts_per_cycle"].max() > 0
    ds = res.to_xarray()
    assert ds["alpha"].shape == (2, 6) and ds["contacts_per_cycle_per_contact"].shape == (2, 1)
    assert ds["displacement_max_m"].shape == ds["abs_acceleration_max_m_s2"].shape == (2, 6)
    assert ds["drift_max_m"].shape == (2, 4)
    assert list(ds["level_structure"].values) == ["first"] * 3 + ["second"] * 3
    assert list(ds["storey_structure"].values) == ["first"] * 2 + ["second"] * 2
    assert len(pd_.plots.plot_sweep(res)) == 7
    with pytest.warns(FutureWarning, match="plot_sweep"):  # (its name before)
        assert len(pd_.plots.plot_structure_sweep(res)) == 7


def test_one_plot_draws_every_system_s_sweeps():
    """plot_sweep draws a building's up and down sweeps on one pair of axes, each direction in its line style
    and every level's and wall side's line labelled with it; a single mass's beside a building's is refused
    with the field named."""
    import matplotlib.pyplot as plt

    b = pd_.Structure(1e3, linear_isolator(1e5, 1e3), [pd_.Storey(1e3, 1e6)],
                      [pd_.Wall(1, 0.01, 0.01, pd_.KelvinVoigt(1e7, 1e3))])
    sweeps = [pd_.sweep(b, 0.2, [1.0, 1.5, 2.0], d, steady="fixed", cycles=4, measure_cycles=1)
              for d in ("up", "down")]
    artists = pd_.plots.plot_sweep(sweeps)
    fig = artists[0].figure
    labels = [line.get_label() for ax in fig.axes for line in ax.get_lines()]
    assert labels == ["level 0 (up)", "level 1 (up)", "level 0 (down)", "level 1 (down)",
                      "wall 0 left (up)", "wall 0 right (up)", "wall 0 left (down)", "wall 0 right (down)"]
    styles = {line.get_label(): line.get_linestyle() for ax in fig.axes for line in ax.get_lines()}
    assert styles["level 1 (up)"] == "-" and styles["level 1 (down)"] == "--"
    assert "up and down" in fig.axes[0].get_title()
    plt.close(fig)
    one = pd_.sweep(pd_.presets.paper_damped(), 0.05, [1.5, 2.0], steady="fixed", cycles=4, measure_cycles=1)
    with pytest.raises(pd_.InputError, match="sweeps"):
        pd_.plots.plot_sweep([one, sweeps[0]])
    # two levels of shaking: the a_G in the labels and the markers, one colour if asked
    other = pd_.sweep(b, 0.3, [1.0, 1.5, 2.0], "up", steady="fixed", cycles=4, measure_cycles=1)
    artists = pd_.plots.plot_sweep([sweeps[0], other], label="moat", color="k")
    lines = [a for a in artists if a.axes is artists[0].axes]
    assert [line.get_label() for line in lines] == [f"level {q} (moat, a_G = {a_g}, up)"
                                                   for a_g in (0.2, 0.3) for q in (0, 1)]
    assert {line.get_color() for line in artists} == {"k"} and lines[0].get_marker() != lines[2].get_marker()
    plt.close("all")
    # the old name draws a one-level structure's sweep by level, as it did
    level = pd_.sweep(pd_.Structure.from_oscillator(pd_.presets.paper_damped()), 0.05, [1.5, 2.0],
                      steady="fixed", cycles=4, measure_cycles=1)
    with pytest.warns(FutureWarning, match="plot_sweep"):
        drawn = pd_.plots.plot_structure_sweep(level)
    assert [a.get_label() for a in drawn] == ["level 0", "wall 0 left", "wall 0 right"]
    plt.close("all")


def test_bad_arguments_are_named():
    b = pd_.Structure(1e3, linear_isolator(1e5, 1e3), [pd_.Storey(1e3, 1e6)])
    with pytest.raises(pd_.InputError, match="measurement"):
        pd_.sweep(b, 0.1, [1.0], measurement=pd_.MeasurementChain())
    with pytest.raises(pd_.InputError, match="state"):
        pd_.sweep(b, 0.1, [1.0], state=pd_.State.at_rest(pd_.presets.paper_damped()))
    res = pd_.sweep(b, 0.1, [1.0, 1.5], steady="fixed", cycles=3, measure_cycles=1)
    with pytest.raises(pd_.InputError, match="level"):
        res.resonance_of(2)
    # (the top level's: the sweep's resonance, as a single mass's own)
    assert res.resonance_hz == res.resonance_of(-1) and res.nu_r == res.resonance_of(-1) / res.f_ref_hz
    again = pd_.sweep(b, 0.1, [2.0], steady="fixed", cycles=3, measure_cycles=1, state=res.final_state)
    assert again.step_start_s[0] == pytest.approx(3.0 + 2.0)
    # a sweep stopped at its first step: NaN metrics, and the summary's table says "-" where nothing was
    # measured
    walled = dataclasses.replace(b, walls=(pd_.Wall(0, 0.002, 0.002, pd_.KelvinVoigt(1e7, 1e3)),))
    stopped = pd_.sweep(walled, 0.3, [1.0, 1.5], max_events_per_cycle=3)
    assert stopped.status != pd_.Status.SUCCESS and stopped.steps_done == 1
    assert np.isnan(stopped.quantities()["alpha_top_max"])
    from rich.console import Console

    from pounding.cli._runs import _structure_sweep_table

    console = Console(record=True, width=150)
    console.print(_structure_sweep_table(stopped))
    assert "level 1" in console.export_text()


def test_what_is_no_system_is_named_by_every_sweep():
    for bad in ("paper", pd_.Bumpers(0.01, 0.01, pd_.KelvinVoigt(1e7, 1e3)), None):
        with pytest.raises(pd_.InputError, match="system"):
            pd_.sweep(bad, 0.1, [1.0])
        with pytest.raises(pd_.InputError, match="system"):
            pd_.bifurcation_diagram(bad, 0.1, [1.0, 1.5])


def test_a_ctrl_c_in_a_step_s_measured_window_keeps_the_steps_before(monkeypatch):
    # (the window of each step is run once more for every level's metrics: a Ctrl-C there drops the step,
    # and the sweep ends where the steps before it left the structure)
    structure_sweep = importlib.import_module("pounding.protocols.sweep")

    b = pd_.Structure(1e3, linear_isolator(1e5, 1e3), [pd_.Storey(1e3, 1e6, 1e3)],
                      [pd_.Wall(0, 0.01, 0.01, pd_.KelvinVoigt(1e7, 1e3))])
    first = pd_.sweep(b, 0.2, [1.0], steady="fixed", cycles=6, measure_cycles=2)
    windows = []
    real = structure_sweep.run_window

    def stopped_at_the_second(*args, **kwargs):
        windows.append(1)
        if len(windows) == 2:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(structure_sweep, "run_window", stopped_at_the_second)
    with pytest.raises(pd_.Interrupted) as info:
        pd_.sweep(b, 0.2, [1.0, 1.5, 2.0], steady="fixed", cycles=6, measure_cycles=2)
    partial = info.value.partial
    assert len(windows) == 2 and partial.steps_done == 1
    np.testing.assert_array_equal(partial.final_state.vector, first.final_state.vector)
    np.testing.assert_array_equal(partial.level_metrics[0], first.level_metrics[0])
    assert np.isnan(partial.level_metrics[1:]).all()


def test_a_campaign_of_a_building_without_and_with_its_moat_wall(tmp_path):
    iso = pd_.Isolator(slopes_n_m=[4.0e5, 1.0e5], breakpoints_m=[0.02], damping_n_s_m=2.0e3)
    bare = pd_.Structure(3.0e3, iso, [pd_.Storey(2.0e3, 4.0e6, 4.0e3)] * 2)
    walled = dataclasses.replace(bare, walls=(pd_.Wall(0, 0.03, 0.03, pd_.KelvinVoigt(2.0e7, 1.0e4)),))
    options = {"freqs_hz": [0.6, 0.9, 1.2], "steady": "fixed", "cycles": 6, "measure_cycles": 2}
    res = pd_.campaign(bare, walled, nbs_a_g=[0.2], ybs_a_g=[0.2, 0.3], **options)
    assert dict(res.data.sizes) == {"configuration": 2, "a_g": 2, "direction": 2, "freq_hz": 3, "level": 3}
    table = res.table2()
    assert len(table) == 6 and list(table.columns[3:5]) == ["nu_r_top", "alpha_top_max"]
    direct = pd_.sweep(walled, 0.3, direction="down", **options)
    row = table[(table["configuration"] == "YBs") & (table["a_g"] == 0.3) & (table["direction"] == "down")]
    for name, value in direct.quantities().items():
        np.testing.assert_equal(row[name].item(), value)
    alpha = res.data["alpha"].sel(configuration="YBs", a_g=0.3, direction="down")
    np.testing.assert_array_equal(alpha.values, direct.alpha[::-1])  # (down: the steps high to low)
    assert np.isnan(table.loc[table["configuration"] == "NBs", "contact_nu_min"]).all()
    assert len(pd_.plots.plot_campaign(res)) == 12
    with pytest.raises(pd_.InputError, match="table3"):
        res.table3()
    with pytest.raises(pd_.InputError, match="nbs_system"):  # (the walled building as NBs)
        pd_.campaign(walled, walled, **options)
    with pytest.raises(pd_.InputError, match="ybs_system"):  # (another building)
        pd_.campaign(bare, pd_.Structure(3.0e3, iso, [pd_.Storey(2.0e3, 4.0e6)], walled.walls), **options)
    # on the command line: a structure's file as the YBs system
    from typer.testing import CliRunner

    from pounding.cli import app

    walled.to_toml(tmp_path / "walled.toml")
    bare.to_toml(tmp_path / "bare.toml")
    result = CliRunner().invoke(app, [
        "campaign", "--nbs", str(tmp_path / "bare.toml"), "--ybs", str(tmp_path / "walled.toml"), "--out",
        str(tmp_path / "c"), "--fmin", "0.6", "--fmax", "1.2", "--fstep", "0.3", "--steady", "fixed",
        "--cycles", "6", "--measure-cycles", "2", "--scheduler", "serial"])
    assert result.exit_code == 0, result.output
    assert "alpha_top_max" in result.output
    assert sorted(p.name for p in (tmp_path / "c").iterdir()) == ["campaign.nc", "campaign.png", "steps.csv",
                                                                  "table2.csv"]


def test_a_fixed_base_s_paper_quantities_are_its_first_floor_s_and_the_ground_has_none():
    wall = pd_.Wall(1, 0.005, 0.005, pd_.KelvinVoigt(1e7, 1e3))
    b = pd_.Structure.fixed_base([pd_.Storey(1e3, 4e5, 2e3), pd_.Storey(1e3, 4e5, 2e3)], [wall])
    res = pd_.sweep(b, 0.1, [2.0, 2.5, 3.0], steady="fixed", cycles=10, measure_cycles=2)
    ground, first = res.paper_quantities(0), res.paper_quantities()
    assert all(math.isnan(v) for v in ground.values())  # (level 0 is the ground: no response of its own)
    assert first == res.paper_quantities(1) and first["alpha"] == np.nanmax(res.alpha[:, 1])
    assert first["eta"] == np.nanmax(res.level_metrics[:, 1, 0] - res.level_metrics[:, 1, 1]) / 0.01
    assert first["contact_nu_min"] == 2.0 and first["peak_force_over_mg"] > 0
    assert res.to_xarray()["alpha"].dims == ("freq_hz", "level")
    # a single mass's loop only: a structure's is refused by name
    with pytest.raises(pd_.InputError, match="hysteresis_loop"):
        res.hysteresis_loop(2.0)
    with pytest.raises(pd_.InputError, match="hysteresis_loop"):
        pd_.sweep(pd_.Structure.from_oscillator(pd_.presets.paper_damped()), 0.05, [1.5]).hysteresis_loop(1.5)
    with pytest.warns(FutureWarning, match="pounding.protocols.SweepResult"):
        from pounding.protocols import StructureSweepResult
    assert StructureSweepResult is pd_.SweepResult
