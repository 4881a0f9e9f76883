"""Rigid stops (issue 51): Newton's impacts, complete chatter, sticking and its release, against closed
forms (tests/reference_impact.py, checked there against solve_ivp) and invariants."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

import pounding
from pounding import Status
from reference_impact import falling_on_stop, impact_orbits

K, M = 100.0, 1.0  # the linear oscillator: omega 10 rad/s
OMEGA = math.sqrt(K / M)


def oscillator(e: float, gap_right_m: float = 0.01, zeta: float = 0.0, gap_left_m: float = 0.5,
               e_left: float | None = None, omega: float = OMEGA) -> pounding.Oscillator:
    iso = pounding.Isolator(slopes_n_m=[M * omega ** 2], damping_n_s_m=2.0 * zeta * omega * M)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (gaps beyond a bumper's plausible range)
        return pounding.Oscillator(M, iso, pounding.Bumpers(
            gap_left_m, gap_right_m, pounding.RigidStop(e if e_left is None else e_left),
            pounding.RigidStop(e)))


def constant(a: float, until: float = 100.0) -> pounding.Record:
    return pounding.Record(np.array([0.0, until]), np.array([a, a]))


def ledger_residual(run) -> float:
    e = run.energy
    return e.input_work - (e.kinetic + e.elastic + e.contact_elastic + e.viscous + e.hysteretic
                           + e.contact_dissipation)


# ---------------------------------------------------------------- complete chatter: the closed form


@pytest.mark.parametrize("e, zeta", [(0.5, 0.0), (0.9, 0.0), (0.5, 0.05), (0.9, 0.02), (0.95, 0.2)])
def test_a_mass_falling_on_a_stop_chatters_and_sticks_as_the_closed_form_says(e, zeta):
    d, x_eq = 0.01, 0.02  # (the static position beyond the stop: a_g = -omega^2 x_eq)
    ref = falling_on_stop(OMEGA, zeta, x_eq, d, e, 0.0, 0.0, n_impacts=400)
    run = pounding.simulate(oscillator(e, d, zeta), constant(-OMEGA ** 2 * x_eq), duration=30.0,
                            sample_rate_hz=0)
    assert run.status == Status.SUCCESS
    c = run.contacts
    impacts = c[c.t_end_s == c.t_start_s]
    n = len(impacts)
    assert 10 < n < len(ref.times_s)
    np.testing.assert_allclose(impacts.t_start_s, ref.times_s[:n], rtol=0, atol=1e-12)
    np.testing.assert_allclose(impacts.v_in_m_s, ref.v_in[:n], rtol=1e-9, atol=1e-13)
    np.testing.assert_allclose(-impacts.v_out_m_s, e * ref.v_in[:n], rtol=1e-9, atol=1e-13)
    # one sequence, accumulated where the series sums to, then held by the closed form's force
    (chatter,) = run.chatters.itertuples()
    assert chatter.accumulated and chatter.t_end_s == pytest.approx(ref.accumulation_s, abs=1e-12)
    assert chatter.impacts == (impacts.t_start_s >= chatter.t_first_s).sum()
    held = c.iloc[-1]
    assert held.t_start_s == pytest.approx(impacts.t_start_s.iloc[-1], abs=1e-15) and math.isnan(held.t_end_s)
    assert held.peak_force_n == pytest.approx(M * ref.sticking_accel, rel=1e-12)
    assert held.impulse_n_s == pytest.approx(M * ref.sticking_accel * (30.0 - held.t_start_s), rel=1e-9)
    end = run.final_state
    assert end.displacement_m == d and end.velocity_m_s == 0.0 and end.in_contact == (False, True)
    # the kinetic energy went into the stop, impact by impact and the remainder at once
    lost = 0.5 * M * (1 - e * e) * ref.v_in[:n] ** 2
    np.testing.assert_allclose(c.bumper_dissipation_j[:n], lost, rtol=1e-8)
    assert abs(ledger_residual(run)) < 1e-12 * run.energy.input_work


# ---------------------------------------------------------------- complete chatter: any last rebound


def _flight(omega: float, zeta: float, a: float, y0: float, v0: float) -> tuple[float, float]:
    """The exact flight of a linear oscillator whose static position lies ``a`` past a stop: its opening
    ``y >= 0`` off the stop follows ``y'' + 2 zeta omega y' + omega^2 (y + a) = 0`` from ``(y0, v0)``; its
    duration (the first root of the closed form, brentq to rounding) and the speed it comes back with. The
    closed form is written in the opening itself: a flight short against the period keeps its digits."""
    s, wd = zeta * omega, omega * math.sqrt(1.0 - zeta * zeta)
    b = (v0 + s * (y0 + a)) / wd

    def y(t: float) -> float:  # (y + a = exp(-s t) ((y0 + a) cos + b sin), the constant a taken out exactly)
        c, sn = math.cos(wd * t), math.sin(wd * t)
        return (math.exp(-s * t) * (y0 * c + b * sn)
                + a * (math.expm1(-s * t) * c - 2.0 * math.sin(0.5 * wd * t) ** 2))

    guess = 2.0 * v0 / (omega * omega * a) if y0 == 0.0 else 0.05 * math.pi / wd
    step = min(guess, 0.05 * math.pi / wd)
    lo = 1e-3 * step if y0 == 0.0 else 0.0
    hi = lo + step
    while y(hi) > 0.0:
        lo, hi = hi, hi + step
    t = brentq(y, lo, hi, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=500)
    c, sn = math.cos(wd * t), math.sin(wd * t)
    back = -math.exp(-s * t) * (v0 * c - (s * b + wd * (y0 + a)) * sn)
    return t, back


def _accumulation(omega: float, zeta: float, a: float, e: float, drop: float) -> float:
    """Where the impacts of the oscillator dropped from rest ``drop`` off the stop accumulate: the sum of its
    exact flights (``_flight``), each rebound ``e`` times the speed it came back with, until a flight is below
    1e-18 s (the rest, a geometric tail, below that over 1 - e)."""
    t, back = _flight(omega, zeta, a, drop, 0.0)
    while True:
        tau, back = _flight(omega, zeta, a, 0.0, e * back)
        t += tau
        if tau < 1e-18:
            return t + tau * e / (1.0 - e)


@pytest.mark.parametrize("zeta", [0.0, 0.02])
@pytest.mark.parametrize("e", [0.5, 0.7, 0.8, 0.9, 0.95])
@pytest.mark.parametrize("past", [5e-6, 5e-8, 5e-10])
def test_a_chatter_accumulates_at_the_sum_of_its_exact_flights_whatever_its_last_rebound(past, e, zeta):
    """The issue's oscillator (1 g on 100 N/m) dropped from 10 mm onto a stop, pushed by a constant table
    whose static position lies ``past`` beyond it (5 mm/s^2 for 50 nm). The impacts are followed one by one
    until their rebound is below the run's length resolution; then the rest is summed at once. The closer the
    static position to the stop, the larger that last rebound against the flight's own velocity scale
    ``omega past``: about 0.08 %, 1 % and 8 % here. Summed to first order in it, the accumulation was up to
    9e-12 s, 9e-9 s and 9e-6 s late."""
    m, k, drop = 0.001, 100.0, 0.01
    omega = math.sqrt(k / m)
    iso = pounding.Isolator(slopes_n_m=[k], damping_n_s_m=2.0 * zeta * omega * m)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (gaps beyond a bumper's plausible range)
        osc = pounding.Oscillator(m, iso, pounding.Bumpers(0.5, 0.0, pounding.RigidStop(e)))
    want = _accumulation(omega, zeta, past, e, drop)
    run = pounding.simulate(osc, constant(-omega ** 2 * past), duration=want + 0.01, sample_rate_hz=0,
                            state=pounding.State.at_rest(osc, displacement_m=-drop))
    assert run.status == Status.SUCCESS
    (chatter,) = run.chatters[run.chatters.accumulated].itertuples()
    assert abs(chatter.t_end_s - want) <= 1e-12
    held = run.contacts.iloc[-1]  # (and held from its last impact on by the push, m omega^2 past)
    assert math.isnan(held.t_end_s) and held.peak_force_n == pytest.approx(m * omega ** 2 * past, rel=1e-12)


def _flight_shaken(omega: float, zeta: float, amp: float, w: float, phase: float, t0: float,
                   u: float) -> tuple[float, float]:
    """The exact flight from a stop at its rest position (the gap 0) of a linear oscillator on a table shaken
    as ``a_g = amp sin(w t + phase)``, leaving at ``t0`` with speed ``u``: its opening ``y = -x`` follows
    ``y'' = -omega^2 y - 2 zeta omega y' + a_g(t)``, summed as its Taylor series about ``t0`` (the table's
    derivatives exact, 80 terms: the flights are shorter than a radian of either frequency); its duration
    (the root of ``y / t``, brentq to rounding) and the speed it comes back with."""
    c = [0.0, u]
    for k in range(78):
        table = amp * w ** k * math.sin(w * t0 + phase + 0.5 * k * math.pi) / math.factorial(k)
        c.append((-omega * omega * c[k] - 2.0 * zeta * omega * (k + 1) * c[k + 1] + table)
                 / ((k + 2) * (k + 1)))
    over_t = np.polynomial.Polynomial(c[1:])
    hi = 2.0 * u / -(amp * math.sin(w * t0 + phase))  # (the first order's, to a bracket)
    while over_t(hi) > 0.0:
        hi *= 1.5
    t = brentq(over_t, 1e-3 * hi, hi, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=500)
    return t, -over_t.deriv()(t) * t - over_t(t)  # (y' = (t f)' with y = t f)


@pytest.mark.parametrize("f_hz, phase, e, zeta", [(2.0, math.pi / 2, 0.9, 0.0), (5.0, math.pi / 3, 0.9, 0.02),
                                                  (5.0, 2 * math.pi / 3, 0.8, 0.0),
                                                  (10.0, math.pi / 4, 0.9, 0.02)])
def test_a_chatter_on_a_shaken_table_accumulates_at_the_sum_of_its_exact_flights(f_hz, phase, e, zeta):
    """The issue's oscillator leaving its stop at 1 um/s while the table pushes it back (5 mm/s^2 at its
    crest), the push rising, at its crest or falling through the chatter: the remainder, taken at a rebound of
    about 1 % of the flight's velocity scale, takes the push's rates in time (the first-order sum, with the
    first rate alone, was 1.4e-9 s to 1.1e-7 s off)."""
    m, k, amp, u0 = 0.001, 100.0, -5e-3, 1e-6
    omega, w = math.sqrt(k / m), 2.0 * math.pi * f_hz
    t, u = 0.0, u0
    while True:
        tau, back = _flight_shaken(omega, zeta, amp, w, phase, t, u)
        t, u = t + tau, e * back
        if tau < 1e-18:
            break
    iso = pounding.Isolator(slopes_n_m=[k], damping_n_s_m=2.0 * zeta * omega * m)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (gaps beyond a bumper's plausible range)
        osc = pounding.Oscillator(m, iso, pounding.Bumpers(0.5, 0.0, pounding.RigidStop(e)))
    table = pounding.Harmonic(a_g=amp, freq_hz=f_hz, phase=phase, g=1.0)
    run = pounding.simulate(osc, table, duration=t + 1e-3, sample_rate_hz=0,
                            state=pounding.State.at_rest(osc, velocity_m_s=-u0))
    (chatter,) = run.chatters[run.chatters.accumulated].itertuples()
    assert abs(chatter.t_end_s - t) <= 1e-12


def test_the_chatter_s_exact_flights_are_the_closed_form_s_of_a_mass_falling_on_a_stop():
    """The oracle above against tests/reference_impact.py's (its own closed form, from rest 10 mm off the
    stop)."""
    for zeta, e in [(0.0, 0.9), (0.02, 0.8)]:
        ref = falling_on_stop(OMEGA, zeta, 0.02, 0.01, e, 0.0, 0.0, n_impacts=400)
        assert _accumulation(OMEGA, zeta, 0.01, e, 0.01) == pytest.approx(ref.accumulation_s, abs=1e-13)


def test_a_plastic_stop_holds_at_the_first_impact_and_an_elastic_one_never():
    push = constant(-OMEGA ** 2 * 0.02)
    plastic = pounding.simulate(oscillator(0.0), push, duration=2.0, sample_rate_hz=0)
    (hit, held) = plastic.contacts.itertuples()
    assert hit.v_out_m_s == 0.0 and hit.t_start_s == held.t_start_s and math.isnan(held.t_end_s)
    assert held.peak_force_n == pytest.approx(1.0, rel=1e-12)  # (omega^2 (x_eq - d) per kg)
    assert plastic.chatters.empty  # (one impact: no sequence)
    elastic = pounding.simulate(oscillator(1.0), push, duration=2.0, sample_rate_hz=0)
    assert elastic.chatters.empty and not elastic.final_state.in_contact[1]
    assert elastic.energy.contact_dissipation == 0.0
    assert (elastic.contacts.v_out_m_s == -elastic.contacts.v_in_m_s).all()


# ---------------------------------------------------------------- sticking and its release


def test_a_mass_at_rest_on_the_stop_is_held_until_the_force_would_pull():
    """Pressed by the spring and the table, ``F = -k d - m A sin(W t + phi)``: held from the start until F
    crosses zero, at ``sin(W t + phi) = -k d / (m A)``."""
    a, f_hz, d = 3.0, 1.0, 0.01
    osc = oscillator(0.5, d)
    table = pounding.Harmonic(a_g=a, freq_hz=f_hz, phase=-math.pi / 2, g=1.0)
    run = pounding.simulate(osc, table, duration=0.5, state=pounding.State.at_rest(osc, displacement_m=d))
    held = run.contacts.iloc[0]
    w = 2.0 * math.pi * f_hz
    release = (math.pi / 2 - math.asin(K * d / (M * a))) / w
    assert held.t_start_s == 0.0 and held.t_end_s == pytest.approx(release, abs=1e-12)
    assert held.peak_force_n == pytest.approx(-K * d + M * a, rel=1e-12)  # (at t = 0)
    # the impulse: the force's integral in closed form
    impulse = -K * d * release + M * a / w * (math.cos(w * release - math.pi / 2) - math.cos(-math.pi / 2))
    assert held.impulse_n_s == pytest.approx(impulse, rel=1e-10)
    # held: the mass moves with the table (its absolute acceleration the table's), pushed, never pulled
    inside = (run.t > 0.0) & (run.t < release)
    np.testing.assert_allclose(run.displacement[inside], d, rtol=0, atol=0)
    np.testing.assert_allclose(run.abs_acceleration[inside], table.acceleration(run.t[inside]), atol=1e-12)
    force = K * -d * 0 + (-K * d - M * table.acceleration(run.t[inside]))
    np.testing.assert_allclose(run.bumper_force_right[inside], force, rtol=1e-9, atol=1e-12)
    assert (run.bumper_force_right >= 0.0).all() and (run.bumper_force_left == 0.0).all()


def test_a_mass_pulled_off_the_stop_at_the_start_leaves_at_once():
    osc = oscillator(0.5, 0.01)
    run = pounding.simulate(osc, pounding.Harmonic(a_g=3.0, freq_hz=1.0, phase=math.pi / 2, g=1.0),
                            duration=0.2, state=pounding.State.at_rest(osc, displacement_m=0.01))
    assert run.status == Status.SUCCESS and run.contacts.empty and run.displacement_max == 0.01


# ---------------------------------------------------------------- the forced impact oscillator

ZETA, A, E, W = 0.05, 3.0, 0.8, 2.0 * math.pi  # (W: the oscillator's natural frequency, rad/s)


def _orbit(r: float, d: float):
    orbs = [o for o in impact_orbits(W, ZETA, A, r * W, d, E) if not o.grazes]
    assert orbs, "no one-impact orbit there"
    return orbs[0]


def impact_oscillator(d: float) -> pounding.Oscillator:
    return oscillator(E, d, ZETA, omega=W)


@pytest.mark.parametrize("r, d", [(1.5, 0.0), (2.0, 0.005), (2.4, 0.005), (3.0, 0.0)])
def test_the_period_one_orbit_of_the_impact_oscillator_returns_after_one_period(r, d):
    o = _orbit(r, d)
    big = r * W
    period = 2.0 * math.pi / big
    osc = impact_oscillator(d)
    # a_g = A cos(W t + phase) = A sin(W t + phase + pi / 2)
    table = pounding.Harmonic(a_g=A, freq_hz=big / (2 * math.pi), phase=o.phase_rad + math.pi / 2, g=1.0)
    start = pounding.State.at_rest(osc, displacement_m=d, velocity_m_s=-E * o.v_in)
    run = pounding.simulate(osc, table, duration=3.0 * period * (1 + 1e-9), state=start, sample_rate_hz=0)
    c = run.contacts
    np.testing.assert_allclose(c.t_start_s, period * np.arange(1, 4), rtol=0, atol=1e-12)
    np.testing.assert_allclose(c.v_in_m_s, o.v_in, rtol=1e-10)


@pytest.mark.parametrize("r, d, settled", [(1.5, 0.0, True), (2.0, 0.005, True), (2.4, 0.005, True),
                                           (2.8, 0.0, False)])
def test_the_period_one_orbit_s_exact_multipliers_are_the_saltation_closed_form_s(r, d, settled):
    """Newton shooting with the exact monodromy (Newton's law's saltation matrix at each impact) finds the
    orbit and the closed form's multipliers, on its stable side and (from a guess on it) its unstable one."""
    o = _orbit(r, d)
    big = r * W
    period = 2.0 * math.pi / big
    osc = impact_oscillator(d)
    # the impact half a period after the table's phase 0, where the orbit is sampled: mid-flight
    table = pounding.Harmonic(a_g=A, freq_hz=big / (2 * math.pi), phase=o.phase_rad + math.pi / 2 - math.pi,
                              g=1.0)
    guess = None
    if not settled:  # (an unstable orbit: the state half a flight before its impact)
        on = pounding.State.at_rest(osc, displacement_m=d, velocity_m_s=-E * o.v_in, time_s=0.5 * period)
        guess = pounding.simulate(osc, table, duration=0.5 * period, state=on, sample_rate_hz=0).final_state
    orbit = pounding.periodic_orbit(osc, table, guess=guess)
    assert orbit.converged and orbit.method == "exact", orbit.message
    np.testing.assert_allclose(np.sort_complex(orbit.multipliers[:2]), np.sort_complex(o.multipliers),
                               atol=1e-8)
    assert orbit.stable == settled


