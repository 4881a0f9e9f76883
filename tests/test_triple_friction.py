"""The triple friction pendulum (four friction surfaces in series, each with its ring) against the solve_ivp
reference with every stick, slip, surface slip and ring as an event (tests/reference_series_friction.py),
the closed forms of its five stages (Fenz and Constantinou) and invariants."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pounding as pd_
from reference_series_friction import ReferenceCapacity, SeriesStructure, reference

G = 9.81
EVENT_S = 1e-9  # the bound on an event's instant against the reference
TFP = dict(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08), capacities_m=(0.35, 0.05, 0.05, 0.35))


def _building(tfp: pd_.TripleFrictionPendulum, base_kg: float = 40_000.0, n_storeys: int = 3,
              damping: float = 1e5) -> pd_.Structure:
    return pd_.Structure(base_kg, tfp, [pd_.Storey(30_000.0, 6.0e7, damping)] * n_storeys, [])


def _reference_of(b: pd_.Structure, accel) -> SeriesStructure:
    iso = b.isolator
    k = iso.kernel_arrays()[0]
    return SeriesStructure(masses_kg=b.masses_kg, storey_k=np.array([s.stiffness_n_m for s in b.storeys]),
                           storey_c=np.array([s.damping_n_s_m for s in b.storeys]), k=k,
                           f=np.array(iso.friction_forces_n), cap=np.array(iso.series_capacities_m),
                           accel=accel, c_r=iso.damping_n_s_m, ring=iso.ring_stiffness_n_m or 0.0)


@st.composite
def triples(draw, stiff: bool = False):
    """A random building of 1 to 3 levels on a random triple friction pendulum, under a harmonic or a record
    (a random acceleration every 10 ms); ``stiff``: with stiff rings, shaken harder (its rings reached)."""
    r_in, r_out = draw(st.floats(0.2, 0.6)), draw(st.floats(1.5, 4.0))
    m_in = draw(st.floats(0.01, 0.03))
    if draw(st.booleans()):  # (the usual symmetric bearing: simultaneous slips and rings)
        m_out, cap_in, cap_out = m_in * draw(st.floats(1.2, 3.0)), draw(st.floats(0.03, 0.08)), \
            draw(st.floats(0.2, 0.5))
        radii, mu = (r_out, r_in, r_in, r_out), (m_out, m_in, m_in, m_out)
        caps = (cap_out, cap_in, cap_in, cap_out)
    else:
        radii = (r_out, r_in, r_in * draw(st.floats(0.8, 1.2)), r_out * draw(st.floats(0.8, 1.2)))
        inner = (m_in, m_in * draw(st.floats(0.8, 1.2)))
        mu = (max(inner) * draw(st.floats(1.2, 3.0)), *inner, max(inner) * draw(st.floats(1.2, 4.0)))
        caps = (draw(st.floats(0.2, 0.5)), draw(st.floats(0.03, 0.08)), draw(st.floats(0.03, 0.08)),
                draw(st.floats(0.2, 0.5)))
    ring = draw(st.floats(2e5, 5e7)) if stiff else None
    tfp = pd_.TripleFrictionPendulum(radii_m=radii, mu=mu, capacities_m=caps,
                                     damping_n_s_m=draw(st.sampled_from([0.0, 2e4])), ring_stiffness_n_m=ring)
    n = draw(st.integers(1, 3))
    storeys = [pd_.Storey(draw(st.floats(5e3, 3e4)), draw(st.floats(1e7, 8e7)), draw(st.floats(0.0, 2e5)))
               for _ in range(n - 1)]
    b = pd_.Structure(draw(st.floats(5e3, 4e4)), tfp, storeys, [])
    if draw(st.booleans()):
        a, f = draw(st.floats(0.3, 0.8) if stiff else st.floats(0.05, 0.4)), draw(st.floats(0.3, 1.5))

        def accel(t, a=a, f=f):
            return a * G * math.sin(2 * math.pi * f * t)
        return b, pd_.Harmonic(a, f), accel, None
    t = np.arange(0.0, 4.0001, 0.01)
    sd = draw(st.floats(3.0, 8.0) if stiff else st.floats(0.5, 3.0))
    acc = np.random.default_rng(draw(st.integers(0, 2**31))).normal(0.0, sd, t.size)

    def accel(tt, t=t, acc=acc):
        return float(np.interp(tt, t, acc))
    return b, pd_.Record(t, acc), accel, t


def _events(run) -> list:
    ev = run.events
    return [(float(t), k, int(i) if k in ("surface_slip", "ring", "ring_off") else -1)
            for t, k, i in zip(ev["t_s"], ev["kind"], ev["index"])]


def _grouped(events: list, ref) -> list:
    """``events`` with each surface slip named by the lowest of the surfaces the reference started at that
    instant: surfaces whose thresholds are one to rounding start together, the event naming whichever the
    rounding put first."""
    out = []
    for t, kind, i in events:
        if kind == "surface_slip":
            i = next((min(group) for tg, group in ref.slip_groups if abs(tg - t) < 1e-6 and i in group), i)
        out.append((t, kind, i))
    return out


def _in_order(events: list) -> list:
    """Events at one instant (two rings at once) in one order, by kind and index."""
    return sorted(events, key=lambda e: (round(e[0], 9), e[1], e[2]))


def _untouched(ref) -> list:
    """The reference's events without a slip from a stick that sticks again with its bearing moved by no
    more than the rounding of the run's lengths (1e-12 of its largest displacement): where the force needed
    to hold the bearing touches its threshold, the engine takes such a slip back (a touch starts no slip, as
    for a single surface); seen: a slip of 17 us that moved the bearing 1e-14 m."""
    u = ref.x[:, 0]  # (the base's displacement: the bearing's)
    scale = max(float(np.abs(u).max()), 1e-3)

    def u_at(t: float) -> float:
        k = int(np.searchsorted(ref.t, t, side="right")) - 1
        assert ref.t[k] == t  # (a phase's end: an event's instant)
        return float(u[k])

    events, out, k = ref.events, [], 0
    while k < len(events):
        if (events[k][1] == "slip" and k + 1 < len(events) and events[k + 1][1] == "stick"
                and out and out[-1][1] == "stick"
                and abs(u_at(events[k + 1][0]) - u_at(events[k][0])) <= 1e-12 * scale):
            k += 2
            continue
        out.append(events[k])
        k += 1
    return out


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(triples())
def test_every_stage_change_matches_the_reference(case):
    _matches_the_reference(case)


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(triples(stiff=True))
def test_stiff_rings_match_the_reference(case):
    """Stiff rings: each surface slides on against its ring and comes off it on the way back, its entry
    (``ring``) and exit (``ring_off``) events on the reference's, the run never stopping at a capacity."""
    b, excitation, _, _ = case
    assert pd_.simulate(b, excitation, 4.0, rtol=1e-12).status == pd_.Status.SUCCESS
    _matches_the_reference(case)


