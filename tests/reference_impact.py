"""Closed forms of rigid impacts (issue 51's oracles), written from the equations alone, no code of the
engine's: a linear oscillator against a rigid stop with Newton's law ``v+ = -e v-``.

In relative coordinates a mass on a linear spring and dashpot, shaken by its base,

    x'' + 2 zeta omega x' + omega^2 x = -a_g(t),

meets a stop at ``x = d`` (it stays at ``x <= d``).  Two classic cases:

- **Falling on the stop** (``a_g`` constant, so that the static position ``x_eq = -a_g / omega^2`` lies
  beyond the stop): each flight from the stop and back is the closed-form free response about ``x_eq``;
  undamped, a flight that leaves at speed ``u`` lasts ``(2 / omega) atan(u / (omega (x_eq - d)))`` and
  returns at speed ``u``, so the rebounds fall as ``e^k`` and the impacts accumulate at the sum of a
  convergent series (complete chatter), after which the mass sticks on the stop, pressed by
  ``omega^2 (x_eq - d)`` per unit mass.  Damped, each flight's end is the root of the closed-form
  trajectory (``brentq`` to rounding).
- **The harmonically forced impact oscillator** (``a_g = a cos(Omega t + phi)``): its period-1 orbit with one
  impact a period.  Over the period the free part ``z = X - X_p`` (``X_p`` the steady-state particular
  response) maps by the flow's transition ``Phi(T)``: with the impact's ends ``(d, -e v)`` and ``(d, v)``,
  ``X_p(0) = (I - Phi)^-1 ((d, v) - Phi (d, -e v))``, linear in ``v``, and ``X_p(0)`` lies on the
  particular response's ellipse: a quadratic in ``v``, its roots the orbits (the impact's phase from
  the ellipse).  Their Floquet multipliers are those of ``S Phi(T)``, ``S`` Newton's law's saltation
  matrix ``[[-e, 0], [(a+ + e a-) / v, -e]]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm
from scipy.optimize import brentq


def free_state(omega: float, zeta: float, x_eq: float, x0: float, v0: float, t: float) -> tuple[float, float]:
    """(x, v) at ``t`` of ``x'' + 2 zeta omega x' + omega^2 (x - x_eq) = 0`` from ``(x0, v0)`` (zeta < 1)."""
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    s = zeta * omega
    y0 = x0 - x_eq
    b = (v0 + s * y0) / wd
    decay, c, sn = math.exp(-s * t), math.cos(wd * t), math.sin(wd * t)
    y = decay * (y0 * c + b * sn)
    v = decay * ((-s * y0 + wd * b) * c + (-s * b - wd * y0) * sn)
    return x_eq + y, v


@dataclass(frozen=True)
class Chatter:
    """Impacts of a mass falling on a stop: ``times_s[k]`` the k-th impact, ``v_in[k]`` its speed in,
    ``v_out[k] = e v_in[k]`` out; ``accumulation_s`` where they accumulate (complete chatter), NaN when
    ``e = 1``; ``sticking_accel`` the stop's push per unit mass once stuck, ``omega^2 (x_eq - d)``."""

    times_s: np.ndarray
    v_in: np.ndarray
    v_out: np.ndarray
    accumulation_s: float
    sticking_accel: float


