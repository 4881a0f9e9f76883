"""The plastic friction circle (``Bearing(..., friction_circle="plastic")``, a friction bearing's default in
plan): elastic-perfectly-plastic in the plane, its sticks and slips located as events.  Against the
independent solve_ivp reference (random eccentric buildings, pairs of components, a moat), along one axis
against the line's exact friction isolator, its force never beyond mu W, a continued run, the state's checks,
the door's and the model's refusals."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from reference_plan import PlanModel, reference
from reference_plan import record_pair as _record
from test_plan_friction import along_x_and_its_line, assert_along_x_is_the_line

import pounding
from pounding import Bearing, Floor, FrictionIsolator, InputError, PlanBuilding, RectangularMoat, _core

ACT = _core.ACTIONS
G = 9.81


def _building(rng, moat=True):
    """One eccentric floor on four friction bearings (pendulums or flat sliders, their numbers drawn)."""
    side = rng.uniform(12.0, 30.0, 2)
    floor = Floor(rng.uniform(2e5, 6e5), tuple(side), centre_m=tuple(rng.uniform(-0.1, 0.1, 2) * side))
    fps = FrictionIsolator(mu=rng.uniform(0.04, 0.1), radius_m=rng.choice([None, rng.uniform(1.5, 4.0)]),
                           preslip_m=rng.uniform(3e-4, 2e-3), damping_n_s_m=rng.uniform(0.0, 2e4))
    bearings = []
    for sx in (-1.0, 1.0):
        for sy in (-1.0, 1.0):
            at = (sx * side[0] / 2 * rng.uniform(0.7, 0.95), sy * side[1] / 2 * rng.uniform(0.7, 0.95))
            bearings.append(Bearing(at, fps))
    gap = RectangularMoat(tuple(0.04 * rng.uniform(0.8, 1.2, 4)),
                          pounding.KelvinVoigt(rng.uniform(5e7, 3e8), rng.uniform(2e4, 2e5)))
    return PlanBuilding([floor], bearings, [], gap if moat else None)


def _restated(b: PlanBuilding) -> PlanModel:
    """The one-floor building as the reference takes it, from its numbers alone: each bearing the pendulum's
    W / R and its dashpot along x and y, and one plastic circle of force mu W z, yield displacement
    preslip_m."""
    f = b.floors[0]
    cx, cy = f.centre_m

    def point(axis, px, py):  # (its displacement along axis: x - (py - cy) th, y + (px - cx) th)
        w = np.zeros(3)
        w[axis] = 1.0
        w[2] = -(py - cy) if axis == 0 else (px - cx)
        return w

    k, c = np.zeros((3, 3)), np.zeros((3, 3))
    springs, tracked, circles = [], [], []
    for bearing in b.bearings:
        law = bearing.isolator
        for axis in (0, 1):
            w = point(axis, *bearing.at_m)
            k += (law.weight_n / law.radius_m if law.radius_m else 0.0) * np.outer(w, w)
            c += law.damping_n_s_m * np.outer(w, w)
            springs.append((w, (law.mu * law.weight_n, law.preslip_m, 1.0, 0.5, 0.5, 2.0)))
            tracked.append(w)
        circles.append((len(springs) - 2, len(springs) - 1))
    walls = []
    if b.moat is not None:
        a, bb = f.size_m
        for side, (axis, sign) in enumerate(((0, -1.0), (0, 1.0), (1, -1.0), (1, 1.0))):
            for p in [(sx * a / 2, sy * bb / 2) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0)]:
                if p[axis] * sign > 0.0:
                    walls.append((point(axis, *p), sign, b.moat.gap_m[side], b.moat.law.stiffness,
                                  b.moat.law.damping))
    influence = np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]])
    return PlanModel(mass=np.array([f.mass_kg, f.mass_kg, f.inertia_kg_m2]), k=k, c=c, influence=influence,
                     record=(np.zeros(1),) * 3, walls=walls, bouc_wen=springs, circles=circles,
                     tracked=tracked, vectors=[(2 * q, 2 * q + 1) for q in range(len(b.bearings))])


def assert_switches_as_the_reference(run, ref):
    """Every stick and slip of every bearing's plastic circle where the reference has it, to 1e-11 s, and
    at least 4 of each (it slid and stuck again)."""
    for action, want in (("circle_slip", ref.circle_slips), ("circle_stick", ref.circle_sticks)):
        got = _switches(run, action)
        assert [q for q, _ in got] == [q for q, _ in sorted(want)], action
        np.testing.assert_allclose([t for _, t in got], [t for _, t in sorted(want)], rtol=0, atol=1e-11)
    assert len(ref.circle_slips) >= 4 and len(ref.circle_sticks) >= 4


def assert_one_floor_as_the_reference(run, ref, moat):
    """A one-floor plan run against the reference's: the moat's contacts' starts to 1e-11 s (at least 4:
    the moats' seeds are drawn so), the final state to 1e-10 of its largest, the Bouc-Wen z to 1e-10, each
    bearing's longest displacement to 1e-10 of the largest and each largest absolute acceleration to
    1e-9."""
    if moat:
        starts = run.event_table[run.event_table[:, 1] == ACT["contact_start"]]
        assert len(starts) >= 4
        np.testing.assert_allclose(starts[:, 0], [t for _, t in ref.contact_starts], rtol=0, atol=1e-11)
    lay, end = run.final_state.layout, run.final_state.vector
    np.testing.assert_allclose(end[lay["x"]:lay["x"] + 3], ref.y[:3], rtol=0,
                               atol=1e-10 * np.max(np.abs(ref.y[:3])))
    np.testing.assert_allclose(end[lay["v"]:lay["v"] + 3], ref.y[3:], rtol=0,
                               atol=1e-10 * np.max(np.abs(ref.y[3:])))
    np.testing.assert_allclose(run.final_state.bouc_wen_zs, ref.z, rtol=0, atol=1e-10)
    top = max(np.max(np.abs(ref.tracked_max)), np.max(np.abs(ref.tracked_min)))
    np.testing.assert_allclose(run.bearing_displacement_max_m, ref.vector_max, rtol=0, atol=1e-10 * top)
    np.testing.assert_allclose(run.abs_acceleration_max[0], ref.abs_acc_max, rtol=1e-9)


def _switches(run, action):
    """A run's circle events of ``action`` as (bearing, t): its x element's index is twice the bearing's."""
    e = run.event_table
    rows = e[e[:, 1] == ACT[action]]
    return sorted((int(i) // 2, float(t)) for t, _, i in rows)


@pytest.mark.parametrize("seed, moat", [(1, False), (4, True), (5, False), (8, True)])
def test_a_building_on_plastic_friction_circles_runs_as_the_reference(seed, moat):
    rng = np.random.default_rng(seed)
    b = _building(rng, moat=moat)
    model = _restated(b)
    t, ax, ay = _record(rng, 2.5, 0.01, rng.uniform(2.0, 4.0))
    model.record = (t, ax, ay)
    pair = pounding.RecordPair(pounding.Record(t, ax, name="x"), pounding.Record(t, ay, name="y"))
    run = pounding.simulate(b, pair, t[-1], sample_rate_hz=200.0, rtol=1e-12)
    assert run.success, run.message
    ref = reference(model, t[-1], np.zeros(6), track_acceleration=True)
    # every stick and slip of every bearing's circle, where the reference has it (measured: switches within
    # 1.1e-14 s, the final state 1.1e-13 of its largest, z 4e-13, the ledger 3e-13 of the flows; the bounds
    # below leave a thousandfold margin for other machines' rounding)
    assert_switches_as_the_reference(run, ref)
    assert_one_floor_as_the_reference(run, ref, b.moat is not None)
    e = run.energy  # (the ledger closes to the numerical phases' tolerance)
    assert abs(e.residual) <= 1e-10 * max(abs(e.input_work), e.viscous, e.kinetic, e.hysteretic)


def test_along_one_axis_the_plastic_circle_is_the_line_s_friction_isolator():
    # a symmetric building shaken along x: every z stays on the x axis, and the circle is the line's
    # elastic-perfectly-plastic friction (its pre-slip a kinematic bilinear spring: exact phases)
    b, line, rec = along_x_and_its_line(True)
    assert all(x.plastic_circle for x in b.bearings)
    run, ref = pounding.simulate(b, rec, 10.0), pounding.simulate(line, rec, 10.0)
    assert ref.displacement_max[0] > 0.05  # (it slid)
    assert_along_x_is_the_line(run, ref)
    # its slips start where the line's spring yields and end where it reverses (each bearing's circle at
    # once: one event per bearing)
    for mine, theirs in (("circle_slip", "yield"), ("circle_stick", "reversal")):
        want = ref.event_table[ref.event_table[:, 1] == ACT[theirs], 0]
        got = [t for q, t in _switches(run, mine) if q == 0]
        assert len(want) >= 5
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)


def test_a_plastic_circle_s_friction_never_exceeds_mu_w_and_sticks_inside_it():
    # each bearing's force less the pendulum's W / R u: the friction, inside mu W to the rounding, on it
    # while it slips; between a stick and the next slip its bearing moves elastically (within 2 preslip_m)
    fps = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4)
    b = PlanBuilding([Floor(4e5, (20.0, 20.0), centre_m=(1.5, -1.0))],
                     [Bearing((sx * 8.0, sy * 8.0), fps) for sx in (-1, 1) for sy in (-1, 1)])
    rec = pounding.records.el_centro().scaled(pga_g=0.6)
    run = pounding.simulate(b, pounding.RecordPair.of_direction(rec, 25.0), 6.0, sample_rate_hz=500.0)
    w = np.array([x.isolator.weight_n for x in b.bearings])
    friction = run.bearing_force - (w / 2.0)[None, :, None] * run.bearing_displacement
    length = np.hypot(friction[..., 0], friction[..., 1]) / (0.06 * w)
    assert np.max(length) <= 1.0 + 1e-9
    assert np.max(length) >= 1.0 - 1e-9  # (it slid: on the circle)
    assert np.max(run.bearing_displacement_max_m) > 50 * 5e-4
    slips, sticks = _switches(run, "circle_slip"), _switches(run, "circle_stick")
    assert len(sticks) >= 8 and abs(len(slips) - len(sticks)) <= 4
    t = run.t
    for q in range(4):
        for (_, t0), (_, t1) in zip([s for s in sticks if s[0] == q], [s for s in slips if s[0] == q][1:]):
            inside = (t > t0) & (t < t1)
            if inside.sum() > 2:
                u = run.bearing_displacement[inside, q]
                assert np.max(np.hypot(*(u - u[0]).T)) <= 2.0 * 5e-4 * (1.0 + 1e-6)
                assert np.all(length[inside, q] <= 1.0 + 1e-9)


