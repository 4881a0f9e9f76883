"""Two-parameter continuation: grazing curves against the closed form, fold curves against
one-parameter branches at other levels, the coexistence map against up and down sweeps; bad
input named; Ctrl-C keeps the curve."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest

import pounding as pd_
from pounding.analysis import _curve

matplotlib.use("Agg")

M, K, C = 500.0, 40000.0, 800.0
GAP_L, GAP_R = 0.025, 0.02


def linear_with_bumpers() -> pd_.Oscillator:
    law = pd_.KelvinVoigt(1.0e6, 2000.0)
    return pd_.Oscillator(M, pd_.Isolator(slopes_n_m=(K,), breakpoints_m=(), damping_n_s_m=C),
                          pd_.Bumpers(GAP_L, GAP_R, law, law))


def grazing_a_g(freq_hz: np.ndarray, gap: float) -> np.ndarray:
    """The a_G at which the linear orbit's amplitude is ``gap``: the closed-form grazing curve."""
    w = 2 * np.pi * np.asarray(freq_hz)
    return gap * np.sqrt((K - M * w**2) ** 2 + (C * w) ** 2) / (M * pd_.Harmonic(1.0, 1.0).peak_m_s2)


@pytest.fixture(scope="module")
def damped() -> tuple:
    osc = pd_.presets.paper_damped()
    return osc, pd_.continuation(osc, 0.05, (1.0, 3.0))


@pytest.fixture(scope="module")
def upper_fold_curve(damped: tuple) -> pd_.BifurcationCurve:
    osc, br = damped
    fold = next(b for b in br.folds() if b.freq_hz > 1.9)
    return pd_.bifurcation_curve(osc, fold, a_g=(0.02, 0.11), freqs_hz=(0.5, 5.0))


def test_grazing_curve_is_the_closed_form() -> None:
    osc = linear_with_bumpers()
    br = pd_.continuation(osc, 0.05, (0.5, 3.0))
    right = [b for b in br.bifurcations if b.kind == "grazing" and b.side == "wall0_right"]
    assert len(right) == 2  # (below and above the resonance, 1.42 Hz)
    curve = pd_.bifurcation_curve(osc, right[0], a_g=(0.02, 0.2), freqs_hz=(0.5, 3.0))
    df = curve.to_dataframe()
    assert curve.success and len(df) > 20, curve
    assert np.allclose(df.a_g, grazing_a_g(df.freq_hz, GAP_R), rtol=1e-6, atol=0)
    # it runs from edge to edge through the resonance: the other grazing is on it
    assert curve.passes(right[1])
    assert df.a_g.min() == pytest.approx(grazing_a_g(np.linspace(1.3, 1.5, 20001), GAP_R).min(), rel=1e-4)
    assert (df.contacts_per_period == 0).all() and np.abs(df.test).max() < 1e-8


def test_fold_curve_holds_the_folds_of_branches_at_other_levels(damped: tuple, upper_fold_curve) -> None:
    osc, br = damped
    curve = upper_fold_curve
    assert curve.success, curve
    df = curve.to_dataframe()
    assert np.abs(df.critical_multiplier - 1.0).max() < 1e-6
    # both folds of the 0.05 branch are on this one curve (through its cusp)
    assert all(curve.passes(f) for f in br.folds() if f.freq_hz > 1.5)
    # below the cusp the sweeps agree: the curve's lowest a_G lies between a level without and one with a jump
    assert 0.02 < df.a_g.min() < 0.05
    # an independent branch at another level: its folds where the curve, followed from the 0.05 folds
    # in a box whose top edge is that level, ends (each end is solved on the edge)
    other = pd_.continuation(osc, 0.075, (1.0, 3.5))
    folds = sorted((f for f in other.folds() if f.freq_hz > 1.5), key=lambda f: f.freq_hz)
    assert len(folds) == 2
    ends = []
    for start in (f for f in br.folds() if f.freq_hz > 1.5):
        part = pd_.bifurcation_curve(osc, start, a_g=(0.05, 0.075), freqs_hz=(0.5, 5.0))
        top = part.to_dataframe().query("a_g == 0.075")
        assert part.success and len(top) == 1, part
        ends.append(float(top.freq_hz.iloc[0]))
    # (the lower fold sits 4e-5 Hz from a grazing: its multiplier runs from 3.2 to 0.65 between two
    # of the branch's points; it was once reported at the nearer point, not located)
    assert all(f.located for f in folds)
    assert np.allclose(sorted(ends), [f.freq_hz for f in folds], rtol=1e-9, atol=0)


