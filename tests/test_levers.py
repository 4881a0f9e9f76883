"""Contacts and elements on levers, at the core's door: a pair whose end is a point of a floor in plan (its
displacement along an axis ``x - y_c theta``: a dof plus an arm times another).

* A building in plan (each floor's x, y and rotation) on bilinear bearings at its corners, its base's
  corners against a rectangular moat of Kelvin-Voigt walls, under a pair of record components: against an
  independent solve_ivp reference with events (tests/reference_plan.py), contact starts and ends, yields and
  sticks within 1e-9 s; the energy ledger closes.
* Three masses on a line under one component (a plain table: kept transitions, whole steps and the screens),
  their bilinear elements and walls on weighted combinations of them: the same reference.
* Tracked pairs on levers (a bearing's displacement along an axis, a frame's drift at its place, a wall's
  point): their exact extrema as the reference's, to 1e-9.
* A lever of arm zero is no lever: a line building's run, its contacts and elements each given a lever of
  arm 0, is the plain run number for number (every levered path gives the plain path's numbers).
* The door refuses what levers cannot carry yet (a rigid stop's impulse, a friction element's tie, the
  monodromy) and a lever that is no other dof.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding import _control, _core
from pounding.engine.layout import L_INPUT
from pounding.engine.run_parts import EnergyLedger
from reference_ndof import TouchAtRest
from reference_plan import PlanModel, reference
from reference_plan import record_pair as _record

KELVIN_VOIGT = _core.LAW_IDS["kelvin_voigt"]
ACT = _core.ACTIONS
PX = _core.PAIR_EXTREMA
NX = _core.NORM_EXTREMA


BUDGET = 2 * 10**6  # (sub-intervals: far above what these runs take, so that a stalled run ends, and fails)


def _run(sy, forcing, state0, t_end, sample_dt=0.0):
    return _core.run(sy, forcing, np.asarray(state0, dtype=float), t_end, sample_dt, 1e-10, 10**6, True,
                     _control.new_control(BUDGET))


def _weights(n, entries):
    w = np.zeros(n)
    for d, v in entries:
        w[d] += v
    return w


def plan_building(rng, levels, gap_m, moat=None):
    """A building in plan of ``levels`` floors (dofs 3 l, 3 l + 1, 3 l + 2: x, y, rotation), on four bilinear
    bearings at its base's corners (an element per axis, kinematic rule), its base's corners against a
    rectangular moat of Kelvin-Voigt walls ``gap_m`` away (two corners against each wall); its storeys are
    lateral lines (frames) placed in plan. As the core takes it and as the reference restates it (``moat``: a
    law of the package for the moat's walls instead, which the reference does not restate: the walls it
    gets are then not the core's)."""
    n = 3 * levels
    a, b = rng.uniform(10.0, 30.0, 2)  # (the plan's sides, m)
    mass = np.zeros(n)
    for level in range(levels):
        m = rng.uniform(2e5, 6e5)
        mass[3 * level:3 * level + 2] = m
        mass[3 * level + 2] = m * (a * a + b * b) / 12.0 * rng.uniform(0.8, 1.2)
    k = np.zeros((n, n))
    for level in range(1, levels):  # (two frames each way at drawn places: stiffness off the mass's centre)
        lo, hi = 3 * (level - 1), 3 * level
        for axis in (0, 1):
            for _ in range(2):
                at = rng.uniform(-0.5, 0.5) * (b if axis == 0 else a)
                arm = -at if axis == 0 else at
                w = _weights(n, [(hi + axis, 1.0), (hi + 2, arm), (lo + axis, -1.0), (lo + 2, -arm)])
                k += rng.uniform(5e7, 2e8) * np.outer(w, w)
    c = 0.02 * np.diag(mass) + 0.001 * k
    # (the reference's linear springs and dashpots: the storeys' and the bearings' elastic parts)
    k_ref, c_ref = k.copy(), c.copy()
    elements, plastic = [], []
    corners = [(sx * a / 2, sy * b / 2) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0)]
    for cx, cy in corners:  # (each near a corner, none two on one line: their yields and sticks apart)
        px, py = cx * rng.uniform(0.7, 0.95), cy * rng.uniform(0.7, 0.95)
        k1, dy = rng.uniform(5e6, 2e7), rng.uniform(0.005, 0.02)
        k2 = k1 * rng.uniform(0.05, 0.3)
        c_d = rng.uniform(0.0, 2e4)
        for axis, arm in ((0, -py), (1, px)):  # (the corner's x is x - py theta, its y is y + px theta)
            elements.append(_core.element(i=axis, j=-1, c_d=c_d, slopes=[k1, k2], breaks=[dy], rule=0,
                                          lever_i=2, arm_i_m=arm))
            w = _weights(n, [(axis, 1.0), (2, arm)])
            k_ref += k2 * np.outer(w, w)
            c_ref += c_d * np.outer(w, w)
            plastic.append((w, k1 - k2, dy))
    k_b, c_b = rng.uniform(5e7, 3e8), rng.uniform(2e4, 2e5)
    params = np.zeros(_core.LAYOUT["N_LAW_PARAMS"])
    params[:2] = k_b, c_b
    contacts, walls = [], []
    for axis, sign in ((0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)):
        for px, py in corners:
            if (px if axis == 0 else py) * sign < 0.0:  # (the two corners on that wall's side)
                continue
            arm = -py if axis == 0 else px
            law, numbers = (KELVIN_VOIGT, params) if moat is None else (moat.LAW_ID, moat.params())
            contacts.append(_core.contact_slot(i=axis, j=-1, sign=sign, gap_m=gap_m, law=law,
                                               params=numbers, lever_i=2, arm_i_m=arm))
            walls.append((_weights(n, [(axis, 1.0), (2, arm)]), sign, gap_m, k_b, c_b))
    if levels >= 2:  # (the first storey: a yielding frame each way, and drift limiters at a corner)
        for axis in (0, 1):
            at = rng.uniform(-0.5, 0.5) * (b if axis == 0 else a)
            arm = -at if axis == 0 else at
            k1, dy = rng.uniform(2e7, 5e7), rng.uniform(0.002, 0.01)
            k2 = k1 * rng.uniform(0.05, 0.5)
            elements.append(_core.element(i=3 + axis, j=axis, c_d=0.0, slopes=[k1, k2], breaks=[dy], rule=0,
                                          lever_i=5, arm_i_m=arm, lever_j=2, arm_j_m=arm))
            w = _weights(n, [(3 + axis, 1.0), (5, arm), (axis, -1.0), (2, -arm)])
            k_ref += k2 * np.outer(w, w)
            plastic.append((w, k1 - k2, dy))
        arm = -b / 2
        w = _weights(n, [(3, 1.0), (5, arm), (0, -1.0), (2, -arm)])
        for sign in (1.0, -1.0):
            contacts.append(_core.contact_slot(i=3, j=0, sign=sign, gap_m=gap_m / 4, law=KELVIN_VOIGT,
                                               params=params, lever_i=5, arm_i_m=arm, lever_j=2, arm_j_m=arm))
            walls.append((w, sign, gap_m / 4, k_b, c_b))
    influence = np.zeros((n, 2))
    influence[0::3, 0] = 1.0
    influence[1::3, 1] = 1.0
    # (every element's displacement tracked: each bearing's along each axis, each frame's drift)
    # (and each bearing's displacement in plan: the vector of its x and y, elements 2 b and 2 b + 1)
    tracked = [_core.tracked_pair(i=el.i, j=el.j, lever_i=el.lever_i, arm_i_m=el.arm_i_m, lever_j=el.lever_j,
                                 arm_j_m=el.arm_j_m) for el in elements]
    vectors = [(2 * b, 2 * b + 1) for b in range(len(corners))]
    sy = _core.system(mass, k, c, elements, True, contacts, tracked, influence=influence, vectors=vectors)
    model = PlanModel(mass=mass, k=k_ref, c=c_ref, influence=influence, record=(np.zeros(1),) * 3,
                      plastic=plastic, walls=walls, tracked=[w for w, _, _ in plastic], vectors=vectors)
    return sy, model


