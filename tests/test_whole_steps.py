"""A record's step taken whole (the core's ``run.cpp``, ``events.cpp`` and ``accumulate.cpp``): a step that a
phase faster than it would cut into three parts or more is tried at once, by one kept transition, and taken so
only where the screen (``screen.hpp``) proves from its ends that no event fires inside it and no extremum lies
inside it beyond those so far; elsewhere it goes in its parts as before.  Its results are the parts' to
rounding: every event and every extremum the parts find is found, at the same instant."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding import _core
from pounding._control import CTL_AUDITED, CTL_ESCAPES, CTL_SERIES, CTL_WHOLE, new_control
from pounding._core import run as run_kernel
from pounding._units import GRAVITY_M_S2
from pounding.engine.assembly import assemble
from pounding.engine.simulate import kernel_forcing
from strategies import buildings

G = GRAVITY_M_S2  # (the weight a friction isolator carries is the masses' times this)


def both(system, forcing, y0, t_end, sample_dt=0.0):
    """The kernel's run taken whole where it may, and in parts: (outputs, control) for each.  The first is
    audited (``audit_screen``): each step it took whole looked at on 31 inner instants, where no event's
    function may be below zero and nothing tracked beyond its extremes so far; none is."""
    runs = []
    for whole in (True, False):
        ctl = new_control(10**9)
        runs.append((run_kernel(system, forcing, np.asarray(y0, dtype=float), t_end, sample_dt, 1e-10, 10**6,
                                True, ctl, whole_steps=whole, audit_screen=whole), ctl))
    ctl = runs[0][1]
    assert ctl[CTL_ESCAPES] == 0, (int(ctl[CTL_ESCAPES]), int(ctl[CTL_AUDITED]), int(ctl[CTL_WHOLE]))
    return runs


def assert_alike(whole, parts, rtol=1e-9, plateaus=(), n=0):
    """The same events (kinds and elements; instants to rounding), extrema (values and instants), ledger and
    end state to ``rtol`` of their sizes.  An extremum whose value is one of ``plateaus`` (a rigid stop's gap,
    where a level rests held: its largest displacement is reached again and again at one value) may be dated
    by either run's first instant at it: its instant is not compared (``n``: the system's dofs)."""
    assert whole.status == parts.status
    assert whole.events.shape == parts.events.shape, (whole.events, parts.events)
    np.testing.assert_allclose(whole.events[:, 0], parts.events[:, 0], rtol=0, atol=1e-9)
    for row, other in zip(whole.events, parts.events):
        # (the same event, or one of two at the same instant to rounding taken in the other order: a triple
        # friction pendulum's outer surfaces reaching their thresholds together)
        tied = parts.events[np.abs(parts.events[:, 0] - row[0]) <= 1e-12, 1:]
        same = np.array_equal(row[1:], other[1:])
        assert same or any(np.array_equal(row[1:], t) for t in tied), (row, other)
    ex_w, ex_p = whole.extrema.copy(), parts.extrema.copy()
    for q in (DOF * i + k for i in range(n) for k in (1, 3)):  # (a displacement's max's instant, its min's)
        if any(abs(abs(ex_p[q - 1]) - g) <= 1e-12 * g for g in plateaus):
            ex_w[q] = ex_p[q]
    for name, a, b in (("extrema", ex_w, ex_p), ("state", whole.state, parts.state),
                       ("ledger", whole.ledger, parts.ledger)):
        scale = np.nanmax(np.abs(b)) if np.size(b) else 0.0
        np.testing.assert_allclose(a, b, rtol=rtol, atol=rtol * scale, err_msg=name)
    assert whole.samples.shape == parts.samples.shape


DOF, PAIR = _core.LAYOUT["DOF_EXTREMA"], _core.LAYOUT["PAIR_EXTREMA"]


def sub_interval_s(system) -> float:
    """A phase's sub-interval as the core sizes it (a period of its fastest rate over 8), from the system's
    mass, stiffness and damping without its isolator's or contacts' stiffness."""
    state = system.__getstate__()
    m = np.asarray(state["mass"])
    n = m.size
    k, c = np.abs(np.reshape(state["k0"], (n, n))), np.abs(np.reshape(state["c0"], (n, n)))
    scale = 1.0 / np.sqrt(np.outer(m, m))
    kap, gam = (k * scale).sum(axis=1).max(), (c * scale).sum(axis=1).max()
    rate = max(np.sqrt(kap + (0.5 * gam) ** 2), gam, 1e-300)
    return 2.0 * np.pi / (8.0 * rate)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(building=buildings(min_levels=2), ratio=st.floats(2.05, 3.15), seed=st.integers(0, 2**32 - 1),
       pga=st.floats(0.5, 8.0), smooth=st.booleans(), sampled=st.booleans())
def test_random_buildings_taken_whole_are_their_parts(building, ratio, seed, pga, smooth, sampled):
    # random buildings (linear, bilinear and friction isolators; a wall of a linear law, a rigid stop or none)
    # under a random record whose step is 2 to 3 of their phases' sub-intervals: the steps the screen clears
    # are taken whole, and the run is the one in parts to rounding
    system = assemble(building).system
    dt = ratio * sub_interval_s(system)
    t = dt * np.arange(int(4.0 / dt) + 2)
    accel = np.random.default_rng(seed).normal(0.0, 1.0, t.size)
    if smooth:
        accel = np.convolve(accel, np.ones(5) / 5, mode="same")
    rec = pd_.Record(t, accel * pga / max(np.abs(accel).max(), 1e-12))
    y0 = pd_.State.at_rest(building).vector
    (whole, _), (parts, _) = both(system, kernel_forcing(rec), y0, t[-1], 0.01 if sampled else 0.0)
    stops = [g for w in building.walls if isinstance(w.law, pd_.RigidStop)
             for g in (w.gap_left_m, w.gap_right_m) if g is not None]
    assert_alike(whole, parts, plateaus=stops, n=system.n)


def test_most_steps_of_a_sliding_building_under_a_record_are_taken_whole():
    # a 4-level building on a friction pendulum under El Centro (its step 2.3 of the phases' sub-intervals):
    # most steps are taken whole, the series is made less often, and the results are the parts'
    iso = pd_.FrictionIsolator(mu=0.06, radius_m=2.2)
    building = pd_.Structure(3.0e4, iso, [pd_.Storey(2.0e4, 4.0e7, 4.0e4)] * 3, [])
    rec = pd_.records.el_centro().scaled(pga_g=0.6)
    system, forcing, y0 = assemble(building).system, kernel_forcing(rec), pd_.State.at_rest(building).vector
    (whole, ctl_w), (parts, ctl_p) = both(system, forcing, y0, rec.duration_s)
    assert_alike(whole, parts)
    steps = rec.t.size - 1
    assert ctl_w[CTL_WHOLE] > steps / 2 and ctl_p[CTL_WHOLE] == 0, (ctl_w[CTL_WHOLE], steps)
    ctl = new_control(10**9)  # (not audited: the audit makes the series it looks at the steps on)
    run_kernel(system, forcing, np.array(y0), rec.duration_s, 0.0, 1e-10, 10**6, True, ctl)
    assert ctl[CTL_SERIES] < ctl_p[CTL_SERIES], (ctl[CTL_SERIES], ctl_p[CTL_SERIES])
    assert len(whole.events) > 50  # (sticks and slips throughout)


def _free_vibration(mu, wall_gap_m=None, peak_at=0.5, excess=1e-3, damping_n_s_m=0.0, steps=12):
    """Two levels of 20 t on a flat slider of friction coefficient ``mu``, stuck, a storey of 4e7 N/m (its
    dashpot ``damping_n_s_m``) between them: the upper level in free vibration under a zero record of
    ``steps`` steps, each 0.2 of its period (about 2.3 of the phases' sub-intervals: three parts), from a zero
    crossing, so that its first peak falls at ``peak_at`` of the second step.  The amplitude puts that peak
    ``excess`` (relative) beyond the slider's friction force mu W (a stick's end), or beyond the gap to a wall
    at the upper level (a contact); the cubic through the step's ends falls short of it by about 1 %.
    (system, forcing, y0, t_end, the peak's instant, the step)."""
    storey = pd_.Storey(2.0e4, 4.0e7, damping_n_s_m)
    w = np.sqrt(storey.stiffness_n_m / storey.mass_kg)
    period = 2.0 * np.pi / w
    dt = 0.2 * period
    t_peak = (1.0 + peak_at) * dt
    t0 = t_peak - 0.25 * period
    if wall_gap_m is None:
        amplitude = mu * 4.0e4 * G / storey.stiffness_n_m * (1.0 + excess)
        walls = []
    else:
        amplitude = wall_gap_m * (1.0 + excess)
        walls = [pd_.Wall(1, wall_gap_m, wall_gap_m, pd_.KelvinVoigt(1e8, 0.0))]
    building = pd_.Structure(2.0e4, pd_.FrictionIsolator(mu=mu, radius_m=None), [storey], walls)
    system = assemble(building).system
    t = dt * np.arange(steps)
    forcing = kernel_forcing(pd_.Record(t, np.zeros(t.size)))
    y0 = np.array(pd_.State.at_rest(building, time_s=t0).vector)
    y0[system.layout["v"] + 1] = amplitude * w  # (the upper level at 0 at t0, on its way to the peak)
    return system, forcing, y0, t[-1], t_peak, dt


@pytest.mark.parametrize("peak_at", [0.3, 0.5, 0.7])
def test_a_stick_whose_force_peaks_inside_a_step_ends_there(peak_at):
    # a building stuck on a flat slider, its upper level swinging: the force the slider needs to hold peaks
    # 1e-3 beyond mu W inside a step the cubic through its ends shows 1 % below it; the step is not taken
    # whole, and the slip starts where the parts find it (the swing's own peak, a new largest, keeps that
    # step in parts too; in the stuck building under a table below, only the events' bound does)
    system, forcing, y0, t_end, t_peak, dt = _free_vibration(0.05, peak_at=peak_at)
    (whole, _), (parts, _) = both(system, forcing, y0, t_end)
    assert len(parts.events) >= 1 and abs(parts.events[0, 0] - t_peak) < 0.05 * dt, (parts.events, t_peak)
    assert_alike(whole, parts)
    # the same with mu W 5 % beyond the peak and the swing damped: no slip, and most steps taken whole (the
    # peaks, each below the last, cleared)
    system, forcing, y0, t_end, _, _ = _free_vibration(0.05, peak_at=peak_at, excess=-0.05, damping_n_s_m=4e4,
                                                       steps=30)
    (held, ctl), _ = both(system, forcing, y0, t_end)
    assert len(held.events) == 0 and ctl[CTL_WHOLE] >= 15, (held.events, ctl[CTL_WHOLE])


@pytest.mark.parametrize("peak_at", [0.3, 0.5, 0.7])
def test_a_wall_reached_inside_a_step_is_struck_there(peak_at):
    # the same building held on its slider, its upper level swinging 1e-3 beyond the gap to a wall inside a
    # step the cubic through its ends shows 1 % short of it: the step is not taken whole, and the contact
    # starts where the parts find it (as above, the swing's new largest keeps that step in parts too; the
    # swing lightly damped: each peak a little lower than the last, none tying another to rounding)
    system, forcing, y0, t_end, t_peak, dt = _free_vibration(0.3, wall_gap_m=0.002, peak_at=peak_at,
                                                             damping_n_s_m=500.0)
    (whole, _), (parts, _) = both(system, forcing, y0, t_end)
    assert len(parts.contacts) >= 1, parts.contacts
    assert abs(parts.contacts[0, 1] - t_peak) < 0.05 * dt, (parts.contacts, t_peak)
    assert_alike(whole, parts)
    np.testing.assert_allclose(whole.contacts, parts.contacts, rtol=1e-9, atol=1e-12)
    system, forcing, y0, t_end, _, _ = _free_vibration(0.3, wall_gap_m=0.002, peak_at=peak_at, excess=-0.05,
                                                       damping_n_s_m=4e4, steps=30)
    (clear, ctl), _ = both(system, forcing, y0, t_end)
    assert len(clear.contacts) == 0 and ctl[CTL_WHOLE] >= 15, (clear.contacts, ctl[CTL_WHOLE])


@pytest.mark.parametrize("excess", [1e-4, 1e-6])
def test_a_stick_force_peaking_inside_a_step_cleared_of_extrema_ends_there(excess):
    # a building stuck on a flat slider whose storey has rung down from a first swing, then a constant table
    # acceleration on it from the ninth step: the force needed to hold the base peaks, inside a step, at
    # (1 + excess) mu W, with no displacement, drift or absolute acceleration beyond those of the first swings
    # (the extrema's screen clears that step): only the events' bound keeps it from going whole, and the slip
    # starts where the parts find it (with no bound on the held force's fourth derivative the slip is missed)
    base, upper, k, c = 2.0e4, 2.0e4, 4.0e7, 2.0 * 0.02 * np.sqrt(4.0e7 * 2.0e4)

    def system_of(mu):
        slider = pd_.FrictionIsolator(mu=mu, radius_m=None)
        building = pd_.Structure(base, slider, [pd_.Storey(upper, k, c)], [])
        return building, assemble(building).system

    building, system = system_of(0.3)
    dt = 2.1 * sub_interval_s(system)
    t = dt * np.arange(20)
    rec = pd_.Record(t, np.where(np.arange(20) > 9, 0.3 * 1.0e4 / upper, 0.0))
    forcing = kernel_forcing(rec)
    y0 = np.array(pd_.State.at_rest(building).vector)
    y0[system.layout["v"] + 1] = 1.0e4 / k * np.sqrt(k / upper)  # (the storey's first swing: 1e4 N)
    # the force needed to hold the base, densely sampled on a run that stays stuck: its largest after the ramp
    held = run_kernel(system, forcing, y0, t[-1], dt / 4000, 1e-10, 10**6, True, new_control(10**9)).samples
    ts, x0, x1, v0, v1 = held[:, 0], held[:, 1], held[:, 2], held[:, 3], held[:, 4]
    force = np.abs(base * np.interp(ts, t, rec.accel) - (k * (x1 - x0) + c * (v1 - v0)))
    after = ts > t[9]
    i = np.argmax(force * after)
    assert 0.25 < (ts[i] / dt) % 1.0 < 0.75 and force[i] > 1.05 * force[~after].max()  # (inside a step)
    mu = force[i] / ((base + upper) * G * (1.0 + excess))
    (whole, ctl), (parts, _) = both(system_of(mu)[1], forcing, y0, t[-1])
    assert len(parts.events) >= 2 and abs(parts.events[0, 0] - ts[i]) < 0.05 * dt, (parts.events, ts[i])
    assert_alike(whole, parts)
    assert ctl[CTL_WHOLE] >= 10, ctl[CTL_WHOLE]


def test_peaks_that_pass_the_largest_by_a_hair_inside_whole_steps_are_each_found():
    # a building on a soft, damped rubber bearing with a stiff light storey, in its steady response to a
    # sampled 0.5 Hz sine growing by 1e-9 a second, its step 2.5 of the storey's sub-intervals: every period's
    # peak of the base passes the largest so far by about 1e-9 of it, inside a step; the steps holding one are
    # not taken whole, most others are, and the largest and its instant are the parts' (the displacement's
    # bound and the absolute acceleration's each refuse those steps: with either alone left out, the other
    # still does)
    building = pd_.Structure(2.0e4, pd_.Isolator((2.0e5,), damping_n_s_m=2.5e4),
                             [pd_.Storey(2.0e3, 8.0e6, 2.0e3)], [])
    system = assemble(building).system
    dt = 2.5 * sub_interval_s(system)
    period = round(2.0 / dt) * dt  # (a whole number of steps: every period's samples the same)
    t = dt * np.arange(int(200.0 / dt) + 2)
    rec = pd_.Record(t, 2.0 * (1.0 + 1e-9 * t) * np.sin(2.0 * np.pi * t / period))
    forcing = kernel_forcing(rec)
    y0 = np.array(pd_.State.at_rest(building).vector)
    start = run_kernel(system, forcing, y0, 100.0, 0.0, 1e-10, 10**6, True, new_control(10**9)).state
    (whole, ctl_w), (parts, _) = both(system, forcing, start, t[-1])
    assert_alike(whole, parts, rtol=1e-12)
    assert whole.extrema[1] > t[-1] - period, whole.extrema[:2]  # (the largest in the last period)
    steps = int((t[-1] - 100.0) / dt)
    assert steps / 5 < ctl_w[CTL_WHOLE] < steps, (ctl_w[CTL_WHOLE], steps)


def test_the_door_takes_whole_steps_only_where_asked():
    # whole_steps=False at the core's door: no step taken whole; the screen's own off (screen_extrema=False)
    # takes none either
    iso = pd_.FrictionIsolator(mu=0.06, radius_m=2.2)
    building = pd_.Structure(3.0e4, iso, [pd_.Storey(2.0e4, 4.0e7, 4.0e4)] * 3, [])
    rec = pd_.records.el_centro().scaled(pga_g=0.6)
    system, forcing, y0 = assemble(building).system, kernel_forcing(rec), pd_.State.at_rest(building).vector
    counts = []
    for options in ({}, {"whole_steps": False}, {"screen_extrema": False}):
        ctl = new_control(10**9)
        run_kernel(system, forcing, np.array(y0), 5.0, 0.0, 1e-10, 10**6, True, ctl, **options)
        counts.append(int(ctl[CTL_WHOLE]))
    assert counts[0] > 0 and counts[1:] == [0, 0], counts
    assert _core.LAYOUT["CTL_WHOLE"] == CTL_WHOLE
