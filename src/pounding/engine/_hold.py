"""A record's quiet intervals at the record's own step: the first-order-hold recurrence.

Between two samples a record is a straight line, so within one linear phase (fixed isolator
branch, no contact) the motion over a sample interval of length ``h`` is a linear function of
its start and of the force polynomial ``p0 + p1 tau`` (``p0 = -r0 - M a_k``, ``p1 = -M`` times the
record's slope)::

    (D1, V1) = Phi (D0, V0) + G (p0, p1)

with ``Phi = exp(A h)`` and ``G`` fixed for the phase's ``(k, c)`` and the step ``h``: the exact
recurrence of a piecewise-linear input (Nigam and Jennings' for spectra), computed once per
phase and step from the closed form of ``_linear`` (its columns are the closed form's answers to
unit starts and forces) and kept in a small table.  The energy integrals over the interval are
quadratic and linear forms of the same four numbers (``int V^2``, ``int V``, ``int tau V``), their
coefficients from an 8-point Gauss-Legendre rule on the same closed form (exact to degree 15:
below rounding on an interval of at most an eighth of the phase's period, the longest this path
takes).

An interval is taken here only when nothing can happen inside it, tested exactly as the event
loop tests it (``_kernel_parts._earliest_event``, ``_velocity_cuts``, ``_subinterval.accumulate``):
every event function (a relaxing bumper's surface in the contact's) keeps its sign with no dip
possible, the velocity keeps its sign and cannot turn back, the absolute acceleration has no
extremum inside that could be the run's peak, no sample falls in it, it ends before a relaxing
bumper's law changes form.  A bumper out of contact
relaxes over it as the general path relaxes it (``_kernel_parts._move_bumpers``).  Otherwise the
loop takes the interval the general way, from the same start; events are located on the exact
trajectory as before.  What differs from the general path is rounding (a different formula for
the same solution, about 1e-15 of the motion), and a record whose sample times wobble in their
last bits (``k * dt`` rounded) is taken with one ``h`` and a first-order correction of the end
and of the integrals by the wobble (its error of the order of its square: 1e-34 s^2 for a record
at 0.01 s).
"""

from __future__ import annotations


import numpy as np

from .._jit import jit, jit_alloc
from ..excitation.record import HOLD_RTOL  # a sample interval within it of the step is one
from ._layout import (
    PH_LEN,
    L_HYSTERETIC,
    L_INPUT,
    L_VISCOUS,
    P_C,
    P_D0,
    P_DL0,
    P_DR0,
    P_H,
    P_K,
    P_P0,
    P_P1,
    P_PHI,
    P_R0,
    P_V0,
    P_W,
    P_XROUND,
    P_XRUN,
    D,
    DEF_L,
    DEF_R,
    T,
    V,
)
from ._isolator import iso_advance
from ._kernel_parts import _move_bumpers
from ._linear import linear_eval, linear_setup
from ._subinterval import _may_turn_back, track_abs_acceleration
from ._trajectory import ROUNDING, event_value

DBL_MAX = 1.7976931348623157e308
GAUSS_X, GAUSS_W = np.polynomial.legendre.leggauss(8)
GAUSS_X = 0.5 * (GAUSS_X + 1.0)  # on [0, 1]
GAUSS_W = 0.5 * GAUSS_W
N_GAUSS = GAUSS_X.size
# a row of the table: the key (k, c, h), then d1's and v1's coefficients of (D0, V0, p0, p1), the
# upper triangle of int V^2's quadratic form (off-diagonal terms doubled), int V's and int tau V's
H_K, H_C, H_H = 0, 1, 2
H_DD = 3
H_VV = 7
H_Q = 11
H_L0 = 21
H_L1 = 25
HOLD_COLS = 29
N_HOLD = 4          # phases kept (a hysteretic isolator goes through a few again and again)
HOLD_ROWS = N_HOLD + 1  # the last row's first value: the row the next new phase takes


SCRATCH_LEN = PH_LEN + 4 * N_GAUSS  # a phase record, then the unit inputs' velocities at the nodes


@jit_alloc
def new_table(record):
    """The recurrence's table and its scratch space (``run_kernel`` makes them once per run;
    one row and no room without a ``record``: never used then)."""
    if not record:
        return np.full((1, HOLD_COLS), np.nan), np.empty(1)
    table = np.full((HOLD_ROWS, HOLD_COLS), np.nan)
    table[N_HOLD, 0] = 0.0
    return table, np.empty(SCRATCH_LEN)