REFERENCE_RTOL_TIGHTEST = 3e-14  # (scipy's floor is 100 eps = 2.2e-14)


def _matches_the_reference(case) -> None:
    """Events within 1e-9 s of the reference's, the final state and the friction's work within 1e-8."""
    b, excitation, accel, knots = case
    run = pd_.simulate(b, excitation, 4.0, rtol=1e-12)
    # (stiff rings: the reference at 1e-13; at 1e-12 its slow threshold crossings after a reversal drifted up
    # to 5.5e-9 s from the engine's instants, at 1e-13 to 3.6e-10 s)
    stiff = bool(b.isolator.ring_stiffness_n_m)
    try:
        return _agrees(run, b, accel, knots, {"rtol": 1e-13, "atol": 1e-16} if stiff else {})
    except AssertionError:
        if not stiff:
            raise
        # the reference is not always converged at 1e-13: where it disagrees it is run once more at the
        # tightest scipy takes, and the engine must agree with that (hypothesis: a ring's exit 1.32e-9 s from
        # the engine's at 1e-13, 4.4e-13 s at 5e-14 and 3e-14)
        return _agrees(run, b, accel, knots, {"rtol": REFERENCE_RTOL_TIGHTEST, "atol": 1e-16})


def _agrees(run, b, accel, knots, tight: dict):
    """The run against the reference at the tolerances ``tight``: its events (returned, grouped), final state,
    friction work and surfaces' slips."""
    t_end = float(run.summary()["t_end_s"])
    engine = _events(run)
    try:
        ref = reference(_reference_of(b, accel), t_end, knots=knots, **tight)
    except ReferenceCapacity:  # (its last event the engine's stop: both at the travel's end)
        assert run.status == pd_.Status.CAPACITY
        return None
    if run.status == pd_.Status.CAPACITY:  # (the reference's last phase ends on the engine's last rings:
        assert engine[-1][1] == "ring"     # a symmetric bearing's last two surfaces reach theirs at once)
        engine = [e for e in engine if not (e[1] == "ring" and e[0] == engine[-1][0])]
    engine, expected = _in_order(_grouped(engine, ref)), _in_order(_grouped(_untouched(ref), ref))
    assert [e[1:] for e in engine] == [e[1:] for e in expected]
    assert max((abs(a[0] - e[0]) for a, e in zip(engine, expected)), default=0.0) < EVENT_S
    n = b.masses_kg.size
    assert np.allclose(run.final_state.vector[1:1 + n], ref.x[-1], rtol=0.0, atol=1e-8)
    assert run.energy.hysteretic == pytest.approx(ref.friction_j, rel=1e-8, abs=1e-6)
    if run.status == pd_.Status.SUCCESS:
        lay = run.final_state.layout
        u = run.final_state.vector[lay["base"]:lay["base"] + 4]
        assert np.allclose(u, ref.u_end, rtol=0.0, atol=1e-8)
    return engine