def test_the_impact_oscillator_settles_on_its_orbit_only_where_its_multipliers_say_it_is_stable():
    """Across its stability boundary (a multiplier through -1 as the forcing frequency grows), a start near
    the orbit comes back to it on the stable side and leaves it on the other."""
    d = 0.0
    ratios = np.linspace(2.3, 3.0, 71)
    stable = [max(abs(_orbit(r, d).multipliers)) < 1.0 for r in ratios]
    k = stable.index(False)  # (the boundary lies between ratios k - 1 and k)
    assert 0 < k and all(stable[:k]) and not any(stable[k:])
    for r, expect in ((ratios[k - 3], True), (ratios[k + 2], False)):
        o = _orbit(r, d)
        big = r * W
        period = 2.0 * math.pi / big
        osc = impact_oscillator(d)
        table = pounding.Harmonic(a_g=A, freq_hz=big / (2 * math.pi), phase=o.phase_rad + math.pi / 2, g=1.0)
        start = pounding.State.at_rest(osc, displacement_m=d - 1e-5, velocity_m_s=-E * o.v_in * 1.001)
        run = pounding.simulate(osc, table, duration=300.0 * period, state=start, sample_rate_hz=0)
        late = run.contacts[run.contacts.t_start_s > 250.0 * period]
        on_orbit = np.allclose(late.v_in_m_s, o.v_in, rtol=1e-6) and len(late) in (49, 50, 51)
        assert on_orbit == expect, (r, late.v_in_m_s.describe())


