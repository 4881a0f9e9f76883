"""A building in plan (pounding.model.plan): its checks, its matrices and modes against closed forms, its
TOML, and its assembly into the core against the independent solve_ivp reference in plan
(tests/reference_plan.py), restated here from the building's numbers with no code of the package's."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings
from hypothesis import strategies as st

import pounding
from pounding import InputError, _control, _core
from pounding.engine.plan_assembly import assemble_plan
from pounding.model.plan import PlanBuilding
from pounding.model.plan_parts import Bearing, Floor, Frame, RectangularMoat
from reference_ndof import TouchAtRest
from reference_plan import PlanModel, reference

ACT = _core.ACTIONS
PX = _core.PAIR_EXTREMA
NX = _core.NORM_EXTREMA


def _iso(k1, k2=None, dy=0.0, c=0.0):
    if k2 is None:
        return pounding.Isolator(slopes_n_m=[k1], breakpoints_m=[], damping_n_s_m=c)
    return pounding.Isolator(slopes_n_m=[k1, k2], breakpoints_m=[dy], damping_n_s_m=c)


def _square(k=1.0e6, a=10.0, b=6.0, mass=2.0e5, ecc=(0.0, 0.0)):
    """One floor on four equal linear bearings at (+-a, +-b)."""
    bearings = [Bearing((sx * a, sy * b), _iso(k)) for sx in (-1, 1) for sy in (-1, 1)]
    return PlanBuilding([Floor(mass, (2.5 * a, 2.5 * b))], bearings, accidental_eccentricity=ecc)


# ---------------------------------------------------------------------------------------- closed forms
def test_a_symmetric_floor_s_periods_are_the_closed_form():
    k, a, b, m = 1.0e6, 10.0, 6.0, 2.0e5
    building = _square(k, a, b, m)
    j = m * ((2.5 * a) ** 2 + (2.5 * b) ** 2) / 12.0
    assert building.floors[0].inertia_kg_m2 == pytest.approx(j, rel=1e-15)
    w2 = [4 * k / m, 4 * k / m, 4 * k * (a * a + b * b) / j]
    expected = sorted((2 * math.pi / math.sqrt(v) for v in w2), reverse=True)
    np.testing.assert_allclose(building.modes().periods_s, expected, rtol=1e-12)
    np.testing.assert_allclose(building.centres_of_stiffness_m(), [[0.0, 0.0]], atol=1e-12)


@pytest.mark.parametrize("e", [0.05, -0.05, 0.1])
def test_an_eccentric_mass_couples_translation_and_rotation_as_the_closed_form(e):
    # the centre of mass moved by e of the side along x: y and rotation coupled, x alone
    k, a, b, m = 1.0e6, 10.0, 6.0, 2.0e5
    building = _square(k, a, b, m, ecc=(e, 0.0))
    ex = e * 2.5 * a
    j = m * ((2.5 * a) ** 2 + (2.5 * b) ** 2) / 12.0
    kyy, kyt, ktt = 4 * k, -4 * k * ex, 4 * k * (a * a + ex * ex + b * b)
    # det([[kyy - m w2, kyt], [kyt, ktt - j w2]]) = 0
    qa, qb, qc = m * j, -(kyy * j + ktt * m), kyy * ktt - kyt * kyt
    roots = [(-qb + s * math.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa) for s in (1, -1)]
    expected = sorted([2 * math.pi / math.sqrt(w2) for w2 in [4 * k / m, *roots]], reverse=True)
    np.testing.assert_allclose(building.modes().periods_s, expected, rtol=1e-12)
    np.testing.assert_allclose(building.eccentricities_m(), [[-ex, 0.0]], atol=1e-12)
    assert building.placed_floors[0].centre_m == pytest.approx((ex, 0.0))
    # the x mode moves x alone
    shapes = building.modes().shapes
    x_mode = np.argmin(np.abs(building.modes().periods_s - 2 * math.pi / math.sqrt(4 * k / m)))
    np.testing.assert_allclose(shapes[:, x_mode], [1.0, 0.0, 0.0], atol=1e-12)


def test_a_storey_s_centre_of_stiffness_is_its_lines_weighted_mean():
    floors = [Floor(3e5, (20.0, 10.0))] * 2
    bearings = [Bearing((sx * 8.0, sy * 4.0), _iso(2e6)) for sx in (-1, 1) for sy in (-1, 1)]
    frames = [Frame(1, "x", -5.0, 1e8), Frame(1, "x", 5.0, 3e8), Frame(1, "y", -10.0, 2e8),
              Frame(1, "y", 4.0, 2e8)]
    b = PlanBuilding(floors, bearings, frames)
    np.testing.assert_allclose(b.centres_of_stiffness_m(), [[0.0, 0.0], [-3.0, 2.5]], atol=1e-12)
    assert len(b.accidental_cases()) == 4
    assert {c.accidental_eccentricity for c in b.accidental_cases()} == {
        (sx * 0.05, sy * 0.05) for sx in (1.0, -1.0) for sy in (1.0, -1.0)}


# ---------------------------------------------------------------------------------------- checks
def _building(**changes):
    values = dict(floors=[Floor(3e5, (20.0, 10.0))] * 2,
                  bearings=[Bearing((sx * 8.0, sy * 4.0), _iso(2e6)) for sx in (-1, 1) for sy in (-1, 1)],
                  frames=([Frame(1, "x", y, 1e8) for y in (-5.0, 5.0)]
                          + [Frame(1, "y", x, 1e8) for x in (-9.0, 9.0)]),
                  moat=RectangularMoat(0.3, pounding.KelvinVoigt(1e9, 1e6)))
    values.update(changes)
    return PlanBuilding(**values)


@pytest.mark.parametrize("make, field", [
    (lambda: Floor(-1.0, (10.0, 10.0)), "floor.mass_kg"),
    (lambda: Floor(1e5, (10.0,)), "floor.size_m"),
    (lambda: Floor(1e5, (10.0, 0.0)), "floor.size_m[1]"),
    (lambda: Floor(1e5, (10.0, 10.0), centre_m=(6.0, 0.0)), "floor.centre_m[0]"),
    (lambda: Floor(1e5, (10.0, 10.0), inertia_kg_m2=float("nan")), "floor.inertia_kg_m2"),
    (lambda: Frame(0, "x", 0.0, 1e8), "frame.storey"),
    (lambda: Frame(1, "z", 0.0, 1e8), "frame.axis"),
    (lambda: Frame(1, "x", float("inf"), 1e8), "frame.at_m"),
    (lambda: Frame(1, "x", 0.0, 1e8, breakpoints_m=[0.01]), "frame.breakpoints_m"),
    (lambda: Bearing((0.0, 0.0, 1.0), _iso(1e6)), "bearing.at_m"),
    (lambda: Bearing((0.0, 0.0), pounding.FrictionIsolator(mu=0.05, radius_m=2.0)),
     "bearing.isolator"),
    (lambda: RectangularMoat((0.1, 0.2), pounding.KelvinVoigt(1e9, 1e6)), "moat.gap_m"),
    (lambda: RectangularMoat(-0.1, pounding.KelvinVoigt(1e9, 1e6)), "moat.gap_m[0]"),
    (lambda: RectangularMoat(0.1, pounding.RigidStop(0.5)), "moat.law"),
    (lambda: RectangularMoat(0.1, "steel"), "moat.law"),
    (lambda: _building(floors=[]), "floors"),
    (lambda: _building(bearings=[]), "bearings"),
    (lambda: _building(frames=[Frame(2, "x", 0.0, 1e8)]), "frames[0].storey"),
    (lambda: _building(frames=[Frame(1, "x", y, 1e8) for y in (-5.0, 5.0)]), "frames"),
    (lambda: _building(frames=[Frame(1, "x", 0.0, 1e8), Frame(1, "y", 0.0, 1e8)]), "frames"),
    (lambda: _building(bearings=[Bearing((0.0, 0.0), _iso(1e6))]), "bearings"),
    (lambda: _building(moat=RectangularMoat(0.1, pounding.KelvinVoigt(1e9, 1e6), level=2)), "moat.level"),
    (lambda: _building(accidental_eccentricity=(0.5, 0.0)), "accidental_eccentricity[0]"),
    (lambda: _building(accidental_eccentricity=(0.05,)), "accidental_eccentricity"),
    (lambda: _building(floors="floor"), "floors"),
])
def test_bad_parts_are_refused_by_name(make, field):
    with pytest.raises(InputError) as info:
        make()
    assert info.value.field == field, str(info.value)
    assert "Fix:" in str(info.value) or "fix" in str(info.value).lower()


def test_an_implausible_inertia_warns():
    with pytest.warns(UserWarning, match="floor.inertia_kg_m2"):
        Floor(1e5, (10.0, 10.0), inertia_kg_m2=1e3)


def test_a_building_in_plan_reads_back_from_toml(tmp_path):
    b = _building(frames=[Frame(1, "x", -5.0, 1e8, 2e4, slopes_after_n_m=[1e7], breakpoints_m=[0.01]),
                          Frame(1, "x", 5.0, 1e8), Frame(1, "y", -9.0, 1e8), Frame(1, "y", 9.0, 1e8)],
                  accidental_eccentricity=(0.05, -0.05))
    path = tmp_path / "plan.toml"
    b.to_toml(path)
    assert PlanBuilding.from_toml(path) == b
    text = b.to_toml_text().replace("stiffness_n_m = 100000000.0", "stiffnes_n_m = 100000000.0", 1)
    with pytest.raises(InputError, match=r"frames\[0\]\.stiffnes_n_m"):
        PlanBuilding.from_toml_text(text)


# ---------------------------------------------------------------------------------------- the reference
def _record(rng, duration_s, dt, pga):
    t = np.arange(0.0, duration_s + dt / 2, dt)
    comps = []
    for _ in range(2):
        a = np.convolve(rng.normal(0.0, 1.0, t.size), np.ones(7) / 7, "same")
        comps.append(pga * a / np.max(np.abs(a)))
    return t, comps[0], comps[1]


def _draw_building(rng, levels, gap_m):
    side = rng.uniform(12.0, 30.0, 2)
    floors = [Floor(rng.uniform(2e5, 6e5), tuple(side), centre_m=tuple(rng.uniform(-0.1, 0.1, 2) * side))
              for _ in range(levels)]
    bearings = []
    for sx in (-1.0, 1.0):
        for sy in (-1.0, 1.0):
            k1, dy = rng.uniform(5e6, 2e7), rng.uniform(0.005, 0.02)
            iso = _iso(k1, k1 * rng.uniform(0.05, 0.3), dy, rng.uniform(0.0, 2e4))
            at = (sx * side[0] / 2 * rng.uniform(0.7, 0.95), sy * side[1] / 2 * rng.uniform(0.7, 0.95))
            bearings.append(Bearing(at, iso))
    frames = []
    for s in range(1, levels):
        for axis, across in (("x", side[1]), ("y", side[0])):
            for _ in range(2):
                frames.append(Frame(s, axis, rng.uniform(-0.5, 0.5) * across, rng.uniform(5e7, 2e8),
                                    rng.uniform(0.0, 1e5)))
            k1 = rng.uniform(2e7, 5e7)
            frames.append(Frame(s, axis, rng.uniform(-0.5, 0.5) * across, k1, 0.0,
                                slopes_after_n_m=[k1 * rng.uniform(0.05, 0.5)],
                                breakpoints_m=[rng.uniform(0.002, 0.01)]))
    moat = RectangularMoat(tuple(gap_m * rng.uniform(0.8, 1.2, 4)),
                           pounding.KelvinVoigt(rng.uniform(5e7, 3e8), rng.uniform(2e4, 2e5)))
    return PlanBuilding(floors, bearings, frames, moat, tuple(rng.uniform(-0.05, 0.05, 2)))


def _restated(b: PlanBuilding) -> PlanModel:
    """The building as the reference takes it, from its numbers alone."""
    n = 3 * len(b.floors)
    centres = [(f.centre_m[0] + b.accidental_eccentricity[0] * f.size_m[0],
                f.centre_m[1] + b.accidental_eccentricity[1] * f.size_m[1]) for f in b.floors]

    def point(level, axis, px, py):  # (its displacement along axis: x - (py - cy) th, y + (px - cx) th)
        w = np.zeros(n)
        if level >= 0:
            cx, cy = centres[level]
            w[3 * level + axis] = 1.0
            w[3 * level + 2] = -(py - cy) if axis == 0 else (px - cx)
        return w

    mass = np.array([v for f in b.floors for v in (f.mass_kg, f.mass_kg, f.inertia_kg_m2)])
    k, c = np.zeros((n, n)), np.zeros((n, n))
    plastic, tracked = [], []
    for bearing in b.bearings:  # (the core's elements: each bearing's x then y, then the yielding frames)
        px, py = bearing.at_m
        iso = bearing.isolator
        for axis in (0, 1):
            w = point(0, axis, px, py)
            k1, k2 = iso.slopes_n_m
            k += k2 * np.outer(w, w)
            c += iso.damping_n_s_m * np.outer(w, w)
            plastic.append((w, k1 - k2, iso.breakpoints_m[0]))
    for f in b.frames:
        axis = "xy".index(f.axis)
        px, py = (0.0, f.at_m) if axis == 0 else (f.at_m, 0.0)
        w = point(f.storey, axis, px, py) - point(f.storey - 1, axis, px, py)
        c += f.damping_n_s_m * np.outer(w, w)
        if f.breakpoints_m:
            k2 = f.slopes_after_n_m[0]
            k += k2 * np.outer(w, w)
            plastic.append((w, f.stiffness_n_m - k2, f.breakpoints_m[0]))
        else:
            k += f.stiffness_n_m * np.outer(w, w)
    for bearing in b.bearings:  # (the tracked points: each bearing's x and y, then each frame's drift)
        tracked += [point(0, axis, *bearing.at_m) for axis in (0, 1)]
    for f in b.frames:
        axis = "xy".index(f.axis)
        px, py = (0.0, f.at_m) if axis == 0 else (f.at_m, 0.0)
        tracked.append(point(f.storey, axis, px, py) - point(f.storey - 1, axis, px, py))
    a, bb = b.floors[0].size_m
    corners = [(sx * a / 2, sy * bb / 2) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0)]
    tracked += [point(0, axis, *p) for p in corners for axis in (0, 1)]
    walls = []
    law = b.moat.law
    for side, (axis, sign) in enumerate(((0, -1.0), (0, 1.0), (1, -1.0), (1, 1.0))):
        for p in corners:
            if p[axis] * sign > 0.0:
                walls.append((point(0, axis, *p), sign, b.moat.gap_m[side], law.stiffness, law.damping))
    influence = np.zeros((n, 2))
    influence[0::3, 0] = 1.0
    influence[1::3, 1] = 1.0
    vectors = [(2 * i, 2 * i + 1) for i in range(len(b.bearings))]
    return PlanModel(mass=mass, k=k, c=c, influence=influence, record=(np.zeros(1),) * 3, plastic=plastic,
                     walls=walls, tracked=tracked, vectors=vectors)


def _same_events(out, action, rows):
    got = out.events[out.events[:, 1] == ACT[action]]
    assert [int(c) for c in got[:, 2]] == [int(c) for c, _ in rows], action
    np.testing.assert_allclose(got[:, 0], [t for _, t in rows], rtol=0, atol=1e-9, err_msg=action)


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), levels=st.integers(1, 2), gap_m=st.floats(0.02, 0.1),
       pga=st.floats(2.0, 5.0))
def test_a_building_in_plan_assembles_into_the_reference_s_motion(seed, levels, gap_m, pga):
    rng = np.random.default_rng(seed)
    b = _draw_building(rng, levels, gap_m)
    asm = assemble_plan(b)
    model = _restated(b)
    t, ax, ay = _record(rng, 2.0, 0.01, pga)
    model.record = (t, ax, ay)
    forcing = _core.Forcing(kind=_core.EXCITATION["record"], p=np.array([t[1] - t[0], 0.0, 0.0]), rec_t=t,
                            rec_a=ax, rec_b=ay)
    sy = asm.system
    out = _core.run(sy, forcing, np.zeros(sy.state_size), t[-1], 0.0, 1e-10, 10**6, True,
                    _control.new_control(2 * 10**6))
    assert out.status == 0, out.status
    try:
        ref = reference(model, t[-1], np.zeros(2 * sy.n))
    except TouchAtRest:
        assume(False)
    event(f"{'walls struck' if ref.contact_starts else 'no wall struck'}, {levels} floor(s)")
    for action, rows in (("contact_start", ref.contact_starts), ("contact_end", ref.contact_ends),
                         ("yield", ref.yields), ("reversal", ref.sticks)):
        _same_events(out, action, rows)
    scale = np.max(np.abs(ref.y))
    np.testing.assert_allclose(out.state[1:1 + 2 * sy.n], ref.y, rtol=0, atol=1e-8 * scale)
    per_pair = out.per_pair(sy.n)
    scale = max(np.max(np.abs(ref.tracked_max)), np.max(np.abs(ref.tracked_min)))
    np.testing.assert_allclose(per_pair[:, PX["max"]], ref.tracked_max, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(per_pair[:, PX["min"]], ref.tracked_min, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(out.norms[:, NX["max"]], ref.vector_max, rtol=0, atol=1e-9 * scale)
    # where each part went
    assert asm.elements[:2] == (("bearing", 0, 0), ("bearing", 0, 1))
    assert [asm.tracked[q] for q in asm.vectors[3]] == [("bearing", 3, 0), ("bearing", 3, 1)]
    assert len(asm.contacts) == 8 and all(asm.tracked[q][0] == "corner" for q in asm.contact_tracks)
