"""The parts of the event loop (``_kernel.run_kernel``): a phase's record, a numerical step, the
phase's events, the cuts where the velocity vanishes, the earliest event, the samples, the bumpers'
recovery, the jump at an event and its record, the run's end.  Each takes the system record
(``_system.System``) where it needs the system, and arrays and scalars otherwise.
"""

from __future__ import annotations

import math

import numpy as np

from .._errors import Status
from .._jit import jit, jit_alloc
from ..model.contact_laws import (
    AT_START,
    N_LAW_PARAMS,
    N_LAW_STATE,
    law_after_event,
    law_contact_state,
    law_energy,
    law_is_linear,
    law_linear_branch,
    law_moved,
    law_relax,
    law_release_state,
)
from ..model.isolator import BW_PARAMS
from ._buffers import grow as _grow
from ._buffers import put as _put
from ._bumpers import bumper_events, law_switches, relax_horizon
from ._forcing import run_scales
from ._isolator import iso_advance, iso_events, iso_linear, iso_transition
from ._layout import (
    A_DSTART,
    A_IMPULSE,
    A_MAXCOMP,
    A_PEAK,
    A_TSTART,
    A_VIN,
    A_WORK,
    ACC_L,
    ACC_R,
    ACT_BOUC_WEN,
    ACT_CONTACT,
    ACT_LAW_BRANCH,
    ACT_RELEASE,
    DEF_L,
    DEF_R,
    E_ACTION,
    E_ALPHA,
    E_DIR,
    E_INDEX,
    E_KIND,
    E_SIDE,
    IN_L,
    IN_R,
    KIND_ZETA,
    L_BUMPER_LOSS,
    L_HYSTERETIC,
    MODE_LINEAR,
    MODE_NUMERIC,
    P_AX0,
    P_AX1,
    P_AXH,
    P_BW,
    P_C,
    P_CBL,
    P_CBR,
    P_CD,
    P_D0,
    P_DL0,
    P_DP5_H,
    P_DR0,
    P_GAPL,
    P_GAPR,
    P_H,
    P_INL,
    P_INR,
    P_JBL,
    P_JBR,
    P_K,
    P_KBL,
    P_KBR,
    P_KISO,
    P_LAWL,
    P_LAWR,
    P_LZL,
    P_LZR,
    P_M,
    P_MODE,
    P_NLL,
    P_NLR,
    P_P0,
    P_P1,
    P_PHI,
    P_PL,
    P_PR,
    P_R0,
    P_RBL,
    P_RBR,
    P_RISO,
    P_V0,
    P_VROUND,
    P_VRUN,
    P_W,
    P_XROUND,
    P_XRUN,
    P_ZETA0,
    SIDE_L,
    SIDE_NONE,
    SIDE_R,
    Z_L,
    Z_R,
    ZETA,
    ZL_AT,
    ZR_AT,
    D,
    T,
    V,
)
from ._linear import linear_eval_angle, reset_ends
from ._numeric import dp5_step
from ._outputs import outputs as _outputs
from ._outputs import outputs_in_phase as _outputs_in_phase
from ._subinterval import track_abs_acceleration, velocity_turn
from ._trajectory import (
    NO_INDEX,
    ROUNDING,
    W_VELOCITY,
    event_value,
    locate_event,
    newton,
    phase_eval,
    phase_zeta,
    value_at_root,
)

# how a run ended: the codes of pounding.Status, the one place they are defined
SUCCESS, ZENO, MAX_EVENTS, DEGENERATE_PHASE, STEP_FAILED, INTERRUPTED, BUDGET, NONFINITE = (
    int(Status.SUCCESS), int(Status.ZENO), int(Status.MAX_EVENTS), int(Status.DEGENERATE_PHASE),
    int(Status.STEP_FAILED), int(Status.INTERRUPTED), int(Status.BUDGET), int(Status.NONFINITE))
SUBINTERVALS_PER_PERIOD = 8.0
ZENO_REPEATS = 200
XTOL_S = 1e-15          # event instants and displacement extrema, s
DBL_MAX = 1.7976931348623157e308
TINY_SPEED = 1e-300     # m/s: the velocity of a start at rest, for the direction it moves
POLL_EVERY = 64         # sub-intervals between two looks at the run control (about 30 us)
TYPED_FALSE = np.bool_(False)  # (a literal False passed on would compile a callee twice: _jit.py)


