"""Friction isolators (flat sliders and friction pendulums) against the solve_ivp reference with stick and
slip events (tests/reference_friction.py), Den Hartog's exact steady state, closed forms and invariants."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pounding as pd_
from reference_friction import FrictionStructure, den_hartog, reference

G = 9.81
EVENT_S = 1e-9  # the bound on a stick's or a slip's instant against the reference


def _system(s: FrictionStructure) -> pd_.Structure:
    """The reference's structure as the package's: its base on a friction isolator, its storeys."""
    radius = None if s.k_r == 0.0 else G * float(np.sum(s.masses_kg)) / s.k_r
    iso = pd_.FrictionIsolator(mu=s.mu, radius_m=radius, damping_n_s_m=s.c_r, mu_fast=s.mu_fast,
                               rate_s_m=s.rate_s_m)
    storeys = [pd_.Storey(float(m), float(k), float(c)) for m, k, c in zip(s.masses_kg[1:], s.storey_k,
                                                                            s.storey_c)]
    return pd_.Structure(float(s.masses_kg[0]), iso, storeys, [])


@st.composite
def frictions(draw, velocity_dependent: bool = False):
    """A random structure of 1 to 4 levels on a flat slider or a friction pendulum, under a harmonic or a
    record (a random acceleration every 10 ms), moving at the start or at rest; ``velocity_dependent``: its
    friction's coefficient goes from mu at rest to mu_fast (larger or smaller) at a random rate."""
    n = draw(st.integers(1, 4))
    masses = np.array([draw(st.floats(1e3, 5e3)) for _ in range(n)])
    weight = G * masses.sum()
    k_r = 0.0 if draw(st.booleans()) else weight / draw(st.floats(1.0, 4.0))
    ks = np.array([draw(st.floats(1e6, 5e7)) for _ in range(n - 1)])
    cs = np.array([draw(st.floats(0.0, 5e4)) for _ in range(n - 1)])
    c_r = draw(st.sampled_from([0.0, draw(st.floats(0.0, 2e4))]))
    mu = draw(st.floats(0.01, 0.2))
    if draw(st.booleans()):
        a, f, phase = draw(st.floats(0.1, 0.6)), draw(st.floats(0.5, 3.0)), draw(st.floats(0.0, 6.28))
        def accel(t, a=a, f=f, phase=phase):
            return a * G * math.sin(2 * math.pi * f * t + phase)
        excitation, knots = pd_.Harmonic(a, f, phase=phase), None
    else:
        seed = draw(st.integers(0, 2**31))
        t = np.arange(0.0, 2.0001, 0.01)
        acc = np.random.default_rng(seed).normal(0.0, 2.0, t.size)
        def accel(tt, t=t, acc=acc):
            return float(np.interp(tt, t, acc))
        excitation, knots = pd_.Record(t, acc), t
    v0 = draw(st.sampled_from([0.0, draw(st.floats(-0.3, 0.3))]))
    mu_fast, rate = ((draw(st.floats(0.01, 0.2)), draw(st.floats(5.0, 100.0))) if velocity_dependent
                     else (None, 0.0))
    structure = FrictionStructure(masses, ks, cs, k_r, c_r, mu, accel, mu_fast=mu_fast, rate_s_m=rate)
    return structure, excitation, knots, v0


def _events(run) -> list[tuple[float, str]]:
    return [(float(t), str(k)) for t, k in zip(run.events["t_s"], run.events["kind"])]


def _reference_events(ref, moving: bool) -> list[tuple[float, str]]:
    """The reference's sticks, slips from rest and reversals as the engine names them (a start that moves is
    a slip the engine does not list: it starts slipping)."""
    out = [(t, "stick") for t in ref.sticks if t > 0.0 or moving]
    out += [(t, "reversal") for t in ref.reversals]
    out += [(t, "slip") for t, _ in ref.slips if t not in ref.reversals and not (t == 0.0 and moving)]
    return sorted(out)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(frictions())
def test_stick_and_slip_match_the_reference(case):
    """Random structures on friction isolators: every stick, slip and reversal at the reference's instant
    within 1e-9 s, the final state and the friction work to 1e-8 of their scales."""
    _matches_the_reference(case)


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(frictions(velocity_dependent=True))
def test_a_velocity_dependent_friction_matches_the_reference(case):
    """The same with a velocity-dependent friction, its slips integrated numerically, the engine's and the
    reference's at tolerances a decade tighter than their defaults (1e-12 and 1e-13: at theirs a slip that
    ends slowly, its velocity's slope small, ends up to 9e-9 s apart, the reference the further from the
    converged instant)."""
    _matches_the_reference(case, rtol=1e-12)


TOUCH_M = 1e-12  # a slip from a stick that moves the base less: a touch of mu W, not an event