def _record_forcing(t, ax, ay=None):
    """A record's forcing (``ay``: its second component, if any) on its uniform step."""
    return _core.Forcing(kind=_core.EXCITATION["record"], p=np.array([t[1] - t[0], 0.0, 0.0]), rec_t=t,
                         rec_a=ax, rec_b=np.zeros(0) if ay is None else ay)


def _forcing(excitation, seed, amp, freq_hz, phase):
    """One component: a record of ``amp`` peak (m/s^2; 6 s at 0.01 s, drawn from ``seed``) or a sine of
    ``amp`` at ``freq_hz`` and ``phase`` (rad)."""
    if excitation == "record":
        t, ax, _ = _record(np.random.default_rng(seed), 6.0, 0.01, amp)
        return _record_forcing(t, ax)
    return _core.Forcing(kind=_core.EXCITATION["harmonic"], p=np.array([amp, 2 * math.pi * freq_hz, phase]),
                         rec_t=np.zeros(1), rec_a=np.zeros(1))


def _events(out, action):
    ev = out.events
    return ev[ev[:, 1] == ACT[action]]


def _times(rows):
    return np.array([t for _, t in rows]), [int(c) for c, _ in rows]


def _assert_same_events(out, action, rows):
    got = _events(out, action)
    times, index = _times(rows)
    assert [int(c) for c in got[:, 2]] == index, action
    np.testing.assert_allclose(got[:, 0], times, rtol=0, atol=1e-9, err_msg=action)