@pytest.mark.parametrize("symmetric", [True, False])
def test_a_bearing_driven_onto_its_stiff_rings_matches_the_reference(symmetric):
    """Driven onto its stiff rings and off them every half cycle (a symmetric bearing: two surfaces at
    once), or under a record: every entry and exit on the reference's, within 1e-9 s."""
    if symmetric:
        tfp = pd_.TripleFrictionPendulum(radii_m=(2.0, 0.4, 0.4, 2.0), mu=(0.05, 0.02, 0.02, 0.05),
                                         capacities_m=(0.3, 0.05, 0.05, 0.3), ring_stiffness_n_m=5e6)
        b = pd_.Structure(20_000.0, tfp, [pd_.Storey(2e4, 4e7, 1e5)], [])

        def accel(t):
            return 0.6 * G * math.sin(2 * math.pi * 0.5 * t)
        case = (b, pd_.Harmonic(0.6, 0.5), accel, None)
    else:
        tfp = pd_.TripleFrictionPendulum(radii_m=(1.8, 0.35, 0.3, 2.4), mu=(0.06, 0.02, 0.025, 0.09),
                                         capacities_m=(0.25, 0.04, 0.06, 0.3), ring_stiffness_n_m=2e6,
                                         damping_n_s_m=2e4)
        b = _building(tfp, base_kg=20_000.0, n_storeys=2)
        t = np.arange(0.0, 4.0001, 0.01)
        acc = 6.0 * np.sin(2 * np.pi * 0.45 * t) + np.random.default_rng(7).normal(0.0, 2.0, t.size)

        def accel(tt):
            return float(np.interp(tt, t, acc))
        case = (b, pd_.Record(t, acc), accel, t)
    kinds = [k for _, k, _ in _matches_the_reference(case)]
    assert kinds.count("ring") >= 4 and kinds.count("ring_off") >= 2


def test_stiff_rings_stiffen_the_slide_and_converge_to_rigid_ones():
    """Past every ring a slide from rest goes on with the surfaces' springs and rings in series,
    ``1 / sum 1 / (W / R_i + k_r)``; the same run's peak displacement comes down to the rigid rings' travel
    as the rings stiffen (as ``1 / sqrt(k_r)``, the bearing's motion into them), and the ledger closes with
    the rings' stored energy."""
    w = _building(pd_.TripleFrictionPendulum(**TFP)).isolator.weight_n
    k = np.array([w / r for r in pd_.TripleFrictionPendulum(**TFP).series_radii_m])
    peaks = []
    for ring in (1e9, 1e10, 1e11):
        b = _building(pd_.TripleFrictionPendulum(**TFP, ring_stiffness_n_m=ring))
        iso = b.isolator
        assert iso.slopes_n_m[-1] == pytest.approx(1.0 / np.sum(1.0 / (k + ring)), rel=1e-12)
        last = iso.breakpoints_m[-1]  # (every surface on its ring: past the travel, the rings giving)
        assert last > iso.travel_m and len(iso.slopes_n_m) == len(iso.breakpoints_m) + 1
        step = np.diff(iso.backbone(np.array([last, 1.5 * last])))[0]
        assert step == pytest.approx(iso.slopes_n_m[-1] * 0.5 * last, rel=1e-9)
        run = pd_.simulate(b, pd_.Harmonic(a_g=0.5, freq_hz=0.5), 6.0)
        assert run.success and "ring_off" in set(run.events["kind"])
        assert abs(run.summary()["energy_residual_j"]) < 1e-9 * run.summary()["input_work_j"]
        peaks.append(abs(run.summary()["displacement_min_m"]))
    travel = _building(pd_.TripleFrictionPendulum(**TFP)).isolator.travel_m
    excess = np.array(peaks) - travel
    assert np.all(excess > 0.0) and np.all(excess[1:] < excess[:-1] / 2.0) and excess[-1] < 5e-3


def test_its_stages_are_fenz_and_constantinou_s():
    """The series' slide from rest has the bearing's five stiffnesses and stage changes (Fenz and
    Constantinou 2008: I on 2 and 3, II on 1 and 3, III on 1 and 4, IV on 2 and 4, V on 2 and 3)."""
    tfp = _building(pd_.TripleFrictionPendulum(**TFP)).isolator
    w = tfp.weight_n
    r1, r2, r3, r4 = tfp.radii_m
    m1, m2, m3, m4 = tfp.mu
    d1, d2, d3, d4 = tfp.capacities_m
    assert tfp.slopes_n_m == pytest.approx([w / (r2 + r3), w / (r1 + r3), w / (r1 + r4), w / (r2 + r4),
                                            w / (r2 + r3)], rel=1e-12)
    u_2 = (m1 - m2) * r2 + (m1 - m3) * r3  # (stage II begins at mu1 W)
    u_3 = u_2 + (m4 - m1) * (r1 + r3)  # (III at mu4 W)
    f_ring1 = m1 * w + w * d1 / r1  # (IV where surface 1 reaches its ring)
    u_4 = u_3 + (f_ring1 - m4 * w) * (r1 + r4) / w
    f_ring4 = m4 * w + w * d4 / r4
    u_5 = u_4 + (f_ring4 - f_ring1) * (r2 + r4) / w
    assert tfp.breakpoints_m[:4] == pytest.approx([u_2, u_3, u_4, u_5], rel=1e-12)
    # (V ends where 2 and 3 reach theirs: each slid d2, d3 in all, in stages I and IV to V)
    assert tfp.breakpoints_m[4] == pytest.approx(tfp.travel_m, rel=1e-12)
    assert tfp.travel_m == pytest.approx(d1 + d2 + d3 + d4, rel=1e-12)
    assert tfp.backbone(np.array([-u_3, u_3])) == pytest.approx([-m4 * w, m4 * w], rel=1e-12)