# ---------------------------------------------------------------- a stiff bumper tends to the rigid stop


def _kv_restitution(stiffness: float, damping: float) -> float:
    """A free mass's restitution on a Kelvin-Voigt bumper (contact ends when its force would pull):
    ``m x'' = -(k x + c x')`` from ``(0, 1)``, solved in closed form (underdamped)."""
    w0 = math.sqrt(stiffness / M)
    z = damping / (2.0 * math.sqrt(stiffness * M))
    wd = w0 * math.sqrt(1 - z * z)

    def state(t: float) -> tuple[float, float]:
        ex = math.exp(-z * w0 * t)
        x = ex * math.sin(wd * t) / wd
        v = ex * (math.cos(wd * t) - z * w0 / wd * math.sin(wd * t))
        return x, v

    from scipy.optimize import brentq
    end = brentq(lambda t: stiffness * state(t)[0] + damping * state(t)[1], 0.5 * math.pi / wd, math.pi / wd,
                 xtol=1e-16)
    return -state(end)[1]


def test_a_stiff_kelvin_voigt_bumper_tends_to_the_rigid_stop_first_order_in_its_contact_time():
    """Held at the same restitution (the damping ratio fixed), the bumper's impacts tend to the rigid
    stop's as its stiffness grows: the first impacts' rebound speeds and times converge, the error falling
    with the contact time (about pi sqrt(m / k))."""
    zeta_b, d = 0.1, 0.01
    table = pounding.Harmonic(a_g=5.0, freq_hz=1.3, g=1.0)
    e = _kv_restitution(1.0, 2.0 * zeta_b)
    rigid = pounding.simulate(oscillator(e, d, 0.02, gap_left_m=d), table, duration=3.0, sample_rate_hz=0)
    ref = rigid.contacts.iloc[:6]
    errors, contact_times = [], []
    for kb in (1e7, 1e8, 1e9, 1e10):
        law = pounding.KelvinVoigt(kb, 2.0 * zeta_b * math.sqrt(kb * M))
        assert _kv_restitution(kb, law.damping) == pytest.approx(e, rel=1e-9)
        iso = pounding.Isolator(slopes_n_m=[K], damping_n_s_m=2.0 * 0.02 * OMEGA * M)
        osc = pounding.Oscillator(M, iso, pounding.Bumpers(d, d, law))
        run = pounding.simulate(osc, table, duration=3.0, sample_rate_hz=0)
        got = run.contacts.iloc[:6]
        errors.append(np.max(np.abs(got.v_out_m_s.values - ref.v_out_m_s.values)))
        contact_times.append(float((got.t_end_s - got.t_start_s).mean()))
    errors, contact_times = np.array(errors), np.array(contact_times)
    assert np.all(np.diff(errors) < 0)
    # first order: the error over the contact time stays the same as both fall 30-fold (about 5 /s here)
    ratio = errors / contact_times
    assert ratio.max() < 1.3 * ratio.min() and errors[-1] < 1e-3 * np.abs(ref.v_out_m_s).max()


