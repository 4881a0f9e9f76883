"""A sliding bearing's elastic pre-slip with a velocity-dependent friction on a line
(``FrictionIsolator(mu, preslip_m=..., mu_fast=..., rate_s_m=...)``: OpenSees' ``flatSliderBearing`` with
``VelDependent``): its slips' friction ``W mu(v)`` at the slip's rate, from ``mu W`` where it yields to where
it turns back.  Against the independent solve_ivp reference (random buildings on it), Coulomb's numbers at
``mu_fast = mu``, the ledger, and a building in plan shaken along one axis, both its circle and one friction
per axis."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from reference_plan import PlanModel, reference
from reference_plan import record_pair as _record
from test_plan_friction import along_x_and_its_line, assert_along_x_is_the_line
from test_plan_friction_circle import _building
from test_plan_friction_circle import _restated as _restated_circles

import pounding
from pounding import FrictionIsolator, _core

ACT = _core.ACTIONS


def _structure(rng):
    """A building of 1 to 3 levels on a friction pendulum or flat slider with a pre-slip and mu_fast."""
    levels = int(rng.integers(1, 4))
    iso = FrictionIsolator(mu=rng.uniform(0.04, 0.08), radius_m=rng.choice([None, rng.uniform(1.5, 3.0)]),
                           damping_n_s_m=rng.uniform(0.0, 5e3), preslip_m=rng.uniform(3e-4, 1.5e-3),
                           mu_fast=rng.uniform(0.02, 0.14), rate_s_m=rng.uniform(10.0, 40.0))
    storeys = [pounding.Storey(rng.uniform(2e4, 6e4), rng.uniform(2e7, 8e7), rng.uniform(1e4, 5e4))
               for _ in range(levels - 1)]
    return pounding.Structure(rng.uniform(2e4, 6e4), iso, storeys, [])


def _restated(s: pounding.Structure, record: tuple) -> PlanModel:
    """The structure as the reference takes it, from its numbers: a shear building whose base has the
    pendulum's W / R and dashpot beside one elastic-perfectly-plastic spring (mu W / preslip_m, yield at
    preslip_m) whose slips' force follows mu(v)."""
    iso = s.isolator
    masses = np.array([s.base_mass_kg, *[st.mass_kg for st in s.storeys]])
    n = masses.size
    k, c = np.zeros((n, n)), np.zeros((n, n))
    k1, k2 = iso.slopes_n_m
    k[0, 0], c[0, 0] = k2, iso.damping_n_s_m
    for i, st in enumerate(s.storeys):
        for mat, v in ((k, st.stiffness_n_m), (c, st.damping_n_s_m)):
            mat[i:i + 2, i:i + 2] += v * np.array([[1.0, -1.0], [-1.0, 1.0]])
    base = np.eye(n)[0]
    influence = np.column_stack([np.ones(n), np.zeros(n)])
    return PlanModel(mass=masses, k=k, c=c, influence=influence, record=record,
                     plastic=[(base, k1 - k2, iso.preslip_m)], plastic_fast={0: (iso.mu_fast / iso.mu,
                                                                                   iso.rate_s_m)},
                     tracked=[base])


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_a_pre_slip_with_a_velocity_dependent_friction_runs_as_the_reference(seed):
    rng = np.random.default_rng(seed)
    s = _structure(rng)
    t, ax, _ = _record(rng, 3.0, 0.01, rng.uniform(3.0, 6.0))
    model = _restated(s, (t, ax, np.zeros_like(ax)))
    run = pounding.simulate(s, pounding.Record(t, ax, name="x"), t[-1], rtol=1e-12)
    assert run.success, run.message
    ref = reference(model, t[-1], np.zeros(2 * model.mass.size), track_acceleration=True)
    # (measured: slips' starts and ends within 1.2e-12 s, final states 8.9e-13 of their largest, peaks
    # 7.7e-13, absolute accelerations 1.8e-11, the ledger 3.9e-13 of the input; mu_fast / mu 0.91 to 2.07)
    events = run.event_table
    for action, want in (("yield", ref.yields), ("reversal", ref.sticks)):  # (every slip's start and end)
        got = events[events[:, 1] == ACT[action], 0]
        assert len(got) == len(want) >= 3, action
        np.testing.assert_allclose(got, [t for _, t in want], rtol=0, atol=1e-11)
    n = model.mass.size
    lay, end = run.final_state.layout, run.final_state.vector
    np.testing.assert_allclose(end[lay["x"]:lay["x"] + n], ref.y[:n], rtol=0,
                               atol=1e-10 * np.max(np.abs(ref.y[:n])))
    np.testing.assert_allclose(end[lay["v"]:lay["v"] + n], ref.y[n:], rtol=0,
                               atol=1e-10 * np.max(np.abs(ref.y[n:])))
    assert run.displacement_max[0] == pytest.approx(ref.tracked_max[0], rel=1e-10)
    assert run.displacement_min[0] == pytest.approx(ref.tracked_min[0], rel=1e-10)
    np.testing.assert_allclose(run.abs_acceleration_max, ref.abs_acc_max, rtol=1e-9)
    e = run.energy
    assert abs(e.residual) <= 1e-10 * max(abs(e.input_work), e.hysteretic)


