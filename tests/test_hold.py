"""A uniform record's quiet sample intervals go by the first-order-hold recurrence
(``engine/_hold.py``); every other interval, and every interval of a run with a sample inside
it, the general way.  Both are checked here against each other and against an independent
first-order hold (scipy's ``lsim``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy import signal

import pounding as pd_
from strategies import LINEAR_LAWS, oscillators


@st.composite
def uniform_records(draw, duration_s=3.0):
    """A record sampled every 2 to 30 ms (its times ``start + k dt``, rounded as files give them),
    white or smoothed, peaks of 0.5 to 8 m/s^2."""
    dt = draw(st.floats(0.002, 0.03))
    start = draw(st.sampled_from([0.0, 0.13]))
    n = int((duration_s - start) / dt) + 1
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    accel = rng.normal(0.0, 1.0, n)
    if draw(st.booleans()):
        accel = np.convolve(accel, np.ones(5) / 5, mode="same")
    accel *= draw(st.floats(0.5, 8.0)) / np.abs(accel).max()
    accel[-1] = 0.0
    if start > 0.0:
        accel[0] = 0.0
    return pd_.Record(start + dt * np.arange(n), accel)


def general(osc, rec, duration, state):
    """The run with a sample inside every record interval: no interval goes by the recurrence."""
    return pd_.simulate(osc, rec, duration, state, sample_rate_hz=2.0 / rec.dt_s)


def _by_time(events):
    return events[np.lexsort((events[:, 2], events[:, 1], np.round(events[:, 0], 8)))]


def assert_same_run(held, ref, rtol=1e-9):
    """Two runs of one system equal but for rounding."""
    assert held.status == ref.status
    assert len(held.event_table) == len(ref.event_table)
    # (events at one instant, e.g. an isolator's equal branches yielding together, come in an
    # order rounding decides)
    np.testing.assert_allclose(_by_time(held.event_table), _by_time(ref.event_table), rtol=0, atol=1e-9)
    assert len(held.contact_table) == len(ref.contact_table)
    scale = np.maximum(np.abs(ref.contact_table).max(axis=0, initial=0.0), 1e-12)
    np.testing.assert_allclose(held.contact_table / scale, ref.contact_table / scale, rtol=0, atol=rtol)
    x_scale = max(ref.displacement_max, -ref.displacement_min)
    assert held.displacement_max == pytest.approx(ref.displacement_max, abs=rtol * x_scale)
    assert held.displacement_min == pytest.approx(ref.displacement_min, abs=rtol * x_scale)
    assert held.abs_acceleration_max == pytest.approx(ref.abs_acceleration_max, rel=rtol)
    flows = max(abs(ref.energy.input_work), abs(ref.energy.viscous), abs(ref.energy.hysteretic), 1e-12)
    for name in ("input_work", "viscous", "hysteretic", "kinetic", "isolator_elastic", "bumper_dissipation"):
        assert getattr(held.energy, name) == pytest.approx(getattr(ref.energy, name), abs=rtol * flows), name
    np.testing.assert_allclose(held.final_state.vector[:3], ref.final_state.vector[:3],
                               rtol=0, atol=rtol * max(x_scale, abs(ref.final_state.velocity_m_s), 1e-9))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(osc=st.sampled_from(LINEAR_LAWS).flatmap(lambda law: oscillators(law=law)), rec=uniform_records(),
       v0=st.floats(-0.5, 0.5))
def test_the_recurrence_equals_the_general_path(osc, rec, v0):
    # random systems (every law with closed-form phases, both isolator rules) under uniform
    # records: events, contacts, extrema, energies and the final state agree to rounding
    state = pd_.State.at_rest(osc, velocity_m_s=v0)
    held = pd_.simulate(osc, rec, 3.2, state, sample_rate_hz=0)
    assert_same_run(held, general(osc, rec, 3.2, state))
    assert abs(held.energy.residual) <= 1e-9 * max(abs(held.energy.input_work), abs(held.energy.viscous),
                                                   abs(held.energy.hysteretic), 1e-12)


def test_a_long_record_with_impacts_equals_the_general_path():
    # the damped paper system under 40 s of smoothed noise at 0.01 s, pounding both bumpers (68
    # impacts).  A sequence of impacts carries rounding forward: the record times 1 + 1e-15 moves
    # these events by 1e-11 s (the printed system's, chaotic under this record, by 5e-5 s)
    rng = np.random.default_rng(11)
    accel = np.convolve(rng.normal(0.0, 1.0, 4001), np.ones(4) / 4, mode="same")
    rec = pd_.Record(0.01 * np.arange(4001), 4.0 * accel / np.abs(accel).max())
    osc = pd_.presets.paper_damped()
    held = pd_.simulate(osc, rec, 40.0, sample_rate_hz=0)
    ref = general(osc, rec, 40.0, pd_.State.at_rest(osc))
    assert len(held.contacts) >= 50 and set(held.contacts["side"]) == {"left", "right"}
    assert_same_run(held, ref, rtol=1e-8)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 1.5])
def test_a_linear_isolator_equals_scipys_first_order_hold(zeta):
    # no bumpers, one branch: the motion under a piecewise-linear record is what lsim's
    # first-order hold (the matrix exponential of the augmented system) gives at the samples
    mass, k = 400.0, 2.5e4
    c = 2.0 * zeta * np.sqrt(k * mass)
    osc = pd_.Oscillator(mass, pd_.Isolator((k,), (), "elastic", c))
    rng = np.random.default_rng(5)
    t = 0.005 * np.arange(2001)
    accel = np.convolve(rng.normal(0.0, 2.0, t.size), np.ones(3) / 3, mode="same")
    system = signal.StateSpace([[0.0, 1.0], [-k / mass, -c / mass]], [[0.0], [-1.0]], np.eye(2),
                               np.zeros((2, 1)))
    _, _, x = signal.lsim(system, accel, t, interp=True)
    run = pd_.simulate(osc, pd_.Record(t, accel), t[-1], sample_rate_hz=0)
    scale = np.abs(x).max(axis=0)
    assert run.final_state.displacement_m == pytest.approx(x[-1, 0], abs=1e-11 * scale[0])
    assert run.final_state.velocity_m_s == pytest.approx(x[-1, 1], abs=1e-11 * scale[1])
    # the peaks lie between samples: at least lsim's
    assert run.displacement_max >= x[:, 0].max() - 1e-12 * scale[0]


def test_only_a_uniform_record_takes_the_recurrence():
    t = 0.01 * np.arange(101)
    accel = np.sin(t)
    assert pd_.Record(t, accel).kernel_arrays()[1][0] == pytest.approx(0.01, rel=1e-12)
    wobbly = t.copy()
    wobbly[50] += 1e-8  # one time 1e-6 of a step off: uniform to the eye, not to the recurrence
    assert pd_.Record(wobbly, accel).kernel_arrays()[1][0] == 0.0
    # and it runs as before, the general way
    osc = replace(pd_.presets.paper_printed(), bumpers=None)
    a = pd_.simulate(osc, pd_.Record(wobbly, accel), 1.0, sample_rate_hz=0)
    b = general(osc, pd_.Record(wobbly, accel), 1.0, pd_.State.at_rest(osc))
    assert a.final_state.displacement_m == b.final_state.displacement_m