def test_a_continued_run_of_a_plastic_circle_equals_one_long_run():
    rng = np.random.default_rng(3)
    b = _building(rng, moat=False)
    t, ax, ay = _record(rng, 4.0, 0.01, 3.0)
    pair = pounding.RecordPair(pounding.Record(t, ax, name="x"), pounding.Record(t, ay, name="y"))
    whole = pounding.simulate(b, pair, 4.0, rtol=1e-11)
    first = pounding.simulate(b, pair, 2.0, rtol=1e-11)
    lay, mid = first.final_state.layout, first.final_state.vector
    assert set(mid[lay["region"]:lay["region"] + 8]) == {1.0}  # (cut in mid-slip: every circle carried on)
    second = pounding.simulate(b, pair, 2.0, state=first.final_state, rtol=1e-11)
    end, want = second.final_state.vector, whole.final_state.vector
    np.testing.assert_allclose(end[lay["x"]:lay["x"] + 6], want[lay["x"]:lay["x"] + 6], rtol=0,
                               atol=1e-8 * np.max(np.abs(want[lay["x"]:lay["x"] + 6])))
    np.testing.assert_array_equal(end[lay["region"]:lay["region"] + 8], want[lay["region"]:lay["region"] + 8])


def test_a_state_off_its_circle_while_slipping_is_refused_by_name():
    rng = np.random.default_rng(3)
    b = _building(rng, moat=False)
    run = pounding.simulate(b, pounding.RecordPair.of_direction(pounding.records.el_centro(), 20.0), 1.0)
    state = run.final_state
    lay = state.layout
    x, v = state.vector[lay["x"]:lay["x"] + 3], state.vector[lay["v"]:lay["v"] + 3]
    asm = pounding.engine.plan_assembly.assemble_plan(b)
    rates = np.array([w @ v for w in asm.element_weights[:2]])  # (bearing 0's along x and y)
    assert np.hypot(*rates) > 0.0 and np.all(np.isfinite(x))
    inwards = -rates / np.hypot(*rates)  # (z against its velocity: z . u' < 0)
    for flags, z, match in (((2.0, 2.0), None, "slip on its friction circle"),
                            ((1.0, 0.0), None, "one circle, one flag"),
                            ((1.0, 1.0), (0.3, 0.4), "inside the circle"),
                            ((1.0, 1.0), inwards, "against its bearing's velocity")):
        vec = state.vector.copy()
        vec[lay["region"]:lay["region"] + 2] = flags
        if z is not None:
            vec[lay["zeta"]:lay["zeta"] + 2] = z
        bad = dataclasses.replace(state, vector=vec)
        with pytest.raises(InputError, match=match) as err:
            pounding.simulate(b, pounding.Harmonic(0.1, 1.0), 0.1, state=bad)
        assert err.value.field in ("state.isolator_branch", f"state.vector[{lay['region']}]")
    # a slip at a run's end can turn inwards by rounding (z . u' = -6e-17 m/s was refused, a final_state of a
    # rigid moat's run): within 1e-9 of the velocities (|u'|, or the levers times the largest) and 1e-12 m/s
    # it is taken, beyond it refused
    across = np.array([-inwards[1], inwards[0]])
    for tilt, taken in ((1e-13, True), (1e-6, False)):
        vec = state.vector.copy()
        vec[lay["region"]:lay["region"] + 2] = 1.0
        vec[lay["zeta"]:lay["zeta"] + 2] = np.cos(tilt) * across + np.sin(tilt) * inwards
        tilted = dataclasses.replace(state, vector=vec)
        if taken:
            assert pounding.simulate(b, pounding.Harmonic(0.1, 1.0), 0.1, state=tilted).success
        else:
            with pytest.raises(InputError, match="against its bearing's velocity"):
                pounding.simulate(b, pounding.Harmonic(0.1, 1.0), 0.1, state=tilted)