def _without_touches(mine: list, theirs: list, ref) -> tuple[list, list]:
    """Both event lists without the touches: a slip from a stick that moves the base less than
    ``TOUCH_M`` before it sticks again.  The engine takes such a slip back as a touch of mu W when it moved
    the base no more than the rounding of the run's lengths (256 eps times them, about 1e-13 m here), and
    the reference lists every one: hypothesis found a force needed to hold 5e-4 over mu W for 21 us, whose
    slip moved the base 7.6e-14 m, listed by the reference and taken back by the engine."""
    touches = []
    for (t0, k0), (t1, k1) in zip(theirs, theirs[1:]):
        if k0 == "slip" and k1 == "stick":
            i0, i1 = np.searchsorted(ref.t, [t0, t1])
            if abs(ref.x[i1, 0] - ref.x[i0, 0]) < TOUCH_M:
                touches.append((t0, t1))

    def keep(events: list) -> list:
        out = list(events)
        for t0, t1 in touches:
            out = [(t, k) for t, k in out if not ((k == "slip" and abs(t - t0) <= EVENT_S)
                                                 or (k == "stick" and abs(t - t1) <= EVENT_S))]
        return out

    return keep(mine), keep(theirs)


def _matches_the_reference(case, rtol: float = 1e-10) -> None:
    s, excitation, knots, v0 = case
    duration = 2.0
    tight = {} if rtol == 1e-10 else {"rtol": 0.1 * rtol, "atol": 1e-16}
    ref = reference(s, duration, np.zeros(s.n), np.full(s.n, v0), knots=knots, **tight)
    system = _system(s)
    start = pd_.State.at_rest(system, velocity_m_s=v0)
    run = pd_.simulate(system, excitation, duration, start, sample_rate_hz=0, rtol=rtol)
    assert run.success
    mine, theirs = _without_touches(_events(run), _reference_events(ref, v0 != 0.0), ref)
    assert [k for _, k in mine] == [k for _, k in theirs]
    assert max((abs(a - b) for (a, _), (b, _) in zip(mine, theirs)), default=0.0) <= EVENT_S
    scale = max(np.abs(ref.x).max(), 1e-3)
    np.testing.assert_allclose(run.final_state.displacements_m, ref.x[-1], rtol=0, atol=1e-8 * scale)
    assert run.energy.hysteretic == pytest.approx(ref.friction_j, rel=1e-8, abs=1e-9 * abs(ref.input_work_j))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(frictions())
def test_the_ledger_closes_and_the_friction_never_exceeds_mu_w(case):
    """The input work equals the viscous and friction works plus the change of the stored energies (to 1e-9
    of the input); the friction force, the isolator's force less its spring and dashpot, is never more than
    mu W, and a stuck base does not move."""
    s, excitation, _, v0 = case
    system = _system(s)
    run = pd_.simulate(system, excitation, 2.0, pd_.State.at_rest(system, velocity_m_s=v0),
                       sample_rate_hz=2000.0)
    e = run.energy
    stored = e.kinetic + e.elastic + e.contact_elastic
    assert e.input_work == pytest.approx(e.viscous + e.hysteretic + e.contact_dissipation + stored,
                                         rel=0, abs=1e-9 * max(abs(e.input_work), 1.0))
    frame = run.to_dataframe()
    iso = system.isolator
    u, du = frame["displacement_m[0]"].to_numpy(), frame["velocity_m_s[0]"].to_numpy()
    t = frame["t_s"].to_numpy()
    friction = frame["isolator_force_n"].to_numpy() - iso.restoring_stiffness_n_m * u - s.c_r * du
    assert np.abs(friction).max() <= iso.friction_force_n * (1 + 1e-9)
    kinds = _events(run)
    for (t0, k0), (t1, _) in zip(kinds, kinds[1:] + [(2.0, "end")]):
        if k0 != "stick":
            continue
        inside = (t > t0) & (t <= t1)  # (a sample at t0 is the slip's end, at its root: moving by rounding)
        assert np.all(du[inside] == 0.0) and (not inside.any() or np.ptp(u[inside]) == 0.0)


@pytest.mark.parametrize("radius_m, storey_c, excess, table_m_s2",
                         [(None, 0.0, 1e-3, 0.0), (None, 500.0, 1e-2, 0.0), (2.0, 0.0, 1e-2, 0.0),
                          (2.0, 2e3, 0.05, 0.0), (None, 500.0, 0.05, 1e-40), (2.0, 2e3, 0.05, 1e-20)])