def test_a_return_that_barely_reaches_the_stop_is_an_impact_not_a_pass_through():
    """Found by a fuzz: the mass comes back to the left stop after each rebound with less to spare, and one
    return dips 7 nm past it inside a sub-interval that ends as it comes back out (its end within the
    rounding of zero): the crossing before the dip is the impact, not the one after it."""
    mass, omega, gap = 823.135633938375, 21.948266301722516, 0.01951727485062605
    iso = pounding.Isolator(slopes_n_m=[mass * omega ** 2])
    osc = pounding.Oscillator(mass, iso, pounding.Bumpers(0.0, gap, pounding.RigidStop(0.15054298312394565),
                                                          pounding.RigidStop(0.0)))
    push = constant(-2.0045586059931297)
    run = pounding.simulate(osc, push, duration=3.0, state=pounding.State.at_rest(osc, displacement_m=gap),
                            sample_rate_hz=0)
    assert run.displacement_min >= -1e-15
    impacts = run.contacts.t_start_s.values
    assert np.any(np.abs(impacts - 1.17582222812465) < 1e-9)  # (the return the engine had passed through)
    assert (run.contacts.v_in_m_s < 0).all()  # (every impact on the left stop, met moving into it)


# ---------------------------------------------------------------- invariants


def test_a_continued_run_equals_one_long_run_through_chatter_and_sticking():
    osc = oscillator(0.7, 0.005, 0.02, gap_left_m=0.005)
    table = pounding.Harmonic(a_g=4.0, freq_hz=0.7, g=1.0)
    one = pounding.simulate(osc, table, duration=6.0, sample_rate_hz=0)
    assert not one.chatters.empty and one.chatters.accumulated.any()
    held = one.contacts[one.contacts.t_end_s > one.contacts.t_start_s + 0.01]
    cut = float(held.t_start_s.iloc[0] + 0.5 * (held.t_end_s.iloc[0] - held.t_start_s.iloc[0]))  # (in a hold)
    first = pounding.simulate(osc, table, duration=cut, sample_rate_hz=0)
    rest = pounding.simulate(osc, table, duration=6.0 - cut, state=first.final_state, sample_rate_hz=0)
    assert rest.final_state.displacement_m == pytest.approx(one.final_state.displacement_m, abs=1e-12)
    assert rest.final_state.velocity_m_s == pytest.approx(one.final_state.velocity_m_s, abs=1e-11)
    whole = one.contacts
    joined = np.concatenate([first.contact_table[~np.isnan(first.contact_table[:, 2])], rest.contact_table])
    later = joined[joined[:, 1] > cut + 1e-9]
    np.testing.assert_allclose(later[:, 1], whole.t_start_s.values[-len(later):], atol=1e-11)