@jit
def _fill_row(ph, hold, row, h):
    """The recurrence's coefficients for the phase ``ph``'s ``(M, k, c)`` and the step ``h`` into
    row ``row`` of ``hold = (table, scratch)``: the closed form answering each unit input, at ``h``
    and at the Gauss nodes."""
    table, scr = hold
    for i in range(PH_LEN):
        scr[i] = ph[i]
    scr[P_H] = 0.0
    scr[P_W] = 0.0
    scr[P_PHI] = 0.0
    out = table[row]
    out[H_K] = ph[P_K]
    out[H_C] = ph[P_C]
    out[H_H] = h
    for i in range(4):
        scr[P_D0] = 1.0 if i == 0 else 0.0
        scr[P_V0] = 1.0 if i == 1 else 0.0
        scr[P_P0] = 1.0 if i == 2 else 0.0
        scr[P_P1] = 1.0 if i == 3 else 0.0
        linear_setup(scr)  # (no harmonic term: always a closed form)
        d1, v1, _ = linear_eval(scr, h)
        out[H_DD + i] = d1
        out[H_VV + i] = v1
        l0 = 0.0
        l1 = 0.0
        for q in range(N_GAUSS):
            tq = h * GAUSS_X[q]
            vq = linear_eval(scr, tq)[1]
            scr[PH_LEN + N_GAUSS * i + q] = vq
            l0 += h * GAUSS_W[q] * vq
            l1 += h * GAUSS_W[q] * tq * vq
        out[H_L0 + i] = l0
        out[H_L1 + i] = l1
    n = 0
    for i in range(4):
        for j in range(i, 4):
            s = 0.0
            for q in range(N_GAUSS):
                s += h * GAUSS_W[q] * scr[PH_LEN + N_GAUSS * i + q] * scr[PH_LEN + N_GAUSS * j + q]
            out[H_Q + n] = s if i == j else 2.0 * s
            n += 1


@jit
def _row(ph, hold, h):
    """The table's row for this phase and the step ``h``, filled now if none is."""
    table = hold[0]
    k, c = ph[P_K], ph[P_C]
    for r in range(N_HOLD):
        if table[r, H_K] == k and table[r, H_C] == c and table[r, H_H] == h:
            return r
    r = int(table[N_HOLD, 0])
    table[N_HOLD, 0] = float((r + 1) % N_HOLD)
    _fill_row(ph, hold, r, h)
    return r


@jit
def _integrals(row, z0, z1, z2, z3):
    """``(int V^2, int V, int tau V)`` over the interval from ``(D0, V0, p0, p1)``."""
    q = H_Q
    vv = (z0 * (row[q] * z0 + row[q + 1] * z1 + row[q + 2] * z2 + row[q + 3] * z3)
          + z1 * (row[q + 4] * z1 + row[q + 5] * z2 + row[q + 6] * z3)
          + z2 * (row[q + 7] * z2 + row[q + 8] * z3) + z3 * row[q + 9] * z3)
    l0 = row[H_L0] * z0 + row[H_L0 + 1] * z1 + row[H_L0 + 2] * z2 + row[H_L0 + 3] * z3
    l1 = row[H_L1] * z0 + row[H_L1 + 1] * z1 + row[H_L1 + 2] * z2 + row[H_L1 + 3] * z3
    return vv, l0, l1


@jit
def _below_peak(coef, h, ends, peak):
    """True when the absolute acceleration cannot reach ``peak`` inside an interval of length
    ``h`` whose displacement is monotone between the ends ``(d0, v0, d1, v1)``.

    ``coef = (p0, p1, m_a0, M, c, k)``.  With ``|D| <= Db = max(|d0|, |d1|)`` and ``|V(tau)| <=
    |v0| + tau max|A|``, ``M |A| <= max|p0 + p1 tau| + |c| |V| + |k| Db`` bounds the velocity by
    ``Vb = (|v0| + h (P + |k| Db) / M) / (1 - h |c| / M)``, and the absolute acceleration
    ``(m_a0 - c V - k D) / M`` by ``(|m_a0| + |c| Vb + |k| Db) / M``.
    """
    p0, p1, m_a0, mass, c, k = coef
    d0, v0, d1, v1 = ends
    shrink = 1.0 - h * abs(c) / mass
    if shrink <= 0.5:
        return False
    d_b = max(abs(d0), abs(d1))
    p_b = max(abs(p0), abs(p0 + p1 * h))
    v_b = (abs(v0) + h * (p_b + abs(k) * d_b) / mass) / shrink
    return (abs(m_a0) + abs(c) * v_b + abs(k) * d_b) / mass < peak