def _ledger_closes(out):
    e = EnergyLedger.of(out.ledger)
    assert out.ledger[L_INPUT] != 0.0
    assert abs(e.residual) <= 1e-9 * max(abs(e.input_work), e.viscous, e.kinetic, e.hysteretic)


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), levels=st.integers(1, 2), gap_m=st.floats(0.02, 0.12),
       pga=st.floats(2.0, 5.0))
def test_a_plan_building_on_bearings_against_a_moat_matches_the_reference(seed, levels, gap_m, pga):
    rng = np.random.default_rng(seed)
    sy, model = plan_building(rng, levels, gap_m)
    t, ax, ay = _record(rng, 2.0, 0.01, pga)
    model.record = (t, ax, ay)
    out = _run(sy, _record_forcing(t, ax, ay), np.zeros(sy.state_size), t[-1])
    assert out.status == 0, out.status
    _ledger_closes(out)  # (first: a force off its lever breaks it, and the reference need not run)
    try:
        ref = reference(model, t[-1], np.zeros(2 * sy.n))
    except TouchAtRest:
        assume(False)
    event(f"{'walls struck' if ref.contact_starts else 'no wall struck'}, {levels} floor(s)")
    _assert_same_events(out, "contact_start", ref.contact_starts)
    _assert_same_events(out, "contact_end", ref.contact_ends)
    _assert_same_events(out, "yield", ref.yields)
    _assert_same_events(out, "reversal", ref.sticks)
    n = sy.n
    scale = np.max(np.abs(ref.y), axis=None)
    np.testing.assert_allclose(out.state[1:1 + 2 * n], ref.y, rtol=0, atol=1e-8 * scale)
    theta = np.abs(ref.y[2:n:3])
    assert np.max(theta) * 10.0 > 1e-3 * np.max(np.abs(ref.y[:n]))  # (the floors turn: no bystander)
    _same_extrema(out, sy.n, ref)


