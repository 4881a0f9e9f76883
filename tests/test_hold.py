"""A uniform record's quiet sample intervals go by the first-order-hold recurrence
(``engine/_hold.py``); every other interval, and every interval of a run with a sample inside
it, the general way.  Both are checked here against each other and against an independent
first-order hold (scipy's ``lsim``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
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


def _close(got, want, allowed, what):
    got, want = np.asarray(got, dtype=float), np.asarray(want, dtype=float)
    off = np.abs(got - want)
    bad = ~((off <= allowed) | (np.isnan(got) & np.isnan(want)))
    assert not bad.any(), (f"{what}: {int(bad.sum())} differ by up to "
                           f"{np.nanmax(np.where(bad, off, 0.0)):.3g}, "
                           f"allowed {np.min(np.broadcast_to(allowed, off.shape)[bad]):.3g}")


NUDGE_FACTOR = 100.0


def assert_same_run(held, ref, rtol=1e-9, nudged=()):
    """Two runs of one system equal but for rounding: to ``rtol`` of each quantity's scale, and
    where the system amplifies rounding (a sequence of impacts can), to NUDGE_FACTOR times what
    rounding-sized changes of the start or the record change (``nudged``: the general path's runs
    after them, :func:`_nudged`)."""
    nudged = list(nudged) or [ref]

    def spread(get):  # the largest change a nudge made, elementwise
        want = np.asarray(get(ref), dtype=float)
        return np.max([np.nan_to_num(np.abs(np.asarray(get(r), dtype=float) - want)) for r in nudged], axis=0)

    assert held.status == ref.status
    assert len(held.event_table) == len(ref.event_table)
    # (events at one instant, e.g. an isolator's equal branches yielding together, come in an
    # order rounding decides)
    _close(_by_time(held.event_table), _by_time(ref.event_table),
           1e-9 + NUDGE_FACTOR * spread(lambda r: _by_time(r.event_table)), "events")
    assert len(held.contact_table) == len(ref.contact_table)
    scale = np.maximum(np.nan_to_num(np.abs(ref.contact_table)).max(axis=0, initial=0.0), 1e-12)
    # (a contact's net work, near 0 for a nearly elastic one, against the work it stores)
    scale[8] = max(scale[8], (ref.contact_table[:, 6] * ref.contact_table[:, 7]).max(initial=0.0))
    _close(held.contact_table, ref.contact_table,
           rtol * scale + NUDGE_FACTOR * spread(lambda r: r.contact_table), "contacts")
    x_scale = max(ref.displacement_max, -ref.displacement_min)
    for name, size in (("displacement_max", x_scale), ("displacement_min", x_scale),
                       ("abs_acceleration_max", ref.abs_acceleration_max)):
        _close(getattr(held, name), getattr(ref, name),
               rtol * size + NUDGE_FACTOR * spread(lambda r: getattr(r, name)), name)
    flows = max(abs(ref.energy.input_work), abs(ref.energy.viscous), abs(ref.energy.hysteretic), 1e-12)
    for name in ("input_work", "viscous", "hysteretic", "kinetic", "isolator_elastic", "bumper_dissipation"):
        _close(getattr(held.energy, name), getattr(ref.energy, name),
               rtol * flows + NUDGE_FACTOR * spread(lambda r: getattr(r.energy, name)), name)
    size = max(x_scale, abs(ref.final_state.velocity_m_s), 1e-9)
    _close(held.final_state.vector[:3], ref.final_state.vector[:3],
           rtol * size + NUDGE_FACTOR * spread(lambda r: r.final_state.vector[:3]), "final state")
    # the ledger closes as well as the general path's does
    assert abs(held.energy.residual) <= max(1e-9 * flows, 10.0 * abs(ref.energy.residual))


def _nudged(osc, rec, duration, v0, ref):
    """The general path from a start 1e-15 m/s faster and under the record times 1 +- 1e-15: how
    much this system amplifies rounding.

    A system whose status or sequence of events such a nudge changes is left out (``assume``):
    two exact methods rounding differently part there as the nudged runs do (hypothesis draws
    impact oscillators chaotic under white noise, and masses that end stuck in a Zeno sequence
    or not by the last bit of the record), and comparing them says nothing.
    """
    runs = [general(osc, rec, duration, pd_.State.at_rest(osc, velocity_m_s=v0 + 1e-15))]
    for factor in (1.0 + 1e-15, 1.0 - 1e-15):
        runs.append(general(osc, pd_.Record(rec.t, rec.accel * factor), duration,
                            pd_.State.at_rest(osc, velocity_m_s=v0)))
    size = max(ref.displacement_max, -ref.displacement_min, abs(ref.final_state.velocity_m_s), 1e-9)
    assume(all(r.status == ref.status and len(r.event_table) == len(ref.event_table)
               and np.abs(r.final_state.vector[1:3] - ref.final_state.vector[1:3]).max() <= 1e-6 * size
               for r in runs))
    return runs


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(osc=st.sampled_from(LINEAR_LAWS).flatmap(lambda law: oscillators(law=law)), rec=uniform_records(),
       v0=st.floats(-0.5, 0.5))
def test_the_recurrence_equals_the_general_path(osc, rec, v0):
    # random systems (every law with closed-form phases, both isolator rules) under uniform
    # records: events, contacts, extrema, energies and the final state agree to rounding
    state = pd_.State.at_rest(osc, velocity_m_s=v0)
    held = pd_.simulate(osc, rec, 3.2, state, sample_rate_hz=0)
    ref = general(osc, rec, 3.2, state)
    assert_same_run(held, ref, nudged=_nudged(osc, rec, 3.2, v0, ref))


NONLINEAR_LAWS = ("elastic_plastic", "hertzdamp", "jankowski")


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(osc=st.tuples(st.sampled_from(LINEAR_LAWS + NONLINEAR_LAWS), st.sampled_from(["open", "zero"]))
       .flatmap(lambda lg: oscillators(law=lg[0], gaps=lg[1])),
       rec=uniform_records(), v0=st.floats(-0.5, 0.5))
def test_the_recurrence_equals_the_general_path_with_any_law_and_gap(osc, rec, v0):
    # the nonlinear laws' phases out of contact are linear (their contacts integrated the general
    # way), a relaxing surface (Hertzdamp's, at constant speed) comes back over held intervals, and
    # a zero gap starts the mass touching a bumper
    state = pd_.State.at_rest(osc, velocity_m_s=v0)
    ref = general(osc, rec, 3.2, state)
    # (a nonlinear law's contacts are integrated to rtol 1e-10 from starts that differ by rounding)
    rtol = 1e-9 if osc.bumpers.law.LINEAR else 1e-8
    assert_same_run(pd_.simulate(osc, rec, 3.2, state, sample_rate_hz=0), ref, rtol,
                    nudged=_nudged(osc, rec, 3.2, v0, ref))


def _kernel_run(osc, rec, duration, sample_dt=0.0):
    """The engine's kernel on its own: its run control (``CTL_HELD``: the intervals the recurrence
    took) and its samples."""
    from pounding._control import new_control
    from pounding.engine._kernel import run_kernel
    from pounding.engine.simulate import kernel_forcing, kernel_system

    ctl = new_control(10**9)
    out = run_kernel(kernel_system(osc), kernel_forcing(rec), np.array(pd_.State.at_rest(osc).vector),
                     duration, sample_dt, 1e-10, 10**7, np.bool_(True), ctl)
    return ctl, out[1]


def test_the_recurrence_takes_the_quiet_intervals_and_leaves_the_sampled_ones():
    from pounding._control import CTL_HELD, CTL_WORK

    rng = np.random.default_rng(2)
    accel = np.convolve(rng.normal(0.0, 1.0, 2001), np.ones(4) / 4, mode="same")
    rec = pd_.Record(0.01 * np.arange(2001), 3.0 * accel / np.abs(accel).max())
    osc = pd_.presets.paper_damped()
    ctl, _ = _kernel_run(osc, rec, 20.0)
    # most of the 2,000 intervals (those with an event, a velocity zero or a new peak go the
    # general way: 8 % here)
    assert ctl[CTL_HELD] > 1600 and ctl[CTL_WORK] > ctl[CTL_HELD]
    assert _kernel_run(osc, rec, 20.0, sample_dt=0.005)[0][CTL_HELD] == 0  # a sample in every interval
    # a sample every 0.2 s: the intervals between samples are held, the samples written the
    # general way, equal to those of the run that holds none
    ctl, samples = _kernel_run(osc, rec, 20.0, sample_dt=0.2)
    assert ctl[CTL_HELD] > 1000
    uniform = samples[np.abs(samples[:, 0] / 0.2 - np.round(samples[:, 0] / 0.2)) < 1e-9]  # (not events')
    assert len(uniform) == 101
    ref = pd_.simulate(osc, rec, 20.0, sample_rate_hz=200.0)
    at = np.searchsorted(ref.t, uniform[:, 0] - 1e-9)
    assert np.abs(ref.t[at] - uniform[:, 0]).max() < 1e-12
    np.testing.assert_allclose(uniform[:, 1], ref.displacement[at], rtol=0, atol=1e-12)


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