def test_a_storey_swinging_its_stuck_base_past_mu_w_slips_and_sticks_at_the_reference_s_instants(
        radius_m, storey_c, excess, table_m_s2):
    """A base stuck on its slider, its storey swinging free (no table, or a constant one of next to nothing):
    the force needed to hold the base passes mu W near each swing's peak, the base's acceleration there zero
    but for the rounding.  Each slip ends where the base's velocity comes back to zero, not at once on that
    rounding's sign (before the mend: a slip of no length and a stick, again and again, until the run
    stopped as Zeno); every instant is the reference's within 1e-9 s, and the final state its own."""
    masses = np.array([2.0e4, 2.0e4])
    k_r = 0.0 if radius_m is None else G * masses.sum() / radius_m
    s = FrictionStructure(masses, np.array([4.0e7]), np.array([storey_c]), k_r, 0.0, 0.05,
                          lambda t: table_m_s2)
    w = math.sqrt(4.0e7 / 2.0e4)
    v0 = np.array([0.0, s.friction_n / 4.0e7 * (1.0 + excess) * w])
    knots = np.arange(0.0, 0.3001, 0.01)
    ref = reference(s, 0.3, np.zeros(2), v0, knots=knots)
    system = _system(s)
    start = pd_.State.at_rest(system)
    vector = np.array(start.vector)
    vector[start.layout["v"]:start.layout["v"] + 2] = v0
    start = dataclasses.replace(start, vector=vector)
    table = pd_.Record(knots, np.full(knots.size, table_m_s2))
    run = pd_.simulate(system, table, 0.3, start, sample_rate_hz=0)
    assert run.success, run.message
    mine, theirs = _without_touches(_events(run), _reference_events(ref, False), ref)
    assert [k for _, k in mine] == [k for _, k in theirs] and len(mine) >= 4, (mine, theirs)
    assert max(abs(a - b) for (a, _), (b, _) in zip(mine, theirs)) <= EVENT_S
    np.testing.assert_allclose(run.final_state.displacements_m, ref.x[-1], rtol=0,
                               atol=1e-8 * np.abs(ref.x).max())


def test_the_samples_inside_a_touch_taken_back_show_the_base_held():
    """A record whose knot makes the force needed to hold the base touch mu W (hypothesis found it): the
    slip it starts is taken back, and the sample at the knot, inside it, shows the base held (no velocity,
    no drift), as every sample inside every stick does."""
    iso = pd_.FrictionIsolator(mu=0.06694994405309965, radius_m=3.3125, damping_n_s_m=255.0)
    b = pd_.Structure(4383.0, iso, [pd_.Storey(4117.0, 35309951.0, 15149.0)], [])
    t = np.arange(0.0, 2.0001, 0.01)
    run = pd_.simulate(b, pd_.Record(t, np.random.default_rng(0).normal(0.0, 2.0, t.size)), 2.0,
                       sample_rate_hz=2000.0)
    frame = run.to_dataframe()
    ts, u, du = (frame[c].to_numpy() for c in ("t_s", "displacement_m[0]", "velocity_m_s[0]"))
    kinds = _events(run)
    sticks = [(t0, t1) for (t0, k0), (t1, _) in zip(kinds, kinds[1:] + [(2.0, "end")]) if k0 == "stick"]
    assert any(t0 < 0.64 < t1 for t0, t1 in sticks)  # (the touch: at the knot 0.64 s, inside a stick)
    for t0, t1 in sticks:
        inside = (ts > t0) & (ts <= t1)
        assert np.all(du[inside] == 0.0) and (not inside.any() or np.ptp(u[inside]) == 0.0)


def test_a_flat_slider_s_mass_accelerates_at_mu_g():
    """A mass on a flat slider: while it slips its absolute acceleration is mu g exactly, so its largest
    is mu g (Coulomb's closed form)."""
    run = pd_.simulate(pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.07)), pd_.Harmonic(0.3, 1.0), 5.0)
    assert run.quantities()["acc_max_g"] == pytest.approx(0.07, rel=1e-12)
    assert (run.events["kind"] == "reversal").sum() >= 8