@jit
def _set_phase(ph, st, sy, a0, a1, amp, omega, phase):
    """Fill ``ph`` for the sub-interval starting at the current state; return (k, c)."""
    mass, bw = sy.mass, sy.bw
    k_iso, r_iso = iso_linear(sy.slopes, sy.breaks, sy.rule, st)
    k = k_iso
    c = sy.c_d
    r0 = r_iso
    ph[P_NLL] = 0.0
    ph[P_NLR] = 0.0
    ph[P_INL] = 0.0
    ph[P_INR] = 0.0
    # (P_KBL ... P_JBR, a linear law's branch, are read only while that side is in contact)
    if sy.has_b:
        if st[IN_L] != 0.0:
            ph[P_INL] = 1.0
            if law_is_linear(sy.law_l):
                # F_L = kb x + rb + cb x' with x = -D - gap_l pushes the mass to the right
                kb, cb, rb, jb = law_linear_branch(sy.law_l, sy.p_l, AT_START, st[DEF_L], -st[V], st, ZL_AT)
                k += kb
                c += cb
                r0 += kb * sy.gap_l - rb
                ph[P_KBL], ph[P_CBL], ph[P_RBL], ph[P_JBL] = kb, cb, rb, float(jb)
            else:
                ph[P_NLL] = 1.0
        if st[IN_R] != 0.0:
            ph[P_INR] = 1.0
            if law_is_linear(sy.law_r):
                kb, cb, rb, jb = law_linear_branch(sy.law_r, sy.p_r, AT_START, st[DEF_R], st[V], st, ZR_AT)
                k += kb
                c += cb
                r0 += rb - kb * sy.gap_r
                ph[P_KBR], ph[P_CBR], ph[P_RBR], ph[P_JBR] = kb, cb, rb, float(jb)
            else:
                ph[P_NLR] = 1.0
    ph[P_M] = mass
    ph[P_C] = c
    ph[P_K] = k
    ph[P_R0] = r0
    ph[P_P0] = -r0 - mass * a0
    ph[P_P1] = -mass * a1
    ph[P_H] = -mass * amp
    ph[P_W] = omega
    ph[P_PHI] = phase
    ph[P_AX0] = a0
    ph[P_AX1] = a1
    ph[P_AXH] = amp
    ph[P_D0] = st[D]
    ph[P_V0] = st[V]
    ph[P_MODE] = MODE_NUMERIC if (ph[P_NLL] != 0.0 or ph[P_NLR] != 0.0 or bw[0] != 0.0) else MODE_LINEAR
    ph[P_ZETA0] = st[ZETA]
    ph[P_DP5_H] = -1.0  # (a new phase: no step of it taken yet)
    ph[P_XROUND] = ph[P_XRUN]  # (a linear phase's linear_setup adds its closed form's terms)
    ph[P_VROUND] = ph[P_VRUN]
    ph[P_DL0] = st[DEF_L]
    ph[P_DR0] = st[DEF_R]
    for q in range(N_LAW_STATE):
        ph[P_LZL + q] = st[Z_L + q]
        ph[P_LZR + q] = st[Z_R + q]
    ph[P_KISO] = k_iso
    ph[P_RISO] = r_iso
    # (the rate of the phase, for its sub-intervals' length: the spring's initial stiffness too)
    if bw[0] != 0.0:
        k += bw[0] * bw[2] / bw[1]
    return k, c


@jit
def _run_constants(ph, sy, fo):
    """What stays the same all run, in the phase record (set once: a phase's record is
    rewritten some 10,000 times a sweep)."""
    reset_ends(ph)
    ph[P_XRUN], ph[P_VRUN] = run_scales(sy.mass, sy.slopes, fo.kind, fo.p, fo.rec_a, sy.gap_l, sy.gap_r,
                                        sy.breaks)
    ph[P_GAPL] = sy.gap_l
    ph[P_GAPR] = sy.gap_r
    ph[P_LAWL] = sy.law_l
    ph[P_LAWR] = sy.law_r
    for j in range(N_LAW_PARAMS):
        ph[P_PL + j] = sy.p_l[j]
        ph[P_PR + j] = sy.p_r[j]
    ph[P_CD] = sy.c_d
    for j in range(BW_PARAMS):
        ph[P_BW + j] = sy.bw[j]


