"""Stepped-sine sweeps: closed forms, the reference, folds, steadiness, results."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding.protocols.sweep import paper_frequencies_hz


def damped_paper(c_d: float, bumpers: bool = True) -> pd_.Oscillator:
    """The printed system with isolator damping ``c_d`` (MODEL.md §5 reads 1 kN s/m)."""
    base = pd_.presets.paper_printed(bumpers=bumpers)
    return pd_.Oscillator(base.mass_kg, dataclasses.replace(base.isolator, damping_n_s_m=c_d), base.bumpers)


@settings(max_examples=8, deadline=None)
@given(m=st.floats(100, 1000), k=st.floats(5e3, 5e4), zeta=st.floats(0.05, 0.3),
       a_g=st.floats(0.01, 0.3), direction=st.sampled_from(["up", "down"]))
def test_linear_sweep_equals_closed_form_frequency_response(m, k, zeta, a_g, direction):
    c = 2 * zeta * math.sqrt(k * m)
    osc = pd_.Oscillator(m, pd_.Isolator((k,), damping_n_s_m=c))
    f_n = math.sqrt(k / m) / (2 * math.pi)
    freqs = f_n * np.array([0.5, 0.9, 1.0, 1.1, 2.0])
    res = pd_.sweep(osc, a_g, freqs, direction, steady_rtol=1e-8, max_cycles=2000)
    assert res.success, res.message
    df = res.to_dataframe()
    omega = 2 * math.pi * df["freq_hz"].to_numpy()
    a_t = a_g * 9.81
    denom = np.abs(k - m * omega**2 + 1j * c * omega)
    np.testing.assert_allclose(df["alpha"], np.abs(k + 1j * c * omega) / denom, rtol=1e-6)
    np.testing.assert_allclose(df["excursion_m"], 2 * m * a_t / denom, rtol=1e-6)
    np.testing.assert_allclose(df["e"], df["excursion_m"] / (a_t / (2 * math.pi * 0.6) ** 2), rtol=1e-12)
    assert df["steady"].all() and (df["period_multiple"] == 1).all()
    assert not df["contact"].any() and df["eta"].isna().all()
    assert res.nu_r == pytest.approx(f_n * (1.0 if zeta < 0.35 else 0.5), rel=0.11)


def test_fold_gives_jumps_at_different_frequencies_up_and_down():
    osc = damped_paper(1000.0)
    freqs = np.arange(10, 26) / 10
    up = pd_.sweep(osc, 0.05, freqs, "up")
    down = pd_.sweep(osc, 0.05, freqs, "down")
    up_drop = up.jumps().query("kind == 'down' and contact_from and not contact_to")
    down_rise = down.jumps().query("kind == 'up' and not contact_from and contact_to")
    assert len(up_drop) == 1 and len(down_rise) == 1
    # the impacting branch is left at a higher frequency going up than it is caught going down
    assert up_drop["freq_from_hz"].iloc[0] > down_rise["freq_to_hz"].iloc[0] + 0.25
    # between the two, both branches coexist: same frequency, different responses
    f = 1.9
    a_up = up.to_dataframe().set_index("freq_hz").loc[f, "alpha"]
    a_down = down.to_dataframe().set_index("freq_hz").loc[f, "alpha"]
    assert a_up > 5 * a_down
    assert up.contact_range_hz[1] > down.contact_range_hz[1]


def test_adaptive_and_fixed_agree_where_periodic():
    osc = damped_paper(1000.0)
    freqs = [1.3, 1.4, 1.5, 3.0, 3.5]
    adaptive = pd_.sweep(osc, 0.05, freqs)
    fixed = pd_.sweep(osc, 0.05, freqs, steady="fixed", cycles=int(adaptive.cycles_run.max()) + 30)
    a, b = adaptive.to_dataframe(), fixed.to_dataframe()
    assert a["steady"].all() and b["steady"].all()
    for col in ("alpha", "excursion_m", "contacts_per_cycle", "restitution", "contact_time_s",
                "mean_force_n", "peak_force_n", "dissipated_energy_j"):
        np.testing.assert_allclose(a[col], b[col], rtol=1e-4, err_msg=col)
    assert (fixed.cycles_run == fixed.cycles).all()


def test_adaptive_never_runs_past_its_maximum_and_says_so():
    osc = pd_.presets.paper_printed()  # C_d = 1 N s/m: no steady state in sight
    res = pd_.sweep(osc, 0.05, [1.0, 1.5, 2.0], max_cycles=25)
    assert (res.cycles_run == 25).all()
    assert not res.to_dataframe()["steady"].any()
    assert "max_cycles = 25" in res.message and "steady False" in res.message


def test_period_three_response_is_detected_and_real():
    osc = damped_paper(300.0)
    res = pd_.sweep(osc, 0.2, np.arange(5, 71) / 10, "up")  # the branch is reached from below
    df = res.to_dataframe().set_index("freq_hz")
    assert df.loc[6.6, "period_multiple"] == 1 and df.loc[7.0, "period_multiple"] == 3
    assert df.loc[7.0, "contacts_per_cycle"] == pytest.approx(2 / 3)
    # independently: from the window state, strobes repeat every third cycle, not every cycle
    i = res.step_index(7.0)
    state = pd_.State(res.window_states[i])
    exc = pd_.Harmonic(0.2, 7.0, phase=-(2 * math.pi * 7.0 * res.step_start_s[i]))
    strobes = []
    for _ in range(4):
        run = pd_.simulate(osc, exc, 1 / 7.0, state, sample_rate_hz=0)
        state = run.final_state
        strobes.append(state.displacement_m)
    assert abs(strobes[3] - strobes[0]) < 1e-6 * df.loc[7.0, "excursion_m"]
    assert abs(strobes[1] - strobes[0]) > 0.1 * df.loc[7.0, "excursion_m"]


def test_continuing_a_sweep_equals_one_long_sweep():
    osc = pd_.presets.paper_printed()
    kw = dict(steady="fixed", cycles=6, measure_cycles=2)
    whole = pd_.sweep(osc, 0.05, [1.0, 1.5, 2.0, 2.5], **kw)
    first = pd_.sweep(osc, 0.05, [1.0, 1.5], **kw)
    second = pd_.sweep(osc, 0.05, [2.0, 2.5], state=first.final_state, **kw)
    joined = np.concatenate([first.to_dataframe().to_numpy(), second.to_dataframe().to_numpy()])
    np.testing.assert_array_equal(whole.to_dataframe().to_numpy().astype(str), joined.astype(str))
    np.testing.assert_array_equal(whole.final_state.vector, second.final_state.vector)


def test_step_metrics_are_the_window_of_a_plain_simulation():
    osc = pd_.presets.paper_printed()
    res = pd_.sweep(osc, 0.1, [1.6], steady="fixed", cycles=10, measure_cycles=4)
    f = 1.6
    exc = pd_.Harmonic(0.1, f)
    warm = pd_.simulate(osc, exc, 6 / f, sample_rate_hz=0)
    run = pd_.simulate(osc, exc, 4 / f, warm.final_state, sample_rate_hz=0)
    row = res.to_dataframe().iloc[0]
    assert row["alpha"] == pytest.approx(run.abs_acceleration_max / exc.peak_m_s2, rel=1e-12)
    assert row["excursion_m"] == pytest.approx(run.excursion_m, rel=1e-12)
    imp = run.impacts.dropna(subset=["contact_time_s"])
    assert row["contacts_per_cycle"] * 4 == len(imp) > 0
    for col in ("restitution", "contact_time_s", "impulse_n_s", "mean_force_n", "peak_force_n",
                "dissipated_energy_j", "bumper_dissipation_j"):
        assert row[col] == pytest.approx(imp[col].mean(), rel=1e-12), col
    for side in ("left", "right"):
        part = imp[imp["side"] == side]
        assert row[f"contacts_per_cycle_{side}"] * 4 == len(part)
        assert row[f"restitution_{side}"] == pytest.approx(part["restitution"].mean(), rel=1e-12)


def test_results_table_xarray_netcdf_and_features(tmp_path):
    osc = damped_paper(1000.0)
    res = pd_.sweep(osc, 0.05, [2.2, 1.2, 1.6, 2.0], "down")
    assert list(res.freqs_hz) == [2.2, 2.0, 1.6, 1.2]
    df = res.to_dataframe()
    assert list(df.columns[:5]) == ["freq_hz", "nu", "level", "alpha", "excursion_m"]  # (its one level: 0)
    ds = res.to_xarray()
    assert list(ds["freq_hz"].values) == [1.2, 1.6, 2.0, 2.2] and ds["alpha"].dims == ("freq_hz",)
    assert ds.attrs["direction"] == "down" and ds["contact"].dtype == bool
    path = tmp_path / "sweep.nc"
    ds.to_netcdf(path)
    back = xr.open_dataset(path)
    np.testing.assert_allclose(back["alpha"].values, ds["alpha"].values)
    assert res.resonance_hz == df.loc[df["alpha"].idxmax(), "freq_hz"]
    assert res.nu_r == res.resonance_hz
    lo, hi = res.contact_range_hz
    assert df.loc[df["freq_hz"].between(lo, hi), "contact"].any()


def test_hysteresis_loop_is_a_closed_steady_cycle():
    osc = damped_paper(1000.0)
    res = pd_.sweep(osc, 0.05, [1.4, 1.6])
    loop = res.hysteresis_loop(1.6)
    row = res.to_dataframe().set_index("freq_hz").loc[1.6]
    assert loop.d[0] == pytest.approx(loop.d[-1], abs=1e-5) and loop.r[0] == pytest.approx(loop.r[-1],
                                                                                           abs=1e-4)
    assert np.max(np.abs(loop.r)) == pytest.approx(row["alpha"] * 0.05, rel=1e-3)
    assert np.ptp(loop.d) * loop.total_gap_m == pytest.approx(row["excursion_m"], rel=1e-5)
    assert loop.bumper_surfaces_d == (-0.5, 0.5)
    assert list(loop.to_dataframe().columns) == ["t", "d", "r"]
    nbs = pd_.sweep(osc.without_bumpers(), 0.05, [1.0])
    with pytest.raises(pd_.InputError, match="total_gap_m"):
        nbs.hysteresis_loop(1.0)
    assert nbs.hysteresis_loop(1.0, total_gap_m=0.03).bumper_surfaces_d is None
    with pytest.raises(pd_.InputError, match="freq_hz = 1.5 is not in this result"):
        res.hysteresis_loop(1.5)


def test_progress_callback_and_interruption_keep_the_finished_steps():
    osc = pd_.presets.paper_printed()
    seen = []

    def progress(n):
        seen.append(n)
        if len(seen) == 3:
            raise KeyboardInterrupt

    with pytest.raises(pd_.Interrupted) as info:
        pd_.sweep(osc, 0.05, [1.0, 1.2, 1.4, 1.6, 1.8], steady="fixed", cycles=4, measure_cycles=2,
                  progress=progress)
    part = info.value.partial
    assert isinstance(info.value, KeyboardInterrupt)
    assert part.steps_done == 3 and info.value.done == 3 and info.value.total == 5
    df = part.to_dataframe()
    assert df["alpha"].iloc[:3].notna().all() and df["alpha"].iloc[3:].isna().all()
    assert "Interrupted after 3 of 5" in part.message


@pytest.mark.parametrize("kwargs, field", [
    (dict(a_g=-0.05), "a_g"),
    (dict(freqs_hz=[1.0, 1.0]), "freqs_hz"),
    (dict(freqs_hz=[1.0, -2.0]), "freqs_hz[1]"),
    (dict(freqs_hz=[[1.0]]), "freqs_hz"),
    (dict(direction="sideways"), "direction"),
    (dict(steady="sometimes"), "steady"),
    (dict(cycles=10), "cycles"),
    (dict(steady="fixed", cycles=3, measure_cycles=5), "cycles"),
    (dict(steady="fixed", max_cycles=3), "max_cycles"),
    (dict(max_cycles=2.5), "max_cycles"),
    (dict(measure_cycles=0), "measure_cycles"),
    (dict(steady_rtol=0.5), "steady_rtol"),
    (dict(state="rest"), "state"),
    (dict(progress="yes"), "progress"),
])
def test_bad_arguments_name_the_field_and_the_fix(kwargs, field):
    args = dict(system=pd_.presets.paper_printed(), a_g=0.05, freqs_hz=[1.0, 2.0])
    args.update(kwargs)
    with pytest.raises(pd_.InputError) as info:
        pd_.sweep(**args)
    assert info.value.field == field and "Fix:" in str(info.value)


def test_paper_frequencies():
    f = paper_frequencies_hz()
    assert f.size == 46 and f[0] == 0.5 and f[-1] == 5.0 and f[22] == 2.7


@pytest.mark.parametrize("size, ratio, steady", [
    (1e-15, -1.02, True),   # rounding noise that does not shrink: converged all the same
    (1e-5, 0.9999, False),  # 10 tolerances from its orbit, and hardly decaying
    (1e-5, 0.5, True),      # decaying fast: within tolerance of its orbit after 40 cycles
])
def test_periodicity_of_strobes_at_and_above_rounding_noise(size, ratio, steady):
    from pounding.engine.kernels import CY_DMAX, CY_DMIN, CYCLE_COLS, periodicity

    def period(strobe, cyc, n):  # steady_rtol 1e-6, windows of 5 cycles
        return periodicity(strobe, cyc, n, 5, 4, 1e-6, 2.0 * math.pi, False)

    n = 40
    amplitude = 0.01
    cyc = np.zeros((n, CYCLE_COLS))
    cyc[:, CY_DMAX], cyc[:, CY_DMIN] = amplitude, -amplitude
    # strobes of a period-1 orbit plus a deviation (relative to the amplitude) multiplied by
    # ``ratio`` each cycle
    deviation = size * amplitude * ratio ** np.arange(n)
    strobe = np.zeros((n, 4))
    strobe[:, 0] = 0.3 * amplitude + deviation
    strobe[:, 1] = 0.02 + deviation
    k, _ = period(strobe, cyc, np.int64(n))
    assert k == (1 if steady else 0)


def test_sweep_shows_one_options_object_and_names_an_unknown_option():
    """One list of options with one set of defaults (SweepOptions): sweep's signature shows them,
    make_plan, campaign and identify take them, and a misspelt one is named with the known ones."""
    import dataclasses
    import inspect

    from pounding.protocols.sweep import SWEEP_OPTIONS, SweepOptions, make_plan

    shown = {n: p.default for n, p in inspect.signature(pd_.sweep).parameters.items()
             if p.kind is inspect.Parameter.KEYWORD_ONLY and n not in ("state", "progress")}
    assert shown == {f.name: f.default for f in dataclasses.fields(SweepOptions)}
    assert tuple(shown) == SWEEP_OPTIONS
    osc = pd_.presets.paper_damped()
    plan = make_plan(osc, 0.05, [1.0], steady="fixed", cycles=7)
    assert (plan.steady, plan.cycles, plan.measure_cycles) == ("fixed", 7, SweepOptions.measure_cycles)
    for call in (lambda: pd_.sweep(osc, 0.05, [1.0], max_cycle=9),
                 lambda: pd_.campaign(None, osc, freqs_hz=[1.0], max_cycle=9)):
        with pytest.raises(pd_.InputError, match="max_cycle.*max_cycles"):
            call()