@pytest.mark.filterwarnings("ignore::pounding._errors.PoundingWarning")  # (implausible mu and R: valid)
@settings(max_examples=25, deadline=None)
@given(b=st.floats(0.3, 3.0), ratio=st.floats(0.0, 0.6), m=st.floats(100.0, 5000.0), fn=st.floats(0.2, 2.0))
def test_a_non_stop_steady_state_is_den_hartog_s(b, ratio, m, fn):
    """Den Hartog's exact non-stop motion through the engine: started at his x0 at rest with his phase, the
    mass reverses at half the period at -x0 and returns to x0, to 1e-9 (a friction pendulum under the
    force P0 cos(w t + phi), the table's -P0/m cos)."""
    from hypothesis import assume

    assume(abs(b - 1.0) > 0.05 and abs(b - 1.0 / 3.0) > 0.02)
    k = m * (2 * math.pi * fn) ** 2
    omega = b * 2 * math.pi * fn
    p0 = 1000.0
    x0, phi = den_hartog(m, k, ratio * p0, p0, omega)
    assume(np.isfinite(x0) and -k * x0 + p0 * math.cos(phi) < -ratio * p0 * (1 + 1e-6))
    mu = ratio * p0 / (G * m)
    assume(mu == 0.0 or mu >= 1e-6)
    iso = (pd_.FrictionIsolator(mu=mu, radius_m=G * m / k) if mu > 0.0 else
           pd_.Isolator([k], hysteresis="elastic"))
    system = pd_.Oscillator(m, iso)
    excitation = pd_.Harmonic(p0 / (m * G), omega / (2 * math.pi), phase=phi - math.pi / 2)
    period = 2 * math.pi / omega
    start = dataclasses.replace(pd_.State.at_rest(system, displacement_m=x0))
    run = pd_.simulate(system, excitation, period, start, sample_rate_hz=0)
    assert run.success
    if mu > 0.0:  # (a stop would not be Den Hartog's motion: there is none)
        kinds = _events(run)
        assert [k for _, k in kinds if k == "stick"] == []
        turns = [t for t, k in kinds if k == "reversal" and t < period * (1 - 1e-9)]
        assert len(turns) == 1 and turns[0] == pytest.approx(period / 2, rel=0, abs=1e-9 * period)
    assert run.displacement_min == pytest.approx(-x0, rel=1e-9)
    assert run.final_state.displacement_m == pytest.approx(x0, rel=1e-9)


@pytest.mark.parametrize("mu", [0.1, 0.125, 0.2])
@pytest.mark.parametrize("phase", [0.0, math.pi / 2])
@pytest.mark.parametrize("radius_m", [None, 2.0])
def test_a_table_that_touches_mu_w_does_not_slip(mu, phase, radius_m):
    """A mass on a flat slider or a friction pendulum under a table whose acceleration peaks at exactly mu g:
    the force needed to hold it touches mu W at each peak without passing it (at the start and at the run's
    end too, with the phase pi / 2), so it never slips (no slip and stick of no length at the peaks); a
    table a millionth stronger slips at every peak, a short slip and its stick."""
    system = pd_.Oscillator(1000.0, pd_.FrictionIsolator(mu=mu, radius_m=radius_m))
    run = pd_.simulate(system, pd_.Harmonic(mu, 1.0, phase=phase), 2.0, sample_rate_hz=100.0)
    frame = run.to_dataframe()
    assert len(run.events) == 0 and len(frame) == 201
    assert np.all(np.abs(frame["displacement_m"]) <= 1e-30) and run.final_state.velocity_m_s == 0.0
    stronger = pd_.simulate(system, pd_.Harmonic(mu * (1 + 1e-6), 1.0), 2.0, sample_rate_hz=0)
    kinds, t = list(stronger.events["kind"]), stronger.events["t_s"].to_numpy()
    assert kinds == ["slip", "stick"] * 4
    assert np.all(np.diff(t)[::2] > 1e-4) and np.all(np.abs(t[::2] - [0.25, 0.75, 1.25, 1.75]) < 1e-3)

def _pendulum_building(sign: float = 1.0) -> tuple[pd_.Structure, pd_.Harmonic]:
    storeys = [pd_.Storey(3.0e3, 4.0e7, 4.0e4), pd_.Storey(3.0e3, 3.0e7, 3.0e4),
               pd_.Storey(2.0e3, 2.0e7, 2.0e4)]
    return (pd_.Structure(4.0e3, pd_.FrictionIsolator(mu=0.1, radius_m=2.0), storeys, []),
            pd_.Harmonic(sign * 0.3, 1.5))