def test_mirrored_stops_give_the_mirrored_motion():
    osc = oscillator(0.6, 0.004, 0.03, gap_left_m=0.007, e_left=0.3)
    table = pounding.Harmonic(a_g=4.0, freq_hz=0.9, g=1.0)
    run = pounding.simulate(osc, table, duration=5.0, sample_rate_hz=0)
    mirror = dataclasses.replace(osc, bumpers=osc.bumpers.mirrored())
    flipped = pounding.simulate(mirror, dataclasses.replace(table, a_g=-4.0), duration=5.0, sample_rate_hz=0)
    np.testing.assert_allclose(flipped.contacts.t_start_s, run.contacts.t_start_s, atol=1e-12)
    np.testing.assert_allclose(flipped.contacts.v_in_m_s, -run.contacts.v_in_m_s, atol=1e-12)
    assert (flipped.contacts.side.values != run.contacts.side.values).all()
    assert flipped.displacement_max == pytest.approx(-run.displacement_min, abs=1e-14)


# ---------------------------------------------------------------- never a hang or a budget stop in chatter


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mass=st.floats(0.1, 1e3), omega=st.floats(1.0, 60.0), zeta=st.sampled_from([0.0, 0.02, 0.3]),
       e=st.one_of(st.sampled_from([0.0, 1.0]), st.floats(0.0, 1.0)),
       gap_l=st.one_of(st.just(0.0), st.floats(0.0, 0.05)),
       gap_r=st.one_of(st.just(0.0), st.floats(0.0, 0.05)),
       a=st.floats(0.0, 20.0), f_hz=st.floats(0.1, 8.0), on_stop=st.booleans(), constant_push=st.booleans())