def falling_on_stop(omega: float, zeta: float, x_eq: float, d: float, e: float, x0: float, v0: float,
                    n_impacts: int = 40, tail_tol: float = 1e-16) -> Chatter:
    """The impacts of ``x'' + 2 zeta omega x' + omega^2 (x - x_eq) = 0`` on the stop ``x = d < x_eq`` from
    ``(x0, v0)``, ``x0 < d`` (or ``x0 = d`` moving away, ``v0 < 0``).

    Undamped, the flights are in closed form and the accumulation time is their series summed until its
    terms fall below ``tail_tol`` times the sum, plus the bound of the rest (``atan(x) <= x``: a geometric
    tail ``2 u_K / (omega^2 A (1 - e))``, below rounding when the loop stops).  Damped, each flight's end is
    a root of the closed-form trajectory and the series is summed the same way (its terms fall faster).
    """
    a = x_eq - d
    if not a > 0.0:
        raise ValueError("the static position must lie beyond the stop (x_eq > d)")
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    t, x, v = 0.0, x0, v0
    times, vin = [], []

    def flight(x: float, v: float) -> float:
        """The time to the next arrival at the stop from (x, v): the first root of x(t) = d after 0."""
        if zeta == 0.0 and x == d:  # (the closed form: tan(theta / 2) = u / (omega A))
            return 2.0 * math.atan(-v / (omega * a)) / omega
        # a point of the flight off the stop (lo), then a grid of steps to the first point at or beyond it
        # (hi), then brentq; from the stop at speed u the flight lasts at most 2 u / (omega^2 A)
        period = 2.0 * math.pi / wd
        lo = 0.0 if x < d else min(0.5 * (-v) / (omega * omega * a), 0.05 * period)
        while lo > 0.0 and free_state(omega, zeta, x_eq, x, v, lo)[0] >= d:
            lo *= 0.5
        step = 0.05 * period if x < d else min(0.05 * period, 4.0 * lo)
        hi = lo + step
        while free_state(omega, zeta, x_eq, x, v, hi)[0] < d:
            lo, hi = hi, hi + step
        return brentq(lambda s: free_state(omega, zeta, x_eq, x, v, s)[0] - d, lo, hi, xtol=1e-300,
                      rtol=4 * np.finfo(float).eps, maxiter=500)

    def away(u: float) -> tuple[float, float]:
        """The flight from the stop at speed ``u`` away: its duration and the speed it comes back with."""
        if zeta == 0.0:
            return 2.0 * math.atan(u / (omega * a)) / omega, u
        if 2.0 * u / (omega * omega * a) * omega < 0.05:
            return _short_flight(omega, zeta, a, u)
        tau = flight(d, -u)
        return tau, free_state(omega, zeta, x_eq, d, -u, tau)[1]

    total_after = math.nan
    for k in range(n_impacts):
        if x == d and v >= 0.0:  # (at the stop, not leaving: stuck already)
            break
        if x == d:
            tau, v_arr = away(-v)
        else:
            tau = flight(x, v)
            _, v_arr = free_state(omega, zeta, x_eq, x, v, tau)
        t += tau
        times.append(t)
        vin.append(v_arr)
        x, v = d, -e * v_arr
    if e < 1.0:
        # the rest of the series: flights from the last rebound on, until the terms are below rounding
        total_after, u = 0.0, -v
        for _ in range(100_000):
            if u <= 0.0:
                break
            tau, u_arr = away(u)
            total_after += tau
            u = e * u_arr
            if tau <= tail_tol * (t + total_after):
                total_after += 2.0 * u / (omega * omega * a * (1.0 - e))  # (the bound of the rest)
                break
    vin_a = np.asarray(vin)
    return Chatter(np.asarray(times), vin_a, e * vin_a, t + total_after if e < 1.0 else math.nan,
                   omega * omega * a)


def _short_flight(omega: float, zeta: float, a: float, u: float, terms: int = 40) -> tuple[float, float]:
    """A short flight from the stop at speed ``u`` away, with ``y = d - x``: ``y'' = -omega^2 a - 2 zeta
    omega y' - omega^2 y`` from ``(0, u)``, by the Taylor series of its exact solution (the closed form
    loses its digits to cancellation when the flight is short against the period).  Its duration (the
    root of ``y(t) / t``) and the speed it comes back with."""
    c = [0.0, u]
    for k in range(terms):
        push = omega * omega * a if k == 0 else 0.0
        rhs = -2.0 * zeta * omega * (k + 1) * c[k + 1] - omega * omega * c[k] - push
        c.append(rhs / ((k + 2) * (k + 1)))

    def over_t(t: float) -> float:
        return sum(c[k] * t ** (k - 1) for k in range(len(c) - 1, 0, -1))

    guess = 2.0 * u / (omega * omega * a)
    tau = brentq(over_t, 0.5 * guess, 2.0 * guess, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500)
    speed = sum(k * c[k] * tau ** (k - 1) for k in range(1, len(c)))
    return tau, -speed


@dataclass(frozen=True)
class ImpactOrbit:
    """A period-1 orbit of the forced impact oscillator with one impact a period: ``phase_rad`` the
    forcing's angle at the impact (``a_g = a cos(Omega t + phase)``, impact at t = 0), ``v_in`` the speed
    in (m/s, > 0: towards the stop), ``multipliers`` its Floquet multipliers, ``grazes`` whether the
    flight touches the stop before the period ends (then it is not a one-impact orbit)."""

    phase_rad: float
    v_in: float
    multipliers: np.ndarray
    grazes: bool


def _flow(omega: float, zeta: float) -> np.ndarray:
    return np.array([[0.0, 1.0], [-omega * omega, -2.0 * zeta * omega]])


def particular(omega: float, zeta: float, a: float, big_omega: float, phase: float, t: float) -> np.ndarray:
    """The steady-state response (x, v) to ``a_g = a cos(Omega t + phase)`` at ``t``."""
    den = complex(omega * omega - big_omega * big_omega, 2.0 * zeta * omega * big_omega)
    amp = -a / den  # (x_p = Re(amp exp(i (Omega t + phase))))
    z = amp * complex(math.cos(big_omega * t + phase), math.sin(big_omega * t + phase))
    return np.array([z.real, (1j * big_omega * z).real])