def test_the_mirror_run_is_the_run_mirrored():
    system, shake = _pendulum_building()
    run = pd_.simulate(system, shake, 6.0, sample_rate_hz=0)
    mirror = pd_.simulate(system, _pendulum_building(-1.0)[1], 6.0, sample_rate_hz=0)
    assert list(mirror.events["kind"]) == list(run.events["kind"])
    np.testing.assert_allclose(mirror.events["t_s"], run.events["t_s"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(mirror.final_state.displacements_m, -run.final_state.displacements_m, rtol=0,
                               atol=1e-14)


def test_a_continued_run_is_one_long_run():
    """Cut while it sticks and while it slips, and continued from the final state: the same run."""
    system, shake = _pendulum_building()
    whole = pd_.simulate(system, shake, 6.0, sample_rate_hz=0)
    for cut in (1.0, 2.35):
        first = pd_.simulate(system, shake, cut, sample_rate_hz=0)
        rest = pd_.simulate(system, shake, 6.0 - cut, first.final_state, sample_rate_hz=0)
        assert list(first.events["kind"]) + list(rest.events["kind"]) == list(whole.events["kind"])
        np.testing.assert_allclose(rest.final_state.displacements_m, whole.final_state.displacements_m,
                                   rtol=0, atol=1e-12)
    kinds = set(whole.events["kind"])
    assert {"stick", "slip"} <= kinds


@pytest.mark.parametrize("preslip_m", [1e-4, 1e-5, 1e-6])
def test_an_elastic_pre_slip_converges_to_the_exact_stick(preslip_m):
    """OpenSees' sliders ring through each stick on a stiff pre-slip branch: with a pre-slip, the isolator is
    that model (exact too); its peak and residual base displacements approach the rigid stick's as the
    pre-slip shrinks, within 30 times the pre-slip."""
    system, shake = _pendulum_building()
    exact = pd_.simulate(system, shake, 6.0, sample_rate_hz=0)
    smeared_system = dataclasses.replace(system, isolator=dataclasses.replace(system.isolator,
                                                                              preslip_m=preslip_m))
    assert smeared_system.isolator.hysteresis == "kinematic"
    smeared = pd_.simulate(smeared_system, shake, 6.0, sample_rate_hz=0)
    assert smeared.quantities()["disp_max_m"] == pytest.approx(exact.quantities()["disp_max_m"], rel=0,
                                                               abs=30 * preslip_m)
    np.testing.assert_allclose(smeared.final_state.displacements_m, exact.final_state.displacements_m,
                               rtol=0, atol=30 * preslip_m)


def test_against_bumpers_its_sticks_are_exact_and_few():
    """A friction pendulum against compliant bumpers in steady harmonic motion: every stick and slip lasts
    longer than a microsecond (no chatter of zero-length slips), and each cycle has the same events (here
    14: four impacts' starts and ends and six reversals)."""
    law = pd_.KelvinVoigt(2.0e6, 500.0)
    system = pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05, radius_m=1.5),
                            pd_.Bumpers(gap_left_m=0.03, gap_right_m=0.03, law=law))
    shake = pd_.Harmonic(0.3, 1.0)
    run = pd_.simulate(system, shake, 40.0, sample_rate_hz=0)
    assert run.success
    ev = run.events[run.events["t_s"] > 20.0]
    friction = ev[ev["kind"].isin(["stick", "slip", "reversal"])]
    assert len(friction) > 0 and np.diff(friction["t_s"].to_numpy()).min() > 1e-6
    per_cycle = np.bincount(np.floor(ev["t_s"].to_numpy()).astype(int) - 20)
    assert np.all(per_cycle == per_cycle[0]) and per_cycle[0] == 14


def test_a_sweep_against_bumpers_counts_its_events_and_its_sticks_are_exact():
    """A sweep of a friction pendulum against bumpers: each step's table gives the events and the sticks per
    cycle of its window; they are the events of the window run again from its state, the same in every cycle
    of its period, and every stick and slip there lasts longer than a microsecond (no chatter)."""
    from pounding.engine.assembly import assemble

    system = pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05, radius_m=1.5),
                            pd_.Bumpers(gap_left_m=0.03, gap_right_m=0.03, law=pd_.KelvinVoigt(2.0e6, 500.0)))
    sw = pd_.sweep(system, 0.1, [0.5, 1.0])
    assert sw.status == pd_.Status.SUCCESS and sw.period_multiple.tolist() == [1, 1]
    table = sw.to_dataframe()
    assert table["sticks_per_cycle"].tolist() == [2.0, 0.0]  # (sticks at 0.5 Hz; at 1 Hz a non-stop slide)
    asm = assemble(system)
    for i, f in enumerate(sw.freqs_hz):
        m = int(sw.window_cycles[i])
        state = pd_.State._of(sw.window_states[i], asm.dofs, asm.system.layout)
        exc = pd_.Harmonic(0.1, f, phase=-(2 * math.pi * f * float(sw.step_start_s[i])))
        run = pd_.simulate(system, exc, m / f, state, sample_rate_hz=0)
        assert run.success
        ev = run.events
        assert len(ev) == sw.window_events[i, 0] == table["events_per_cycle"][i] * m
        assert (ev["kind"] == "stick").sum() == sw.window_events[i, 1]
        cycle = np.floor((ev["t_s"].to_numpy() - state.time_s) * f + 1e-9).astype(int)
        assert np.all(np.bincount(cycle, minlength=m) == table["events_per_cycle"][i])
        friction = ev[ev["kind"].isin(["stick", "slip", "reversal"])]["t_s"].to_numpy()
        assert len(friction) > 0 and np.diff(friction).min() > 1e-6