@jit
def _numeric_step(ph, st, h, h_num, rtol, t):
    """One Dormand-Prince step of a nonlinear phase from the state, at most ``h`` and at most the
    last accepted step's growth ``h_num``, shortened until its error is within ``rtol``.

    Returns ``(status, h, h_num, shortened, d1, v1, a1)``: ``STEP_FAILED`` when the step would
    fall below the clock's resolution; ``shortened`` when it is less than the ``h`` asked.
    """
    shortened = False
    if h_num < h:
        h = h_num
        shortened = True
    atol_d = rtol * 1e-3
    atol_v = rtol * 1e-2
    while True:
        d1, v1, a1, ed, ev, z1, ez = dp5_step(ph, h)
        err = max(abs(ed) / (atol_d + rtol * max(abs(st[D]), abs(d1))),
                  abs(ev) / (atol_v + rtol * max(abs(st[V]), abs(v1))),
                  abs(ez) / (rtol * (1.0 + abs(z1))))  # (z is of order 1; 0 without a spring)
        if err <= 1.0:
            h_num = h * (5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2))
            return SUCCESS, h, h_num, shortened, d1, v1, a1
        h *= max(0.2, 0.9 * err ** -0.2)
        shortened = True
        if h <= 1e-15 * max(1.0, abs(t)):
            return STEP_FAILED, h, h_num, shortened, d1, v1, a1


@jit
def _phase_events(ph, st, sy, evs):
    """The phase's event rows in ``evs`` (the isolator's, the bumpers', the Bouc-Wen z's return
    through zero); their count.  They stay the same until one of them fires."""
    n_ev = iso_events(sy.slopes, sy.breaks, sy.rule, st, evs, np.int64(0))  # typed, not literal
    n_ev = bumper_events(st, ph, sy, evs, n_ev)
    if sy.bw[0] != 0.0 and st[ZETA] != 0.0:  # the Bouc-Wen z back through zero: its law changes form
        row = evs[n_ev]
        row[E_KIND] = KIND_ZETA
        # (value -alpha z: positive until z changes sign)
        row[E_ALPHA] = -math.copysign(1.0, st[ZETA])
        row[E_SIDE] = SIDE_NONE
        row[E_ACTION] = ACT_BOUC_WEN
        row[E_INDEX] = 0.0
        row[E_DIR] = 0.0
        n_ev += 1
    return n_ev


@jit
def _velocity_cuts(ph, evs, has_bw, h, v0s, a0, y1):
    """Where the velocity vanishes inside the sub-interval of length ``h`` (start velocity
    ``v0s``, acceleration ``a0``; end ``y1 = (d1, v1, a1, s1, c1)``).

    A law whose force changes form with the sign of the compression rate (Jankowski's dashpot
    acts on the approach only) ends a numerical step where the velocity is zero, so that no step
    straddles the kink; a velocity that turns inside keeping its sign (two zeros) cuts the
    sub-interval where it turns.  Returns ``(h, cut, y1, t_vel, d_vel)``: ``cut`` when ``h``
    shrank (``y1`` then at the new end), and the instant and displacement of the velocity zero
    left inside (``t_vel`` -1 when none).
    """
    d1, v1, a1, s1, c1 = y1
    cut = False
    if v0s * v1 < 0.0 and ph[P_MODE] != MODE_LINEAR and (law_switches(ph) or has_bw):
        t_v = newton(W_VELOCITY, NO_INDEX, ph, evs, 0.0, h, v0s, v1, a0, a1, XTOL_S)[0]
        if 0.0 < t_v < h:
            h = t_v
            cut = True
            d1, v1, a1 = phase_eval(ph, h)
    if v0s * v1 > 0.0 and a0 * a1 < 0.0:  # the velocity turns inside, keeping its sign?
        t_a = velocity_turn(ph, evs, h, v0s, v1, a0, a1)
        if t_a > 0.0:  # two velocity zeros: cut the sub-interval where it turns
            h = t_a
            cut = True
            if ph[P_MODE] == MODE_LINEAR:
                d1, v1, a1, s1, c1 = linear_eval_angle(ph, h)
            else:
                d1, v1, a1 = phase_eval(ph, h)
    t_vel = -1.0
    d_vel = 0.0
    if v0s * v1 < 0.0:
        t_vel, xe, _, _, de, ve, ae = newton(W_VELOCITY, NO_INDEX, ph, evs, 0.0, h, v0s, v1, a0, a1, XTOL_S)
        if not math.isnan(xe):  # the displacement, stationary there, from Newton's last evaluation
            d_vel = value_at_root(t_vel, xe, de, ve, ae)
        else:
            d_vel = phase_eval(ph, t_vel)[0]
    return h, cut, (d1, v1, a1, s1, c1), t_vel, d_vel