def _same_extrema(out, n, ref):
    """Each tracked point's exact extrema (a bearing's displacement along an axis, a frame's drift at its
    place) as the reference's, to 1e-9 of the largest."""
    per_pair = out.per_pair(n)
    scale = max(np.max(np.abs(ref.tracked_max)), np.max(np.abs(ref.tracked_min)))
    np.testing.assert_allclose(per_pair[:, PX["max"]], ref.tracked_max, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(per_pair[:, PX["min"]], ref.tracked_min, rtol=0, atol=1e-9 * scale)
    if ref.vector_max is not None and ref.vector_max.size:
        np.testing.assert_allclose(out.norms[:, NX["max"]], ref.vector_max, rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(np.hypot(out.norms[:, NX["at_p"]], out.norms[:, NX["at_q"]]),
                                   out.norms[:, NX["max"]], rtol=1e-15, atol=0)


def test_a_moat_struck_at_a_corner_turns_the_building():
    # the reference's draw with most walls struck: the starts, the ends and the whole state
    rng = np.random.default_rng(3)
    sy, model = plan_building(rng, 2, 0.06)
    t, ax, ay = _record(rng, 3.0, 0.01, 3.0)
    model.record = (t, ax, ay)
    out = _run(sy, _record_forcing(t, ax, ay), np.zeros(sy.state_size), t[-1], 1e-3)
    _ledger_closes(out)
    ref = reference(model, t[-1], np.zeros(2 * sy.n))
    assert len(ref.contact_starts) >= 10 and len({c for c, _ in ref.contact_starts}) >= 6
    # (the floor's turn moves the struck corner by a fifth of the gap and more: the lever is no bystander)
    turn = [abs(model.walls[c][0][2] * out.samples[np.searchsorted(out.samples[:, 0], t_c), 3])
            for c, t_c in ref.contact_starts]
    assert max(turn) > 0.2 * 0.06
    for action, rows in (("contact_start", ref.contact_starts), ("contact_end", ref.contact_ends),
                         ("yield", ref.yields), ("reversal", ref.sticks)):
        _assert_same_events(out, action, rows)


def _line_building(lever: bool):
    """A line of three masses on a bilinear isolator, a bilinear storey, Kelvin-Voigt walls at the base and
    a Hunt-Crossley bumper between the top two: every pair given a lever of arm 0 on another dof when
    ``lever``."""
    def arms(i, j):
        if not lever:
            return {}
        out = {"lever_i": (i + 1) % 3, "arm_i_m": 0.0}
        if j >= 0:
            out.update(lever_j=(j + 2) % 3 if (j + 2) % 3 != j else (j + 1) % 3, arm_j_m=0.0)
        return out

    mass = np.array([4.0e3, 2.5e3, 2.0e3])
    k0 = np.array([[0.0, 0.0, 0.0], [0.0, 3.0e6, -3.0e6], [0.0, -3.0e6, 3.0e6]])
    c0 = 1e-3 * k0
    elements = [_core.element(i=0, j=-1, c_d=800.0, slopes=[4.0e5, 4.0e4], breaks=[0.01], rule=0,
                              **arms(0, -1)),
                _core.element(i=1, j=0, c_d=0.0, slopes=[5.0e6, 1.0e6], breaks=[0.004], rule=0,
                              **arms(1, 0))]
    kv = np.zeros(_core.LAYOUT["N_LAW_PARAMS"])
    kv[:2] = 2.0e7, 4.0e3
    hc = pd_.HuntCrossley(stiffness=3.0e8, exponent=1.5, damping=0.4).params()
    contacts = [_core.contact_slot(i=0, j=-1, sign=s, gap_m=0.03, law=KELVIN_VOIGT, params=kv, **arms(0, -1))
                for s in (-1.0, 1.0)]
    contacts.append(_core.contact_slot(i=2, j=1, sign=1.0, gap_m=0.004, law=_core.LAW_IDS["hunt_crossley"],
                                       params=hc, **arms(2, 1)))
    return _core.system(mass, k0, c0, elements, True, contacts, tracked=((1, 0), (2, 1)))


def _same(a, b):
    return np.array_equal(a, b, equal_nan=True)


@pytest.mark.parametrize("excitation", ["record", "harmonic"])
def test_a_lever_of_arm_zero_is_no_lever(excitation):
    # every path a lever takes (forces, stiffness, event rows and their polynomials, velocity zeros, kept
    # transitions, the screens, the numerical phases) gives the plain pair's numbers when its arms are 0
    plain, levered = _line_building(False), _line_building(True)
    assert levered.levered and not plain.levered
    forcing = _forcing(excitation, 5, 6.0 if excitation == "record" else 5.0, 1.2, 0.0)
    a, b = (_run(sy, forcing, np.zeros(sy.state_size), 6.0, 0.01) for sy in (plain, levered))
    assert a.status == b.status == 0
    assert len(_events(a, "contact_start")) >= 4 and len(_events(a, "yield")) >= 4
    for name in ("state", "samples", "contacts", "events", "ledger", "extrema"):
        assert _same(getattr(a, name), getattr(b, name)), name


def test_a_system_with_levers_travels_by_pickle():
    import pickle

    sy, _ = plan_building(np.random.default_rng(3), 2, 0.06)  # (arms of metres: lost ones would show)
    again = pickle.loads(pickle.dumps(sy))
    assert again.levered and again.__getstate__() == sy.__getstate__()
    rng = np.random.default_rng(4)
    forcing = _record_forcing(*_record(rng, 2.0, 0.01, 3.0))
    a, b = (_run(s, forcing, np.zeros(s.state_size), 2.0, 0.01) for s in (sy, again))
    assert len(_events(a, "contact_start")) > 0
    for name in ("samples", "events", "contacts", "extrema", "norms"):
        assert _same(getattr(a, name), getattr(b, name)), name


def _refused(match, **changes):
    kv = np.zeros(_core.LAYOUT["N_LAW_PARAMS"])
    kv[:2] = 1e7, 1e3
    contact = dict(i=0, j=-1, sign=1.0, gap_m=0.05, law=KELVIN_VOIGT, params=kv)
    element = dict(i=0, j=-1, c_d=0.0, slopes=[1e6], breaks=[], rule=1)
    target = contact if changes.pop("on", "contact") == "contact" else element
    target.update(changes)
    with pytest.raises(ValueError, match=match):
        _core.system(np.ones(3), np.zeros((3, 3)), np.zeros((3, 3)), [_core.element(**element)], True,
                     [_core.contact_slot(**contact)])


def test_the_door_refuses_a_lever_it_cannot_carry():
    _refused("not another of the 3 dofs", lever_i=0, arm_i_m=1.0)  # (its own dof)
    _refused("not another of the 3 dofs", lever_i=3, arm_i_m=1.0)
    _refused("not another of the 3 dofs", lever_j=2, arm_j_m=1.0)  # (the ground's end)
    _refused("arm of end i", lever_i=2, arm_i_m=math.inf)
    _refused("arm of end i", on="element", lever_i=1, arm_i_m=math.nan)
    _refused("rigid stop on levers between two dofs", law=_core.LAW_IDS["rigid"], params=np.zeros(10), j=1,
             lever_i=2, arm_i_m=1.0)
    _refused("friction element on a lever", on="element", rule=2, friction_n=100.0, lever_i=2, arm_i_m=1.0)
    _refused("levers cancel", i=0, j=1, lever_i=1, arm_i_m=1.0, lever_j=0, arm_j_m=1.0)
    for builder in (_core.contact_slot, _core.element, _core.tracked_pair):  # (an arm the core would drop)
        kv = {_core.contact_slot: dict(sign=1.0, gap_m=0.05, law=KELVIN_VOIGT, params=[1e7]),
              _core.element: dict(c_d=0.0, slopes=[1e6], breaks=[], rule=1)}.get(builder, {})
        for arms in (dict(arm_i_m=2.0), dict(arm_j_m=-1.0), dict(lever_i=2, arm_i_m=math.nan)):
            with pytest.raises(ValueError, match="arm of end"):
                builder(i=0, j=1, **arms, **kv)
    sy = _line_building(True)
    with pytest.raises(ValueError, match="levers"):
        _core.monodromy(sy, np.zeros(sy.state_size), np.zeros((0, 3)), 1.0, 6.0, 1.0, 0.0)


def line_with_levers(rng, arm_scale=1.0):
    """Three masses on a line moved by one component (a plain table: kept transitions, whole steps and the
    screens on), whose elements and walls act on weighted combinations of them (levers of drawn arms): as the
    core takes it and as the reference restates it."""
    n = 3
    mass = rng.uniform(2e3, 6e3, n)
    k = np.zeros((n, n))
    for lo in range(n - 1):
        w = _weights(n, [(lo + 1, 1.0), (lo, -1.0)])
        k += rng.uniform(2e6, 8e6) * np.outer(w, w)
    c = 1e-3 * k
    k_ref, c_ref = k.copy(), c.copy()
    arm = rng.uniform(-0.6, 0.6, 6) * arm_scale
    elements, plastic = [], []
    for (i, li, ai, j, lj, aj), (k1, ratio, dy, c_d) in zip(
            [(0, 1, arm[0], -1, -1, 0.0), (1, 2, arm[1], 0, 2, arm[2])],
            [(rng.uniform(3e5, 8e5), rng.uniform(0.05, 0.3), rng.uniform(0.004, 0.015), rng.uniform(0, 2e3)),
             (rng.uniform(2e6, 6e6), rng.uniform(0.1, 0.5), rng.uniform(0.002, 0.006), 0.0)]):
        elements.append(_core.element(i=i, j=j, c_d=c_d, slopes=[k1, k1 * ratio], breaks=[dy], rule=0,
                                      lever_i=li, arm_i_m=ai, lever_j=lj, arm_j_m=aj))
        w = _weights(n, [(i, 1.0), (li, ai)] + ([(j, -1.0), (lj, -aj)] if j >= 0 else []))
        k_ref += k1 * ratio * np.outer(w, w)
        c_ref += c_d * np.outer(w, w)
        plastic.append((w, k1 * (1.0 - ratio), dy))
    k_b, c_b = rng.uniform(1e7, 5e7), rng.uniform(1e3, 1e4)
    params = np.zeros(_core.LAYOUT["N_LAW_PARAMS"])
    params[:2] = k_b, c_b
    contacts, walls = [], []
    gap = rng.uniform(0.01, 0.04)
    for i, li, ai, j, lj, aj, sign, g in [(0, 2, arm[3], -1, -1, 0.0, 1.0, gap),
                                          (0, 2, arm[3], -1, -1, 0.0, -1.0, gap),
                                          (2, 0, arm[4], 1, 0, arm[5], 1.0, gap / 3)]:
        contacts.append(_core.contact_slot(i=i, j=j, sign=sign, gap_m=g, law=KELVIN_VOIGT, params=params,
                                           lever_i=li, arm_i_m=ai, lever_j=lj, arm_j_m=aj))
        w = _weights(n, [(i, 1.0), (li, ai)] + ([(j, -1.0), (lj, -aj)] if j >= 0 else []))
        walls.append((w, sign, g, k_b, c_b))
    tracked = [_core.tracked_pair(i=p.i, j=p.j, lever_i=p.lever_i, arm_i_m=p.arm_i_m, lever_j=p.lever_j,
                                 arm_j_m=p.arm_j_m) for p in (*elements, contacts[0], contacts[2])]
    sy = _core.system(mass, k, c, elements, True, contacts, tracked)
    influence = np.column_stack([np.ones(n), np.zeros(n)])
    return sy, PlanModel(mass=mass, k=k_ref, c=c_ref, influence=influence, record=(np.zeros(1),) * 3,
                         plastic=plastic, walls=walls,
                         tracked=[w for w, _, _ in plastic] + [walls[0][0], walls[2][0]])


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), pga=st.floats(2.0, 6.0))
def test_levers_on_a_line_match_the_reference(seed, pga):
    rng = np.random.default_rng(seed)
    sy, model = line_with_levers(rng)
    assert sy.plain
    t, ax, _ = _record(rng, 2.5, 0.02, pga)  # (a step of several sub-intervals: some go whole)
    model.record = (t, ax, np.zeros_like(ax))
    forcing = _record_forcing(t, ax)
    ctl = _control.new_control(BUDGET)
    # (audited: each extremum or whole step the screens clear is looked at all the same, none escapes)
    out = _core.run(sy, forcing, np.zeros(sy.state_size), t[-1], 0.0, 1e-10, 10**6, True, ctl,
                    audit_screen=True)
    assert out.status == 0, out.status
    assert ctl[_core.LAYOUT["CTL_ESCAPES"]] == 0 and ctl[_core.LAYOUT["CTL_AUDITED"]] > 0
    _ledger_closes(out)
    try:
        ref = reference(model, t[-1], np.zeros(2 * sy.n))
    except TouchAtRest:
        assume(False)
    whole = int(ctl[_core.LAYOUT["CTL_WHOLE"]] > 0)
    event(f"{'walls struck' if ref.contact_starts else 'no wall struck'}, {whole} whole steps")
    for action, rows in (("contact_start", ref.contact_starts), ("contact_end", ref.contact_ends),
                         ("yield", ref.yields), ("reversal", ref.sticks)):
        _assert_same_events(out, action, rows)
    np.testing.assert_allclose(out.state[1:1 + 2 * sy.n], ref.y, rtol=0, atol=1e-8 * np.max(np.abs(ref.y)))
    _same_extrema(out, sy.n, ref)