def test_fold_curve_points_are_periodic_orbits_with_a_multiplier_one(upper_fold_curve) -> None:
    curve = upper_fold_curve
    df = curve.to_dataframe()
    for i in np.linspace(0, len(df) - 1, 4).astype(int):
        row = df.iloc[i]
        orbit = pd_.periodic_orbit(curve.oscillator, pd_.Harmonic(row.a_g, row.freq_hz, phase=row.phase_rad),
                                   guess=pd_.State(curve.states[i]), tol=1e-8)
        # (a fold's Newton is singular: the curve's point is the orbit to the curve's tolerance)
        assert orbit.converged and orbit.iterations == 0
        assert np.min(np.abs(orbit.multipliers - 1.0)) < 1e-5


def test_coexistence_map_matches_the_sweeps() -> None:
    osc = pd_.presets.paper_damped()
    m = pd_.coexistence_map(osc, a_g=(0.02, 0.11), freqs_hz=(1.0, 3.0), levels=[0.05, 0.075], kinds=["fold"])
    assert len(m.branches) == 2 and len(m.matrix) == 2 * 21
    # the 0.075 branch's upper folds are on the curve from the 0.05 branch's: followed once
    uppers = [c for c in m.curves if c.data.freq_hz.max() > 2.0]
    assert len(uppers) == 1
    for level in (0.05, 0.075):
        up, down = pd_.sweep(osc, level, np.round(np.arange(1.0, 3.0001, 0.1), 10), "up"), \
            pd_.sweep(osc, level, np.round(np.arange(1.0, 3.0001, 0.1), 10), "down")
        a_up, a_down = up.to_dataframe().alpha.to_numpy(), down.to_dataframe().alpha.to_numpy()[::-1]
        rows = m.matrix[np.isclose(m.matrix.a_g, level)]
        differ = np.abs(a_up - a_down) > 0.05 * np.maximum(a_up, a_down)
        two = rows.stable_orbits.to_numpy() >= 2
        assert differ.any() and np.all(two[differ]), (level, rows.freq_hz[differ & ~two].tolist())
    ax = m.plot()  # (its Figure)
    assert ax and len(m.to_dataframe()) == sum(len(c) for c in m.curves)
    assert "coexisting" in repr(m)


@pytest.mark.parametrize("kwargs, field", [
    ({"a_g": (0.1, 0.2)}, "a_g"),
    ({"freqs_hz": (0.5,)}, "freqs_hz"),
    ({"freqs_hz": (-1.0, 3.0)}, "freqs_hz"),
    ({"max_step": 2.0}, "max_step"),
    ({"tol": 0.1}, "tol"),
    ({"method": "guess"}, "method"),
    ({"max_points": 1}, "max_points"),
])
def test_bad_arguments_are_named(damped: tuple, kwargs: dict, field: str) -> None:
    osc, br = damped
    with pytest.raises(pd_.InputError, match=field):
        pd_.bifurcation_curve(osc, br.folds()[0], **kwargs)