@jit
def _earliest_event(ph, evs, n_ev, ev_end, continuing, h, y0, y1, t_vel, d_vel):
    """The earliest event in ``(0, h]`` and where: ``(tau, i)``, ``(h, -1)`` when none.

    ``y0 = (d0, v0s, a0)`` and ``y1 = (d1, v1, a1)`` are the sub-interval's ends; the event
    values at its end are kept in ``ev_end`` (a continuing phase's next sub-interval starts
    with them).
    """
    d0, v0s, a0 = y0
    d1, v1, a1 = y1
    tau = h
    i_ev = -1
    for i in range(n_ev):
        if continuing:
            g0, gp0, sc0 = ev_end[i, 0], ev_end[i, 1], ev_end[i, 2]
        else:
            g0, gp0, sc0 = event_value(evs, i, ph, 0.0, d0, v0s, a0)
        g1, gp1, sc1 = event_value(evs, i, ph, h, d1, v1, a1)
        ev_end[i, 0] = g1
        ev_end[i, 1] = gp1
        ev_end[i, 2] = sc1
        tol0 = ROUNDING * sc0
        if g0 > tol0 and g1 > 0.0 and not (gp0 < 0.0 and gp1 > 0.0):
            continue
        r = locate_event(i, ph, evs, h, g0, gp0, tol0, g1, gp1, ROUNDING * sc1, XTOL_S, t_vel, d_vel)
        if r >= 0.0 and (r < tau or (i_ev < 0 and r <= tau)):
            tau = r
            i_ev = i
    return tau, i_ev


@jit_alloc
def _samples_inside(ph, samples, n_s, j_next, sample_dt, t_run0, t, tau, t_end):
    """The history's uniform samples strictly inside ``(t, t + tau]`` (and not past ``t_end``):
    ``(samples, n_s, j_next)``, the array grown when full."""
    while True:
        ts = t_run0 + j_next * sample_dt
        if ts > t + tau or ts > t_end:
            break
        ds, vs, as_ = phase_eval(ph, ts - t)
        if n_s >= samples.shape[0]:
            samples = _grow(samples, n_s)
        out = _outputs_in_phase(ph, ts - t, ds, vs, as_)
        _put(samples, n_s, ts, ds, vs, out[0], out[1], out[2], out[3], 0.0, 0.0)
        n_s += 1
        j_next += 1
    return samples, n_s, j_next


@jit
def _move_bumpers(st, sy, d1, tau, ledger):
    """The bumpers at the end of a sub-interval of length ``tau``: one in contact follows the
    mass (now at ``d1``), one out of contact relaxes, its loss added to the ledger."""
    for side in (SIDE_L, SIDE_R):
        idx = DEF_L if side == SIDE_L else DEF_R
        law = sy.law_l if side == SIDE_L else sy.law_r
        p = sy.p_l if side == SIDE_L else sy.p_r
        zo = ZL_AT if side == SIDE_L else ZR_AT
        if (st[IN_L] if side == SIDE_L else st[IN_R]) != 0.0:
            gap = sy.gap_l if side == SIDE_L else sy.gap_r
            st[idx] = max(0.0, (-d1 if side == SIDE_L else d1) - gap)
            law_moved(law, p, AT_START, st, zo, st[idx], 1.0)
        elif st[idx] > 0.0:
            relaxed = law_relax(law, p, AT_START, st[idx], tau, st, zo)[0]
            e0 = law_energy(law, p, st[idx], st, zo)
            law_moved(law, p, AT_START, st, zo, relaxed, 0.0)
            ledger[L_BUMPER_LOSS] += e0 - law_energy(law, p, relaxed, st, zo)
            st[idx] = relaxed