def test_a_friction_isolator_s_toml_round_trips_and_its_weight_follows_the_system(tmp_path):
    system, _ = _pendulum_building()
    assert system.isolator.weight_n == pytest.approx(G * 12.0e3)
    path = system.to_toml(tmp_path / "fps.toml")
    text = path.read_text()
    assert "mu = 0.1" in text and "weight_n" not in text
    assert pd_.Structure.from_toml(path) == system
    heavier = dataclasses.replace(system, base_mass_kg=8.0e3)
    assert heavier.isolator.weight_n == pytest.approx(G * 16.0e3)
    given_weight = dataclasses.replace(system, isolator=pd_.FrictionIsolator(mu=0.1, radius_m=2.0,
                                                                             weight_n=1.0e5))
    assert dataclasses.replace(given_weight, base_mass_kg=8.0e3).isolator.weight_n == 1.0e5
    assert given_weight.isolator.restoring_stiffness_n_m == pytest.approx(5.0e4)


@pytest.mark.parametrize("kwargs, field", [
    ({"mu": 0.0}, "isolator.mu"),
    ({"mu": 1.5}, "isolator.mu"),
    ({"mu": math.nan}, "isolator.mu"),
    ({"mu": 0.05, "radius_m": -1.0}, "isolator.radius_m"),
    ({"mu": 0.05, "preslip_m": -1e-3}, "isolator.preslip_m"),
    ({"mu": 0.05, "weight_n": 0.0}, "isolator.weight_n"),
    ({"mu": 0.05, "damping_n_s_m": -1.0}, "isolator.damping_n_s_m"),
    ({"mu": 0.05, "weight_carried": True}, "isolator.weight_carried"),
    ({"mu": 0.05, "mu_fast": 0.1}, "isolator.mu_fast"),
    ({"mu": 0.05, "rate_s_m": 20.0}, "isolator.rate_s_m"),
    ({"mu": 0.05, "mu_fast": 0.1, "rate_s_m": -1.0}, "isolator.rate_s_m"),
    ({"mu": 0.05, "mu_fast": 0.0, "rate_s_m": 20.0}, "isolator.mu_fast"),
])
def test_bad_friction_isolators_are_refused_by_name(kwargs, field):
    with pytest.raises(pd_.InputError) as info:
        pd_.FrictionIsolator(**kwargs)
    assert info.value.field == field


def test_a_velocity_dependent_slip_s_friction_is_its_law_and_the_ledger_closes():
    """A building on a friction pendulum whose friction grows from mu 0.05 at rest to 0.11 fast (OpenSees'
    VelDependent): at every sample of a slip the friction (the isolator's force less its spring) is
    W (mu_fast - (mu_fast - mu) exp(-rate |v|)) to 1e-9 of mu W, the ledger closes to 1e-9 of the input,
    it round-trips through TOML, and its slips are larger than a Coulomb slider's at mu_fast."""
    system, shake = _pendulum_building()
    iso = pd_.FrictionIsolator(mu=0.05, radius_m=2.0, mu_fast=0.11, rate_s_m=25.0)
    system = dataclasses.replace(system, isolator=iso)
    iso = system.isolator
    assert iso.friction_at(0.0) == pytest.approx(iso.friction_force_n)
    assert iso.friction_at(10.0) == pytest.approx(iso.friction_fast_force_n)
    run = pd_.simulate(system, shake, 6.0, sample_rate_hz=500.0)
    e = run.energy
    assert e.residual == pytest.approx(0.0, abs=1e-9 * e.input_work)
    frame = run.to_dataframe()
    u, du = frame["displacement_m[0]"].to_numpy(), frame["velocity_m_s[0]"].to_numpy()
    friction = frame["isolator_force_n"].to_numpy() - iso.restoring_stiffness_n_m * u
    slipping = du != 0.0
    assert slipping.sum() > 100
    np.testing.assert_allclose(np.abs(friction[slipping]), iso.friction_at(du[slipping]), rtol=0,
                               atol=1e-9 * iso.friction_force_n)
    moving = np.abs(du) > 1e-12  # (a reversal's sample: its velocity zero to rounding, either sign)
    assert np.all(np.sign(friction[moving]) == np.sign(du[moving]))
    assert pd_.Structure.from_dict(system.to_dict()) == system
    coulomb = dataclasses.replace(system, isolator=pd_.FrictionIsolator(mu=0.11, radius_m=2.0))
    fast = pd_.simulate(coulomb, shake, 6.0).summary()
    assert run.summary()["displacement_max_m"] > fast["displacement_max_m"]