def test_the_ledger_closes_and_a_continued_run_is_one_long_run():
    b = _building(pd_.TripleFrictionPendulum(**TFP))
    ex = pd_.Harmonic(a_g=0.15, freq_hz=0.5)
    one = pd_.simulate(b, ex, 8.0)
    assert one.success and one.summary()["slips"] >= 1
    assert abs(one.summary()["energy_residual_j"]) < 1e-9 * one.summary()["input_work_j"]
    first = pd_.simulate(b, ex, 3.7)
    rest = pd_.simulate(b, ex, 4.3, first.final_state)
    assert np.allclose(rest.final_state.vector, one.final_state.vector, rtol=0.0, atol=1e-12)


def test_the_mirror_run_is_the_run_mirrored():
    b = _building(pd_.TripleFrictionPendulum(**TFP))
    up = pd_.simulate(b, pd_.Harmonic(a_g=0.2, freq_hz=0.6), 6.0)
    down = pd_.simulate(b, pd_.Harmonic(a_g=-0.2, freq_hz=0.6), 6.0)
    assert _events(up) and [e[1:] for e in _events(up)] == [e[1:] for e in _events(down)]
    assert np.allclose(up.final_state.vector[1:5], -down.final_state.vector[1:5], rtol=0.0, atol=1e-12)


def test_a_bearing_that_uses_up_its_travel_stops_the_run_saying_so():
    b = _building(pd_.TripleFrictionPendulum(**TFP))
    run = pd_.simulate(b, pd_.Harmonic(a_g=0.5, freq_hz=0.5), 6.0)
    assert run.status == pd_.Status.CAPACITY and not run.success
    assert "travel" in run.status.message
    assert abs(run.summary()["displacement_min_m"]) == pytest.approx(b.isolator.travel_m, rel=1e-9)
    assert list(run.events["kind"]).count("ring") == 4


def test_a_triple_friction_pendulum_round_trips_through_toml_and_is_refused_by_name():
    from pounding.model.oscillator import isolator_from_dict

    tfp = pd_.TripleFrictionPendulum(**TFP, damping_n_s_m=1e3)
    assert isolator_from_dict(tfp.to_dict()) == tfp
    stiff = pd_.TripleFrictionPendulum(**TFP, ring_stiffness_n_m=2e6)
    assert isolator_from_dict(stiff.to_dict()) == stiff and stiff.to_dict()["ring_stiffness_n_m"] == 2e6
    b = _building(tfp)
    assert b.isolator.weight_n == pytest.approx(G * b.masses_kg.sum())
    for kwargs, field in [(dict(TFP, radii_m=(2.1, 0.3, 0.3)), "isolator.radii_m"),
                          (dict(TFP, radii_m=(0.2, 0.3, 0.3, 2.1)), "isolator.radii_m[0]"),
                          (dict(TFP, mu=(0.05, 0.06, 0.02, 0.08)), "isolator.mu"),
                          (dict(TFP, capacities_m=(0.35, -0.05, 0.05, 0.35)), "isolator.capacities_m[1]"),
                          (dict(TFP, mu=(0.05, 0.02, math.nan, 0.08)), "isolator.mu[2]"),
                          (dict(TFP, ring_stiffness_n_m=-1e6), "isolator.ring_stiffness_n_m"),
                          (dict(TFP, ring_stiffness_n_m=math.inf), "isolator.ring_stiffness_n_m")]:
        with pytest.raises(pd_.InputError) as err:
            pd_.TripleFrictionPendulum(**kwargs)
        assert err.value.field == field


def test_a_state_whose_surfaces_do_not_sum_to_the_base_is_refused():
    b = _building(pd_.TripleFrictionPendulum(**TFP))
    ex = pd_.Harmonic(a_g=0.15, freq_hz=0.5)
    first = pd_.simulate(b, ex, 3.7)
    v = first.final_state.vector.copy()
    v[first.final_state.layout["base"]] += 0.01
    with pytest.raises(pd_.InputError, match="sum to"):
        pd_.simulate(b, ex, 1.0, pd_.State(v, first.final_state.dofs, first.final_state.layout))


def test_what_it_cannot_do_is_refused_by_name():
    """A start beyond the rigid rings' travel and a run continued from one that used up the travel are
    refused, naming the field."""
    b = _building(pd_.TripleFrictionPendulum(**TFP))
    with pytest.raises(pd_.InputError, match="travel") as err:
        pd_.State.at_rest(b, displacement_m=-1.01 * b.isolator.travel_m)
    assert err.value.field == "displacement_m"
    ex = pd_.Harmonic(a_g=0.5, freq_hz=0.5)
    stopped = pd_.simulate(b, ex, 6.0)
    assert stopped.status == pd_.Status.CAPACITY
    with pytest.raises(pd_.InputError, match="travel used up"):
        pd_.simulate(b, ex, 2.0, stopped.final_state)