@pytest.mark.parametrize("with_elements", [False, True])
@pytest.mark.parametrize("m, k, c, amp_x, amp_y, w", [(2.0, 80.0, 1.5, 0.7, 0.3, 4.1),
                                                     (1.0e4, 4.0e5, 0.0, 0.5, 1.2, 9.0),
                                                     (3.0, 30.0, 4.0, 0.2, 0.25, 3.0)])
def test_an_elliptic_orbit_s_longest_is_the_closed_form(with_elements, m, k, c, amp_x, amp_y, w):
    # a_x = A cos(w t), a_y = B sin(w t) on a linear isotropic oscillator: its steady orbit is the ellipse
    # x = Re(-A e^(i w t) / D), y = Re(i B e^(i w t) / D), D = k/m - w^2 + i c w/m, whose longest radius is
    # max(A, B) / |D|, reached twice a period inside the run's sub-intervals
    if with_elements:
        elements = [_core.element(i=i, j=-1, c_d=c, slopes=[k], breaks=[], rule=1) for i in (0, 1)]
        k0 = c0 = np.zeros((2, 2))
    else:
        elements, k0, c0 = [], k * np.eye(2), c * np.eye(2)
    sy = _core.system([m, m], k0, c0, elements, False, [], ((0, -1), (1, -1)), influence=np.eye(2),
                      vectors=((0, 1),))
    den = complex(k / m - w * w, c * w / m)
    zx, zy = -amp_x / den, 1j * amp_y / den
    state0 = np.zeros(sy.state_size)
    lay = sy.layout
    state0[lay["x"]:lay["x"] + 2] = zx.real, zy.real
    state0[lay["v"]:lay["v"] + 2] = (1j * w * zx).real, (1j * w * zy).real
    forcing = _core.Forcing(kind=_core.EXCITATION["harmonic"], p=np.array([amp_x, w, np.pi / 2, amp_y, 0.0]),
                            rec_t=np.zeros(1), rec_a=np.zeros(1))
    period = 2 * np.pi / w
    out = _run(sy, forcing, state0, 3.3 * period, 0.0)
    longest = max(amp_x, amp_y) / abs(den)
    np.testing.assert_allclose(out.norms[0, NX["max"]], longest, rtol=1e-9)
    # (reached where the closed form puts it: at a whole number of half periods past the phase of D)
    t_max = out.norms[0, NX["max_t"]]
    x, y = (z * np.exp(1j * w * t_max) for z in (zx, zy))
    np.testing.assert_allclose(np.hypot(x.real, y.real), longest, rtol=1e-9)
    assert 0.0 < t_max < 3.3 * period