def test_a_floor_held_still_by_walls_while_its_circles_slip_goes_on_as_one_long_run():
    # plastic walls stop a floor in a corner while its circles slip: its velocities are the rounding of the
    # impulses that stopped it (1e-17 m/s), and so is a circle's slip rate, either way; such final states were
    # refused as starts (z . u' = -1.1e-17 m/s at 6.1 s)
    fps = FrictionIsolator(mu=0.05, radius_m=2.5, preslip_m=1e-3)
    b = PlanBuilding([Floor(4e5, (20.0, 20.0), centre_m=(1.0, 0.5))],
                     [Bearing((sx * 8.0, sy * 8.0), fps) for sx in (-1, 1) for sy in (-1, 1)],
                     moat=RectangularMoat(0.01, pounding.RigidStop(0.0)))
    pair = pounding.records.fema_p695_pairs("far_field")[0].scaled(1.5)
    whole = pounding.simulate(b, pair, 12.0, sample_rate_hz=0.0)
    lay = whole.final_state.layout
    held_at = 0
    for t in np.linspace(0.3, 11.7, 60)[[30, 42, 46]]:  # (measured: three such ends among the 60)
        first = pounding.simulate(b, pair, float(t), sample_rate_hz=0.0)
        vec = first.final_state.vector
        still = np.max(np.abs(vec[lay["v"]:lay["v"] + 3])) < 1e-15 and np.any(vec[lay["in"]:lay["in"] + 8])
        held_at += bool(still and np.any(vec[lay["region"]:lay["region"] + 8] == 1.0))
        rest = pounding.simulate(b, pair, 12.0 - float(t), state=first.final_state, sample_rate_hz=0.0)
        # (measured: within 3.7e-15 m and m/s)
        np.testing.assert_allclose(rest.final_state.vector[lay["x"]:lay["x"] + 6],
                                   whole.final_state.vector[lay["x"]:lay["x"] + 6], rtol=0, atol=1e-12)
    assert held_at == 3

