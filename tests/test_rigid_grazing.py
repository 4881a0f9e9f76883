"""Continuation through grazing (issue 51): where an orbit clear of a stop comes to touch it, the branch is
followed past it, the grazing located where the closed form puts it, and the Poincare map's singular term
there measured: a square root at a rigid stop, against its closed form (tests/reference_impact.py)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

import pounding
from pounding import Status
from reference_impact import grazing, impact_orbits

ZETA, A, E, W, D = 0.05, 3.0, 0.8, 2.0 * math.pi, 0.01  # (the gallery's oscillator, its stop 10 mm off)


def _oscillator(law) -> pounding.Oscillator:
    iso = pounding.Isolator(slopes_n_m=[W ** 2], damping_n_s_m=2.0 * ZETA * W)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (a gap of 10 m on the left: no stop there)
        return pounding.Oscillator(1.0, iso, pounding.Bumpers(10.0, D, law))


def _grazing_a_g(freq_hz: float) -> float:
    """The a_g (in g) at which the linear response's amplitude at freq_hz is the gap D: its grazing."""
    big = 2.0 * math.pi * freq_hz
    return D * abs(complex(W * W - big * big, 2.0 * ZETA * W * big)) / 9.81


def _period_doubling_hz() -> float:
    """Where the one-impact orbit's multiplier crosses -1 (closed form)."""
    def smallest(f: float) -> float:
        orbit = next(o for o in impact_orbits(W, ZETA, A, 2.0 * math.pi * f, D, E) if not o.grazes)
        return float(min(orbit.multipliers.real)) + 1.0
    return brentq(smallest, 2.3, 2.5, xtol=1e-14)


@pytest.mark.parametrize("freqs_hz", [(2.0, 4.0), (4.0, 2.9)])
def test_a_branch_is_continued_through_a_rigid_stop_s_grazing_with_the_map_s_square_root(freqs_hz):
    """From the impacting side (its impact speed falls to 0) and from the clear side (its clearance falls
    to 0: the steps cannot pass, and the orbit past it is found from the map's normal form)."""
    branch = pounding.continuation(_oscillator(pounding.RigidStop(E)), A / 9.81, freqs_hz, tol=1e-12)
    assert branch.status == Status.SUCCESS, branch.message
    grazings = [b for b in branch.bifurcations if b.kind == "grazing"]
    assert len(grazings) == 1 and grazings[0].located and grazings[0].side == "wall0_right"
    bif = grazings[0]
    closed = grazing(W, ZETA, A, D, E, bif.phase_rad, 2.5, 3.5)
    # to the orbits' accuracy: tol 1e-12 of the length scale (5 m: the 10 m gap) over dC/df 7.7e-3 m/Hz
    assert abs(bif.value - closed.freq_hz) < 1e-9
    f = branch.data["freq_hz"]
    assert f.min() < closed.freq_hz - 0.02 and f.max() > closed.freq_hz + 0.02  # (orbits both sides)
    # the square root, and its term: the truncation falls as the depth's square root (relative 4.9e-3,
    # 4.9e-4, 4.9e-5 at depths 1e-6, 1e-8, 1e-10 of the orbit's size; measured at 1e-10)
    assert abs(bif.scaling_exponent - 0.5) < 1e-5
    np.testing.assert_allclose(bif.scaling_term[:2], closed.term, rtol=1e-4)
    assert not bif.scaling_term[2:].any()
    # the multipliers jump at the grazing (unbounded on the impacting side, as 1 / impact speed): no
    # period-doubling is reported there, only the one the closed form has
    others = [b for b in branch.bifurcations if b.kind != "grazing"]
    if min(freqs_hz) < 2.3:
        assert [b.kind for b in others] == ["period-doubling"]
        assert abs(others[0].value - _period_doubling_hz()) < 1e-8
    else:
        assert not others


@pytest.mark.parametrize("damping, exponent", [(0.0, 1.5), (50.0, 1.0)])
def test_a_deformable_bumper_s_grazing_scales_with_the_power_its_force_starts_with(damping, exponent):
    """A spring's force starts from 0 at the touch: the map's change goes as the depth to 3/2; a dashpot's
    jumps to c v: as the depth itself.  The grazing is where the linear response's amplitude is the gap."""
    law = pounding.KelvinVoigt(stiffness=1e5, damping=damping)
    branch = pounding.continuation(_oscillator(law), A / 9.81, (4.0, 2.5))
    assert branch.status == Status.SUCCESS, branch.message
    (bif,) = [b for b in branch.bifurcations if b.kind == "grazing"]
    closed = grazing(W, ZETA, A, D, E, bif.phase_rad, 2.5, 3.5)
    assert bif.located and abs(bif.value - closed.freq_hz) < 1e-7  # (tol 1e-10 of the 5 m length scale)
    assert abs(bif.scaling_exponent - exponent) < 5e-3  # (measured: 1.50010, 1.00195)
    assert not [b for b in branch.bifurcations if abs(b.value - bif.value) < 1e-4 and b is not bif]


