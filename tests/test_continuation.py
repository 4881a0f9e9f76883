"""pounding.continuation: branches of periodic orbits against closed forms, sweeps and the
engine; bifurcations located; bad input named."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest
from typer.testing import CliRunner

import pounding as pd_
from pounding.analysis import _arclength
from pounding.cli import app

matplotlib.use("Agg")

M, K, C = 500.0, 40000.0, 800.0


def linear() -> pd_.Oscillator:
    return pd_.Oscillator(M, pd_.Isolator(slopes_n_m=(K,), breakpoints_m=(), damping_n_s_m=C))


def closed_form_excursion(a_g: float, freq_hz: np.ndarray, c: np.ndarray | float = C) -> np.ndarray:
    peak = pd_.Harmonic(a_g, 1.0).peak_m_s2
    w = 2 * np.pi * np.asarray(freq_hz)
    return 2 * M * peak / np.sqrt((K - M * w**2) ** 2 + (c * w) ** 2)


@pytest.fixture(scope="module")
def damped() -> pd_.Branch:
    return pd_.continuation(pd_.presets.paper_damped(), 0.05, (1.0, 3.0))


@pytest.fixture(scope="module")
def sweeps() -> tuple:
    osc = pd_.presets.paper_damped()
    return pd_.sweep(osc, 0.05, direction="up"), pd_.sweep(osc, 0.05, direction="down")


def test_linear_branch_is_the_closed_form_frequency_response() -> None:
    br = pd_.continuation(linear(), 0.05, (0.5, 3.0))
    df = br.to_dataframe()
    assert br.success and df.freq_hz.iloc[0] == 0.5 and df.freq_hz.iloc[-1] == pytest.approx(3.0, abs=1e-12)
    assert np.allclose(df.excursion_m, closed_form_excursion(0.05, df.freq_hz), rtol=1e-8, atol=0)
    lam = np.roots([M, C, K])
    mu = np.exp(np.outer(1.0 / df.freq_hz.to_numpy(), lam))
    got = br.multipliers[:, :2]
    # the pair, either order
    err = np.minimum(np.abs(got - mu).max(axis=1), np.abs(got - mu[:, ::-1]).max(axis=1))
    assert err.max() < 1e-9
    assert not br.bifurcations and df.stable.all()


def test_linear_branch_in_a_g_and_in_a_system_number() -> None:
    by_a = pd_.continuation(linear(), (0.01, 0.2), 1.2, parameter="a_g")
    df = by_a.to_dataframe()
    assert np.allclose(df.excursion_m, closed_form_excursion(1.0, 1.2) * df.a_g, rtol=1e-8)
    by_c = pd_.continuation(linear(), 0.05, 1.2, parameter="isolator.damping_n_s_m", values=(200.0, 2000.0))
    dc = by_c.to_dataframe()
    c = dc["isolator.damping_n_s_m"].to_numpy()
    assert c[0] == 200.0 and c[-1] == pytest.approx(2000.0)
    assert np.allclose(dc.excursion_m, closed_form_excursion(0.05, 1.2, c), rtol=1e-8)


def test_each_sweep_jump_lies_within_a_step_of_a_fold(damped: pd_.Branch, sweeps: tuple) -> None:
    folds = np.array([b.freq_hz for b in damped.folds()])
    jumps = []
    for sw in sweeps:
        j = sw.jumps()
        big = j[j.contact_from != j.contact_to]  # the jumps into or out of pounding
        jumps += [tuple(sorted(r)) for r in zip(big.freq_from_hz, big.freq_to_hz)]
    # the up sweep drops at 2.0 -> 2.1 Hz, the down sweep climbs at 1.7 -> 1.6 Hz (and the low-frequency
    # ridgelets): every jump between 1.5 and 3 Hz has a fold inside its step
    main = [(lo, hi) for lo, hi in jumps if lo >= 1.5]
    assert len(main) == 2
    for lo, hi in main:
        assert np.any((folds > lo) & (folds < hi)), (lo, hi, folds)
    assert damped.success and damped.data.freq_hz.iloc[-1] == pytest.approx(3.0)


def test_branch_orbits_are_periodic_and_match_the_sweep(damped: pd_.Branch, sweeps: tuple) -> None:
    df = damped.to_dataframe()
    assert (df.residual <= 1e-10).all()
    assert (~df.stable).any() and df.stable.any()
    up = sweeps[0].to_dataframe()
    at3 = up[np.isclose(up.freq_hz, 3.0)].iloc[0]
    assert df.alpha.iloc[-1] == pytest.approx(at3.alpha, rel=1e-6)
    # an unstable orbit returns to itself over one period, and departs over many
    i = int(np.flatnonzero(~df.stable.to_numpy())[len(np.flatnonzero(~df.stable.to_numpy())) // 2])
    orbit = damped.orbit(i)
    assert orbit.residual < 1e-8 and not orbit.stable
    exc = orbit.run.excitation
    far = pd_.simulate(orbit.run.oscillator, exc, 60 * orbit.period_s, orbit.state,
                       sample_rate_hz=0).final_state
    assert abs(far.displacement_m - orbit.state.displacement_m) > 1e-4


def test_bifurcations_are_located(damped: pd_.Branch) -> None:
    kinds = [b.kind for b in damped.bifurcations]
    assert {"fold", "grazing", "branch-point", "period-doubling"} <= set(kinds)
    for b in damped.folds():
        assert abs(np.abs(b.multipliers).max() - 1.0) < 1e-3  # a multiplier at +1
    osc = damped.oscillator
    for b in damped.bifurcations:
        if b.kind != "grazing":
            continue
        exc = pd_.Harmonic(b.a_g, b.freq_hz, phase=b.phase_rad)
        run = pd_.simulate(osc, exc, 1.0 / b.freq_hz, b.state, sample_rate_hz=0)
        reach = run.displacement_max if b.side == "wall0_right" else -run.displacement_min
        gap = osc.bumpers.gap_right_m if b.side == "wall0_right" else osc.bumpers.gap_left_m
        assert reach == pytest.approx(gap, rel=1e-7)
    table = damped.bifurcation_table()
    assert list(table.kind) == kinds


def test_exact_and_finite_difference_monodromy_give_the_same_folds() -> None:
    osc = pd_.presets.paper_damped()
    exact = pd_.continuation(osc, 0.05, (1.5, 2.5))
    fd = pd_.continuation(osc, 0.05, (1.5, 2.5), method="finite-difference")
    fe, ff = ([b.freq_hz for b in br.folds()] for br in (exact, fd))
    assert len(fe) == len(ff) == 2
    assert np.allclose(fe, ff, rtol=1e-6)


def test_period_doubling_starts_the_doubled_branch(damped: pd_.Branch) -> None:
    pd1 = next(b for b in damped.bifurcations if b.kind == "period-doubling")
    doubled = pd_.continuation(pd_.presets.paper_damped(), 0.05, (1.0, 3.0), guess=pd1)
    assert doubled.period_multiple == 2 and len(doubled) > 5
    osc = damped.oscillator
    row = doubled.data.iloc[len(doubled) // 2]
    state = pd_.State(doubled.states[len(doubled) // 2])
    exc = pd_.Harmonic(row.a_g, row.freq_hz, phase=row.phase_rad)
    one = pd_.simulate(osc, exc, 1.0 / row.freq_hz, state, sample_rate_hz=0).final_state
    two = pd_.simulate(osc, exc, 2.0 / row.freq_hz, state, sample_rate_hz=0).final_state
    assert abs(two.displacement_m - state.displacement_m) < 1e-9      # a period-2 orbit
    assert abs(one.displacement_m - state.displacement_m) > 1e-6      # not a period-1 one
    # the second one is where the multipliers jump across -1 (a mode change): refused, and said why
    pd2 = [b for b in damped.bifurcations if b.kind == "period-doubling"][1]
    assert np.min(np.abs(pd2.multipliers + 1.0)) > 1e-3
    with pytest.raises(pd_.InputError, match="jump"):
        pd_.continuation(pd_.presets.paper_damped(), 0.05, (1.0, 3.0), guess=pd2)


def test_branch_plot_with_sweeps(damped: pd_.Branch, sweeps: tuple) -> None:
    artists = pd_.plots.plot_branch(damped, sweeps=list(sweeps))
    assert artists and artists[0].figure is not None
    assert damped.plot(sweeps=list(sweeps)).__class__.__name__ == "Figure"
    with pytest.raises(pd_.InputError, match="not in this result"):
        damped.plot(y="nonsense")
    with pytest.raises(pd_.InputError, match="index"):
        damped.orbit(10_000)


@pytest.mark.parametrize("kwargs, field", [
    ({"freqs_hz": (1.0, 1.0)}, "freqs_hz"),
    ({"freqs_hz": 1.0}, "freqs_hz"),
    ({"freqs_hz": (1.0, -2.0)}, "freqs_hz[1]"),
    ({"a_g": (0.1, 0.2)}, "a_g"),
    ({"parameter": "a_g"}, "a_g"),
    ({"parameter": "bumpers.nothing", "values": (1, 2)}, "parameter"),
    ({"parameter": "bumpers.gap_left_m"}, "values"),
    ({"parameter": "bumpers.gap_left_m", "values": (0.01, -0.01), "freqs_hz": 1.5}, "values[1]"),
    ({"parameter": 3}, "parameter"),
    ({"tol": 1.0}, "tol"),
    ({"max_step": 0.0}, "max_step"),
    ({"max_points": 1}, "max_points"),
    ({"period_multiple": 0}, "period_multiple"),
    ({"method": "magic"}, "method"),
    ({"guess": "rest"}, "guess"),
    ({"f_ref_hz": 0.0}, "f_ref_hz"),
])
def test_bad_arguments_are_named(kwargs: dict, field: str) -> None:
    args = {"a_g": 0.05, "freqs_hz": (1.0, 2.0)}
    args.update(kwargs)
    with pytest.raises(pd_.InputError) as info:
        pd_.continuation(pd_.presets.paper_damped(), args.pop("a_g"), args.pop("freqs_hz"), **args)
    assert info.value.field == field


def test_a_fold_is_no_start(damped: pd_.Branch) -> None:
    with pytest.raises(pd_.InputError, match="fold"):
        pd_.continuation(pd_.presets.paper_damped(), 0.05, (1.0, 3.0), guess=damped.folds()[0])


def test_ctrl_c_keeps_the_branch_followed(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = {"n": 0}
    real = _arclength.Family.correct

    def interrupted(self, *args, **kwargs):
        calls["n"] += 1
        if calls["n"] > 20:
            raise KeyboardInterrupt
        return real(self, *args, **kwargs)

    monkeypatch.setattr(_arclength.Family, "correct", interrupted)
    with pytest.raises(pd_.Interrupted) as info:
        pd_.continuation(linear(), 0.05, (0.5, 3.0))
    part = info.value.partial
    assert isinstance(part, pd_.Branch) and 1 <= len(part) <= 20 and part.status == pd_.Status.INTERRUPTED


def test_cli_continue_writes_the_branch(tmp_path) -> None:
    out, bif, png = tmp_path / "b.csv", tmp_path / "f.csv", tmp_path / "b.png"
    res = CliRunner().invoke(app, ["continue", "--preset", "paper-damped", "--a-g", "0.05", "--from", "1.5",
                                   "--to", "2.5", "--out", str(out), "--bifurcations", str(bif), "--plot",
                                   str(png)])
    assert res.exit_code == 0, res.output
    assert "fold" in res.output and out.exists() and bif.exists() and png.exists()
    bad = CliRunner().invoke(app, ["continue", "--preset", "paper-damped", "--a-g", "0.05", "--from", "1.5",
                                   "--to", "1.5"])
    assert bad.exit_code == 2 and "freqs_hz" in bad.output


def test_a_bifurcation_of_another_forcing_is_refused(damped: pd_.Branch) -> None:
    pd1 = next(b for b in damped.bifurcations if b.kind == "period-doubling")
    with pytest.raises(pd_.InputError, match="a_g = 0.05"):
        pd_.continuation(pd_.presets.paper_damped(), 0.2, (1.0, 1.3), guess=pd1)
    with pytest.raises(pd_.InputError, match="has type float"):
        damped.orbit(1.0)


def test_edge_arguments_are_named() -> None:
    """A frequency too low to settle from names settle_cycles and the way out, not the run's duration;
    an angle too large to reduce is refused; Branch.orbit names an unknown keyword."""
    osc = pd_.presets.paper_damped()
    with pytest.raises(pd_.InputError, match="settle_cycles = 100 periods at 1e-09 Hz"):
        pd_.continuation(osc, 0.05, (1e-9, 1.0))
    with pytest.raises(pd_.InputError, match="settle_cycles"):
        pd_.periodic_orbit(osc, pd_.Harmonic(0.05, 1e-9))
    with pytest.raises(pd_.InputError, match="phase_rad"):
        pd_.continuation(osc, 0.05, (1.0, 2.0), phase_rad=1e300)
    br = pd_.continuation(osc, 0.05, (1.5, 1.6), phase_rad=2 * np.pi + 0.5)
    assert br.to_dataframe().phase_rad.iloc[0] == pytest.approx(0.5)
    with pytest.raises(pd_.InputError, match="bogus.*max_iter"):
        br.orbit(0, bogus=1)


def test_a_descending_range_stops_where_branch_switching_loops() -> None:
    """From 3 down to 1 Hz the follower switches at the branch points near 1.237 and 1.083 Hz and comes
    back to the first: it stops there (it once went round until max_points, 5000 orbits)."""
    br = pd_.continuation(pd_.presets.paper_damped(), 0.05, (3.0, 1.0))
    assert br.success and "loop" in br.message and len(br) < 1000, br
    folds = sorted(b.freq_hz for b in br.folds())
    assert any(abs(f - 2.01438) < 1e-4 for f in folds) and any(abs(f - 1.60526) < 1e-4 for f in folds)


def test_a_follower_stuck_at_tiny_steps_steps_in_the_parameter_alone(monkeypatch: pytest.MonkeyPatch) -> None:
    """Steps stuck far below the largest for CREEP_POINTS points in a row (here: every step counted as
    stuck) are a non-smooth point: the follower steps in the parameter alone, and says so."""
    from pounding.analysis import _follower

    monkeypatch.setattr(_follower.Follower, "CREEP", 2.0)
    monkeypatch.setattr(_follower.Follower, "CREEP_POINTS", 20)
    br = pd_.continuation(linear(), 0.05, (0.5, 3.0))
    assert br.success and "alone past" in br.message
    assert np.allclose(br.to_dataframe().excursion_m, closed_form_excursion(0.05, br.to_dataframe().freq_hz),
                       rtol=1e-8, atol=0)


def test_a_guess_at_any_time_starts_on_its_own_orbit() -> None:
    """Two responses coexist at 2 Hz on the calibrated system; the up sweep's state there (1000 s into
    the sweep, under its own forcing's phase) starts the branch on the impacting one, alpha 37 (the
    guess's section was once taken as time 0 with phase_rad unchanged: a wrong forcing angle, from
    which Newton found the other orbit, alpha 1.05)."""
    osc = pd_.presets.paper_calibrated()
    up = pd_.sweep(osc, 0.05, np.round(np.arange(0.5, 2.05, 0.1), 10), "up")
    i = int(np.argmin(np.abs(up.freqs_hz - 2.0)))
    f = float(up.freqs_hz[i])
    guess = pd_.State(up.window_states[i])
    phase = -(2 * np.pi * f * float(up.step_start_s[i]))
    br = pd_.continuation(osc, 0.05, (f, f + 0.02), guess=guess, phase_rad=phase)
    alpha_sweep = float(up.to_dataframe().alpha.iloc[i])
    assert guess.time_s > 100.0 and alpha_sweep > 30.0  # (the impacting response)
    assert br.to_dataframe().alpha.iloc[0] == pytest.approx(alpha_sweep, rel=1e-6)