def test_no_run_hangs_or_stops_on_its_budget_in_chatter(mass, omega, zeta, e, gap_l, gap_r, a, f_hz,
                                                       on_stop, constant_push):
    assume(gap_l + gap_r > 0.0)  # (no gap at all: a clamp, refused; the test below)
    iso = pounding.Isolator(slopes_n_m=[mass * omega ** 2], damping_n_s_m=2.0 * zeta * omega * mass)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        osc = pounding.Oscillator(mass, iso, pounding.Bumpers(gap_l, gap_r, pounding.RigidStop(e)))
        table = constant(-a) if constant_push else pounding.Harmonic(a_g=a, freq_hz=f_hz, g=1.0)
    start = pounding.State.at_rest(osc, displacement_m=gap_r if on_stop else 0.0)
    run = pounding.simulate(osc, table, duration=3.0, state=start, sample_rate_hz=0, max_events=2_000_000)
    assert run.status == Status.SUCCESS, run.message
    en = run.energy
    scale = sum(abs(x) for x in (en.input_work, en.kinetic, en.elastic, en.viscous,
                                 en.contact_dissipation))
    stored = mass * omega ** 2 * max(gap_l, gap_r, 1e-3) ** 2
    assert abs(ledger_residual(run)) <= 1e-9 * scale + 1e-15 * stored
    holds = run.contacts[~(run.contacts.t_end_s == run.contacts.t_start_s)]
    assert (holds.impulse_n_s.fillna(0.0) >= -1e-12 * mass * max(a, 1.0)).all()  # (a stop never pulls)
    assert -gap_l - 1e-12 <= run.displacement_min and run.displacement_max <= gap_r + 1e-12


# ---------------------------------------------------------------- structures: a wall, two masses


