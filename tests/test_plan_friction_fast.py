"""A velocity-dependent friction circle in plan (``FrictionIsolator(mu_fast=..., rate_s_m=...)`` under a
:class:`pounding.Bearing`): its force ``W (mu_fast - (mu_fast - mu) exp(-rate_s_m s)) z`` at the slip's rate
``s``.  Against the independent solve_ivp reference (random eccentric buildings, pairs of components, a moat;
both circles), Coulomb's numbers when ``mu_fast = mu``, the closed-form orbit under circular shaking at the
friction of its speed, the line's exact rigid stick as the pre-slip shrinks, the ledger, a continued run, a
file, and the door."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from reference_plan import reference
from reference_plan import record_pair as _record
from test_plan_friction import steady_orbit_radius
from test_plan_friction_circle import (_building, _restated, assert_one_floor_as_the_reference,
                                       assert_switches_as_the_reference)

import pounding
from pounding import Bearing, Floor, FrictionIsolator, PlanBuilding, _core

G = 9.81


def _fast(b: PlanBuilding, mu_fast: float, rate_s_m: float, circle: str) -> PlanBuilding:
    """The building with every bearing's friction velocity-dependent and its circle ``circle``."""
    bearings = [Bearing(x.at_m, dataclasses.replace(x.isolator, mu_fast=mu_fast, rate_s_m=rate_s_m),
                        friction_circle=circle) for x in b.bearings]
    return dataclasses.replace(b, bearings=bearings)


def _restated_fast(b: PlanBuilding):
    """The reference's model of ``b`` (one floor): each bearing's circle with its velocity dependence."""
    model = _restated(b)
    law = b.bearings[0].isolator
    model.fast = {first: (law.mu_fast / law.mu, law.rate_s_m) for first, _ in model.circles}
    if b.bearings[0].friction_circle == "bouc_wen":  # (Bouc-Wen's smooth circle: a bidirectional spring)
        model.bidirectional, model.circles = model.circles, []
    return model


CASES = [(1, False, "plastic", 1.8), (4, True, "plastic", 0.6), (5, False, "bouc_wen", 1.8),
         (8, True, "bouc_wen", 0.6)]


@pytest.mark.parametrize("seed, moat, circle, ratio", CASES)
def test_a_velocity_dependent_friction_circle_runs_as_the_reference(seed, moat, circle, ratio):
    rng = np.random.default_rng(seed)
    plain = _building(rng, moat=moat)
    b = _fast(plain, ratio * plain.bearings[0].isolator.mu, 25.0, circle)
    model = _restated_fast(b)
    t, ax, ay = _record(rng, 2.5, 0.01, rng.uniform(2.0, 4.0))
    model.record = (t, ax, ay)
    pair = pounding.RecordPair(pounding.Record(t, ax, name="x"), pounding.Record(t, ay, name="y"))
    run = pounding.simulate(b, pair, t[-1], sample_rate_hz=200.0, rtol=1e-12)
    assert run.success, run.message
    ref = reference(model, t[-1], np.zeros(6), track_acceleration=True)
    # (measured: switches within 1e-14 s, peak accelerations 1.7e-13 (plastic) and 4.3e-11 (Bouc-Wen) of
    # theirs; without the f' s' term in their rate 4e-8 to 6e-6)
    if circle == "plastic":  # (every stick and slip of every bearing's circle, where the reference has it)
        assert_switches_as_the_reference(run, ref)
    # (and each floor's largest absolute acceleration, located where its rate, the circle's f' s' term in
    # it, crosses zero)
    assert_one_floor_as_the_reference(run, ref, b.moat is not None)
    end = run.final_state.vector
    # the velocity dependence moved it: against the same building's Coulomb friction
    coulomb = pounding.simulate(_fast(plain, plain.bearings[0].isolator.mu, 25.0, circle), pair, t[-1])
    assert np.max(np.abs(coulomb.final_state.vector[:6] - end[:6])) > 1e-3 * np.max(np.abs(end[:6]))
    e = run.energy  # (the ledger closes to the numerical phases' tolerance)
    assert abs(e.residual) <= 1e-10 * max(abs(e.input_work), e.viscous, e.kinetic, e.hysteretic)


