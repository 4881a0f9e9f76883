"""Records at their own step: the table acceleration is linear between two samples, so a record's
interval is one sub-interval of its phase (one series, exact) unless an event cuts it.  Checked here
against an independent first-order hold (scipy's ``lsim``), for the work it takes (one sub-interval
per quiet interval), and for what the history's sampling must not change: the motion."""

from __future__ import annotations


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


def sampled(osc, rec, duration, state):
    """The run with two history samples inside every record interval."""
    return pd_.simulate(osc, rec, duration, state, sample_rate_hz=2.0 / rec.dt_s)


def assert_same_motion(a, b):
    """Two runs of one system whose histories differ: their motion is the same to the last bit."""
    assert a.status == b.status
    np.testing.assert_array_equal(a.event_table, b.event_table)
    np.testing.assert_array_equal(a.contact_table, b.contact_table)
    np.testing.assert_array_equal(a.final_state.vector, b.final_state.vector)
    for name in ("displacement_max", "displacement_min", "displacement_max_time_s", "displacement_min_time_s",
                 "abs_acceleration_max", "abs_acceleration_max_time_s"):
        assert getattr(a, name) == getattr(b, name), name
    np.testing.assert_array_equal(a.energy.to_series().to_numpy(), b.energy.to_series().to_numpy())


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(osc=st.tuples(st.sampled_from(LINEAR_LAWS + ("elastic_plastic", "hertzdamp", "jankowski")),
                     st.sampled_from(["open", "zero"]))
       .flatmap(lambda lg: oscillators(law=lg[0], gaps=lg[1])),
       rec=uniform_records(), v0=st.floats(-0.5, 0.5))
def test_the_history_never_changes_the_motion(osc, rec, v0):
    # random systems (every law, both isolator rules, open and zero gaps) under uniform records:
    # samples inside every interval are read off the trajectory, they do not cut it
    state = pd_.State.at_rest(osc, velocity_m_s=v0)
    assert_same_motion(pd_.simulate(osc, rec, 3.2, state, sample_rate_hz=0), sampled(osc, rec, 3.2, state))


def _kernel_run(osc, rec, duration, sample_dt=0.0):
    """The engine's kernel on its own: its run control and its samples."""
    from pounding._control import new_control
    from pounding._core import run as run_kernel
    from pounding.engine.simulate import kernel_forcing, kernel_system

    ctl = new_control(10**9)
    out = run_kernel(kernel_system(osc), kernel_forcing(rec), np.array(pd_.State.at_rest(osc).vector),
                     duration, sample_dt, 1e-10, 10**7, True, ctl)
    return ctl, out


def test_a_record_goes_interval_by_interval():
    from pounding._control import CTL_WORK

    rng = np.random.default_rng(2)
    accel = np.convolve(rng.normal(0.0, 1.0, 2001), np.ones(4) / 4, mode="same")
    rec = pd_.Record(0.01 * np.arange(2001), 3.0 * accel / np.abs(accel).max())
    osc = pd_.presets.paper_damped()
    ctl, out = _kernel_run(osc, rec, 20.0)
    events = len(out.events)
    # 2,000 intervals, each one sub-interval (shorter than an eighth of the phases' periods), plus the
    # pieces the events and the velocity turns cut off
    assert 2000 <= ctl[CTL_WORK] <= 2000 + 2 * events + 50
    # a sample every 0.2 s, read off the same trajectory as a 200 Hz history's
    _, out = _kernel_run(osc, rec, 20.0, sample_dt=0.2)
    samples = out.samples
    uniform = samples[np.abs(samples[:, 0] / 0.2 - np.round(samples[:, 0] / 0.2)) < 1e-9]  # (not events')
    assert len(uniform) == 101
    ref = pd_.simulate(osc, rec, 20.0, sample_rate_hz=200.0)
    at = np.searchsorted(ref.t, uniform[:, 0] - 1e-9)
    assert np.abs(ref.t[at] - uniform[:, 0]).max() < 1e-12
    np.testing.assert_allclose(uniform[:, 1], ref.displacement[at], rtol=0, atol=1e-12)


