"""The event-driven simulation kernel: arrays and scalars in, arrays out.

The run is cut into sub-intervals, each inside one phase of motion (fixed isolator state,
fixed contacts, one piece of the excitation) and short against the phase's periods.  On
each sub-interval the trajectory is known in closed form (linear phases) or from one
Dormand-Prince step (nonlinear contact laws); every event function is checked for a
crossing or a graze and the earliest root is located by Newton's method kept inside the
bracket.  What the sub-interval adds to the run (energy integrals, extrema, contact
statistics) is ``_subinterval.accumulate``'s; then the state jumps at the event.

``run_kernel`` is the loop; each of its parts is a function of ``_kernel_parts``: the phase's record
(``_set_phase``), a numerical step (``_numeric_step``), the phase's events
(``_phase_events``), the cuts where the velocity vanishes (``_velocity_cuts``), the earliest
event (``_earliest_event``), the samples (``_samples_inside``), the bumpers' recovery
(``_move_bumpers``), the jump at an event (``_jump``) and the run's end (``_finish``).  The
system and the forcing come as records (``_system.System``, ``Forcing``).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit_entry
from ..model.contact_laws import MULTILINEAR, MULTILINEAR_KINEMATIC
from ._buffers import put as _put
from ._forcing import EXC_HARMONIC, RESOLUTION, excitation_piece
from ._hold import hold_run, new_table
from ._kernel_parts import (  # noqa: F401  (the status codes: other modules read them here)
    BUDGET,
    DBL_MAX,
    DEGENERATE_PHASE,
    INTERRUPTED,
    MAX_EVENTS,
    NONFINITE,
    POLL_EVERY,
    STEP_FAILED,
    SUBINTERVALS_PER_PERIOD,
    SUCCESS,
    TINY_SPEED,
    TYPED_FALSE,
    XTOL_S,
    ZENO,
    ZENO_REPEATS,
    _advance_mass,
    _continue_phase,
    _earliest_event,
    _finish,
    _jump,
    _move_bumpers,
    _new_phase,
    _numeric_step,
    _phase_events,
    _record_event,
    _run_constants,
    _samples_inside,
    _set_phase,
    _velocity_cuts,
)
from ._layout import (
    CONTACT_COLS,
    CTL_BUDGET,
    CTL_HELD,
    CTL_STOP,
    CTL_WORK,
    EV_COLS,
    EVENT_COLS,
    L_BUMPER,
    L_ISOLATOR,
    L_KINETIC,
    LEDGER_LEN,
    MODE_LINEAR,
    P_AX0,
    P_AX1,
    P_C,
    P_H,
    P_K,
    P_MODE,
    P_P0,
    P_P1,
    P_R0,
    P_SPHI,
    P_VRUN,
    P_XRUN,
    IN_L,
    IN_R,
    PH_LEN,
    SAMPLE_COLS,
    D,
    T,
    V,
)
from ._linear import fill_end, linear_eval_angle, linear_eval_end, linear_forcing, linear_setup, linear_start
from ._outputs import energies as _energies
from ._outputs import outputs as _outputs
from ._subinterval import accumulate, track_abs_acceleration
from ._trajectory import phase_eval


@jit_entry
def run_kernel(sy, fo, state0, t_end, sample_dt, rtol, max_events, with_energy, ctl):
    """Simulate the system ``sy`` (``_system.System``) under the forcing ``fo`` (``Forcing``)
    from ``state0`` to ``t_end``.

    ``sample_dt`` is the history's step (0: events only; -1: not even those).
    ``with_energy`` False skips the energy quadrature outside contacts (a sweep needs the
    contacts' impulse and work, not the ledger); the ledger is then NaN.  ``ctl`` is the
    run control (``_layout.CTL_*``): the loop stops with ``INTERRUPTED`` as soon as
    ``ctl[CTL_STOP]`` is set (by another thread) and with ``BUDGET`` when the sub-intervals
    counted in ``ctl[CTL_WORK]`` reach ``ctl[CTL_BUDGET]``; it adds its own to the count.
    A state that leaves floating point (inf, NaN) stops it with ``NONFINITE``.

    Returns ``(state, samples, contacts, events, ledger, extrema, status)``; see ``_layout``
    for the columns.
    """
    mass, bw, law_l, law_r = sy.mass, sy.bw, sy.law_l, sy.law_r
    st = state0.copy()
    t_run0 = st[T]
    samples = np.empty((256, SAMPLE_COLS))
    contacts = np.empty((16, CONTACT_COLS))
    events = np.empty((64, EVENT_COLS))
    n_s = np.int64(0)  # typed, not literal, counters: see _layout.py
    n_c = np.int64(0)
    n_e = np.int64(0)
    ledger = np.zeros(LEDGER_LEN)
    extrema = np.array([st[D], t_run0, st[D], t_run0, 0.0, t_run0, 0.0])
    ph = np.zeros(PH_LEN)
    _run_constants(ph, sy, fo)
    z_max = (bw[2] / (bw[3] + bw[4])) ** (1.0 / bw[5]) if bw[0] != 0.0 else 0.0
    v_res = RESOLUTION * ph[P_VRUN]
    resolution = (v_res, RESOLUTION * ph[P_XRUN], mass * v_res)
    evs = np.zeros((2 * (sy.slopes.size - 1) + 11, EV_COLS))  # (+ the bumpers' 2 x 5, + Bouc-Wen's z)
    # After a sub-interval without event in a linear phase, the next one continues the same
    # phase (``continuing``): same coefficients, length and events, and the event values at
    # the end of one are those at the start of the next.  Under harmonic forcing the
    # sub-interval must have been a full one; a record's next piece changes the forcing
    # polynomial only (the particular solution is redone, not the rest).
    ev_end = np.empty((evs.shape[0], 3))
    # a record's quiet sample intervals go by the first-order-hold recurrence (_hold)
    record = fo.kind != EXC_HARMONIC
    hold = new_table(record)
    ev_new = np.empty((evs.shape[0] if record else 1, 3))
    continuing = TYPED_FALSE
    t_horizon = np.inf
    has_ml = sy.has_b and (law_l == MULTILINEAR or law_r == MULTILINEAR or law_l == MULTILINEAR_KINEMATIC
                           or law_r == MULTILINEAR_KINEMATIC)  # (the laws with a horizon)
    h_phase = 0.0
    s1 = c1 = 0.0  # the forcing angle's sine and cosine at the end of the last sub-interval
    t_last = h_last = 0.0  # its start and length
    n_ev = np.int64(0)
    kin0, iso0, bmp0 = _energies(st, sy)
    status = SUCCESS
    zero_run = 0
    h_num = 1e-4
    a_abs, f_iso, f_l, f_r = _outputs(st, st[D], st[V], sy)
    _put(samples, n_s, t_run0, st[D], st[V], a_abs, f_iso, f_l, f_r, 0.0, 0.0)
    n_s += 1
    track_abs_acceleration(extrema, t_run0, a_abs)
    j_next = np.int64(1)
    j_rec = np.int64(0)  # the record's sample interval last met (excitation_piece starts there)
    work = np.int64(0)
    work_left = ctl[CTL_BUDGET] - ctl[CTL_WORK]
    next_poll = np.int64(0)
    while st[T] < t_end:
        # the run control, polled every POLL_EVERY sub-intervals (one compare in between)
        if work >= next_poll:
            if ctl[CTL_STOP] != 0:
                status = INTERRUPTED
                break
            if work >= work_left:
                status = BUDGET
                break
            next_poll = min(work + POLL_EVERY, work_left)
        if record and continuing and st[IN_L] == 0.0 and st[IN_R] == 0.0:
            t_limit = min(t_end, t_horizon)
            if sample_dt > 0.0:
                t_limit = min(t_limit, t_run0 + j_next * sample_dt)
            n_hold, j_rec = hold_run(ph, st, sy, fo, j_rec, (evs, n_ev, ev_end, ev_new), hold,
                                     (ledger, extrema), (t_limit, h_phase, next_poll - work, with_energy))
            if n_hold > 0:
                work += n_hold
                ctl[CTL_HELD] += n_hold
                continue
        work += 1
        t = st[T]
        a0x, a1x, amp, omega, phase, t_knot, j_rec = excitation_piece(fo.kind, fo.p, fo.rec_t, fo.rec_a, t,
                                                                      j_rec)
        if continuing:  # the same linear phase under harmonic forcing: only the start values move
            _continue_phase(ph, st, phase)
            h = h_phase
        else:
            h, horizon = _new_phase(ph, st, sy, (a0x, a1x, amp, omega, phase), has_ml)
            if has_ml:
                t_horizon = t + horizon
            h_phase = h
        t_stop = min(t_knot, t_end, t_horizon)
        to_stop = h >= t_stop - t
        if to_stop:
            h = t_stop - t
        if continuing:
            # the forcing angle where the last sub-interval ended (by angle addition), moved on
            # by the rounding of the clock, t - t_last - h: without it the difference between
            # this angle and the clock's, omega t + phase, would grow sub-interval after
            # sub-interval (first order suffices: the rounding is ~1e-16 t)
            wd = omega * ((t - t_last) - h_last)
            if fo.kind != EXC_HARMONIC:  # (the record's piece: a0x + a1x tau, a new one at each knot)
                ph[P_P0] = -ph[P_R0] - mass * a0x
                ph[P_P1] = -mass * a1x
                ph[P_AX0] = a0x
                ph[P_AX1] = a1x
                linear_forcing(ph)  # (no harmonic term: never resonant)
            linear_start(ph, s1 + wd * c1, c1 - wd * s1)
            fill_end(ph, h)
            d1, v1, a1, s1, c1 = linear_eval_end(ph, h)
        elif ph[P_MODE] == MODE_LINEAR:
            if not linear_setup(ph):
                status = DEGENERATE_PHASE
                break
            fill_end(ph, h)
            d1, v1, a1, s1, c1 = linear_eval_end(ph, h)
        else:
            s1 = c1 = 0.0  # (the forcing angle serves linear phases only)
            status, h, h_num, shortened, d1, v1, a1 = _numeric_step(ph, st, h, h_num, rtol, t)
            if shortened:
                to_stop = False
            if status != SUCCESS:
                break
        d0, v0 = st[D], st[V]
        if ph[P_MODE] == MODE_LINEAR:  # sin(phi) is linear_setup's
            a0 = (ph[P_P0] + ph[P_H] * ph[P_SPHI] - ph[P_C] * v0 - ph[P_K] * d0) / mass
        else:
            a0 = phase_eval(ph, 0.0)[2]
        if not continuing:  # (a phase's events stay the same until one of them fires)
            n_ev = _phase_events(ph, st, sy, evs)
        # A start at rest (t = 0, or the mass at rest against a bumper) moves the way a0
        # points: the sign tests below and the events' rates at the start take the velocity as
        # the smallest of that sign.  With 0 itself, an event of the displacement alone would
        # start with rate 0, and a dip into it at once (the table pushing a mass resting
        # against a bumper at zero gap into it, then back) would go unseen.
        v0s = v0
        if v0 == 0.0 and a0 != 0.0:
            v0s = math.copysign(TINY_SPEED, a0)
        h, cut, ends, t_vel, d_vel = _velocity_cuts(ph, evs, bw[0] != 0.0, h, v0s, a0, (d1, v1, a1, s1, c1))
        d1, v1, a1, s1, c1 = ends
        if cut:
            to_stop = False
        tau, i_ev = _earliest_event(ph, evs, n_ev, ev_end, continuing, h, (d0, v0s, a0), (d1, v1, a1),
                                    t_vel, d_vel)
        # (stopped at a record's knot, not at a relaxing law's horizon or the end)
        continuing = (i_ev < 0 and ph[P_MODE] == MODE_LINEAR
                      and (not to_stop or (fo.kind != EXC_HARMONIC and t_knot < min(t_horizon, t_end))))
        if i_ev >= 0:
            to_stop = False
            if tau < h:
                if ph[P_MODE] == MODE_LINEAR:
                    d1, v1, a1, s1, c1 = linear_eval_angle(ph, tau)
                else:
                    d1, v1, a1 = phase_eval(ph, tau)
        if t_vel > tau:
            t_vel = -1.0
        accumulate(ph, st, t, tau, d0, v0, a0, d1, v1, a1, s1, c1, ledger, extrema, evs, t_vel, d_vel,
                   with_energy)
        if sample_dt > 0.0:  # (samples strictly inside (t, t + tau])
            samples, n_s, j_next = _samples_inside(ph, samples, n_s, j_next, sample_dt, t_run0, t, tau, t_end)
        # advance the state to the end of the sub-interval
        _move_bumpers(st, sy, d1, tau, ledger)
        if not (abs(d1) <= DBL_MAX and abs(v1) <= DBL_MAX):  # inf or NaN: nothing after it holds
            status = NONFINITE
            break
        _advance_mass(st, sy, ph, tau, d0, d1, v1, ledger, z_max)
        st[T] = t_stop if to_stop else t + tau
        t_last = t
        h_last = tau
        if i_ev < 0:
            continue
        # the event: jump of the state
        contacts, n_c = _jump(st, sy, evs, i_ev, contacts, n_c, resolution)
        events, n_e, samples, n_s = _record_event(st, sy, evs[i_ev], events, n_e, samples, n_s, sample_dt,
                                                  extrema)
        zero_run = zero_run + 1 if tau <= 1e-12 * max(1.0, abs(t)) else 0
        if zero_run > ZENO_REPEATS:
            status = ZENO
            break
        if n_e >= max_events:
            status = MAX_EVENTS
            break
    samples, n_s, contacts, n_c = _finish(st, sy, samples, n_s, contacts, n_c)
    ctl[CTL_WORK] += work
    kin1, iso1, bmp1 = _energies(st, sy)
    ledger[L_KINETIC] = kin1 - kin0
    ledger[L_ISOLATOR] = iso1 - iso0
    ledger[L_BUMPER] = bmp1 - bmp0
    if not with_energy:
        for j in range(LEDGER_LEN):
            ledger[j] = np.nan
    return (st, samples[:n_s].copy(), contacts[:n_c].copy(), events[:n_e].copy(), ledger,
            extrema, status)
