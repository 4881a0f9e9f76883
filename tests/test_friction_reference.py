"""The friction isolator's reference (tests/reference_friction.py) against Den Hartog's exact steady state and
against invariants: the reference the engine's friction isolators will be tested against (issue 64) is itself
tested first."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import pounding as pd_
from reference_friction import FrictionStructure, den_hartog, energy, reference


def _one_mass(m: float, k: float, friction: float, p0: float, omega: float,
              phi: float) -> FrictionStructure:
    """A mass on a friction pendulum (k) forced by P0 cos(w t + phi): the table's a_g = -(P0/m) cos(...)."""
    return FrictionStructure(np.array([m]), np.zeros(0), np.zeros(0), k, 0.0, friction / (9.81 * m),
                             lambda t: -p0 / m * math.cos(omega * t + phi))


@settings(max_examples=25, deadline=None)
@given(b=st.floats(0.3, 3.0), ratio=st.floats(0.0, 0.6), m=st.floats(100.0, 5000.0),
       fn=st.floats(0.2, 2.0))
def test_a_non_stop_steady_state_is_den_hartog_s(b, ratio, m, fn):
    """Started at Den Hartog's x0 at rest, with his phase, the reference's base reaches -x0 at rest half a
    period later, its velocity never zero between, and x0 again a period later: to 1e-9."""
    # (near resonance the amplitude grows without bound; near b = 1/3 a friction makes the motion stop)
    assume(abs(b - 1.0) > 0.05 and abs(b - 1.0 / 3.0) > 0.02)
    k = m * (2 * math.pi * fn) ** 2
    omega = b * 2 * math.pi * fn
    p0 = 1000.0
    friction = ratio * p0
    x0, phi = den_hartog(m, k, friction, p0, omega)
    assume(np.isfinite(x0))
    s = _one_mass(m, k, friction, p0, omega, phi)
    # without stops: at x0 at rest the spring and the load overcome the friction (it slips on at once)
    assume(-k * x0 + p0 * math.cos(phi) < -friction * (1 + 1e-6))
    period = 2 * math.pi / omega
    try:
        run = reference(s, period, np.array([x0]), np.array([0.0]))
    except RuntimeError:
        assume(False)
    # a motion with a stop in between is not Den Hartog's: the reference says so by a stick
    assume(not run.sticks)
    turns = [tt for tt, _ in run.slips[1:] if tt < period * (1 - 1e-9)]
    assert len(turns) == 1, run.slips  # (one reversal inside the period, at its half; the next at its end)
    assert turns[0] == pytest.approx(period / 2, rel=0, abs=1e-9 * period)
    half = int(np.argmin(np.abs(run.t - turns[0])))
    assert run.x[half, 0] == pytest.approx(-x0, rel=1e-9)
    assert run.x[-1, 0] == pytest.approx(x0, rel=1e-9)
    assert abs(run.v[-1, 0]) <= 1e-9 * omega * x0


def test_den_hartog_without_friction_is_the_linear_steady_state():
    m, k, omega = 500.0, 4.0e4, 5.0
    x0, phi = den_hartog(m, k, 0.0, 1000.0, omega)
    assert x0 == pytest.approx(1000.0 / abs(k - m * omega**2), rel=1e-15) and phi == 0.0


def _building(mu: float, sign: float = 1.0) -> FrictionStructure:
    """Three storeys on a friction pendulum of R = 2 m, shaken at 0.3 g, 1.5 Hz (it sticks and slips 18 times
    in 6 s with mu = 0.1)."""
    masses = np.array([4.0e3, 3.0e3, 3.0e3, 2.0e3])
    w = 9.81 * masses.sum()
    return FrictionStructure(masses, np.array([4.0e7, 3.0e7, 2.0e7]), np.array([4.0e4, 3.0e4, 2.0e4]),
                             w / 2.0, 0.0, mu, lambda t: sign * 0.3 * 9.81 * math.sin(2 * math.pi * 1.5 * t))


@pytest.fixture(scope="module")
def stick_slip():
    return reference(_building(0.1), 6.0, np.zeros(4), np.zeros(4))