def test_the_model_and_the_door_refuse_what_is_no_plastic_circle(tmp_path):
    fps = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4)
    with pytest.raises(InputError) as err:
        Bearing((0.0, 0.0), fps, friction_circle="exact")
    assert err.value.field == "bearing.friction_circle" and "plastic" in str(err.value)
    smooth = Bearing((0.0, 0.0), fps, friction_circle="bouc_wen")
    for other in (dict(isolator=pounding.Isolator([1e7])), dict(bidirectional=False)):  # (no circle here)
        with pytest.raises(InputError) as err:
            Bearing((0.0, 0.0), **({"isolator": fps} | other), friction_circle="bouc_wen")
        assert err.value.field == "bearing.friction_circle"
    assert not smooth.plastic_circle and Bearing((0.0, 0.0), fps).plastic_circle
    assert not Bearing((0.0, 0.0), fps, bidirectional=False).plastic_circle
    # a file keeps a Bouc-Wen circle; the default is left out
    b = PlanBuilding([Floor(4e5, (20.0, 20.0))], [smooth, Bearing((5.0, 0.0), fps), Bearing((0.0, 5.0), fps)])
    text = b.to_toml_text()
    assert text.count("friction_circle") == 1
    assert PlanBuilding.from_toml_text(text) == b
    with pytest.raises(InputError) as err:
        PlanBuilding.from_toml_text(text.replace('"bouc_wen"', '"smooth"'))
    assert err.value.field == "bearings[0].friction_circle"
    # the door: a plastic circle is two mates' (a = 1, beta + gamma = 1, the kinematic rule)
    bw = [30.0, 5e-4, 1.0, 0.5, 0.5, 2.0]

    def system(first, second):
        return _core.system(np.ones(2), np.zeros((2, 2)), np.zeros((2, 2)), [first, second], False, [])

    def el(i, mate, plastic, numbers=bw, rule=0):
        return _core.element(i=i, j=-1, c_d=0.0, slopes=[1.0], breaks=[], rule=rule, bw=numbers, bw_mate=mate,
                             bw_plastic=plastic)

    system(el(0, 1, True), el(1, 0, True))
    other = [30.0, 5e-4, 1.0, 0.5, 0.4, 2.0]  # (beta + gamma 0.9)
    soft = [30.0, 5e-4, 0.9, 0.5, 0.5, 2.0]  # (a 0.9)
    for first, second, match in (
            (el(0, -1, True), el(1, -1, False), "give its mate"),
            (el(0, 1, True), el(1, 0, False), "both mates'"),
            (el(0, 1, True, soft), el(1, 0, True, soft), "a = 1"),
            (el(0, 1, True, other), el(1, 0, True, other), "beta \\+ gamma = 1"),
            (el(0, 1, True, rule=1), el(1, 0, True, rule=1), "kinematic"),
            (el(0, 1, True, []), el(1, 0, True, []), "give its numbers")):
        with pytest.raises(ValueError, match=match):
            system(first, second)


