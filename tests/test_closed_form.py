"""Closed forms: the linear oscillator, free and forced."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pounding as pd_


def _steady_state(m, k, c, a_t, omega, t):
    z = -m * a_t / (k - m * omega**2 + 1j * c * omega)
    return np.imag(z * np.exp(1j * omega * t)), np.imag(1j * omega * z * np.exp(1j * omega * t))


@settings(max_examples=30, deadline=None)
@given(m=st.floats(50, 2000), k=st.floats(1e3, 1e5), zeta=st.floats(0.05, 0.5),
       a_g=st.floats(0.01, 0.5), f=st.floats(0.2, 6.0))
def test_linear_isolator_reaches_closed_form_steady_state(m, k, zeta, a_g, f):
    c = 2 * zeta * math.sqrt(k * m)
    osc = pd_.Oscillator(m, pd_.Isolator((k,), damping_n_s_m=c))
    exc = pd_.Harmonic(a_g, f)
    decay_s = 40.0 / (zeta * math.sqrt(k / m))  # e^-40: transients gone
    warm = pd_.simulate(osc, exc, decay_s, sample_rate_hz=0)
    run = pd_.simulate(osc, exc, 2.0 / f, warm.final_state, sample_rate_hz=200 * f)
    d_ss, v_ss = _steady_state(m, k, c, exc.peak_m_s2, exc.omega_rad_s, run.t)
    amp = abs(m * exc.peak_m_s2 / (k - m * exc.omega_rad_s**2 + 1j * c * exc.omega_rad_s))
    np.testing.assert_allclose(run.displacement, d_ss, rtol=0, atol=1e-9 * amp)
    np.testing.assert_allclose(run.velocity, v_ss, rtol=0, atol=1e-9 * amp * exc.omega_rad_s)
    # exact extrema, and the absolute acceleration of a linear system
    assert run.excursion_m == pytest.approx(2 * amp, rel=1e-9)
    a_abs_amp = abs((k + 1j * c * exc.omega_rad_s) * (-exc.peak_m_s2) / (k - m * exc.omega_rad_s**2
                                                                        + 1j * c * exc.omega_rad_s))
    assert run.abs_acceleration_max == pytest.approx(a_abs_amp, rel=1e-9)


def test_a_long_run_stays_on_the_closed_form_steady_state():
    # 3000 s of one linear phase: 53,000 sub-intervals each continuing the last one's forcing
    # angle; the clock's rounding must not pile up between that angle and the clock's
    m, k, zeta, a_g, f = 500.0, 2e4, 0.05, 0.1, 2.2
    c = 2 * zeta * math.sqrt(k * m)
    osc = pd_.Oscillator(m, pd_.Isolator((k,), damping_n_s_m=c))
    exc = pd_.Harmonic(a_g, f)
    warm = pd_.simulate(osc, exc, 3000.0, sample_rate_hz=0)
    run = pd_.simulate(osc, exc, 2.0 / f, warm.final_state, sample_rate_hz=200 * f)
    d_ss, _ = _steady_state(m, k, c, exc.peak_m_s2, exc.omega_rad_s, run.t)
    amp = abs(m * exc.peak_m_s2 / (k - m * exc.omega_rad_s**2 + 1j * c * exc.omega_rad_s))
    np.testing.assert_allclose(run.displacement, d_ss, rtol=0, atol=1e-10 * amp)


@pytest.mark.parametrize("zeta", [0.0, 0.3, 1.0, 2.5])
def test_free_vibration_every_damping_regime(zeta):
    m, k = 200.0, 8e3
    wn = math.sqrt(k / m)
    c = 2 * zeta * math.sqrt(k * m)
    osc = pd_.Oscillator(m, pd_.Isolator((k,), damping_n_s_m=c))
    v0 = 0.3
    run = pd_.simulate(osc, pd_.Record([0.0, 1.0], [0.0, 0.0]), 3.0,
                       pd_.State.at_rest(osc, velocity_m_s=v0), sample_rate_hz=500)
    t = run.t
    if zeta < 1:
        wd = wn * math.sqrt(1 - zeta**2)
        exact = v0 / wd * np.exp(-zeta * wn * t) * np.sin(wd * t)
    elif zeta == 1:
        exact = v0 * t * np.exp(-wn * t)
    else:
        r = wn * math.sqrt(zeta**2 - 1)
        exact = v0 / r * np.exp(-zeta * wn * t) * np.sinh(r * t)
    np.testing.assert_allclose(run.displacement, exact, rtol=0, atol=1e-12)


def test_plastic_isolator_with_zero_final_slope_and_no_damping():
    # elastic-perfectly-plastic isolator (k = 0 once slipping, c = 0): exercises the k = c = 0 phase
    osc = pd_.Oscillator(100.0, pd_.Isolator((1e4, 0.0), (0.01,)))
    run = pd_.simulate(osc, pd_.Harmonic(0.3, 1.0), 5.0, sample_rate_hz=0)
    assert run.success
    assert abs(run.energy.residual) <= 1e-8 * max(abs(run.energy.input_work), 1e-12)
    assert run.energy.hysteretic > 0


def test_undamped_resonance_grows_as_its_closed_form():
    # x'' + w^2 x = -A sin(w t) from rest: x = A t cos(w t) / (2 w) - A sin(w t) / (2 w^2), growing without
    # bound, bounded at any instant (no particular solution of the usual form exists: none is needed)
    m, k = 100.0, 1e4
    w = math.sqrt(k / m)
    osc = pd_.Oscillator(m, pd_.Isolator((k,)))
    exc = pd_.Harmonic(0.1, w / (2 * math.pi))
    run = pd_.simulate(osc, exc, 10.0, sample_rate_hz=200)
    assert run.success
    a, t = exc.peak_m_s2, run.t
    exact = a * t * np.cos(w * t) / (2 * w) - a * np.sin(w * t) / (2 * w * w)
    np.testing.assert_allclose(run.displacement, exact, rtol=0, atol=1e-12 * np.abs(exact).max())
    assert abs(run.energy.residual) <= 1e-9 * abs(run.energy.input_work)


@settings(max_examples=20, deadline=None)
@given(m=st.floats(50, 2000), k=st.floats(1e3, 1e5), zeta=st.floats(0.05, 0.5),
       a_g=st.floats(0.01, 0.5), f=st.floats(0.2, 6.0), span=st.floats(0.3, 3.0))
def test_steady_state_energy_flows_match_closed_form(m, k, zeta, a_g, f, span):
    # started on the steady-state orbit, V = W cos(w t + psi): int c V^2 and -int M A_g V over
    # any window in closed form
    c = 2 * zeta * math.sqrt(k * m)
    osc = pd_.Oscillator(m, pd_.Isolator((k,), damping_n_s_m=c))
    exc = pd_.Harmonic(a_g, f)
    w, a_t = exc.omega_rad_s, exc.peak_m_s2
    z = -m * a_t / (k - m * w**2 + 1j * c * w)           # D = Im(z e^{i w t})
    state = pd_.State.at_rest(osc, displacement_m=z.imag, velocity_m_s=(1j * w * z).imag)
    t1 = span / f
    run = pd_.simulate(osc, exc, t1, state, sample_rate_hz=0)
    amp, psi = abs(w * z), np.angle(z)                    # V = amp cos(w t + psi)
    viscous = c * amp**2 * (t1 / 2 + (math.sin(2 * (w * t1 + psi)) - math.sin(2 * psi)) / (4 * w))
    # sin(w t) cos(w t + psi) = (sin(2 w t + psi) - sin(psi)) / 2
    sin_v = amp / 2 * (-(math.cos(2 * w * t1 + psi) - math.cos(psi)) / (2 * w) - math.sin(psi) * t1)
    # the terms' size: the integrands' amplitudes over the window
    assert run.energy.viscous == pytest.approx(viscous, abs=1e-12 * c * amp**2 * t1)
    assert run.energy.input_work == pytest.approx(-m * a_t * sin_v, abs=1e-12 * m * a_t * amp * t1)