@pytest.mark.parametrize("ring", [None, 5e6])
@pytest.mark.parametrize("d", [0.0, 0.02, -0.3, 0.72, -0.9])
def test_a_start_off_centre_is_where_a_slow_push_leaves_it_and_runs_as_the_reference(d, ring):
    """State.at_rest off centre: each surface where a slow push from the centre leaves it (they sum to the
    displacement; every one that slid holds the slide's force there, its rigid ring's at its ring; the mirror
    push the mirror state); run from there, moving, against the reference started from the same state."""
    tfp = pd_.TripleFrictionPendulum(**TFP, ring_stiffness_n_m=ring)
    b = _building(tfp, n_storeys=2)
    iso = b.isolator
    if ring is None and abs(d) > iso.travel_m:
        with pytest.raises(pd_.InputError, match="travel"):
            pd_.State.at_rest(b, displacement_m=d)
        return
    state = pd_.State.at_rest(b, displacement_m=d, velocity_m_s=-0.3 * math.copysign(1.0, d))
    lay = state.layout
    u_g = state.vector[lay["base"]:lay["base"] + 4]
    held = state.vector[lay["base"] + lay["n_springs"]:lay["base"] + lay["n_springs"] + 4]
    assert u_g.sum() == pytest.approx(d, rel=1e-12)
    k, f, cap = iso.kernel_arrays()[0], np.array(iso.friction_forces_n), np.array(iso.series_capacities_m)
    spring = k * u_g + (ring or 0.0) * np.sign(u_g) * np.maximum(np.abs(u_g) - cap, 0.0)
    slid = (u_g != 0.0) & (held == 0.0)
    assert np.allclose((spring + np.sign(d) * f)[slid], iso.backbone(d), rtol=1e-12)
    assert np.allclose(np.abs(u_g[held != 0.0]), cap[held != 0.0], rtol=1e-12)
    mirror = pd_.State.at_rest(b, displacement_m=-d).vector
    assert np.array_equal(mirror[lay["base"]:lay["base"] + 8], -state.vector[lay["base"]:lay["base"] + 8])

    def accel(t):
        return 0.15 * G * math.sin(2 * math.pi * 0.6 * t)
    run = pd_.simulate(b, pd_.Harmonic(0.15, 0.6), 3.0, state, rtol=1e-12)
    x0 = state.displacements_m
    ref = reference(_reference_of(b, accel), 3.0,
                    start=(x0, state.velocities_m_s, u_g, held))
    engine, expected = _in_order(_grouped(_events(run), ref)), _in_order(_grouped(_untouched(ref), ref))
    assert [e[1:] for e in engine] == [e[1:] for e in expected] and len(engine) >= 3
    assert max(abs(a[0] - e[0]) for a, e in zip(engine, expected)) < EVENT_S
    assert np.allclose(run.final_state.displacements_m, ref.x[-1], rtol=0.0, atol=1e-8)


def test_rings_that_leave_no_surface_slipping_jump_to_the_next_threshold():
    """Inner rings reached before mu1 W: the series, rigid for an instant, takes the force that starts the
    next surface (a jump in force at one displacement); the run goes on, as the reference does."""
    tfp = pd_.TripleFrictionPendulum(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.10, 0.01, 0.01, 0.12),
                                     capacities_m=(0.05, 0.01, 0.01, 0.05))
    b = _building(tfp, n_storeys=0)
    u, f, _ = b.isolator._backbone_points()
    assert np.any((np.diff(u) == 0.0) & (np.diff(f) > 0.0))
    assert b.isolator.breakpoints_m[-1] == pytest.approx(0.12)

    def accel(t):
        return 0.1 * G * math.sin(2 * math.pi * 0.5 * t)
    run = pd_.simulate(b, pd_.Harmonic(0.1, 0.5), 3.0, rtol=1e-12)
    assert run.success and abs(run.summary()["energy_residual_j"]) < 1e-9 * run.summary()["input_work_j"]
    ref = reference(_reference_of(b, accel), 3.0)
    engine, expected = _in_order(_events(run)), _in_order(ref.events)
    assert [e[1:] for e in engine] == [e[1:] for e in expected]
    assert max(abs(a[0] - e[0]) for a, e in zip(engine, expected)) < EVENT_S