@jit
def hold_run(ph, st, sy, fo, j, ev, hold, out, lim):
    """Take the record's quiet sample intervals from the state on, in the linear phase ``ph``.

    The state is at the record's sample ``j`` (else nothing is taken); ``ev = (evs, n_ev, ev_end,
    ev_new)`` the phase's event rows, their values at the state (``_earliest_event``'s ``ev_end``)
    and room for the next ones; ``hold`` the recurrence's table and scratch (``new_table``); ``out = (ledger,
    extrema)``; ``lim = (t_limit, h_phase, n_max, with_energy)``: no interval ends at or past
    ``t_limit`` (the run's end, a relaxing law's horizon, the next sample), none is longer than
    the phase's sub-interval ``h_phase``, at most ``n_max`` are taken.

    Returns ``(n, j)``: the intervals taken and the sample the state is now at.  The state, the
    event values, the ledger and the extrema are as the event loop would have left them.
    """
    evs, n_ev, ev_end, ev_new = ev
    ledger, extrema = out
    t_limit, h_phase, n_max, with_energy = lim
    rec_t, rec_a = fo.rec_t, fo.rec_a
    n_rec = rec_t.size
    mass, c_d = sy.mass, sy.c_d
    k, c, r0 = ph[P_K], ph[P_C], ph[P_R0]
    x_run = ph[P_XRUN]
    n = 0
    h_key = fo.p[0]  # the record's step when uniform (Record.kernel_arrays), else 0
    if j + 1 < n_rec and rec_t[j] != st[T] and rec_t[j + 1] == st[T]:
        j += 1
    if h_key <= 0.0 or h_key > h_phase or j + 1 >= n_rec or rec_t[j] != st[T]:
        return n, j
    row = hold[0][_row(ph, hold, h_key)]
    while n < n_max and j + 1 < n_rec:
        t = rec_t[j]
        t1 = rec_t[j + 1]
        h = t1 - t
        if t1 >= t_limit or h > h_phase or abs(h - h_key) > HOLD_RTOL * h:
            break
        # the piece, as excitation_piece and the event loop write it
        slope = (rec_a[j + 1] - rec_a[j]) / h
        a0x = rec_a[j]
        p0 = -r0 - mass * a0x
        p1 = -mass * slope
        d0, v0 = st[D], st[V]
        d1 = row[H_DD] * d0 + row[H_DD + 1] * v0 + row[H_DD + 2] * p0 + row[H_DD + 3] * p1
        v1 = row[H_VV] * d0 + row[H_VV + 1] * v0 + row[H_VV + 2] * p0 + row[H_VV + 3] * p1
        a1 = (p0 + p1 * h_key - c * v1 - k * d1) / mass
        wobble = h - h_key  # (the end moved along the trajectory by the sample times' rounding)
        d1 += v1 * wobble
        v1 += a1 * wobble
        a1 = (p0 + p1 * h - c * v1 - k * d1) / mass
        a0 = (p0 - c * v0 - k * d0) / mass
        if not (abs(d1) <= DBL_MAX and abs(v1) <= DBL_MAX):
            break
        # the velocity keeps its sign and does not turn back (_velocity_cuts)
        if not v0 * v1 > 0.0:
            break
        if a0 * a1 < 0.0 and _may_turn_back(h, v0, v1, a0, a1):
            break
        # no extremum of the absolute acceleration inside (accumulate), or none that can be the
        # run's peak
        if (c * a0 + k * v0) * (c * a1 + k * v1) < 0.0 and not _below_peak(
                (p0, p1, p0 + mass * a0x, mass, c, k), h, (d0, v0, d1, v1), extrema[4]):
            break
        # no event (_earliest_event's test); a contact's scale has the phase's closed form in it
        b0 = 0.0
        if k != 0.0:
            b0 = (p0 - c * (p1 / k)) / k
        ph[P_XROUND] = max(x_run, abs(b0))
        ph[P_DL0] = st[DEF_L]  # (a bumper relaxing from here: _continue_phase)
        ph[P_DR0] = st[DEF_R]
        quiet = True
        for i in range(n_ev):
            g1, gp1, sc1 = event_value(evs, i, ph, h, d1, v1, a1)
            g0, gp0 = ev_end[i, 0], ev_end[i, 1]
            if not (g0 > ROUNDING * ev_end[i, 2] and g1 > 0.0 and not (gp0 < 0.0 and gp1 > 0.0)):
                quiet = False
                break
            ev_new[i, 0] = g1
            ev_new[i, 1] = gp1
            ev_new[i, 2] = sc1
        if not quiet:
            break
        # taken: what the interval adds (accumulate), and the new state
        for i in range(n_ev):
            ev_end[i, 0] = ev_new[i, 0]
            ev_end[i, 1] = ev_new[i, 1]
            ev_end[i, 2] = ev_new[i, 2]
        if with_energy:
            i_vv, i_v, i_tv = _integrals(row, d0, v0, p0, p1)
            i_vv += v1 * v1 * wobble  # (over the interval's own length)
            i_v += v1 * wobble
            i_tv += h * v1 * wobble
            ledger[L_INPUT] -= mass * (a0x * i_v + slope * i_tv)
            ledger[L_VISCOUS] += c_d * i_vv
        for jj in range(2):
            tj, dj = (t, d0) if jj == 0 else (t + h, d1)
            if dj > extrema[0]:
                extrema[0] = dj
                extrema[1] = tj
            if dj < extrema[2]:
                extrema[2] = dj
                extrema[3] = tj
        m_a0 = p0 + mass * a0x
        track_abs_acceleration(extrema, t, (m_a0 - c * v0 - k * d0) / mass)
        track_abs_acceleration(extrema, t + h, (m_a0 - c * v1 - k * d1) / mass)
        _move_bumpers(st, sy, d1, h, ledger)
        ledger[L_HYSTERETIC] += iso_advance(sy.slopes, sy.breaks, sy.rule, st, d0, d1)
        st[D] = d1
        st[V] = v1
        st[T] = t1
        j += 1
        n += 1
    return n, j