@pytest.mark.parametrize("circle", ["plastic", "bouc_wen"])
def test_mu_fast_equal_to_mu_is_coulomb_s_friction_number_for_number(circle):
    rng = np.random.default_rng(2)
    b = _building(rng, moat=True)
    coulomb = dataclasses.replace(b, bearings=[Bearing(x.at_m, x.isolator, friction_circle=circle)
                                               for x in b.bearings])
    same = _fast(b, b.bearings[0].isolator.mu, 25.0, circle)
    pair = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.5), 30.0)
    a, c = pounding.simulate(coulomb, pair, 4.0), pounding.simulate(same, pair, 4.0)
    assert np.max(a.bearing_displacement_max_m) > 20 * 5e-4 * 4  # (it slid)
    for name in ("displacement", "velocity", "bearing_force", "bearing_displacement_max_m"):
        np.testing.assert_array_equal(getattr(a, name), getattr(c, name))
    np.testing.assert_array_equal(a.final_state.vector, c.final_state.vector)
    assert a.energy == c.energy
    # (the engine's factor is F_fast over the circle's own force at rest, bw[0] = (mu W / preslip_m)
    # preslip_m, which is not mu W in about one draw in ten: F_fast is laid on it, so that mu_fast = mu is 1)
    for w, preslip in rng.uniform([1e3, 1e-4], [1e7, 2e-3], (300, 2)):
        iso = FrictionIsolator(mu=0.06, preslip_m=preslip, weight_n=w, mu_fast=0.06, rate_s_m=25.0)
        assert iso.kernel_friction_in_plane["friction_fast_n"] == iso.kernel_arrays_in_plane()[3][0]


def _speed_radius(fps, c_per_bearing, freq_hz, a_g):
    """The steady orbit's radius of the square floor on ``fps`` under circular shaking (about its own
    centre), and the closed form of the rigid-plastic circle whose friction is that of the orbit's speed:
    ``|(k - m w^2) r + i (c w r + W mu(w r))| = m A``, solved for r."""
    from scipy.optimize import brentq

    got = steady_orbit_radius(fps, c_per_bearing, freq_hz, a_g)
    w = 2.0 * math.pi * freq_hz
    k_m = 0.0 if fps.radius_m is None else G / fps.radius_m
    c_m, acc = 4 * c_per_bearing / 4e5, a_g * G

    def gap(r):  # (per unit mass: the force the table gives against the one the orbit needs)
        mu = fps.mu if fps.mu_fast is None else fps.mu_fast - (fps.mu_fast - fps.mu) * math.exp(
            -fps.rate_s_m * w * r)
        return math.hypot((k_m - w * w) * r, c_m * w * r + mu * G) - acc

    return got, brentq(gap, 1e-6, 10.0, xtol=1e-15, rtol=1e-15)


@pytest.mark.parametrize("radius_m, mu_fast, freq_hz, a_g", [(2.0, 0.1, 0.7, 0.3), (None, 0.03, 0.7, 0.3)])
def test_circular_shaking_drives_the_closed_form_orbit_at_its_speed_friction(radius_m, mu_fast, freq_hz, a_g):
    # a rigid floor on sliding bearings under circularly polarised shaking settles on a circle at a steady
    # speed w r, its friction W mu(w r) along the velocity: the rigid-plastic closed form at that friction.
    # The pre-slip lags the force: the radius differs to the first order of preslip / r (five times less
    # pre-slip, five times less difference)
    errors = []
    for preslip in (1e-3, 2e-4):
        fps = FrictionIsolator(mu=0.06, radius_m=radius_m, preslip_m=preslip, mu_fast=mu_fast, rate_s_m=5.0)
        got, closed = _speed_radius(fps, 3e5, freq_hz, a_g)
        coulomb, _ = _speed_radius(dataclasses.replace(fps, mu_fast=None, rate_s_m=0.0), 3e5, freq_hz, a_g)
        assert abs(np.mean(coulomb) / closed - 1.0) > 5 * preslip / closed  # (mu(w r) is not mu)
        assert np.ptp(got) < 1e-6 * closed  # (a circle)
        error = abs(float(np.mean(got)) / closed - 1.0)
        assert error < preslip / closed, (preslip, error)
        errors.append(error)
    assert 3.5 < errors[0] / errors[1] < 6.5


def test_along_one_axis_a_shrinking_pre_slip_tends_to_the_line_s_rigid_stick():
    # a symmetric floor shaken along x: each circle's z stays on the x axis and its slip's rate is the
    # bearing's velocity, so the circle is the line's velocity-dependent friction with an elastic pre-slip;
    # the line's isolator sticks rigidly and exactly.  The difference shrinks with the pre-slip
    rec = pounding.records.el_centro().scaled(pga_g=0.8)
    line = pounding.Structure(3e5, FrictionIsolator(mu=0.06, radius_m=2.2, mu_fast=0.11, rate_s_m=20.0),
                              [pounding.Storey(3e5, 3e8, 2e5)], [])
    ref = pounding.simulate(line, rec, 10.0)
    assert ref.displacement_max[0] > 0.05  # (it slid)
    errors = []
    for preslip in (4e-4, 1e-4):
        fps = FrictionIsolator(mu=0.06, radius_m=2.2, preslip_m=preslip, mu_fast=0.11, rate_s_m=20.0)
        frames = [pounding.Frame(1, axis, s * at, 1.5e8, 1e5) for axis, at in (("x", 7.0), ("y", 11.0))
                  for s in (-1.0, 1.0)]
        b = PlanBuilding([Floor(3e5, (24.0, 16.0))] * 2,
                         [Bearing((sx * 10.0, sy * 6.0), fps) for sx in (-1, 1) for sy in (-1, 1)], frames)
        run = pounding.simulate(b, rec, 10.0)
        assert np.max(np.abs(run.displacement[..., 1:])) < 1e-15 * np.max(run.displacement_max)  # (along x)
        errors.append(abs(run.displacement_max[0, 0] / ref.displacement_max[0] - 1.0))
    # (measured: 6.1 % and 2.0 %, and 1.0 % at 2.5e-5 m; Coulomb's friction the same way 2.2, 1.1 and 0.3 %:
    # the pre-slip's own lag, which the velocity dependence leaves alone)
    assert errors[0] < 0.08 and errors[1] < 0.5 * errors[0], errors