def test_its_loop_is_drawn_with_its_stages():
    """plot_isolator_loop draws a triple friction pendulum's loop with its slide from rest both ways, which
    the loop's first slide follows."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    b = _building(pd_.TripleFrictionPendulum(**TFP))
    run = pd_.simulate(b, pd_.Harmonic(a_g=0.2, freq_hz=0.5), 6.0)
    artists = pd_.plots.plot_isolator_loop(run)
    stages = [a for a in artists if a.get_label() == "slide from rest (stages)"]
    assert len(stages) == 1 and len(artists) == 3
    u_mm, f_kn = stages[0].get_data()
    assert np.allclose(f_kn, b.isolator.backbone(u_mm * 1e-3) / 1e3, equal_nan=True)
    plt.close("all")


def test_a_pair_s_second_building_on_stiff_rings_lists_its_own_entries_and_exits():
    """In a pair, the building on a triple friction pendulum with stiff rings lists its surfaces' slips,
    ring entries and exits, numbered from 0 as its own; the other building none of them."""
    import dataclasses
    from pathlib import Path

    pair = pd_.Adjacent.from_toml(Path(__file__).parents[1] / "examples" / "adjacent_buildings.toml")
    tfp = pd_.TripleFrictionPendulum(radii_m=(2.0, 0.4, 0.4, 2.0), mu=(0.05, 0.02, 0.02, 0.05),
                                     capacities_m=(0.3, 0.05, 0.05, 0.3), ring_stiffness_n_m=5e6)
    pair = dataclasses.replace(pair, second=dataclasses.replace(pair.second, isolator=tfp,
                                                                base_mass_kg=30_000.0))
    run = pd_.simulate(pair, pd_.Harmonic(0.6, 0.5), 5.0)
    assert run.success
    mine = run.second.events[run.second.events["kind"].isin(["surface_slip", "ring", "ring_off"])]
    assert set(mine["kind"]) == {"surface_slip", "ring", "ring_off"}
    assert set(mine["index"]) == {0, 1, 2, 3}
    assert not run.first.events["kind"].isin(["surface_slip", "ring", "ring_off"]).any()
    s = run.summary()
    assert (s["second_surface_slips"], s["second_rings"]) == (list(mine["kind"]).count("surface_slip"),
                                                              list(mine["kind"]).count("ring"))
    everyone = run.events["kind"]
    assert (everyone == "ring_off").sum() == (mine["kind"] == "ring_off").sum()


def test_a_stiff_surface_s_state_must_match_where_it_is():
    """A state whose stiff surface is marked on its ring while within its travel, or within its travel while
    past its ring, is refused by its place in the vector."""
    b = _building(pd_.TripleFrictionPendulum(**TFP, ring_stiffness_n_m=2e7))
    ex = pd_.Harmonic(0.6, 0.4)
    run = pd_.simulate(b, ex, 3.1)
    lay = run.final_state.layout
    states = slice(lay["base"] + lay["n_springs"], lay["base"] + lay["n_springs"] + 4)
    v = run.final_state.vector
    assert np.all(np.abs(v[states]) == 3.0)  # (every surface on its ring, sliding)
    for change in (lambda w: w.__setitem__(states, w[states] / 3.0),  # (as if within their travels)
                   lambda w: w.__setitem__(lay["base"], 0.01 * np.sign(w[lay["base"]]))):
        w = v.copy()
        change(w)
        if w[lay["base"]] != v[lay["base"]]:  # (surface 0 back within its travel: the rest keep the sum)
            w[lay["base"] + 1] += v[lay["base"]] - w[lay["base"]]
        with pytest.raises(pd_.InputError, match="travel"):
            pd_.simulate(b, ex, 1.0, pd_.State(w, run.final_state.dofs, lay))
    assert pd_.simulate(b, ex, 1.0, run.final_state).success


def test_a_touch_of_a_surface_s_threshold_leaves_every_surface_where_it_was():
    """A table that only touches the inner surfaces' threshold: the touch is taken back, the bearing and
    each of its surfaces exactly where they were (their displacements still summing to the bearing's)."""
    osc = pd_.Oscillator(1000.0, pd_.TripleFrictionPendulum(**TFP))
    run = pd_.simulate(osc, pd_.Harmonic(0.02, 1.0), 3.0)
    lay = run.final_state.layout
    assert run.final_state.displacement_m == 0.0
    assert np.array_equal(run.final_state.vector[lay["base"]:lay["base"] + 4], np.zeros(4))


@pytest.mark.parametrize("a_g, freq_hz, phase, ring", [(0.2, 0.5, 0.0, None), (0.3, 0.8, 0.0, None),
                                                        (0.4, 0.45, 2.5, 5e6)])
def test_a_periodic_orbit_is_the_map_s_fixed_point_with_its_multipliers(a_g, freq_hz, phase, ring):
    """A single mass's periodic orbit on a triple friction pendulum (its monodromy composed exactly): a fixed
    point of the run over a period (to 1e-11 m), and its multipliers those of that map differenced here
    through simulate in the map's coordinates (the base's x and v, and each surface held at
    the section), each state built from the series' own law (the slipping surfaces where the force puts
    them): every surface slipping at the section, or one held, or one on its stiff ring."""
    tfp = pd_.TripleFrictionPendulum(**TFP, ring_stiffness_n_m=ring)
    osc = pd_.Oscillator(1e4 if ring is None else 2e4, tfp)
    exc = pd_.Harmonic(a_g, freq_hz, phase=phase)
    orbit = pd_.periodic_orbit(osc, exc, settle_cycles=30 if ring is None else 200)
    assert orbit.converged and orbit.stable and orbit.method == "exact", orbit.message
    st, lay = orbit.state, orbit.state.layout
    k, f = osc.isolator.kernel_arrays()[0], np.array(osc.isolator.friction_forces_n)
    d = np.array(osc.isolator.series_capacities_m)
    s = st.vector[lay["region"]]
    states = st.vector[lay["base"] + lay["n_springs"]:lay["base"] + lay["n_springs"] + 4]
    on = (states == s) | (states == 3 * s)
    assert s != 0.0 and on.any() and (ring is None or (states == 3 * s).any())
    stiff = np.where(states == 3 * s, k + (ring or 0.0), k)  # (on its stiff ring: k + k_r, and an offset)
    side = np.where(states == 3 * s, (ring or 0.0) * d * np.sign(st.vector[lay["base"]:lay["base"] + 4]), 0.0)

    base = lay["base"]
    held = np.flatnonzero(states == 0.0)  # (each a coordinate of the map: where it is held)

    def state_at(p: np.ndarray) -> pd_.State:  # (x, v, the held surfaces)
        vec = st.vector.copy()
        vec[lay["x"]], vec[lay["v"]] = p[0], p[1]
        vec[base + held] = p[2:]
        force = (p[0] - vec[base + held].sum() + np.sum((s * f[on] - side[on]) / stiff[on])) / np.sum(
            1.0 / stiff[on])
        vec[base:base + 4][on] = (force - s * f[on] + side[on]) / stiff[on]
        return pd_.State(vec, st.dofs, lay)

    def image(p: np.ndarray) -> np.ndarray:
        end = pd_.simulate(osc, exc, 1.0 / freq_hz, state_at(p), sample_rate_hz=0).final_state
        return np.array([end.displacement_m, end.velocity_m_s, *end.vector[base + held]])

    p0 = np.array([st.displacement_m, st.velocity_m_s, *st.vector[base + held]])
    assert np.allclose(image(p0), p0, rtol=0.0, atol=1e-11)
    h = 1e-6
    jac = np.column_stack([(image(p0 + h * e) - image(p0 - h * e)) / (2 * h) for e in np.eye(p0.size)])
    mine = np.sort_complex(np.linalg.eigvals(jac))
    assert np.allclose(mine, np.sort_complex(orbit.multipliers), rtol=0.0, atol=1e-6)


def test_an_orbit_s_multipliers_are_the_same_whether_the_section_sticks_or_slips():
    """Sections in a stick and in a slip of one orbit: the same multipliers (a stuck bearing's surface that
    slips first follows the base; the ones that never slip are constants, no coordinates)."""
    osc = pd_.Oscillator(1e4, pd_.TripleFrictionPendulum(**TFP))
    stuck = pd_.periodic_orbit(osc, pd_.Harmonic(0.025, 1.5), settle_cycles=60)
    slipping = pd_.periodic_orbit(osc, pd_.Harmonic(0.025, 1.5, phase=1.0), settle_cycles=60)
    lay = stuck.state.layout
    assert stuck.state.vector[lay["region"]] == 0.0 and slipping.state.vector[lay["region"]] != 0.0
    assert np.abs(stuck.multipliers).max() == pytest.approx(np.abs(slipping.multipliers).max(), rel=1e-6)
    assert np.abs(stuck.multipliers).max() < 0.9  # (not a frozen surface's 1)


def test_a_branch_of_orbits_and_the_lyapunov_exponents_of_a_triple_friction_pendulum():
    """Continuation follows its orbits across a frequency range (each where periodic_orbit finds it), and
    the Lyapunov spectrum of a periodic response is its multipliers' ln|mu| / T."""
    osc = pd_.Oscillator(1e4, pd_.TripleFrictionPendulum(**TFP))
    branch = pd_.continuation(osc, 0.15, (0.5, 1.2))
    frame = branch.to_dataframe()
    assert frame["freq_hz"].max() == pytest.approx(1.2) and frame["stable"].all()
    mid = frame.iloc[(frame["freq_hz"] - 0.8).abs().argmin()]
    orbit = pd_.periodic_orbit(osc, pd_.Harmonic(0.15, float(mid["freq_hz"])), settle_cycles=30)
    assert orbit.alpha == pytest.approx(float(mid["alpha"]), rel=1e-6)
    spectrum = pd_.lyapunov(osc, pd_.Harmonic(0.15, 0.7), cycles=200, transient_cycles=50)
    orbit = pd_.periodic_orbit(osc, pd_.Harmonic(0.15, 0.7), settle_cycles=30)
    expected = np.log(np.abs(orbit.multipliers).max()) * 0.7
    assert spectrum.exponents[0] == pytest.approx(expected, rel=1e-3)


def test_basins_start_a_triple_friction_pendulum_off_centre():
    """Basins of a single mass on a triple friction pendulum against bumpers: its initial states off centre
    (State.at_rest) each settle on a response."""
    tfp = pd_.TripleFrictionPendulum(radii_m=(2.0, 0.4, 0.4, 2.0), mu=(0.05, 0.02, 0.02, 0.05),
                                     capacities_m=(0.3, 0.05, 0.05, 0.3), ring_stiffness_n_m=5e6)
    osc = pd_.Oscillator(500.0, tfp, pd_.Bumpers(gap_left_m=0.3, gap_right_m=0.3,
                                                 law=pd_.KelvinVoigt(2e6, 500.0)))
    b = pd_.basins(osc, pd_.Harmonic(0.15, 0.5), displacement_m=(-0.25, 0.25), velocity_m_s=(-0.5, 0.5),
                   n=(3, 3), workers=1)
    assert len(b.attractors) >= 2 and b.attractors["fraction"].sum() == pytest.approx(1.0)


def test_a_stuck_section_s_steps_keep_the_surfaces_on_the_base_and_its_layout_follows_them():
    """At a section where the bearing sticks: a step along any one coordinate (as a grazing's scaling takes
    them, without the layout's embedding) leaves the surfaces summing to the base's displacement, the
    first to slip following it; and a state of the same mode whose first to slip is another surface gets
    its own layout (not the one cached for the first)."""
    from pounding.analysis._shooter import _Shooter

    osc = pd_.Oscillator(1e4, pd_.TripleFrictionPendulum(**TFP))
    exc = pd_.Harmonic(0.025, 1.5)
    orbit = pd_.periodic_orbit(osc, exc, settle_cycles=60)
    vec, lay = np.array(orbit.state.vector), orbit.state.layout
    base = lay["base"]
    assert vec[lay["region"]] == 0.0
    sh = _Shooter(osc, exc, 1 / 1.5, False)
    free, emb = sh._layout(vec)
    for q in range(emb.shape[0]):
        moved = sh._moved(vec, np.eye(emb.shape[0])[q] * 1e-7)
        assert moved[lay["x"]] - moved[base:base + 4].sum() == pytest.approx(0.0, abs=1e-15)
        sh._image(moved)  # (a state of the system: it runs)
    other = vec.copy()
    other[base] -= 0.06  # (same mode; surface 0 now the first to slip)
    other[base + 3] += 0.06
    assert sh.names(other) == [sh._names[i] for i in sh._new_layout(other, ())[0]] != sh.names(vec)


def test_a_surface_s_slip_inside_a_short_slip_is_found_whatever_the_run_s_length():
    """A slip from rest so short that it crosses a held surface's threshold and sticks again inside one
    sub-interval (the surface's guard dips below zero and comes back): the surface's slip is found in runs of
    every length, and a run continued at its end is the one long run.  (Found by a review: at a slip from
    rest the pair's acceleration is zero but for the rounding, whose sign had the guard rising at the start
    and the velocity's zero found at the start itself; runs longer than 0.92 s missed the surface's slip.)"""
    mu_out, mu_in = 0.0515552292951012, 0.01995535499736283
    tfp = pd_.TripleFrictionPendulum(radii_m=(1.6, 0.5, 0.5, 1.6), mu=(mu_out, mu_in, mu_in, mu_out),
                                     capacities_m=(0.3794394027646527, 0.07960883287238998,
                                                   0.06402395755721013, 0.5120610596425584),
                                     damping_n_s_m=20000.0, ring_stiffness_n_m=24959546.30814191)
    osc = pd_.Oscillator(26523.026550384122, tfp)
    table = pd_.Harmonic(0.02, 0.3)
    rest = pd_.simulate(osc, table, 10.0, sample_rate_hz=0).final_state  # (stuck)
    vec, base = rest.vector.copy(), rest.layout["base"]
    vec[base + 1] -= 0.5e-6  # (the inner surfaces 1e-6 m apart, the same sum: one slips first)
    vec[base + 2] += 0.5e-6
    start = pd_.State(vec, rest.dofs, rest.layout)
    ends = []
    for duration in (0.92, 0.95, 2.0):
        run = pd_.simulate(osc, table, duration, start, sample_rate_hz=0)
        assert list(run.events["kind"][:3]) == ["slip", "surface_slip", "stick"], (duration, run.events)
        ends.append(run.final_state.vector[base:base + 4])
    np.testing.assert_array_equal(ends[1], ends[0])  # (stuck after the stick: nothing moves)
    half = pd_.simulate(osc, table, 0.95, start, sample_rate_hz=0)
    rest_of = pd_.simulate(osc, table, 1.05, half.final_state, sample_rate_hz=0)
    np.testing.assert_array_equal(rest_of.final_state.vector, pd_.simulate(osc, table, 2.0, start,
                                                                           sample_rate_hz=0).final_state.vector)


def test_a_stick_whose_force_turns_twice_inside_a_sub_interval_still_slips():
    """A stuck bearing whose tie's force, rising at both ends of a record's 10 ms interval, falls across its
    threshold and back between two turns inside it (hypothesis found it: seed 241352 of its records): the
    sub-interval is cut where the force's rate turns, and the 4 ms slip at 1.2944 s that the reference takes
    is found, every event then the reference's.  (Without the cut the engine stayed stuck there, the same on
    the build before this stop's changes.)"""
    mu_out = 0.027070272936040297
    tfp = pd_.TripleFrictionPendulum(radii_m=(1.5, 0.36237392216241504, 0.4222248564906086,
                                              1.2000000000000002),
                                     mu=(mu_out, 0.019899678907458106, 0.02255856078003358, mu_out),
                                     capacities_m=(0.47461077714333, 0.04850811856876388, 0.0706400156055815,
                                                   0.34983510672120777), damping_n_s_m=20000.0)
    b = pd_.Structure(10000.0, tfp, [pd_.Storey(22758.848261809628, 34810122.96591607, 0.0)], [])
    t = np.arange(0.0, 4.0001, 0.01)
    acc = np.random.default_rng(241352).normal(0.0, 0.6546157638966267, t.size)

    def accel(tt):
        return float(np.interp(tt, t, acc))

    run = pd_.simulate(b, pd_.Record(t, acc), 1.33, rtol=1e-12)
    near = [(round(s, 6), k) for s, k in zip(run.events["t_s"], run.events["kind"]) if 1.29 < s < 1.3]
    assert near == [(1.294376, "slip"), (1.298472, "stick")]
    _matches_the_reference((b, pd_.Record(t, acc), accel, t))