@jit_alloc
def _jump(st, sy, evs, i_ev, contacts, n_c, resolution):
    """The state's jump at event row ``i_ev`` (at the state's time): a contact starts or ends (an
    ended one appended to ``contacts`` unless it is below ``resolution = (speed m/s, depth m,
    impulse N s)``: a graze), a law's branch or a Bouc-Wen spring changes, or the isolator's
    state does.  Returns ``(contacts, n_c)``."""
    v_res, depth_res, impulse_res = resolution
    action = int(evs[i_ev, E_ACTION])
    index = int(evs[i_ev, E_INDEX])
    t_ev = st[T]
    if action == ACT_CONTACT:
        acc = ACC_L if index == SIDE_L else ACC_R
        st[IN_L if index == SIDE_L else IN_R] = 1.0
        comp = st[DEF_L if index == SIDE_L else DEF_R]
        st[acc + A_TSTART] = t_ev
        # below the resolution the mass met the surface at rest (its restitution is NaN)
        st[acc + A_VIN] = st[V] if abs(st[V]) > v_res else 0.0
        if index == SIDE_L:  # (an elastic-plastic law starts unloaded; Hertzdamp's damping from v_in)
            law_contact_state(sy.law_l, sy.p_l, AT_START, -st[acc + A_VIN], st, ZL_AT, comp)
        else:
            law_contact_state(sy.law_r, sy.p_r, AT_START, st[acc + A_VIN], st, ZR_AT, comp)
        st[acc + A_DSTART] = comp
        st[acc + A_IMPULSE] = 0.0
        st[acc + A_PEAK] = 0.0
        st[acc + A_MAXCOMP] = comp
        st[acc + A_WORK] = 0.0
    elif action == ACT_RELEASE:
        acc = ACC_L if index == SIDE_L else ACC_R
        st[IN_L if index == SIDE_L else IN_R] = 0.0
        if index == SIDE_L:
            law_release_state(sy.law_l, sy.p_l, AT_START, st, ZL_AT, st[DEF_L])
        else:
            law_release_state(sy.law_r, sy.p_r, AT_START, st, ZR_AT, st[DEF_R])
        # a touch below the resolution in both depth and impulse (a graze, or a mass resting
        # on a bumper that pushes with zero force) is no impact: the motion went through it
        # exactly, the contact table leaves it out
        if (st[acc + A_MAXCOMP] - st[acc + A_DSTART] > depth_res
                or abs(st[acc + A_IMPULSE]) > impulse_res):
            if n_c >= contacts.shape[0]:
                contacts = _grow(contacts, n_c)
            _put(contacts, n_c, float(index), st[acc + A_TSTART], t_ev, st[acc + A_VIN], st[V],
                 st[acc + A_IMPULSE], st[acc + A_PEAK], st[acc + A_MAXCOMP], st[acc + A_WORK])
            n_c += 1
    elif action == ACT_LAW_BRANCH:  # the next branch is the next phase's; a law's state may change
        if index == SIDE_L:
            law_after_event(sy.law_l, sy.p_l, AT_START, st, ZL_AT, st[DEF_L], evs[i_ev, E_DIR])
        else:
            law_after_event(sy.law_r, sy.p_r, AT_START, st, ZR_AT, st[DEF_R], evs[i_ev, E_DIR])
    elif action == ACT_BOUC_WEN:  # z crossed zero: exactly 0 from here (the next phase starts there)
        st[ZETA] = 0.0
    else:
        iso_transition(sy.slopes, sy.breaks, sy.rule, st, action, index, evs[i_ev, E_DIR])
    return contacts, n_c


