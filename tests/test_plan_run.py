"""A building in plan's runs (``pounding.simulate`` of a PlanBuilding): against the independent solve_ivp
reference in plan (tests/reference_plan.py), the building restated from its numbers with no code of the
package's; a symmetric building against the line structure it is along x; mirror symmetry; a continued run
against one long run; the checks of its arguments; its tables and plot."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings
from hypothesis import strategies as st

import pounding
from pounding import InputError, _core
from pounding.model.plan import PlanBuilding
from pounding.model.moats import CircularMoat, RectangularMoat
from pounding.model.plan_parts import Bearing, Floor, Frame
from reference_ndof import TouchAtRest
from reference_plan import PlanModel, reference
from reference_plan import record_pair as _record

ACT = _core.ACTIONS


def _iso(k1, k2=None, dy=0.0, c=0.0):
    if k2 is None:
        return pounding.Isolator(slopes_n_m=[k1], breakpoints_m=[], damping_n_s_m=c)
    return pounding.Isolator(slopes_n_m=[k1, k2], breakpoints_m=[dy], damping_n_s_m=c)


def _draw_building(rng, levels, gap_m, moat_level=None):
    side = rng.uniform(12.0, 30.0, 2)
    floors = [Floor(rng.uniform(2e5, 6e5), tuple(side), centre_m=tuple(rng.uniform(-0.1, 0.1, 2) * side))
              for _ in range(levels)]
    bearings = []
    for sx in (-1.0, 1.0):
        for sy in (-1.0, 1.0):
            laws = []
            for _ in range(2):  # (along x, and another along y for some)
                k1, dy = rng.uniform(5e6, 2e7), rng.uniform(0.005, 0.02)
                laws.append(_iso(k1, k1 * rng.uniform(0.05, 0.3), dy, rng.uniform(0.0, 2e4)))
            at = (sx * side[0] / 2 * rng.uniform(0.7, 0.95), sy * side[1] / 2 * rng.uniform(0.7, 0.95))
            bearings.append(Bearing(at, laws[0], laws[1] if rng.random() < 0.5 else None))
    frames = []
    for s in range(1, levels):
        for axis, across in (("x", side[1]), ("y", side[0])):
            for _ in range(2):
                frames.append(Frame(s, axis, rng.uniform(-0.5, 0.5) * across, rng.uniform(5e7, 2e8),
                                    rng.uniform(0.0, 1e5)))
            k1 = rng.uniform(2e7, 5e7)
            frames.append(Frame(s, axis, rng.uniform(-0.5, 0.5) * across, k1, rng.uniform(0.0, 1e5),
                                slopes_after_n_m=[k1 * rng.uniform(0.05, 0.5)],
                                breakpoints_m=[rng.uniform(0.002, 0.01)]))
    moat = RectangularMoat(tuple(gap_m * rng.uniform(0.8, 1.2, 4)),
                           pounding.KelvinVoigt(rng.uniform(5e7, 3e8), rng.uniform(2e4, 2e5)),
                           level=int(rng.integers(0, levels)) if moat_level is None else moat_level)
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
        for axis in (0, 1):
            iso = bearing.isolator if axis == 0 or bearing.isolator_y is None else bearing.isolator_y
            w = point(0, axis, px, py)
            k1, k2 = (*iso.slopes_n_m, iso.slopes_n_m[0])[:2]  # (a linear one: its slope twice)
            k += k2 * np.outer(w, w)
            c += iso.damping_n_s_m * np.outer(w, w)
            if iso.breakpoints_m:
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
    level = b.moat.level  # (its walls stand on the ground: a corner's displacement relative to it)
    a, bb = b.floors[level].size_m
    corners = [(sx * a / 2, sy * bb / 2) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0)]
    tracked += [point(level, axis, *p) for p in corners for axis in (0, 1)]
    walls = []
    law = b.moat.law
    for side, (axis, sign) in enumerate(((0, -1.0), (0, 1.0), (1, -1.0), (1, 1.0))):
        for p in corners:
            if p[axis] * sign > 0.0:
                walls.append((point(level, axis, *p), sign, b.moat.gap_m[side],  # (a rigid stop: no k, c)
                              getattr(law, "stiffness", None), getattr(law, "damping", None)))
    influence = np.zeros((n, 2))
    influence[0::3, 0] = 1.0
    influence[1::3, 1] = 1.0
    first = len(tracked)  # (each floor's centre of mass along x and y: a vector too)
    tracked += [point(level, axis, *centres[level]) for level in range(len(b.floors)) for axis in (0, 1)]
    vectors = [(2 * i, 2 * i + 1) for i in range(len(b.bearings))]
    vectors += [(first + 2 * level, first + 2 * level + 1) for level in range(len(b.floors))]
    return PlanModel(mass=mass, k=k, c=c, influence=influence, record=(np.zeros(1),) * 3, plastic=plastic,
                     walls=walls, tracked=tracked, vectors=vectors)


def _same_events(run, action, rows):
    got = run.event_table[run.event_table[:, 1] == ACT[action]]
    assert [int(c) for c in got[:, 2]] == [int(c) for c, _ in rows], action
    np.testing.assert_allclose(got[:, 0], [t for _, t in rows], rtol=0, atol=1e-9, err_msg=action)




def _pair(t, ax, ay):
    return pounding.RecordPair(pounding.Record(t, ax, name="x"), pounding.Record(t, ay, name="y"))


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), levels=st.integers(1, 2), gap_m=st.floats(0.02, 0.1),
       pga=st.floats(2.0, 5.0))
def test_a_building_in_plan_runs_as_the_reference(seed, levels, gap_m, pga):
    ref = _same_as_the_reference(np.random.default_rng(seed), levels, gap_m, pga)
    assume(ref is not None)
    event(f"{'walls struck' if ref.contact_starts else 'no wall struck'}, {levels} floor(s)")


@pytest.mark.parametrize("seed", [3, 8])
def test_a_moat_around_an_upper_floor_stands_on_the_ground(seed):
    # (the walls stop the floor's motion relative to the ground, not its drift: against the reference)
    ref = _same_as_the_reference(np.random.default_rng(seed), 2, 0.05, 4.0, moat_level=1)
    assert len(ref.contact_starts) >= 4


def _same_as_the_reference(rng, levels, gap_m, pga, moat_level=None):
    """A drawn building's run against the reference's: events, final state, every exact extremum, the
    ledger; the reference's result (None where the reference cannot follow the draw)."""
    b = _draw_building(rng, levels, gap_m, moat_level)
    model = _restated(b)
    t, ax, ay = _record(rng, 2.0, 0.01, pga)
    model.record = (t, ax, ay)
    run = pounding.simulate(b, _pair(t, ax, ay), t[-1], sample_rate_hz=200.0)
    assert run.success, run.message
    try:
        ref = reference(model, t[-1], np.zeros(2 * 3 * levels))
    except TouchAtRest:  # (the reference's own limit: two springs yielding at once)
        return None
    for action, rows in (("contact_start", ref.contact_starts), ("contact_end", ref.contact_ends),
                         ("yield", ref.yields), ("reversal", ref.sticks)):
        _same_events(run, action, rows)
    n = 3 * levels
    scale = np.max(np.abs(ref.y))
    lay = run.final_state.layout
    end = run.final_state.vector
    np.testing.assert_allclose(end[lay["x"]:lay["x"] + n], ref.y[:n], rtol=0, atol=1e-8 * scale)
    np.testing.assert_allclose(end[lay["v"]:lay["v"] + n], ref.y[n:], rtol=0, atol=1e-8 * scale)
    # every exact extremum the run reports, against the reference's tracked points (bearings' x and y, the
    # frames' drifts, the corners' x and y) and vectors
    scale = max(np.max(np.abs(ref.tracked_max)), np.max(np.abs(ref.tracked_min)))
    nb, nf = len(b.bearings), len(b.frames)
    top, bottom = ref.tracked_max, ref.tracked_min
    close = dict(rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(run.bearing_axis_max_m.ravel(), top[:2 * nb], **close)
    np.testing.assert_allclose(run.bearing_axis_min_m.ravel(), bottom[:2 * nb], **close)
    np.testing.assert_allclose(run.frame_drift_max_m, top[2 * nb:2 * nb + nf], **close)
    np.testing.assert_allclose(run.frame_drift_min_m, bottom[2 * nb:2 * nb + nf], **close)
    at = slice(2 * nb + nf, 2 * nb + nf + 8)  # (the corners', then the floors' centres)
    np.testing.assert_allclose(run.corner_displacement_max_m.ravel(), top[at], **close)
    np.testing.assert_allclose(run.corner_displacement_min_m.ravel(), bottom[at], **close)
    np.testing.assert_allclose(run.bearing_displacement_max_m, ref.vector_max[:nb], **close)
    np.testing.assert_allclose(run.plan_displacement_max_m, ref.vector_max[nb:], **close)
    np.testing.assert_allclose(run.displacement_max[:, :2].ravel(), top[at.stop:], **close)
    corners = top[at].reshape(4, 2), bottom[at].reshape(4, 2)
    approach = [-corners[1][:, 0].min(), corners[0][:, 0].max(),
                -corners[1][:, 1].min(), corners[0][:, 1].max()]
    np.testing.assert_allclose(run.clearance_m, np.array(b.moat.gap_m) - approach, **close)
    # the samples: each bearing's displacement is its floor's point, and no sample passes an exact extremum
    assert np.all(np.linalg.norm(run.bearing_displacement, axis=2) <= run.bearing_displacement_max_m + 1e-12)
    assert np.all(run.displacement <= run.displacement_max + 1e-12)
    assert np.all(run.displacement >= run.displacement_min - 1e-12)
    e = run.energy
    assert abs(e.residual) <= 1e-9 * max(abs(e.input_work), e.viscous, e.kinetic, e.hysteretic)
    return ref


# ---------------------------------------------------------------------------------------- the line it is
def _symmetric(k1=1.2e7, k2=1.5e6, dy=0.01, c=2e4, gap=0.05, mass=3e5, levels=3):
    """A building symmetric about both axes: four equal bearings, equal frames in pairs, centred masses."""
    floors = [Floor(mass, (24.0, 16.0))] * levels
    bearings = [Bearing((sx * 10.0, sy * 6.0), _iso(k1, k2, dy, c)) for sx in (-1, 1) for sy in (-1, 1)]
    frames = [Frame(s, axis, sign * at, 1.5e8, 1e5) for s in range(1, levels)
              for axis, at in (("x", 7.0), ("y", 11.0)) for sign in (-1.0, 1.0)]
    return PlanBuilding(floors, bearings, frames, RectangularMoat(gap, pounding.KelvinVoigt(2e8, 4e5)))


def test_a_symmetric_building_along_x_is_its_line_structure():
    b = _symmetric()
    rec = pounding.records.el_centro().scaled(pga_g=0.6)
    run = pounding.simulate(b, rec, 12.0)
    # the line: the four bearings side by side, each storey's two frames along x, each wall's two corners
    line = pounding.Structure(3e5, _iso(4 * 1.2e7, 4 * 1.5e6, 0.01, 4 * 2e4),
                              [pounding.Storey(3e5, 3e8, 2e5)] * 2,
                              [pounding.Wall(0, 0.05, 0.05, pounding.KelvinVoigt(4e8, 8e5))])
    ref = pounding.simulate(line, rec, 12.0)
    assert len(ref.contacts) >= 4
    np.testing.assert_allclose(run.displacement_max[:, 0], ref.displacement_max, rtol=1e-9)
    np.testing.assert_allclose(run.displacement_min[:, 0], ref.displacement_min, rtol=1e-9)
    np.testing.assert_allclose(run.abs_acceleration_max[:, 0], ref.abs_acceleration_max, rtol=1e-9)
    # nothing moves along y or turns (its stiffness and its masses are symmetric: to the rounding of the
    # phases' exponentials, 1e-34 m)
    assert np.max(np.abs(run.displacement[:, :, 1:])) < 1e-20 * np.max(np.abs(run.displacement))
    # each contact of the line is two corners' at once, at the same instants
    starts = np.sort(run.contacts["t_start_s"].to_numpy())
    np.testing.assert_allclose(starts[::2], ref.contacts["t_start_s"].to_numpy(), rtol=0, atol=1e-9)
    np.testing.assert_allclose(starts[1::2], starts[::2], rtol=0, atol=0)
    assert run.energy.input_work == pytest.approx(ref.energy.input_work, rel=1e-9)
    # every bearing moves as the base, along x
    np.testing.assert_allclose(run.bearing_displacement_max_m, max(ref.displacement_max[0],
                                                                    -ref.displacement_min[0]), rtol=1e-9)


def test_one_component_along_y_is_the_same_line_turned():
    b = _symmetric()
    rec = pounding.records.el_centro().scaled(pga_g=0.6)
    along_x = pounding.simulate(b, pounding.RecordPair.of_direction(rec, 0.0), 8.0)
    iso = b.bearings[0].isolator
    turned = dataclasses.replace(b, floors=[Floor(3e5, (16.0, 24.0))] * 3,
                                 bearings=[Bearing((sx * 6.0, sy * 10.0), iso)
                                           for sx in (-1, 1) for sy in (-1, 1)],
                                 frames=[dataclasses.replace(f, axis="yx"[f.axis == "y"]) for f in b.frames])
    along_y = pounding.simulate(turned, pounding.RecordPair.of_direction(rec, 90.0), 8.0)
    # (cos 90 deg is 6e-17, not 0: the turned building feels a trace along x)
    np.testing.assert_allclose(along_y.displacement_max[:, 1], along_x.displacement_max[:, 0], rtol=1e-9)
    np.testing.assert_allclose(along_y.bearing_displacement_max_m, along_x.bearing_displacement_max_m,
                               rtol=1e-9)


# ---------------------------------------------------------------------------------------- invariants
def _mirrored(b):
    """The building mirrored about the x axis (y to -y)."""
    floors = [dataclasses.replace(f, centre_m=(f.centre_m[0], -f.centre_m[1])) for f in b.floors]
    bearings = [dataclasses.replace(x, at_m=(x.at_m[0], -x.at_m[1])) for x in b.bearings]
    frames = [dataclasses.replace(f, at_m=-f.at_m if f.axis == "x" else f.at_m) for f in b.frames]
    g = b.moat.gap_m
    moat = dataclasses.replace(b.moat, gap_m=(g[0], g[1], g[3], g[2]))
    ecc = (b.accidental_eccentricity[0], -b.accidental_eccentricity[1])
    return PlanBuilding(floors, bearings, frames, moat, ecc)


def test_a_mirrored_building_under_the_mirrored_motion_moves_as_the_mirror():
    rng = np.random.default_rng(11)
    b = _draw_building(rng, 2, 0.05)
    t, ax, ay = _record(rng, 3.0, 0.01, 4.0)
    run = pounding.simulate(b, _pair(t, ax, ay), t[-1])
    mirror = pounding.simulate(_mirrored(b), _pair(t, ax, -ay), t[-1])
    assert len(run.contacts) > 0
    flip = np.array([1.0, -1.0, -1.0])
    scale = np.max(np.abs(run.displacement[:, :, :2]))
    np.testing.assert_allclose(mirror.displacement * flip, run.displacement, rtol=0, atol=1e-10 * scale * 30)
    np.testing.assert_allclose(mirror.bearing_displacement_max_m, run.bearing_displacement_max_m, rtol=1e-10)
    np.testing.assert_allclose(mirror.clearance_m[[0, 1, 3, 2]], run.clearance_m, rtol=0, atol=1e-10 * scale)
    assert len(mirror.contacts) == len(run.contacts)


def test_a_continued_run_is_one_long_run():
    rng = np.random.default_rng(5)
    b = _draw_building(rng, 2, 0.04)
    t, ax, ay = _record(rng, 4.0, 0.01, 4.0)
    pair = _pair(t, ax, ay)
    whole = pounding.simulate(b, pair, 4.0)
    first = pounding.simulate(b, pair, 1.73)
    second = pounding.simulate(b, pair, 4.0 - 1.73, state=first.final_state)
    assert len(first.contacts) + len(second.contacts) >= len(whole.contacts) > 0
    scale = np.max(np.abs(whole.final_state.vector[1:]))
    np.testing.assert_allclose(second.final_state.vector, whole.final_state.vector, rtol=0,
                               atol=1e-10 * scale)
    both = np.maximum(first.bearing_displacement_max_m, second.bearing_displacement_max_m)
    np.testing.assert_allclose(both, whole.bearing_displacement_max_m, rtol=1e-10)
    work = first.energy.input_work + second.energy.input_work
    assert work == pytest.approx(whole.energy.input_work, rel=1e-9)


# ---------------------------------------------------------------------------------------- checks
def test_a_run_s_bad_arguments_are_refused_by_name():
    b = _symmetric(levels=1)
    rec = pounding.records.el_centro()
    line = pounding.Structure(3e5, _iso(1e6), [])
    for kwargs, field in ((dict(excitation="el centro"), "excitation"), (dict(duration=-1.0), "duration"),
                          (dict(rtol=1.0), "rtol"), (dict(max_steps=0), "max_steps"),
                          (dict(sample_rate_hz=-1.0), "sample_rate_hz"),
                          (dict(state=pounding.simulate(line, rec, 0.1).final_state), "state"),
                          (dict(state="rest"), "state"), (dict(duration=1e5, max_steps=1000), "duration")):
        args = {"excitation": rec, "duration": 1.0, **kwargs}
        with pytest.raises(InputError) as info:
            pounding.simulate(b, **args)
        assert info.value.field == field, str(info.value)
    with pytest.raises(InputError, match="record"):
        pounding.RecordPair.of_direction(np.zeros(3), 30.0)


# ---------------------------------------------------------------------------------------- its tables and plot
def test_a_plan_run_s_tables_and_plot(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    b = _symmetric(levels=2, gap=0.03)
    rec = pounding.records.el_centro().scaled(pga_g=0.5)
    run = pounding.simulate(b, pounding.RecordPair.of_direction(rec, 30.0), 6.0, sample_rate_hz=100.0)
    frame = run.to_dataframe()
    assert list(frame.columns[:4]) == ["t_s", "level0_x_m", "level0_y_m", "level0_theta_rad"]
    assert frame.shape[0] == run.t.size and "bearing3_y_m" in frame
    assert list(run.peaks().index) == [0, 1] and "theta_max_rad" in run.peaks()
    bearings = run.bearings()
    assert len(bearings) == 4 and np.all(bearings["displacement_max_m"] > 0)
    np.testing.assert_allclose(np.hypot(bearings["x_at_max_m"], bearings["y_at_max_m"]),
                               bearings["displacement_max_m"], rtol=1e-14)
    contacts = run.contacts
    assert len(contacts) > 0 and set(contacts["wall"].astype(str)) <= {"-x", "+x", "-y", "+y"}
    struck_x = contacts["wall"].astype(str).isin(["-x", "+x"])
    assert np.all(np.abs(contacts.loc[struck_x, "at_m"]) <= 8.0 + 0.1)  # (a corner's y, near +-8 m)
    summary = run.summary()
    assert summary["contacts"] == len(contacts) and summary["status"] == "SUCCESS"
    assert summary["clearance_min_m"] < 0.0
    fig = run.plot()
    ax = fig.axes[0]
    assert ax.get_xlabel() == "x (mm)" and len(ax.lines) >= 5
    fig.savefig(tmp_path / "orbit.png")


def test_a_plan_run_s_bearing_forces_and_contact_places():
    # linear bearings without dashpots: each bearing's force is its stiffness times its displacement there;
    # a contact's place on its wall is its corner's coordinate along the wall when it began
    k = 4.0e6
    floors = [Floor(3e5, (24.0, 16.0), centre_m=(1.0, -0.5))]
    bearings = [Bearing((sx * 10.0, sy * 6.0), _iso(k * (1.5 if sx > 0 else 1.0))) for sx in (-1, 1)
                for sy in (-1, 1)]
    b = PlanBuilding(floors, bearings, moat=RectangularMoat(0.06, pounding.KelvinVoigt(2e8, 4e5)),
                     accidental_eccentricity=(0.02, 0.03))
    cx, cy = 1.0 + 0.02 * 24.0, -0.5 + 0.03 * 16.0  # (the centre of mass, moved)
    rec = pounding.records.el_centro().scaled(pga_g=0.5)
    run = pounding.simulate(b, pounding.RecordPair.of_direction(rec, 35.0), 6.0, sample_rate_hz=200.0)
    stiff = np.array([bb.isolator.slopes_n_m[0] for bb in bearings])
    np.testing.assert_allclose(run.bearing_force, stiff[None, :, None] * run.bearing_displacement, rtol=1e-12,
                               atol=1e-9 * np.max(np.abs(run.bearing_force)))
    x, y, th = (run.displacement[:, 0, j] for j in range(3))
    for p, bb in enumerate(bearings):  # (a bearing's displacement: its floor's point there)
        px, py = bb.at_m
        np.testing.assert_allclose(run.bearing_displacement[:, p, 0], x - (py - cy) * th, rtol=0, atol=1e-15)
        np.testing.assert_allclose(run.bearing_displacement[:, p, 1], y + (px - cx) * th, rtol=0, atol=1e-15)
    contacts = run.contacts
    assert len(contacts) >= 2 and abs(th).max() > 1e-4
    corners = [(-12.0, -8.0), (-12.0, 8.0), (12.0, -8.0), (12.0, 8.0)]
    for wall, corner, at, t0 in contacts[["wall", "corner", "at_m", "t_start_s"]].itertuples(index=False):
        q = int(np.searchsorted(run.t, t0))
        assert run.t[q] == t0
        px, py = corners[corner]
        across_x = wall in ("-x", "+x")
        expected = (py + y[q] + (px - cx) * th[q]) if across_x else (px + x[q] - (py - cy) * th[q])
        assert at == pytest.approx(expected, abs=1e-12)


# ---------------------------------------------------------------------------------------- the command line
def test_the_command_line_runs_a_building_in_plan_and_refuses_what_it_cannot(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    examples = Path(__file__).parents[1] / "examples"
    plan, line = str(examples / "plan_building.toml"), str(examples / "building_moat.toml")
    record = str(examples / "el_centro_ns.AT2")
    runner = CliRunner()
    history = str(tmp_path / "h.csv")
    done = runner.invoke(app, ["simulate", plan, "--record", record, "--scale-pga", "0.5",
                               "--direction", "60", "--history", history], catch_exceptions=False)
    assert done.exit_code == 0, done.output
    assert "largest bearing displacement in plan" in done.output and "along 60 deg" in done.output
    building = PlanBuilding.from_toml(plan)
    quake = pounding.RecordPair.of_direction(pounding.Record.from_at2(record).scaled(pga_g=0.5), 60.0)
    run = pounding.simulate(building, quake, quake.t[-1], sample_rate_hz=0.0)
    assert f"{run.bearing_displacement_max_m.max() * 1e3:.2f}" in done.output
    assert (tmp_path / "h.csv").stat().st_size > 0
    both = runner.invoke(app, ["simulate", plan, "--record", record, "--record-y", record,
                               "--direction", "10", "--duration", "2"], catch_exceptions=False)
    assert both.exit_code == 0 and "turned by 10 deg" in both.output, both.output
    sine = ["--a-g", "0.1", "--freq", "1"]
    for args, words in ((["simulate", line, "--record", record, "--direction", "10"], "building in plan"),
                        (["simulate", line, "--record", record, "--record-y", record], "building in plan"),
                        (["simulate", plan, *sine, "--direction", "10"], "harmonic"),
                        (["simulate", plan, *sine, "--velocity", "0.1"], "at rest"),
                        (["simulate", plan, *sine, "--record-y", record], "--record")):
        refused = runner.invoke(app, args)
        assert refused.exit_code != 0 and words in refused.output, (args, refused.output)


# ---------------------------------------------------------------------------------------- the protocols
def test_the_orientations_of_a_pair_turn_a_building_in_plan():
    b = PlanBuilding.from_toml(Path(__file__).parents[1] / "examples" / "plan_building.toml")
    quake = pounding.records.el_centro().scaled(pga_g=0.5)
    pair = pounding.RecordPair(quake, quake.scaled(factor=0.7))
    found = pounding.orientations(b, pair, [0.0, 75.0, 180.0, 255.0], duration_s=8.0)
    # each angle is the run under the pair turned by it (both components, in the building's axes)
    run = pounding.simulate(b, pair.rotated(75.0), 8.0)
    peaks = run.quantities()
    for name in ("disp_max_m", "theta_max_rad", "clearance_min_m", "impacts", "drift_ratio_max", "acc_max_g"):
        assert found.data.loc[75.0, name] == peaks[name], name
    assert peaks["disp_max_m"] == np.max(run.bearing_displacement_max_m)
    assert peaks["top_disp_max_m"] == run.plan_displacement_max_m[-1]
    # the motion turned by 180 degrees is the motion reversed: a building with equal gaps on opposite sides
    # and symmetric laws moves as its mirror through its centre, to the same peaks
    for a in (0.0, 75.0):
        assert found.data.loc[a + 180.0, "disp_max_m"] == pytest.approx(found.data.loc[a, "disp_max_m"],
                                                                          rel=1e-12)
    assert found.critical("disp_max_m")[1] == found.data["disp_max_m"].max()
    assert found.critical("clearance_min_m")[1] == found.data["clearance_min_m"].min()  # (the nearest a wall)


def test_a_run_s_times_of_its_extrema_are_where_they_were_reached():
    # a run stopped at an extremum's time ends there: its displacement is the extremum's value
    rng = np.random.default_rng(21)
    b = _draw_building(rng, 2, 0.05, moat_level=0)
    t, ax, ay = _record(rng, 3.0, 0.01, 4.0)
    pair = _pair(t, ax, ay)
    run = pounding.simulate(b, pair, 3.0)
    lay = run.final_state.layout
    for level, dof, field, value in ((1, 0, "displacement_max_time_s", run.displacement_max),
                                     (0, 1, "displacement_min_time_s", run.displacement_min),
                                     (0, 2, "displacement_max_time_s", run.displacement_max)):
        at = getattr(run, field)[level, dof]
        upto = pounding.simulate(b, pair, at, sample_rate_hz=0.0)
        got = upto.final_state.vector[lay["x"] + 3 * level + dof]
        assert got == pytest.approx(value[level, dof], rel=1e-9, abs=1e-12), field
    q = int(np.argmax(run.bearing_displacement_max_m))
    upto = pounding.simulate(b, pair, run.bearing_displacement_max_time_s[q], sample_rate_hz=0.0)
    x = upto.final_state.vector[lay["x"]:lay["x"] + 6]
    px, py = b.bearings[q].at_m
    c = b.placed_floors[0].centre_m
    at_max = (x[0] - (py - c[1]) * x[2], x[1] + (px - c[0]) * x[2])
    np.testing.assert_allclose(at_max, run.bearing_displacement_at_max_m[q], rtol=1e-9, atol=1e-12)
    # the velocities sampled are the state's: the last sample is the final state's
    np.testing.assert_allclose(run.velocity[-1].ravel(), run.final_state.vector[lay["v"]:lay["v"] + 6],
                               rtol=0, atol=0)
    theta = run.summary()["theta_max_rad"]
    assert theta == max(abs(run.displacement_max[0, 2]), abs(run.displacement_min[0, 2]))


def test_a_state_the_building_cannot_be_in_is_refused():
    # a state taken in contact with a moat 2 cm away, given to the same building with a moat 20 cm away:
    # its compressions are no longer its corners' depths
    near = _symmetric(levels=1, gap=0.02)
    quake = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.5), 30.0)
    run = pounding.simulate(near, quake, 3.0)
    starts = run.contacts["t_start_s"].to_numpy()
    assert len(starts)
    touching = pounding.simulate(near, quake, float(starts[0]) + 1e-3).final_state
    assert any(touching.in_contact)
    far = dataclasses.replace(near, moat=dataclasses.replace(near.moat, gap_m=0.2))
    with pytest.raises(InputError, match="bumper_compression_m") as info:
        pounding.simulate(far, quake, 1.0, state=touching)
    assert "moat wall" in str(info.value)
    pounding.simulate(near, quake, 1.0, state=touching)  # (its own building takes it)


def test_a_plan_run_as_a_dataset():
    b = _symmetric(levels=2, gap=0.03)
    rec = pounding.records.el_centro().scaled(pga_g=0.5)
    run = pounding.simulate(b, pounding.RecordPair.of_direction(rec, 30.0), 3.0, sample_rate_hz=100.0)
    ds = run.to_xarray()
    assert ds.sizes["sample"] == run.t.size and ds.sizes["level"] == 2 and ds.sizes["bearing"] == 4
    np.testing.assert_array_equal(ds["displacement"].sel(dof="theta").values, run.displacement[:, :, 2])
    np.testing.assert_array_equal(ds["bearing_displacement_max_m"].values, run.bearing_displacement_max_m)
    assert list(ds["wall"].values) == ["-x", "+x", "-y", "+y"] and ds.attrs["status"] == "SUCCESS"


# ---------------------------------------------------------------------------------------- closed forms
def _isotropic(gap_m=None, moat_kind=RectangularMoat):
    """A square floor on four equal linear bearings (each 2.5 MN/m, 150 kN s/m), its mass centred: x and y
    alike, apart from the turn; a moat (``moat_kind``: four walls, or a ring) of ``gap_m`` (stiff walls)."""
    iso = pounding.Isolator(slopes_n_m=[2.5e6], breakpoints_m=[], damping_n_s_m=1.5e5)
    moat = None if gap_m is None else moat_kind(gap_m, pounding.KelvinVoigt(1e9, 1e6))
    return PlanBuilding([Floor(4e5, (20.0, 20.0))], [Bearing((sx * 8.0, sy * 8.0), iso) for sx in (-1, 1)
                                                     for sy in (-1, 1)], moat=moat)


def _dynamic_factor(freq_hz):
    """|k/m - w^2 + i c w / m| of the isolated floor (its four bearings together)."""
    w = 2.0 * np.pi * freq_hz
    k_m, c_m = 4 * 2.5e6 / 4e5, 4 * 1.5e5 / 4e5
    return float(np.hypot(k_m - w * w, c_m * w))


@pytest.mark.parametrize("freq_hz, a_g", [(0.7, 0.2), (0.3, 0.05), (1.6, 0.4)])
def test_circular_shaking_drives_a_circular_orbit_of_the_closed_form_radius(freq_hz, a_g):
    # a_x = A sin(w t), a_y = A cos(w t) on an isotropic isolator: the steady orbit is a circle of radius
    # A / |k/m - w^2 + i c w / m|; after the transient (zeta = 0.15 at 5 rad/s: e^-30 in 40 s), every
    # bearing's largest displacement in plan over a further run is that radius, and it turns not at all
    b = _isotropic()
    table = pounding.HarmonicPair.circular(a_g, freq_hz)
    radius = a_g * 9.81 / _dynamic_factor(freq_hz)
    steady = pounding.simulate(b, table, 40.0, sample_rate_hz=0.0).final_state
    run = pounding.simulate(b, table, 2.0 / freq_hz, state=steady, sample_rate_hz=200.0)
    np.testing.assert_allclose(run.plan_displacement_max_m, radius, rtol=1e-9)
    np.testing.assert_allclose(run.bearing_displacement_max_m, radius, rtol=1e-9)
    np.testing.assert_allclose(np.hypot(run.displacement[:, 0, 0], run.displacement[:, 0, 1]), radius,
                               rtol=1e-9)  # (every sample on the circle)
    assert np.max(np.abs(run.displacement[:, 0, 2])) < 1e-12


@pytest.mark.parametrize("moat_kind", [RectangularMoat, CircularMoat])
def test_a_moat_around_the_circle_is_grazed_at_the_closed_form_amplitude(moat_kind):
    # the orbit's radius reaches the moat's gap at A = gap |k/m - w^2 + i c w / m|: just below, no contact and
    # a clearance of the radius's shortfall, exactly; just above (by more than the engine's length
    # resolution, 1e-9 of the system's lengths), contacts.  A ring's too: the floor does not turn, so each
    # corner's largest distance from the ring's centre is its own plus the orbit's radius
    gap, freq_hz = 0.2, 0.7
    graze_g = gap * _dynamic_factor(freq_hz) / 9.81
    far, near = _isotropic(1.0, moat_kind), _isotropic(gap, moat_kind)
    for excess, struck in ((-1e-9, False), (-1e-7, False), (1e-8, True), (1e-6, True)):
        table = pounding.HarmonicPair.circular(graze_g * (1.0 + excess), freq_hz)
        steady = pounding.simulate(far, table, 40.0, sample_rate_hz=0.0).final_state  # (the moat's layout)
        run = pounding.simulate(near, table, 3.0, state=steady, sample_rate_hz=0.0)
        assert (len(run.contacts) > 0) == struck, excess
        if not struck:
            np.testing.assert_allclose(run.clearance_m, -gap * excess, rtol=1e-3)