def test_a_building_sticks_and_slips_and_its_ledger_closes(stick_slip):
    run, s = stick_slip, _building(0.1)
    assert len(run.sticks) >= 10 and len(run.slips) >= 10  # (it sticks and slips, again and again)
    work = run.viscous_j + run.friction_j + energy(s, run.x[-1], run.v[-1]) - energy(s, run.x[0], run.v[0])
    assert run.input_work_j == pytest.approx(work, rel=1e-9)
    assert run.friction_j > 0.0
    # held, the base never needs more than the friction can give
    assert run.stick_force_max_n <= s.friction_n * (1 + 1e-9)


def test_a_stuck_base_does_not_move(stick_slip):
    run = stick_slip
    starts = run.sticks
    ends = [tt for tt, _ in run.slips if tt > starts[0]]
    for a, b in zip(starts, ends):
        inside = (run.t >= a) & (run.t <= b)  # (the first: the slip's end, its velocity 0 to rounding)
        assert np.ptp(run.x[inside, 0]) == 0.0 and np.all(run.v[inside, 0][1:] == 0.0)
        assert abs(run.v[inside, 0][0]) < 1e-12
        assert np.ptp(run.x[inside, 3]) > 0.0  # (the storeys above still move)


def test_the_mirror_run_is_the_run_mirrored(stick_slip):
    mirror = reference(_building(0.1, sign=-1.0), 6.0, np.zeros(4), np.zeros(4))
    assert mirror.sticks == pytest.approx(stick_slip.sticks, abs=1e-9)
    assert [d for _, d in mirror.slips] == [-d for _, d in stick_slip.slips]
    np.testing.assert_allclose(mirror.x[-1], -stick_slip.x[-1], rtol=0, atol=1e-9)


def test_without_friction_the_reference_is_the_linear_one():
    s = _building(0.0)
    v0 = np.full(4, 0.1)  # (moving: at rest where nothing pushes, a friction of 0 would hold it an instant)
    run = reference(s, 3.0, np.zeros(4), v0)
    assert run.sticks == [] and run.friction_j == 0.0 and len(run.reversals) > 2
    from scipy.integrate import solve_ivp

    k, c = s.matrices()
    m = s.masses_kg

    def rhs(t, y):
        return np.concatenate([y[4:], (-m * s.accel(t) - k @ y[:4] - c @ y[4:]) / m])

    lin = solve_ivp(rhs, (0.0, 3.0), np.concatenate([np.zeros(4), v0]), method="DOP853", rtol=1e-12,
                    atol=1e-15)
    np.testing.assert_allclose(run.x[-1], lin.y[:4, -1], rtol=0, atol=1e-9 * np.abs(lin.y[:4]).max())


@pytest.mark.parametrize("preslip_m", [1e-4, 1e-5, 1e-6])
def test_the_engine_s_stiff_pre_slip_converges_to_the_reference_s_stick(stick_slip, preslip_m):
    """A friction pendulum with an elastic pre-slip (the isolator's kinematic rule: slopes k_pre + W/R and
    W/R, slipping at mu W, i.e. at a displacement ``preslip_m``) is the engine's today, exact; as k_pre grows
    its peak and residual base displacements converge to the reference's rigid stick and slip, their errors
    O(preslip_m) (the trend OpenSees' flat sliders show against an exact friction)."""
    s = _building(0.1)
    k_r, friction = s.k_r, s.friction_n
    iso = pd_.Isolator(slopes_n_m=[friction / preslip_m + k_r, k_r], breakpoints_m=[preslip_m],
                       hysteresis="kinematic")
    storeys = [pd_.Storey(m, k, c) for m, k, c in zip(s.masses_kg[1:], s.storey_k, s.storey_c)]
    run = pd_.simulate(pd_.Structure(float(s.masses_kg[0]), iso, storeys, []), pd_.Harmonic(0.3, 1.5), 6.0,
                       sample_rate_hz=0)
    assert run.success and run.t[-1] == 6.0
    peak = max(abs(run.displacement_max[0]), abs(run.displacement_min[0]))
    assert abs(peak - np.abs(stick_slip.x[:, 0]).max()) <= 30 * preslip_m
    np.testing.assert_allclose(run.displacement[-1], stick_slip.x[-1], rtol=0, atol=30 * preslip_m)