def test_a_building_against_a_rigid_moat_wall_and_two_buildings_against_each_other_close_their_ledgers():
    rec = pounding.records.el_centro().scaled(pga_g=0.6)
    b = pounding.Structure.from_toml("examples/building_moat.toml")
    for e in (0.0, 0.5, 1.0):
        rigid = dataclasses.replace(b, walls=(dataclasses.replace(b.walls[0], law=pounding.RigidStop(e)),))
        run = pounding.simulate(rigid, rec, duration=20.0, sample_rate_hz=0)
        assert run.success and len(run.contacts) > 3
        assert abs(run.energy.residual) < 1e-9 * run.energy.input_work
    pair = pounding.Adjacent.from_toml("examples/adjacent_buildings.toml")
    for e in (0.0, 0.6, 1.0):
        link = dataclasses.replace(pair.links[0], law=pounding.RigidStop(e))
        rigid = dataclasses.replace(pair, links=(link,))
        run = pounding.simulate(rigid, rec.scaled(pga_g=0.5), duration=20.0, sample_rate_hz=0)
        assert run.success and len(run.links) > 0
        assert abs(run.energy.residual) < 1e-9 * run.energy.input_work
        impacts = run.links[run.links.t_end_s == run.links.t_start_s]
        np.testing.assert_allclose(impacts.v_out_m_s, -e * impacts.v_in_m_s, atol=1e-12)


def test_rigid_stops_on_both_sides_without_a_gap_are_refused_as_a_clamp():
    with pytest.raises(pounding.InputError, match="bumpers.gap_left_m.*clamped"):
        pounding.Bumpers(0.0, 0.0, pounding.RigidStop(0.5))
    with pytest.raises(pounding.InputError, match="wall.gap_left_m.*clamped"):
        pounding.Wall(0, 0.0, 0.0, pounding.RigidStop(1.0))
    # (one deformable side, or a gap: a mass that can move)
    assert pounding.Bumpers(0.0, 0.0, pounding.RigidStop(0.5), pounding.KelvinVoigt(1e6)).gap_right_m == 0.0
    assert pounding.Wall(0, 0.0, 0.001, pounding.RigidStop(1.0)).gap_right_m == 0.001


def test_a_rigid_stop_refuses_a_restitution_outside_0_to_1():
    for bad in (-0.1, 1.5, math.nan, "x"):
        with pytest.raises(pounding.InputError, match="restitution"):
            pounding.RigidStop(bad)


# ---------------------------------------------------------------- the analyses with rigid stops


def _classic() -> pounding.Oscillator:
    """The gallery's impact oscillator: 1 Hz, 5 % damping, a rigid stop at its rest position (e = 0.8)."""
    iso = pounding.Isolator(slopes_n_m=[W ** 2], damping_n_s_m=2.0 * ZETA * W)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (a gap of 10 m on the left: no stop there)
        return pounding.Oscillator(1.0, iso, pounding.Bumpers(10.0, 0.0, pounding.RigidStop(E)))


def test_lyapunov_exponents_with_rigid_impacts_exact_against_finite_differences():
    table = pounding.Harmonic(a_g=A, freq_hz=3.0, g=1.0)  # (chaotic: past the period-doubling cascade)
    exact = pounding.lyapunov(_classic(), table, cycles=100)
    fd = pounding.lyapunov(_classic(), table, cycles=100, method="finite-difference")
    assert exact.method == "exact" and fd.method == "finite-difference"
    np.testing.assert_allclose(exact.exponents, fd.exponents, rtol=0, atol=1e-5 * np.abs(fd.exponents).max())


def test_an_impacting_branch_is_continued_with_no_grazing_and_basins_sort_its_states():
    """On its impacting branch the orbit's clearance of the rigid stop is 0 at every point: the grazing test
    is its slowest impact's speed instead, which stays away from 0 there (no grazing is reported)."""
    branch = pounding.continuation(_classic(), A / 9.81, (2.0, 2.6))
    assert branch.status == Status.SUCCESS and not branch.bifurcations
    # there one attractor, the stable period-one orbit (its largest multiplier 0.7 in modulus): every start
    # ends on it
    table = pounding.Harmonic(a_g=A, freq_hz=2.3, g=1.0)
    b = pounding.basins(_classic(), table, n=(4, 4))
    assert b.not_settled == 0.0 and len(b.attractors) == 1 and b.attractors["period"].iloc[0] == 1
    orbit = pounding.periodic_orbit(_classic(), table)
    assert orbit.stable and orbit.method == "exact"
    np.testing.assert_allclose(orbit.max_abs_multiplier, max(abs(_orbit(2.3, 0.0).multipliers)), rtol=1e-8)


def test_a_building_s_orbit_against_a_rigid_wall_has_its_finite_difference_multipliers():
    """Two masses (a base on its isolator, a floor) with the floor against a rigid stop: Newton's law acts on
    the floor alone, and the exact multipliers equal those of finite differences of the same orbit."""
    iso = pounding.Isolator(slopes_n_m=[8.0 * math.pi ** 2], damping_n_s_m=0.4 * math.pi)
    stop = pounding.Wall(1, 0.5, 0.0, pounding.RigidStop(0.8))
    building = pounding.Structure(1.0, iso, [pounding.Storey(1.0, 16.0 * math.pi ** 2)], [stop])
    for f_hz in (1.5, 2.5):  # (stable, and past a Neimark-Sacker point)
        table = pounding.Harmonic(3.0 / 9.81, f_hz)
        exact = pounding.periodic_orbit(building, table)
        fd = pounding.periodic_orbit(building, table, method="finite-difference")
        assert exact.method == "exact" and exact.converged and fd.converged
        np.testing.assert_allclose(np.sort_complex(exact.multipliers), np.sort_complex(fd.multipliers),
                                   atol=1e-5)
    branch = pounding.continuation(building, 3.0 / 9.81, (2.6, 1.8))
    assert branch.status == Status.SUCCESS
    assert not [b for b in branch.bifurcations if b.kind == "grazing"]  # (it impacts all along)