@jit
def _continue_phase(ph, st, phase):
    """The phase record for the next sub-interval of the same linear phase: only the start values
    move (the forcing's angle ``phase`` too)."""
    ph[P_PHI] = phase
    ph[P_D0] = st[D]
    ph[P_V0] = st[V]
    ph[P_DP5_H] = -1.0
    ph[P_DL0] = st[DEF_L]
    ph[P_DR0] = st[DEF_R]


@jit
def _new_phase(ph, st, sy, piece, has_ml):
    """A new phase from the state under the forcing piece ``(a0, a1, amp, omega, phase)``: its
    record, and ``(h, horizon)``: its sub-intervals' length (an eighth of its fastest period: its
    frequency, or its fastest decay when overdamped, or the forcing's) and the time (s) until a
    relaxing bumper's surface changes its law at a branch's end, where no sub-interval may pass
    (inf without multi-linear laws, ``has_ml`` False)."""
    a0x, a1x, amp, omega, phase = piece
    mass = sy.mass
    k, c = _set_phase(ph, st, sy, a0x, a1x, amp, omega, phase)
    horizon = relax_horizon(st, sy) if has_ml else np.inf
    rate = max(math.sqrt(abs(k) / mass + (0.5 * c / mass) ** 2), abs(c) / mass)
    return 2.0 * math.pi / (SUBINTERVALS_PER_PERIOD * max(max(rate, omega), 1e-300)), horizon


@jit
def _advance_mass(st, sy, ph, tau, d0, d1, v1, ledger, z_max):
    """The mass and the isolator at the end of a sub-interval of length ``tau`` (the isolator's
    hysteretic work added to the ledger; a Bouc-Wen z held within ``z_max``: an explicit step
    overshoots it by up to its tolerance)."""
    ledger[L_HYSTERETIC] += iso_advance(sy.slopes, sy.breaks, sy.rule, st, d0, d1)
    if sy.bw[0] != 0.0:
        st[ZETA] = min(max(phase_zeta(ph, tau), -z_max), z_max)
    st[D] = d1
    st[V] = v1


@jit_alloc
def _record_event(st, sy, row, events, n_e, samples, n_s, sample_dt, extrema):
    """An event (its row of the phase's events) just applied: its line in ``events``, the state's
    sample after it (unless ``sample_dt`` < 0) and the acceleration's extrema.  Returns
    ``(events, n_e, samples, n_s)``, the arrays grown when full."""
    if n_e >= events.shape[0]:
        events = _grow(events, n_e)
    _put(events, n_e, st[T], row[E_ACTION], row[E_INDEX], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    n_e += 1
    a_abs, f_iso, f_l, f_r = _outputs(st, st[D], st[V], sy)
    track_abs_acceleration(extrema, st[T], a_abs)
    if sample_dt >= 0.0:
        if n_s >= samples.shape[0]:
            samples = _grow(samples, n_s)
        _put(samples, n_s, st[T], st[D], st[V], a_abs, f_iso, f_l, f_r, 0.0, 0.0)
        n_s += 1
    return events, n_e, samples, n_s


@jit_alloc
def _finish(st, sy, samples, n_s, contacts, n_c):
    """The run's end: the last sample, and the contacts still going on (their end NaN).
    Returns ``(samples, n_s, contacts, n_c)``."""
    if samples[n_s - 1, 0] < st[T]:
        if n_s >= samples.shape[0]:
            samples = _grow(samples, n_s)
        out = _outputs(st, st[D], st[V], sy)
        _put(samples, n_s, st[T], st[D], st[V], out[0], out[1], out[2], out[3], 0.0, 0.0)
        n_s += 1
    for side in (SIDE_L, SIDE_R):
        if (st[IN_L] if side == SIDE_L else st[IN_R]) != 0.0:
            acc = ACC_L if side == SIDE_L else ACC_R
            if n_c >= contacts.shape[0]:
                contacts = _grow(contacts, n_c)
            _put(contacts, n_c, float(side), st[acc + A_TSTART], np.nan, st[acc + A_VIN], np.nan,
                 st[acc + A_IMPULSE], st[acc + A_PEAK], st[acc + A_MAXCOMP], st[acc + A_WORK])
            n_c += 1
    return samples, n_s, contacts, n_c