def test_a_grazing_is_followed_at_one_named_contact(damped: tuple) -> None:
    """A grazing of both bumpers at once (the branch's summary line) or one named in 0.x's words is
    refused with the contact names the system has, not a KeyError deep in the follower."""
    import dataclasses

    osc, br = damped
    graze = next(b for b in br.bifurcations if b.kind == "grazing")
    for side in ("wall0_left and wall0_right", "left", ""):
        with pytest.raises(pd_.InputError, match=r"bifurcation\.side.*wall0_left, wall0_right"):
            pd_.bifurcation_curve(osc, dataclasses.replace(graze, side=side))


def test_only_folds_and_grazings_are_followed(damped: tuple) -> None:
    osc, br = damped
    pd = next(b for b in br.bifurcations if b.kind == "period-doubling")
    with pytest.raises(pd_.InputError, match="one parameter only"):
        pd_.bifurcation_curve(osc, pd)
    with pytest.raises(pd_.InputError, match="bifurcation"):
        pd_.bifurcation_curve(osc, "fold")
    with pytest.raises(pd_.InputError, match="not of this system"):
        pd_.bifurcation_curve(pd_.Oscillator(M, pd_.Isolator(slopes_n_m=(K,), breakpoints_m=(),
                                                             damping_n_s_m=C)),
                              br.folds()[0])
    for kwargs, field in (({"levels": [0.5]}, "levels"), ({"kinds": ["period-doubling"]}, "kinds"),
                          ({"levels": "0.05"}, "levels"), ({"freq_step_hz": 0.0}, "freq_step_hz")):
        with pytest.raises(pd_.InputError, match=field):
            pd_.coexistence_map(osc, **kwargs)


def test_ctrl_c_keeps_the_curve_followed(damped: tuple, monkeypatch: pytest.MonkeyPatch) -> None:
    osc, br = damped
    real = _curve.CurveFollower.step
    calls = []

    def interrupted(self, *args, **kwargs):
        calls.append(1)
        if len(calls) > 5:
            raise KeyboardInterrupt
        return real(self, *args, **kwargs)

    monkeypatch.setattr(_curve.CurveFollower, "step", interrupted)
    with pytest.raises(pd_.Interrupted) as info:
        pd_.bifurcation_curve(osc, br.folds()[-1])
    part = info.value.partial
    assert isinstance(part, pd_.BifurcationCurve) and part.status == pd_.Status.INTERRUPTED and len(part) >= 2


def test_cli_coexistence_writes_the_curves_and_the_matrix(tmp_path) -> None:
    from typer.testing import CliRunner

    from pounding.cli import app

    out, matrix, plot = tmp_path / "c.csv", tmp_path / "m.csv", tmp_path / "c.png"
    res = CliRunner().invoke(app, ["coexistence", "--preset", "paper-damped", "--from", "1.5", "--to", "2.5",
                                   "--a-g-min", "0.04", "--a-g-max", "0.06", "--levels", "0.05",
                                   "--out", str(out), "--matrix", str(matrix), "--plot", str(plot)])
    assert res.exit_code == 0, res.output
    import pandas as pd

    curves, counts = pd.read_csv(out), pd.read_csv(matrix)
    assert set(curves.kind) == {"fold"} and len(counts) == 11 and counts.stable_orbits.max() == 2
    assert plot.stat().st_size > 0 and "coexisting" in res.output
    bad = CliRunner().invoke(app, ["coexistence", "--preset", "paper-damped", "--levels", "a,b"])
    assert bad.exit_code != 0 and "--levels" in bad.output


def test_a_curve_from_either_fold_of_a_level_is_the_same_curve_through_its_cusp() -> None:
    """(Once, a section moved while following one direction was kept for the other, whose first step
    then failed; and a curve whose steps are mostly in the orbit's state was taken as closed after
    four points.)  From each fold of the 0.0285 and 0.03 branches: one curve, edge to edge."""
    osc = pd_.presets.paper_damped()
    for level in (0.0285, 0.03):
        br = pd_.continuation(osc, level, (1.0, 3.0))
        lower = min((f for f in br.folds() if f.freq_hz > 1.3), key=lambda f: f.freq_hz)
        curve = pd_.bifurcation_curve(osc, lower, a_g=(0.02, 0.11), freqs_hz=(0.5, 5.0))
        df = curve.to_dataframe()
        assert curve.success and "edge" in curve.message, curve
        assert df.a_g.min() == pytest.approx(0.028193, abs=2e-6)  # the cusp
        # (both legs end on the top edge)
        assert np.isclose(df.a_g.iloc[[0, -1]], 0.11, rtol=0, atol=1e-12).all()