def test_a_plan_building_s_exact_extrema_bound_its_samples():
    # a moat of Hunt-Crossley walls (a law integrated numerically while in contact: the absolute
    # accelerations' rates through the levers, the Dormand-Prince phases) struck at the corners: every sample
    # of every dof, of every tracked point and of every bearing's vector lies within the run's exact extrema,
    # and the extrema are reached (the samples come within a hair of them)
    rng = np.random.default_rng(21)
    sy, model = plan_building(rng, 2, 0.05, moat=pd_.HuntCrossley(stiffness=2.0e9, exponent=1.5, damping=0.3))
    t, ax, ay = _record(rng, 3.0, 0.01, 3.5)
    out = _run(sy, _record_forcing(t, ax, ay), np.zeros(sy.state_size), t[-1], 1e-4)
    assert out.status == 0
    assert len(_events(out, "contact_start")) >= 4
    _ledger_closes(out)
    n, s = sy.n, out.samples
    x, acc = s[:, 1:1 + n], s[:, 1 + 2 * n:1 + 3 * n]
    per_dof = out.per_dof(n)
    ex = _core.DOF_EXTREMA
    for q in range(n):
        scale = np.max(np.abs(x[:, q]))
        assert per_dof[q, ex["d_max"]] >= np.max(x[:, q]) - 1e-12 * scale
        assert per_dof[q, ex["d_min"]] <= np.min(x[:, q]) + 1e-12 * scale
        assert np.max(x[:, q]) >= per_dof[q, ex["d_max"]] - 1e-4 * scale
        top = per_dof[q, ex["a_abs_max"]]
        assert top >= np.max(np.abs(acc[:, q])) * (1.0 - 1e-9), q
        assert np.max(np.abs(acc[:, q])) >= top * (1.0 - 1e-2), q
    ws = [w for w, _, _ in model.plastic]
    u = x @ np.array(ws).T  # (each tracked point's samples)
    per_pair = out.per_pair(n)
    for p in range(len(ws)):
        scale = np.max(np.abs(u[:, p]))
        assert per_pair[p, PX["max"]] >= np.max(u[:, p]) - 1e-12 * scale
        assert per_pair[p, PX["min"]] <= np.min(u[:, p]) + 1e-12 * scale
    for v, (p, q) in enumerate(model.vectors):
        length = np.hypot(u[:, p], u[:, q])
        assert out.norms[v, NX["max"]] >= np.max(length) * (1.0 - 1e-12)
        assert np.max(length) >= out.norms[v, NX["max"]] * (1.0 - 1e-4)


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), arm_scale=st.sampled_from([10.0, 100.0]))
def test_long_levers_keep_the_screens_bounds(seed, arm_scale):
    # arms ten and a hundred times the line's (a lever's weights then dwarf a plain pair's 1 or 2): every
    # extremum and every whole step the screens clear is looked at all the same, and none lies beyond the
    # bound (the bound's sum |w| taken as a plain pair's lets 1,213 through at x10 on 40 draws)
    rng = np.random.default_rng(seed)
    sy, _ = line_with_levers(rng, arm_scale)
    t, ax, _ = _record(rng, 2.5, 0.02, 4.0)
    forcing = _record_forcing(t, ax)
    ctl = _control.new_control(BUDGET)
    out = _core.run(sy, forcing, np.zeros(sy.state_size), t[-1], 0.0, 1e-10, 10**6, True, ctl,
                    audit_screen=True)
    assert out.status == 0
    assert ctl[_core.LAYOUT["CTL_AUDITED"]] > 100
    assert ctl[_core.LAYOUT["CTL_ESCAPES"]] == 0