def test_mu_fast_equal_to_mu_is_the_pre_slip_s_coulomb_friction_number_for_number():
    s = _structure(np.random.default_rng(5))
    coulomb = dataclasses.replace(s, isolator=dataclasses.replace(s.isolator, mu_fast=None, rate_s_m=0.0))
    same = dataclasses.replace(s, isolator=dataclasses.replace(s.isolator, mu_fast=s.isolator.mu))
    rec = pounding.records.el_centro().scaled(pga_g=0.5)
    a, b = pounding.simulate(coulomb, rec, 6.0), pounding.simulate(same, rec, 6.0)
    assert a.displacement_max[0] > 20 * s.isolator.preslip_m  # (it slid)
    np.testing.assert_array_equal(a.final_state.vector, b.final_state.vector)
    np.testing.assert_array_equal(a.displacement, b.displacement)
    assert a.energy == b.energy


@pytest.mark.parametrize("bidirectional", [True, False])
def test_a_building_in_plan_shaken_along_x_is_the_line_s_pre_slip_with_mu_fast(bidirectional):
    # a symmetric building shaken along x: its bearings' circles (or their friction along x) are the line's
    # pre-slip, their slips' friction W mu(|u'|) both ways
    b, line, rec = along_x_and_its_line(bidirectional)
    fast = {"mu_fast": 0.12, "rate_s_m": 20.0}
    b = dataclasses.replace(b, bearings=[
        dataclasses.replace(x, isolator=dataclasses.replace(x.isolator, **fast)) for x in b.bearings])
    line = dataclasses.replace(line, isolator=dataclasses.replace(line.isolator, **fast))
    run, ref = pounding.simulate(b, rec, 10.0), pounding.simulate(line, rec, 10.0)
    assert ref.displacement_max[0] > 0.03  # (it slid)
    assert_along_x_is_the_line(run, ref)
    np.testing.assert_allclose(run.abs_acceleration_max[:, 0], ref.abs_acceleration_max, rtol=1e-9)


def test_the_door_takes_a_pre_slip_s_velocity_dependence_on_two_slopes_only():
    def el(**kw):
        return _core.element(i=0, j=-1, c_d=0.0, **({"slopes": [1.01e6, 1e4], "breaks": [1e-3], "rule": 0,
                                                    "friction_n": 1e3, "friction_fast_n": 2e3,
                                                    "friction_rate_s_m": 20.0} | kw))

    def system(e):
        return _core.system(np.ones(1), np.zeros((1, 1)), np.zeros((1, 1)), [e], False, [])

    system(el())
    for kw, match in (({"friction_n": 0.0}, "friction at rest"),
                      ({"friction_n": 2e3}, "the force at which it slips"),
                      ({"slopes": [1e4, 1e6]}, "the force at which it slips"),
                      ({"slopes": [1e6, 1e5, 1e4], "breaks": [1e-3, 2e-3]}, "no other rule"),
                      ({"friction_rate_s_m": 0.0, "friction_fast_n": 0.0}, "no other rule")):
        with pytest.raises(ValueError, match=match):
            system(el(**kw))


def test_one_friction_per_axis_in_plan_runs_as_the_reference():
    # bidirectional=False: each bearing's x and y a pre-slip of its own with the velocity dependence, both
    # slipping under a pair of components (an eccentric floor: it turns)
    rng = np.random.default_rng(7)
    plain = _building(rng, moat=False)
    fast = {"mu_fast": 1.7 * plain.bearings[0].isolator.mu, "rate_s_m": 25.0}
    b = dataclasses.replace(plain, bearings=[
        pounding.Bearing(x.at_m, dataclasses.replace(x.isolator, **fast), bidirectional=False)
        for x in plain.bearings])
    model = _restated_circles(b)
    plastic = []
    for bearing, (w_x, w_y) in zip(b.bearings, zip(model.tracked[::2], model.tracked[1::2])):
        law = bearing.isolator
        k1, k2 = law.slopes_n_m
        for w in (w_x, w_y):
            plastic.append((w, k1 - k2, law.preslip_m))
    model.plastic = plastic
    model.plastic_fast = {q: (law.mu_fast / law.mu, law.rate_s_m) for q in range(len(plastic))}
    model.bouc_wen, model.circles = [], []
    t, ax, ay = _record(rng, 2.5, 0.01, 3.0)
    model.record = (t, ax, ay)
    pair = pounding.RecordPair(pounding.Record(t, ax, name="x"), pounding.Record(t, ay, name="y"))
    run = pounding.simulate(b, pair, t[-1], rtol=1e-12)
    ref = reference(model, t[-1], np.zeros(6), track_acceleration=True)
    assert len(ref.yields) >= 8
    got = np.sort(run.event_table[run.event_table[:, 1] == ACT["yield"], 0])
    np.testing.assert_allclose(got, sorted(t for _, t in ref.yields), rtol=0, atol=1e-11)
    lay, end = run.final_state.layout, run.final_state.vector
    np.testing.assert_allclose(end[lay["x"]:lay["x"] + 3], ref.y[:3], rtol=0,
                               atol=1e-10 * np.max(np.abs(ref.y[:3])))
    np.testing.assert_allclose(run.abs_acceleration_max[0], ref.abs_acc_max, rtol=1e-9)
    np.testing.assert_allclose(run.bearing_displacement_max_m, ref.vector_max, rtol=1e-10)