def impact_orbits(omega: float, zeta: float, a: float, big_omega: float, d: float,
                  e: float) -> list[ImpactOrbit]:
    """The period-1 one-impact orbits of ``x'' + 2 zeta omega x' + omega^2 x = -a cos(Omega t + phase)``
    against the stop ``x = d``: the roots of the quadratic in ``v`` (module docstring), each with its phase,
    multipliers and whether its flight stays off the stop."""
    period = 2.0 * math.pi / big_omega
    phi = expm(_flow(omega, zeta) * period)
    inv = np.linalg.inv(np.eye(2) - phi)
    w0 = inv @ (np.array([d, 0.0]) - phi @ np.array([d, 0.0]))
    w1 = inv @ (np.array([0.0, 1.0]) - phi @ np.array([0.0, -e]))
    den = complex(omega * omega - big_omega * big_omega, 2.0 * zeta * omega * big_omega)
    amp = a / abs(den)
    # X_p(0) = w0 + v w1 on the ellipse (x / amp)^2 + (v_p / (Omega amp))^2 = 1
    sx, sv = 1.0 / amp, 1.0 / (big_omega * amp)
    qa = (w1[0] * sx) ** 2 + (w1[1] * sv) ** 2
    qb = 2.0 * (w0[0] * w1[0] * sx * sx + w0[1] * w1[1] * sv * sv)
    qc = (w0[0] * sx) ** 2 + (w0[1] * sv) ** 2 - 1.0
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return []
    out = []
    for v in sorted({(-qb + s * math.sqrt(disc)) / (2.0 * qa) for s in (1.0, -1.0)}):
        if not v > 0.0:
            continue
        xp = w0 + v * w1
        # the phase: X_p(0) = Re(-a / den * exp(i phase)) and its derivative
        z0 = complex(xp[0], -xp[1] / big_omega)  # (x_p = Re(z), v_p = Re(i Omega z) = -Omega Im(z))
        unit = z0 / (-a / den)
        phase = math.atan2(unit.imag, unit.real) % (2.0 * math.pi)
        # accelerations just before and after the impact (the dashpot sees the velocity jump)
        ag = a * math.cos(phase)
        acc_in = -2.0 * zeta * omega * v - omega * omega * d - ag
        acc_out = -2.0 * zeta * omega * (-e * v) - omega * omega * d - ag
        salt = np.array([[-e, 0.0], [(acc_out + e * acc_in) / v, -e]])
        mult = np.linalg.eigvals(salt @ phi)
        grazes = _touches(omega, zeta, a, big_omega, phase, d, e, v, period)
        out.append(ImpactOrbit(phase, v, mult, grazes))
    return out


def _touches(omega: float, zeta: float, a: float, big_omega: float, phase: float, d: float, e: float,
             v: float, period: float, samples: int = 4000) -> bool:
    """Whether the flight from (d, -e v) reaches the stop before the period ends (sampled densely on the
    closed form: the free part's transition at each sample)."""
    x0 = np.array([d, -e * v]) - particular(omega, zeta, a, big_omega, phase, 0.0)
    flow = _flow(omega, zeta)
    for s in np.linspace(0.0, period, samples + 1)[1:-1]:
        x = (expm(flow * s) @ x0)[0] + particular(omega, zeta, a, big_omega, phase, s)[0]
        if x > d + 1e-12 * max(1.0, abs(d)):
            return True
    return False


@dataclass(frozen=True)
class Grazing:
    """Where the forced impact oscillator's orbit clear of the stop grazes it, and the Poincare map's
    square-root term there.  ``freq_hz`` the forcing frequency at which the steady state's amplitude
    is ``d``; ``term`` (2,) the map's change over ``sqrt(delta)`` (``delta`` the depth the free orbit
    would reach past the stop) at the section where the forcing's angle is ``phase_rad``
    (``a_g = a sin(Omega t + phase)``): the impact's velocity jump ``-(1 + e) sqrt(2 Omega^2 d delta)``
    (``Omega^2 d`` the steady state's acceleration away from the stop at its crest) carried over the rest
    of the period by the free part's transition ``Phi(T - t_g)``."""

    freq_hz: float
    term: np.ndarray


def grazing(omega: float, zeta: float, a: float, d: float, e: float, phase_rad: float,
            lo_hz: float, hi_hz: float) -> Grazing:
    """The grazing between ``lo_hz`` and ``hi_hz`` (the amplitude ``a / |omega^2 - Omega^2 + 2 i zeta
    omega Omega|`` crosses ``d`` once there)."""
    def amplitude(f: float) -> float:
        w = 2.0 * math.pi * f
        return a / abs(complex(omega * omega - w * w, 2.0 * zeta * omega * w))

    f = brentq(lambda f: amplitude(f) - d, lo_hz, hi_hz, xtol=1e-15, rtol=1e-15)
    big = 2.0 * math.pi * f
    den = complex(omega * omega - big * big, 2.0 * zeta * omega * big)
    amp = -a / den  # (a sin(Omega t + phase) = a cos(Omega t + phase - pi / 2): x_p = Re(amp e^(i angle)))
    angle0 = phase_rad - 0.5 * math.pi
    t_g = ((-angle0 - math.atan2(amp.imag, amp.real)) % (2.0 * math.pi)) / big  # (the crest's time)
    jump = np.array([0.0, -(1.0 + e) * math.sqrt(2.0 * big * big * d)])
    return Grazing(f, expm(_flow(omega, zeta) * (2.0 * math.pi / big - t_g)) @ jump)
