"""The closed forms of rigid impacts (``tests/reference_impact.py``, issue 51's oracles) against scipy's
solve_ivp with events, restarted at each impact with Newton's law ``v+ = -e v-``.

- A mass falling on a stop: every impact time (1e-9 s) and speed, undamped and damped; the undamped
  accumulation time equals its series of closed-form flights.
- The harmonically forced impact oscillator: a one-impact orbit returns to itself after a period with one
  impact, and its multipliers equal those of the stroboscopic map differentiated numerically; an orbit the
  reference says grazes does touch the stop inside the period.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from reference_impact import falling_on_stop, impact_orbits

OMEGA = 2.0 * math.pi
RTOL, ATOL = 1e-12, 1e-15


def impacts(zeta: float, ag, d: float, e: float, t0: float, y0, t_end: float, max_impacts: int = 100):
    """Integrate ``x'' + 2 zeta omega x' + omega^2 x = -ag(t)`` from ``y0`` at ``t0`` to ``t_end`` with the
    stop ``x = d``: the impacts ``(t, speed in)`` and the state at ``t_end``."""

    def rhs(t, y):
        return [y[1], -2.0 * zeta * OMEGA * y[1] - OMEGA ** 2 * y[0] - ag(t)]

    def hit(t, y):
        return y[0] - d

    hit.terminal, hit.direction = True, 1.0
    out, t, y = [], t0, np.asarray(y0, dtype=float)
    while t < t_end and len(out) < max_impacts:
        sol = solve_ivp(rhs, (t, t_end), y, method="DOP853", rtol=RTOL, atol=ATOL, events=hit)
        if sol.status != 1:
            return out, sol.y[:, -1]
        t = float(sol.t_events[0][0])
        v_in = float(sol.y_events[0][0][1])
        out.append((t, v_in))
        y = np.array([d, -e * v_in])
    return out, y


@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_a_mass_falling_on_a_stop(zeta):
    x_eq, d, e = 0.01, 0.0, 0.7
    ref = falling_on_stop(OMEGA, zeta, x_eq, d, e, -0.004, 0.05, n_impacts=12)
    got, _ = impacts(zeta, lambda t: -OMEGA ** 2 * x_eq, d, e, 0.0, [-0.004, 0.05], ref.times_s[-1] + 1e-6)
    assert len(got) == len(ref.times_s) == 12
    np.testing.assert_allclose([t for t, _ in got], ref.times_s, rtol=0, atol=1e-9)
    np.testing.assert_allclose([v for _, v in got], ref.v_in, rtol=1e-8)
    assert np.all(np.diff(ref.times_s) > 0) and ref.accumulation_s > ref.times_s[-1]
    assert ref.sticking_accel == pytest.approx(OMEGA ** 2 * (x_eq - d))
    if zeta == 0.0:  # each flight back to the stop in closed form, and their sum
        u = ref.v_in[0] * e ** np.arange(1, 200)  # (the speeds out of the stop)
        flights = 2.0 * np.arctan(u / (OMEGA * (x_eq - d))) / OMEGA
        np.testing.assert_allclose(np.diff(ref.times_s), flights[:11], rtol=1e-12)
        assert ref.accumulation_s == pytest.approx(ref.times_s[0] + flights.sum(), rel=1e-14)


def _orbit(r: float, d: float):
    orbs = [o for o in impact_orbits(OMEGA, 0.05, 3.0, r * OMEGA, d, 0.8) if not o.grazes]
    assert orbs, "no one-impact orbit there"
    return orbs[0]


@pytest.mark.parametrize("r, d", [(1.2, 0.0), (2.0, 0.005), (3.0, 0.005)])
def test_a_one_impact_orbit_returns_after_a_period_with_its_multipliers(r, d):
    e, a, big = 0.8, 3.0, r * OMEGA
    o = _orbit(r, d)
    period = 2.0 * math.pi / big

    def ag(t):
        return a * math.cos(big * t + o.phase_rad)

    got, end = impacts(0.05, ag, d, e, 0.0, [d, -e * o.v_in], period * (1.0 + 1e-9))
    assert len(got) == 1 and got[0][0] == pytest.approx(period, abs=1e-9)
    assert got[0][1] == pytest.approx(o.v_in, rel=1e-8)

    # the stroboscopic map from a small time after the impact, differentiated by central differences
    eps = 0.05 * period

    def strobe(y):
        return impacts(0.05, ag, d, e, eps, y, period + eps)[1]

    _, y_eps = impacts(0.05, ag, d, e, 0.0, [d, -e * o.v_in], eps)
    np.testing.assert_allclose(strobe(y_eps), y_eps, atol=1e-9)  # (a fixed point of the map)
    h = 1e-7
    jac = np.column_stack([(strobe(y_eps + h * col) - strobe(y_eps - h * col)) / (2 * h)
                           for col in np.eye(2)])
    fd = np.sort_complex(np.linalg.eigvals(jac))
    np.testing.assert_allclose(np.sort_complex(o.multipliers), fd, atol=1e-5)


def test_an_orbit_said_to_graze_touches_the_stop_inside_its_period():
    o = next(o for o in impact_orbits(OMEGA, 0.05, 3.0, 0.8 * OMEGA, 0.0, 0.8) if o.grazes)
    big = 0.8 * OMEGA
    got, _ = impacts(0.05, lambda t: 3.0 * math.cos(big * t + o.phase_rad), 0.0, 0.8, 0.0,
                     [0.0, -0.8 * o.v_in], 2.0 * math.pi / big * (1.0 - 1e-6))
    assert got and got[0][0] < 2.0 * math.pi / big * (1.0 - 1e-6)