def test_a_branch_that_turns_at_the_grazing_reports_the_grazing_and_its_fold_where_the_closed_form_has_them():
    """In a_g at 1.3 Hz the orbit past the grazing lies back on the clear side (the normal form's beta < 0: a
    non-smooth fold): the grazing, and the fold it makes, at the a_g where the linear response's amplitude is
    the gap; the impacting branch then turns again at a smooth fold of its own."""
    osc = _oscillator(pounding.RigidStop(E))
    branch = pounding.continuation(osc, (0.005, 0.1), 1.3, parameter="a_g")
    assert branch.status == Status.SUCCESS, branch.message
    closed = _grazing_a_g(1.3)
    kinds = [(b.kind, b.located) for b in branch.bifurcations]
    assert kinds == [("grazing", True), ("fold", True), ("fold", True)], kinds
    graze, turn, smooth = branch.bifurcations
    assert abs(graze.value - closed) < 1e-9 * closed and turn.value == graze.value
    assert abs(graze.scaling_exponent - 0.5) < 1e-5 and smooth.value < graze.value


def test_a_branch_that_meets_the_non_smooth_fold_from_its_impacting_side_goes_round_it_onto_the_clear_one():
    """The same branch the other way: down the impacting orbits to their smooth fold, up to the grazing,
    where the impacting branch ends and the clear one turns back; the follower goes round it (no branch
    point or grazing reported where a step lands on the clear branch, no retracing of the impacting one)
    and on down the clear orbits to the range's end."""
    osc = _oscillator(pounding.RigidStop(E))
    branch = pounding.continuation(osc, (0.1, 0.005), 1.3, parameter="a_g")
    assert branch.status == Status.SUCCESS, branch.message
    assert "a_g = 0.005" in branch.message
    closed = _grazing_a_g(1.3)
    kinds = [(b.kind, b.located) for b in branch.bifurcations]
    assert kinds == [("fold", True), ("grazing", True), ("fold", True)], kinds
    smooth, graze, turn = branch.bifurcations
    assert abs(graze.value - closed) < 1e-9 * closed and turn.value == graze.value
    assert abs(graze.scaling_exponent - 0.5) < 1e-5
    ahead = pounding.continuation(osc, (0.005, 0.1), 1.3, parameter="a_g").bifurcations[-1]
    assert abs(smooth.value - ahead.value) < 1e-7 * ahead.value  # (the same smooth fold: 3e-8 apart)
    # past the turn every orbit is the linear response, clear of the stop
    p = branch.to_dataframe()["a_g"].to_numpy()
    past = p[int(np.argmin(np.abs(p - graze.value))) + 1:]
    assert np.all(np.diff(past) < 0.0) and past[-1] == 0.005


def test_a_branch_that_stalls_next_to_a_non_smooth_fold_goes_round_it():
    """The printed YBs isolator with a rigid stop 15 mm to the right, down in frequency: the impacting
    branch's steps stall next to a grazing where it ends (the slowest impact 5e-6 m over the forcing's
    angular frequency, multipliers of 3,600), and the clear orbit is Newton's a little ahead; the grazing
    is located from them, with the square root, and the branch goes on."""
    base = pounding.presets.paper_printed()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        stops = pounding.Bumpers(0.3, 0.015, pounding.RigidStop(0.8))
        osc = pounding.Oscillator(base.mass_kg, base.isolator, stops)
    branch = pounding.continuation(osc, 0.1, (3.0, 1.0))
    assert branch.status == Status.SUCCESS, branch.message
    grazings = [b for b in branch.bifurcations if b.kind == "grazing"]
    assert len(grazings) == 2 and all(g.located and abs(g.scaling_exponent - 0.5) < 1e-3 for g in grazings)
    folds = {b.value for b in branch.bifurcations if b.kind == "fold" and b.located}
    assert {g.value for g in grazings} <= folds  # (each grazing a non-smooth fold)
    assert abs(grazings[1].value - 1.63596) < 1e-4


def test_a_grazing_of_both_stops_at_once_is_located_and_said_where_the_branch_stops():
    """Symmetric stops, a symmetric orbit: both stops grazed at the closed form's a_g at once.  The map there
    goes as the depth's fourth root (the first impact's square root moves the second's depth), which one
    stop's normal form does not describe: the branch stops there and says so, with no fold of that normal
    form reported."""
    iso = pounding.Isolator(slopes_n_m=[W ** 2], damping_n_s_m=2.0 * ZETA * W)
    osc = pounding.Oscillator(1.0, iso, pounding.Bumpers(D, D, pounding.RigidStop(E)))
    branch = pounding.continuation(osc, (0.005, 0.1), 1.3, parameter="a_g")
    assert branch.status == Status.STEP_FAILED and "two stops at once" in branch.message
    (graze,) = branch.bifurcations
    closed = _grazing_a_g(1.3)
    assert graze.kind == "grazing" and graze.side == "wall0_left and wall0_right" and graze.located
    assert abs(graze.value - closed) < 1e-9 * closed
    assert abs(graze.scaling_exponent - 0.25) < 0.01


@pytest.mark.parametrize("e", [0.0, 1.0])
def test_no_period_doubling_is_reported_where_the_multipliers_jump_at_a_grazing(e):
    """Past a rigid stop's grazing the impacting orbit's multipliers are unbounded (as one over its impact
    speed), below -1 at once: the count of those past -1 changes at the grazing, with no crossing of -1."""
    branch = pounding.continuation(_oscillator(pounding.RigidStop(e)), A / 9.81, (4.0, 2.5))
    assert branch.status == Status.SUCCESS, branch.message
    assert [b.kind for b in branch.bifurcations] == ["grazing"]
    assert abs(branch.bifurcations[0].value - grazing(W, ZETA, A, D, e, 0.0, 2.5, 3.5).freq_hz) < 1e-7
    past = branch.data[branch.data["freq_hz"] < branch.bifurcations[0].value - 1e-3]
    assert (past["max_abs_multiplier"] > 1.0).all()  # (unstable all the way down to 2.5 Hz)