def test_a_velocity_dependent_slip_s_largest_absolute_acceleration_is_above_every_sample():
    # the extremum is located where the acceleration's rate crosses zero; that rate holds the friction's
    # own, (F_fast - F) rate e^(-rate |u'|) u'' (without it the peak was 3.3e-5 below the samples' largest).
    # Sampled at 80 kHz the samples' largest is the peak to 1.1e-9 and 2.2e-8 (measured)
    rec = pd_.records.el_centro().scaled(pga_g=0.8)
    line = pd_.Structure(3e5, pd_.FrictionIsolator(mu=0.06, radius_m=2.2, mu_fast=0.11, rate_s_m=20.0),
                         [pd_.Storey(3e5, 3e8, 2e5)], [])
    run = pd_.simulate(line, rec, 4.0, sample_rate_hz=80000.0)
    sampled = np.max(np.abs(run.abs_acceleration), axis=0)
    assert np.all(sampled <= run.abs_acceleration_max * (1.0 + 1e-12))
    np.testing.assert_allclose(run.abs_acceleration_max, sampled, rtol=1e-7)


def test_a_pre_slip_too_stiff_for_the_weight_and_a_slip_against_its_velocity_are_refused_by_name():
    with pytest.raises(pd_.InputError, match="under the weight") as info:
        pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05, preslip_m=1e-15))
    assert info.value.field == "isolator.preslip_m"
    system = pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05, radius_m=1.5))
    start = pd_.State.at_rest(system, velocity_m_s=-0.3)
    vector = np.array(start.vector, dtype=float)
    vector[start.layout["region"]] = 1.0  # (slipping the way it does not move)
    with pytest.raises(pd_.InputError, match="against its pair's velocity") as info:
        pd_.simulate(system, pd_.Harmonic(0.1, 1.0), 1.0, dataclasses.replace(start, vector=vector))
    assert info.value.field == "state.isolator_branch"


def test_a_rigid_stop_beside_a_friction_isolator_is_refused_with_the_fix():
    with pytest.raises(pd_.InputError, match="compliant law") as info:
        pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05),
                       pd_.Bumpers(gap_left_m=0.03, gap_right_m=0.03, law=pd_.RigidStop(0.5)))
    assert info.value.field == "bumpers.law"


def _orbit_systems() -> list:
    building = pd_.Structure(4000.0, pd_.FrictionIsolator(mu=0.1, radius_m=2.0),
                             [pd_.Storey(3000.0, 4e6, 4e3), pd_.Storey(2000.0, 3e6, 3e3)], [])
    bumpers = pd_.Bumpers(0.03, 0.03, pd_.KelvinVoigt(2.0e6, 500.0))
    return [(pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.1, radius_m=1.5), bumpers),
             pd_.Harmonic(0.2, 0.6)),
            (pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05, radius_m=1.5, damping_n_s_m=300.0)),
             pd_.Harmonic(0.08, 0.5)),
            (building, pd_.Harmonic(0.25, 0.8))]


@pytest.mark.parametrize("case", range(3))
def test_an_orbit_that_sticks_has_exact_multipliers_equal_to_finite_differences(case):
    """Periodic orbits that stick and slip in each period (against bumpers, with a dashpot, a building's
    base): their monodromy composed exactly through every stick (its saltation: the slip's velocity the
    guard, the held mode after it, the pair's velocity perturbation erased) and slip (the field continuous at
    the force's balance), equal to the finite differences' to 1e-6."""
    system, table = _orbit_systems()[case]
    kinds = set(pd_.simulate(system, table, 40.0, sample_rate_hz=0).events["kind"])
    assert {"stick", "slip"} <= kinds
    exact = pd_.periodic_orbit(system, table)
    fd = pd_.periodic_orbit(system, table, method="finite-difference")
    assert exact.converged and fd.converged
    assert exact.method == "exact", exact.message
    np.testing.assert_allclose(np.sort_complex(exact.multipliers), np.sort_complex(fd.multipliers), atol=1e-6)
    assert np.sum(np.abs(exact.multipliers) < 1e-12) >= 1  # (a stick forgets its pair's perturbations)


def test_an_unsupported_monodromy_says_why():
    from pounding.analysis._hybrid import unsupported

    assert unsupported(pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05))) is None
    assert unsupported(pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.05, preslip_m=1e-4))) is None
    fast = pd_.FrictionIsolator(mu=0.05, mu_fast=0.1, rate_s_m=20.0)
    assert "depends on the velocity" in unsupported(pd_.Oscillator(500.0, fast))
    triple = pd_.TripleFrictionPendulum(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08),
                                        capacities_m=(0.35, 0.05, 0.05, 0.35))
    assert unsupported(pd_.Oscillator(500.0, triple)) is None


def test_a_flat_slider_has_no_period_for_a_spectrum():
    with pytest.raises(pd_.InputError, match="flat slider"):
        pd_.pounding_spectrum(pd_.records.el_centro(), [1.0], gaps_m=[0.05],
                              isolator=pd_.FrictionIsolator(mu=0.05))