# A lever as a change of coordinates (the review's check): three dofs q (masses M), a ground pair on the lever
# w1 = q0 + 1.5 q1 and a pair between dofs on w2 = q2 - (q0 - 0.5 q1), M^-1-orthonormal; in the coordinates
# s = R M^1/2 q (unit masses, the table's influence R M^1/2 1) they are the plain pairs s0 and s1, so the same
# laws on plain pairs give the same motion
EQ_M, EQ_W1, EQ_W2 = np.array([4.0, 3.0, 1.5]), np.array([1.0, 1.5, 0.0]), np.array([-1.0, 0.5, 1.0])
EQ_LAWS = {
    "kelvin_voigt": lambda: pd_.KelvinVoigt(stiffness=4e5, damping=300.0),
    "hunt_crossley": lambda: pd_.HuntCrossley(stiffness=5e6, exponent=1.5, damping=0.5),
    "jankowski": lambda: pd_.Jankowski(stiffness=5e6, damping_ratio=0.2, effective_mass=2.0),
    "multilinear": lambda: pd_.MultilinearBumper(slopes=(2e5, 8e5), breakpoints=(0.004,), damping=150.0),
    "multilinear_kinematic": lambda: pd_.MultilinearBumper(slopes=(4e5, 5e4), breakpoints=(0.003,),
                                                           damping=100.0, hysteresis="kinematic"),
    "elastic_plastic": lambda: pd_.ElasticPlastic(stiffness=4e5, post_yield_stiffness=4e4,
                                                  yield_compression=0.003),
    "hertzdamp": lambda: pd_.Hertzdamp(stiffness=5e6, xi_norm=0.3),
}