def test_a_plastic_circle_that_never_slips_is_its_elastic_spring_on_exact_phases():
    # shaken below mu W (circularly, slowly), every bearing sticks: the circle is then a linear spring of
    # mu W / preslip_m beside the pendulum's W / R, and its phases are exact, as a linear bearing's: equal to
    # the rounding (8.6e-16 m measured, the tolerance 1e-11 of the largest displacement, where numerical
    # sticks at rtol 1e-10 were 2.5e-12 m off)
    fps = FrictionIsolator(mu=0.08, radius_m=2.0, preslip_m=5e-4, damping_n_s_m=2e4)
    floor = Floor(4e5, (20.0, 14.0), centre_m=(1.0, -0.5))
    at = [(sx * 8.0, sy * 5.0) for sx in (-1, 1) for sy in (-1, 1)]
    sliding = PlanBuilding([floor], [Bearing(p, fps) for p in at])
    linear = PlanBuilding([floor], [Bearing(p, pounding.Isolator(
        [x.isolator.friction_force_n / 5e-4 + x.isolator.weight_n / 2.0], damping_n_s_m=2e4))
        for p, x in zip(at, sliding.bearings)])
    pair = pounding.HarmonicPair.circular(0.035, 0.5)  # (m a_g: 0.035 W, twice that at its start)
    a, b = pounding.simulate(sliding, pair, 10.0), pounding.simulate(linear, pair, 10.0)
    assert len(_switches(a, "circle_slip")) == 0  # (it never slipped)
    weights = np.array([x.isolator.weight_n for x in sliding.bearings])
    friction = a.bearing_force - (weights / 2.0)[None, :, None] * a.bearing_displacement
    assert np.max(np.hypot(friction[..., 0], friction[..., 1])) > 0.5 * 0.08 * weights[0]  # (near its circle)
    top = np.max(np.abs(b.displacement))
    np.testing.assert_allclose(a.displacement, b.displacement, rtol=0, atol=1e-11 * top)
    np.testing.assert_allclose(a.bearing_force, b.bearing_force, rtol=0,
                               atol=1e-11 * np.max(np.abs(b.bearing_force)))
    assert a.energy.input_work == pytest.approx(b.energy.input_work, rel=1e-11)