def test_mu_and_the_radius_are_identified_from_a_table_s_sweeps():
    """Model updating of a friction pendulum: the peak alpha and excursion of two sweeps of a known bearing
    (mu 0.06, R 1.5 m) without bumpers, and identify() finds mu and R again, by their names in the system's
    file, within bounds a factor of two or more either side."""
    truth = pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.06, radius_m=1.5))
    freqs = np.round(np.arange(0.2, 1.01, 0.1), 2)
    records = []
    for a_g in (0.066, 0.072):  # (slipping, and below Den Hartog's unbounded resonance: a_g < 4 mu / pi)
        frame = pd_.sweep(truth, a_g, freqs_hz=freqs).to_dataframe()
        records += [{"configuration": "NBs", "a_g": a_g, "quantity": "alpha", "value": frame["alpha"].max()},
                    {"configuration": "NBs", "a_g": a_g, "quantity": "excursion_max_m",
                     "value": frame["excursion_m"].max()}]
    bounds = {"isolator.mu": (0.03, 0.12), "isolator.radius_m": (0.7, 4.0)}
    fit = pd_.identify(pd_.Targets.from_records(records), pd_.SystemFamily(truth), bounds, seed=1, popsize=6,
                       maxiter=8, freqs_hz=freqs, workers=1)
    assert fit.parameters["isolator.mu"] == pytest.approx(0.06, rel=1e-4)
    assert fit.parameters["isolator.radius_m"] == pytest.approx(1.5, rel=1e-4)


def test_a_run_s_summary_has_its_residual_displacement_and_its_sticks():
    """The summary every run has: the base's displacement at the end (a slide's residual) and the friction
    isolator's sticks and slips, as its events count them (0 with a rubber bearing)."""
    system, shake = _pendulum_building()
    run = pd_.simulate(system, shake, 6.0, sample_rate_hz=0)
    s = run.summary()
    kinds = list(run.events["kind"])
    assert s["displacement_end_m"] == run.final_state.displacements_m[0]
    assert (s["sticks"], s["slips"]) == (kinds.count("stick"), kinds.count("slip")) and s["sticks"] > 0
    rubber = pd_.simulate(pd_.presets.paper_damped(), pd_.Harmonic(0.05, 1.5), 3.0).summary()
    assert (rubber["sticks"], rubber["slips"]) == (0, 0)
    assert rubber["displacement_end_m"] != 0.0


def test_a_pair_s_summary_has_each_structure_s_sticks_and_residual():
    """Two adjacent buildings, the first on a friction pendulum: each structure's run and the pair's summary
    count its isolator's sticks and slips as the pair's events do, and its base's displacement at the end."""
    pair = pd_.Adjacent.from_toml(Path(__file__).parents[1] / "examples" / "adjacent_buildings.toml")
    pair = dataclasses.replace(pair, first=dataclasses.replace(
        pair.first, isolator=pd_.FrictionIsolator(mu=0.05, radius_m=2.0)))
    run = pd_.simulate(pair, pd_.Harmonic(0.3, 0.8), 5.0)
    kinds = list(run.events["kind"])
    s = run.summary()
    assert (s["first_sticks"], s["first_slips"]) == (kinds.count("stick"), kinds.count("slip"))
    assert s["first_sticks"] > 0 and list(run.first.events["kind"]).count("slip") == s["first_slips"]
    assert s["first_displacement_end_m"] == run.final_state.displacements_m[0]


def test_the_isolator_loop_is_drawn_for_any_run():
    """plot_isolator_loop: a mass on a friction pendulum between bumpers (its loop, the two slip lines and
    the bumpers' two gaps), a building's (the same through its run); what it cannot draw says why."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    osc = pd_.Oscillator(500.0, pd_.FrictionIsolator(mu=0.1, radius_m=1.5),
                         pd_.Bumpers(0.03, 0.03, pd_.KelvinVoigt(2.0e6, 500.0)))
    run = pd_.simulate(osc, pd_.Harmonic(0.2, 0.6), 10.0)
    artists = pd_.plots.plot_isolator_loop(run, t_start_s=5.0)
    assert len(artists) == 5
    x, y = artists[0].get_data()
    inside = run.t >= 5.0
    np.testing.assert_array_equal(x, run.displacement[inside] * 1e3)
    np.testing.assert_array_equal(y, run.levels.isolator_force[inside] / 1e3)
    system, shake = _pendulum_building()
    assert pd_.simulate(system, shake, 3.0).plot_isolator_loop() is not None
    with pytest.raises(pd_.InputError, match="t_start_s"):
        run.plot_isolator_loop(t_start_s=20.0)
    fixed = pd_.Structure(None, None, [pd_.Storey(1.0e3, 1.0e6)], [])
    with pytest.raises(pd_.InputError, match="isolated base"):
        pd_.plots.plot_isolator_loop(pd_.simulate(fixed, shake, 1.0))
    plt.close("all")