def _coordinates():
    r0, r1 = EQ_W1 / np.sqrt(EQ_M), EQ_W2 / np.sqrt(EQ_M)
    r2 = np.cross(r0, r1)
    rot = np.vstack([r0, r1, r2 / np.linalg.norm(r2)])
    return rot, rot.T / np.sqrt(EQ_M)[:, None]  # (R, and T with q = T s)


def _twins(law1, law2, bouc_wen, rules):
    rot, t_of = _coordinates()
    k = np.array([[800.0, -240.0, 0.0], [-240.0, 472.0, -300.0], [0.0, -300.0, 3000.0]])
    c = 0.01 * k + np.diag([2.0, 1.0, 0.5])
    bw = pd_.BoucWen(stiffness_n_m=600.0, yield_displacement_m=0.004).kernel_array() if bouc_wen else ()
    (l1, p1), (l2, p2) = ((int(law.LAW_ID), law.params()) for law in (EQ_LAWS[law1](), EQ_LAWS[law2]()))

    def build(lever):
        e1, e2 = ((dict(i=0, j=-1, lever_i=1, arm_i_m=1.5), dict(i=2, j=0, lever_j=1, arm_j_m=-0.5)) if lever
                  else (dict(i=0, j=-1), dict(i=1, j=-1)))
        kk, cc = (k, c) if lever else (t_of.T @ k @ t_of, t_of.T @ c @ t_of)
        infl = None if lever else np.column_stack([rot @ np.sqrt(EQ_M), np.zeros(3)])
        els = [_core.element(c_d=40.0, slopes=[2e3, 300.0], breaks=[0.01], rule=rules[0], bw=bw, **e1),
               _core.element(c_d=0.0, slopes=[1.5e3, 400.0], breaks=[0.006], rule=rules[1], **e2)]
        cts = [_core.contact_slot(sign=s, gap_m=0.012, law=l1, params=p1, **e1) for s in (-1.0, 1.0)]
        cts.append(_core.contact_slot(sign=1.0, gap_m=0.004, law=l2, params=p2, **e2))
        tracked = [_core.tracked_pair(**e1), _core.tracked_pair(**e2)]
        return _core.system(EQ_M if lever else np.ones(3), kk, cc, els, True, cts, tracked,
                            influence=infl)

    return build(True), build(False), t_of


@pytest.mark.parametrize("law1, law2, bouc_wen, rules, excitation", [
    ("kelvin_voigt", "hunt_crossley", True, (0, 1), "record"),
    ("jankowski", "kelvin_voigt", False, (0, 1), "harmonic"),
    ("multilinear_kinematic", "hertzdamp", True, (1, 0), "record"),
    ("elastic_plastic", "multilinear", False, (0, 0), "harmonic"),
])
def test_a_lever_is_a_change_of_coordinates(law1, law2, bouc_wen, rules, excitation):
    # every law on a lever, a Bouc-Wen isolator on one (numerical phases that cut at a pair's velocity zero:
    # a levered pair's zero used to be found again a rounding's time on, for ever), elastic and kinematic
    # elements: the levered run is its plain twin's, mapped back, to rounding
    levered, plain, t_of = _twins(law1, law2, bouc_wen, rules)
    forcing = _forcing(excitation, 1, 10.0, 1.3, 0.2)
    a, b = (_run(sy, forcing, np.zeros(sy.state_size), 6.0, 0.01) for sy in (levered, plain))
    assert a.status == b.status == 0, (a.status, b.status)
    assert len(_events(a, "contact_start")) >= 2
    assert np.array_equal(a.events[:, 1:], b.events[:, 1:])
    np.testing.assert_allclose(a.events[:, 0], b.events[:, 0], rtol=0, atol=1e-9)
    n = 3
    # (the samples at a contact's start left out of the forces and accelerations: there Jankowski's dashpot,
    # of sqrt(sqrt(d)), turns the compression's rounding, 1e-20 m or 0, into 1e-3 N)
    away = ~np.isin(a.samples[:, 0], _events(a, "contact_start")[:, 0])
    for lo in (1, 1 + n, 1 + 2 * n):  # (displacements, velocities, absolute accelerations: q = T s)
        got, want = a.samples[away, lo:lo + n], b.samples[away, lo:lo + n] @ t_of.T
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-8 * np.abs(got).max())
    forces_a, forces_b = a.samples[away, 1 + 3 * n:], b.samples[away, 1 + 3 * n:]  # (elements', contacts')
    np.testing.assert_allclose(forces_a, forces_b, rtol=0, atol=1e-8 * np.abs(forces_a).max())
    np.testing.assert_allclose(a.per_pair(n), b.per_pair(n), rtol=0, atol=1e-8 * np.abs(a.per_pair(n)).max())
    np.testing.assert_allclose(a.ledger, b.ledger, rtol=0, atol=1e-8 * np.nanmax(np.abs(a.ledger)))