# ---------------------------------------------------------------- holds between structures (a review)


def _pair(wall_on_first: bool) -> tuple:
    """Two fixed-base one-storey structures of 1000 kg, pressed by a constant table towards a rigid wall
    (no restitution) of one of them, the other against it through a rigid link 2 mm wide."""
    soft, stiff, m = 5e5, 1e6, 1000.0

    def storey(k: float) -> pounding.Storey:
        return pounding.Storey(m, k, 2 * 0.2 * math.sqrt(k * m), height_m=3.0)

    stop = pounding.RigidStop(0.0)
    if wall_on_first:  # ground | wall | first | link | second, pushed left
        first = pounding.Structure.fixed_base([storey(stiff)], [pounding.Wall(1, 0.01, 0.5, stop)])
        second, a = pounding.Structure.fixed_base([storey(soft)]), 20.0
    else:  # first | link | second | wall | ground, pushed right
        first = pounding.Structure.fixed_base([storey(soft)])
        second = pounding.Structure.fixed_base([storey(stiff)], [pounding.Wall(1, 0.5, 0.01, stop)])
        a = -20.0
    pair = pounding.Adjacent(first, second, (pounding.Link(1, 1, 0.002, pounding.RigidStop(0.0)),))
    return pair, constant(a)


@pytest.mark.parametrize("wall_on_first", [True, False])
def test_a_structure_held_on_its_wall_holds_its_neighbour_through_a_link_as_statics_says(wall_on_first):
    """At rest at the end: the link carries the soft structure's push, 20 kN less its spring's 6 kN, and the
    wall both structures' (40 kN less 10 and 6 kN of their springs), whichever side the wall is on."""
    pair, table = _pair(wall_on_first)
    run = pounding.simulate(pair, table, duration=3.0, sample_rate_hz=100)
    assert run.status == Status.SUCCESS
    walled = run.first if wall_on_first else run.second
    np.testing.assert_allclose(run.link_force[-1], [14000.0], rtol=1e-6)
    np.testing.assert_allclose(np.max(walled.contact_force[-1]), 24000.0, rtol=1e-6)
    assert abs(run.energy.residual) < 1e-12 * run.energy.input_work


def test_an_impact_on_a_held_pair_lets_go_of_the_link_that_would_pull():
    """The first presses the second through a held link; the second then hits its own wall moving away from
    the first: the wall's impulse acts on the second alone (1 kg), the link would have to pull and lets go."""
    first = pounding.Structure.fixed_base([pounding.Storey(1.0, 4000.0, 0.0, height_m=3.0)])
    second = pounding.Structure.fixed_base([pounding.Storey(1.0, 100.0, 0.0, height_m=3.0)],
                                           [pounding.Wall(1, 0.01, 0.5, pounding.RigidStop(0.0))])
    pair = pounding.Adjacent(first, second, (pounding.Link(1, 1, 0.0005, pounding.RigidStop(0.0)),))
    run = pounding.simulate(pair, constant(60.0), duration=0.1, sample_rate_hz=0)
    assert run.status == Status.SUCCESS
    hit = run.second.contacts.iloc[0]
    assert hit.impulse_n_s == pytest.approx(1.0 * abs(hit.v_in_m_s), rel=1e-12)


def test_two_structures_at_rest_on_a_zero_gap_rigid_link_are_held_from_the_start():
    pair = pounding.Adjacent.from_toml("examples/adjacent_buildings.toml")
    for e in (0.0, 1.0):
        link = dataclasses.replace(pair.links[0], law=pounding.RigidStop(e), gap_m=0.0)
        run = pounding.simulate(dataclasses.replace(pair, links=(link,)),
                                pounding.Harmonic(a_g=0.2, freq_hz=1.0, phase=math.pi), duration=5.0,
                                sample_rate_hz=0)
        assert run.status == Status.SUCCESS and len(run.links) > 0


def test_a_mass_held_on_a_stop_has_the_table_s_crest_as_its_peak_acceleration():
    osc = oscillator(0.0, 0.005, 0.02, gap_left_m=0.005)
    run = pounding.simulate(osc, pounding.Harmonic(a_g=10.0, freq_hz=1.3, g=1.0), duration=6.0,
                            sample_rate_hz=0)
    assert run.abs_acceleration_max == pytest.approx(10.0, rel=1e-12)