def test_a_continued_run_equals_one_long_run_and_the_ledger_closes():
    rng = np.random.default_rng(3)
    plain = _building(rng, moat=False)
    b = _fast(plain, 1.6 * plain.bearings[0].isolator.mu, 30.0, "plastic")
    t, ax, ay = _record(rng, 4.0, 0.01, 3.0)
    pair = pounding.RecordPair(pounding.Record(t, ax, name="x"), pounding.Record(t, ay, name="y"))
    whole = pounding.simulate(b, pair, 4.0, rtol=1e-11)
    first = pounding.simulate(b, pair, 2.0, rtol=1e-11)
    lay, mid = first.final_state.layout, first.final_state.vector
    assert set(mid[lay["region"]:lay["region"] + 8]) == {1.0}  # (cut in mid-slip)
    second = pounding.simulate(b, pair, 2.0, state=first.final_state, rtol=1e-11)
    end, want = second.final_state.vector, whole.final_state.vector
    np.testing.assert_allclose(end[lay["x"]:lay["x"] + 6], want[lay["x"]:lay["x"] + 6], rtol=0,
                               atol=1e-8 * np.max(np.abs(want[lay["x"]:lay["x"] + 6])))
    e = whole.energy
    assert abs(e.residual) <= 1e-10 * max(abs(e.input_work), e.hysteretic)
    assert e.hysteretic > 0.3 * e.input_work  # (the friction took most of it)


def test_a_file_keeps_it_and_the_door_takes_it_on_two_mates_alike():
    fast = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4, mu_fast=0.1, rate_s_m=25.0)
    for circle in ("plastic", "bouc_wen"):
        at = [(sx * 8.0, sy * 8.0) for sx in (-1, 1) for sy in (-1, 1)]
        b = PlanBuilding([Floor(4e5, (20.0, 20.0))], [Bearing(p, fast, friction_circle=circle) for p in at])
        text = b.to_toml_text()
        assert "mu_fast" in text and PlanBuilding.from_toml_text(text) == b
    # the door: a velocity dependence is the friction rule's or a circle's, the same in both mates
    bw = [30.0, 5e-4, 1.0, 0.5, 0.5, 2.0]

    def el(i, mate, fast_n=40.0, rate=25.0):
        return _core.element(i=i, j=-1, c_d=0.0, slopes=[1.0], breaks=[], rule=0, bw=bw, bw_mate=mate,
                             bw_plastic=mate >= 0, friction_fast_n=fast_n, friction_rate_s_m=rate)

    def system(first, second):
        return _core.system(np.ones(2), np.zeros((2, 2)), np.zeros((2, 2)), [first, second], False, [])

    system(el(0, 1), el(1, 0))
    for first, second, match in ((el(0, -1), el(1, -1, 0.0, 0.0), "friction circle's"),
                                 (el(0, 1), el(1, 0, 50.0), "velocity dependence")):
        with pytest.raises(ValueError, match=match):
            system(first, second)


def test_rigid_walls_struck_while_the_circles_slip_leave_the_friction_inside_its_law():
    # an impulse can turn a slipping circle's motion inwards (z . u' < 0) until its stick is found: its slip's
    # rate is then held at 0 (mu W), never read backwards (at -0.2 m/s mu(s) W would be -117 mu W)
    fps = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4, mu_fast=0.11, rate_s_m=25.0)
    b = PlanBuilding([Floor(4e5, (20.0, 14.0), centre_m=(1.0, -0.5))],
                     [Bearing((sx * 8.0, sy * 5.0), fps) for sx in (-1, 1) for sy in (-1, 1)],
                     moat=pounding.RectangularMoat(0.03, pounding.RigidStop(0.5)))
    pair = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.6), 30.0)
    run = pounding.simulate(b, pair, 8.0, sample_rate_hz=1000.0)
    assert run.success, run.message
    assert len(run.contacts) >= 10  # (struck again and again)
    w = np.array([x.isolator.weight_n for x in b.bearings])
    friction = run.bearing_force - (w / 2.0)[None, :, None] * run.bearing_displacement
    ratio = np.hypot(friction[..., 0], friction[..., 1]) / w
    assert np.max(ratio) <= 0.11 * (1.0 + 1e-9) and np.max(ratio) > 0.09  # (within mu_fast W, and fast)
    e = run.energy
    assert abs(e.residual) <= 1e-9 * max(abs(e.input_work), e.hysteretic)