@pytest.mark.parametrize("kwargs, field", [
    ({"kinds": 5}, "kinds"), ({"kinds": None}, "kinds"), ({"kinds": []}, "kinds"),
    ({"levels": np.array(0.05)}, "levels"), ({"levels": [0.05, 0.05]}, "levels"),
    ({"a_g": {1: 2, 3: 4}}, "a_g"), ({"freqs_hz": (1.0, 2.0, 3.0)}, "freqs_hz"),
    ({"freq_step_hz": 1e-12}, "freq_step_hz"), ({"a_g": (0.02, float("nan"))}, "a_g"),
    ({"levels": [0.05, float("inf")]}, "levels"),
])
def test_coexistence_map_names_bad_input(kwargs: dict, field: str) -> None:
    with pytest.raises(pd_.InputError, match=field):
        pd_.coexistence_map(pd_.presets.paper_damped(), **kwargs)


def _walk(curve, ts: np.ndarray) -> list[np.ndarray]:
    return [np.asarray(curve(t), dtype=float) for t in ts]


def _closes_at(points: list[np.ndarray], steps: np.ndarray) -> int | None:
    """The index of the step (into ``points``) at which one Closure, as the followers use it, says the
    walk came back to its first point; None if never."""
    from pounding.analysis._arclength import Closure

    closure = Closure(points[0])
    for i in range(1, len(points)):
        if closure.passed(points[i - 1], points[i], steps[i - 1]):
            return i
    return None


@pytest.mark.parametrize("turn_rad", [0.05, 0.2, 0.45])
def test_a_closed_curve_closes_after_one_turn_whatever_its_steps(turn_rad: float) -> None:
    """The followers' one closure test (analysis/_arclength.Closure): a circle walked in steps that
    turn by up to the followers' largest angle (arccos 0.9), starting off the grid of the first
    turn, closes on the step that passes its start again, not before; the points carry the
    corrector's noise."""
    rng = np.random.default_rng(7)
    ts = np.cumsum(np.r_[0.0, turn_rad * rng.uniform(0.6, 1.0, 200)])
    points = _walk(lambda t: (np.cos(t), np.sin(t), 0.3 * np.sin(t)), ts)
    points = [p + 1e-9 * rng.standard_normal(3) for p in points]
    steps = np.array([np.linalg.norm(b - a) for a, b in zip(points, points[1:])])
    i = _closes_at(points, steps)
    assert i is not None and ts[i - 1] < 2 * np.pi <= ts[i]


def test_a_curve_crossing_itself_closes_only_where_it_returns() -> None:
    """A figure eight passes its own crossing heading another way: no closure there; it closes when
    it comes back to its start.  A spiral that comes near its start but a little inside never
    closes."""
    ts = np.linspace(0.0, 2 * np.pi + 0.5, 300)
    eight = _walk(lambda t: (np.sin(t), np.sin(t) * np.cos(t), 0.0), ts)  # (crossing at t = 0 and pi)
    steps = np.array([np.linalg.norm(b - a) for a, b in zip(eight, eight[1:])])
    i = _closes_at(eight, steps)
    assert i is not None and ts[i - 1] < 2 * np.pi <= ts[i]
    spiral = _walk(lambda t: ((1 - 0.05 * t) * np.cos(t), (1 - 0.05 * t) * np.sin(t), 0.0), ts)
    steps = np.array([np.linalg.norm(b - a) for a, b in zip(spiral, spiral[1:])])
    assert _closes_at(spiral, steps) is None