def test_a_long_record_with_impacts_is_the_same_motion_sampled_or_not():
    # the damped paper system under 40 s of smoothed noise at 0.01 s, pounding both bumpers
    rng = np.random.default_rng(11)
    accel = np.convolve(rng.normal(0.0, 1.0, 4001), np.ones(4) / 4, mode="same")
    rec = pd_.Record(0.01 * np.arange(4001), 4.0 * accel / np.abs(accel).max())
    osc = pd_.presets.paper_damped()
    run = pd_.simulate(osc, rec, 40.0, sample_rate_hz=0)
    assert len(run.contacts) >= 50 and set(run.contacts["side"]) == {"left", "right"}
    assert_same_motion(run, sampled(osc, rec, 40.0, pd_.State.at_rest(osc)))


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


@pytest.mark.parametrize("k, least_parts", [(2.0e7, 4), (2.0e9, 30)])
def test_a_record_interval_longer_than_the_phase_s_sub_interval_goes_in_equal_parts_exactly(k, least_parts):
    # a stiff linear building (its fastest motion about 280 rad/s, or 2,800: a sub-interval of 2.8 ms, or
    # 0.28) under a record at 0.01 s: every interval is cut at its knot in 4 (or 36) equal parts, each by the
    # phase's kept transition, the last ending at the knot however the clock drifts over the parts; at every
    # knot the state is lsim's first-order hold, and the work is exactly the parts
    from pounding._control import CTL_WORK, new_control
    from pounding._core import run as run_kernel
    from pounding.engine.assembly import assemble
    from pounding.engine.simulate import kernel_forcing

    masses, k_iso, c = (2.0e3, 1.0e3, 1.0e3), 8.0e5, 2.0e3
    building = pd_.Structure(masses[0], pd_.Isolator((k_iso,), (), "elastic", 1.0e3),
                             [pd_.Storey(m, k, c) for m in masses[1:]], [])
    rng = np.random.default_rng(8)
    t = 0.01 * np.arange(1001)
    accel = np.convolve(rng.normal(0.0, 2.0, t.size), np.ones(3) / 3, mode="same")
    ctl = new_control(10**9)
    asm = assemble(building)
    state = np.array(pd_.State.at_rest(building).vector)
    forcing = kernel_forcing(pd_.Record(t, accel))
    out = run_kernel(asm.system, forcing, state, t[-1], 0.01, 1e-10, 10**7, True, ctl)
    # (the same number of parts in every interval, no sliver before a knot: the last part ends there)
    parts, left = divmod(int(ctl[CTL_WORK]), 1000)
    assert left == 0 and least_parts <= parts <= 1.25 * least_parts
    # lsim: x'' = -M^-1 (K x + C v) - a_g on every level
    K = np.array([[k_iso + k, -k, 0.0], [-k, 2 * k, -k], [0.0, -k, k]])
    C = np.array([[1.0e3 + c, -c, 0.0], [-c, 2 * c, -c], [0.0, -c, c]])
    Minv = np.diag(1.0 / np.array(masses))
    A = np.block([[np.zeros((3, 3)), np.eye(3)], [-Minv @ K, -Minv @ C]])
    B = np.concatenate([np.zeros(3), -np.ones(3)])[:, None]
    _, _, x = signal.lsim(signal.StateSpace(A, B, np.eye(6), np.zeros((6, 1))), accel, t, interp=True)
    samples = out.samples
    at_knots = samples[np.abs(samples[:, 0] / 0.01 - np.round(samples[:, 0] / 0.01)) < 1e-9]
    assert len(at_knots) == t.size
    scale = np.abs(x).max(axis=0)
    for q in range(6):  # (each level's displacement, then velocity)
        np.testing.assert_allclose(at_knots[:, 1 + q], x[:, q], rtol=0, atol=1e-10 * scale[q])
