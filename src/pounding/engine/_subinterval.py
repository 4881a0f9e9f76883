"""What one sub-interval adds to a run: its integrals, extrema and contact statistics.

Energy flows (input work, viscous, bumper dashpot) and each contact's impulse and work are
integrated by a two-point Hermite rule on the derivatives at the sub-interval's ends in
linear phases (``_linear.linear_integrals``), by 7-point Gauss-Lobatto quadrature of the
numerical solution with a nonlinear contact law; the extrema of the
displacement come from the velocity's zero (located by the kernel), those of the absolute
acceleration and of contact forces from the zeros of their rates.  Before all that,
:func:`velocity_turn` tells the kernel where to cut a sub-interval whose velocity has two
zeros (it turns inside), so that each part has one at most.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit
from ..model.contact_laws import law_branch_loss, law_is_linear
from ._layout import (A_IMPULSE, A_MAXCOMP, A_PEAK, A_WORK, ACC_L, ACC_R, L_BUMPER_LOSS, L_HYSTERETIC,
                      L_INPUT, L_VISCOUS, MODE_LINEAR, P_AX0, P_C,
                      P_CBL, P_CBR, P_CD, P_GAPL, P_GAPR, P_INL, P_INR, P_JBL, P_JBR, P_K, P_KBL, P_KBR,
                      P_LAWL,
                      P_BW, P_LAWR, P_M, P_MODE, P_P0, P_RBL, P_RBR, P_ZETA0, PL_AT, PR_AT, PZL_AT, PZR_AT,
                      SIDE_L, SIDE_R)
from ._linear import linear_integrals
from ._trajectory import (NO_INDEX, W_AABS_RATE, W_ACCELERATION, W_FORCE_RATE, abs_acceleration_rate,
                          bouc_wen_aabs_rate, phase_zeta,
                          brent, contact_force, newton, phase_eval, table_acceleration, value_at_root)



def _lobatto(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of the ``n``-point Gauss-Lobatto rule on [0, 1] (exact to degree 2n - 3)."""
    legendre = np.polynomial.legendre.Legendre.basis(n - 1)
    x = np.concatenate([[-1.0], np.sort(legendre.deriv().roots().real), [1.0]])
    w = 2.0 / (n * (n - 1) * legendre(x) ** 2)
    return 0.5 * (x + 1.0), 0.5 * w


# Phases with a nonlinear contact law (the others use linear_integrals' Hermite rule): the
# integrands are products (V^2, A V) at twice the motion's frequency, over sub-intervals of
# 1/8 of its period.  Measured on a stiff, lightly damped contact (3 s, 13 impacts), the
# energy ledger closed to 1.0e-8 of the largest flow with 6 nodes, 1.1e-11 with 7 and
# 8.6e-13 with 8.
N_LOBATTO = 7
LOBATTO_X, LOBATTO_W = _lobatto(N_LOBATTO)
LAST_NODE = N_LOBATTO - 1
XTOL_EXTREMUM_S = 1e-10  # instants of extrema other than events': the value's error is quadratic in it


@jit
def accumulate(ph, st, t0, tau, d0, v0, a0, d1, v1, a1, s1, c1, ledger, extrema, evs, t_vel, d_vel,
               with_energy):
    """Integrals, extrema and contact statistics over ``[t0, t0 + tau]`` of one sub-interval
    (the energy integrals outside contacts only ``with_energy``); ``s1``, ``c1``: sine and
    cosine of the forcing angle at its end (linear phases)."""
    mass = ph[P_M]
    c_d = ph[P_CD]
    in_l = ph[P_INL] != 0.0
    in_r = ph[P_INR] != 0.0
    linear = ph[P_MODE] == MODE_LINEAR
    m_a0 = ph[P_P0] + mass * ph[P_AX0]
    if tau > 0.0 and linear and (with_energy or in_l or in_r):
        i_vv, i_d, i_gv = linear_integrals(ph, tau, d0, v0, a0, d1, v1, a1, s1, c1)
        ledger[L_INPUT] -= mass * i_gv
        ledger[L_VISCOUS] += c_d * i_vv
        for side in (SIDE_L, SIDE_R):
            if (side == SIDE_L and in_l) or (side == SIDE_R and in_r):
                # a linear law's branch: F = k_b x + r_b + c_b x' (law_linear_branch), compression
                # x = +-D - gap
                if side == SIDE_L:
                    sign, gap, k_b, c_b, r_b, acc = -1.0, ph[P_GAPL], ph[P_KBL], ph[P_CBL], ph[P_RBL], ACC_L
                    law, o, zo, j_b = int(ph[P_LAWL]), PL_AT, PZL_AT, int(ph[P_JBL])
                else:
                    sign, gap, k_b, c_b, r_b, acc = 1.0, ph[P_GAPR], ph[P_KBR], ph[P_CBR], ph[P_RBR], ACC_R
                    law, o, zo, j_b = int(ph[P_LAWR]), PR_AT, PZR_AT, int(ph[P_JBR])
                x0 = sign * d0 - gap
                x1 = sign * d1 - gap
                st[acc + A_IMPULSE] += k_b * (sign * i_d - gap * tau) + r_b * tau + c_b * (x1 - x0)
                st[acc + A_WORK] += 0.5 * k_b * (x1 * x1 - x0 * x0) + r_b * (x1 - x0) + c_b * i_vv
                ledger[L_BUMPER_LOSS] += c_b * i_vv + law_branch_loss(law, ph, o, j_b, x0, x1, ph, zo)
    elif tau > 0.0 and (with_energy or in_l or in_r):
        bw = ph[P_BW]  # the Bouc-Wen spring's force per unit z (0 without one)
        for q in range(N_LOBATTO):
            tq = tau * LOBATTO_X[q]
            wq = tau * LOBATTO_W[q]
            if q == 0:
                d, v, a = d0, v0, a0
            elif q == LAST_NODE:
                d, v, a = d1, v1, a1
            else:
                d, v, a = phase_eval(ph, tq)
            ledger[L_INPUT] -= wq * mass * (_abs_acceleration(ph, linear, m_a0, tq, d, v, a) - a) * v
            ledger[L_VISCOUS] += wq * c_d * v * v
            if bw != 0.0:  # its work, less what it stores (below): what it dissipates
                ledger[L_HYSTERETIC] += wq * bw * phase_zeta(ph, tq) * v
            for side in (SIDE_L, SIDE_R):
                if (side == SIDE_L and in_l) or (side == SIDE_R and in_r):
                    f, fel, _, rate = contact_force(ph, side, d, v, a)
                    acc = ACC_L if side == SIDE_L else ACC_R
                    st[acc + A_IMPULSE] += wq * f
                    st[acc + A_WORK] += wq * f * rate
                    ledger[L_BUMPER_LOSS] += wq * (f - fel) * rate
        if bw != 0.0:
            ledger[L_HYSTERETIC] -= (bouc_wen_energy(ph, phase_zeta(ph, tau))
                                     - bouc_wen_energy(ph, ph[P_ZETA0]))
        for side in (SIDE_L, SIDE_R):  # a linear law's branch in a numerical phase (a Bouc-Wen isolator's):
            # what its spring dissipates (the quadrature above has its dashpot's)
            if (side == SIDE_L and in_l) or (side == SIDE_R and in_r):
                if side == SIDE_L:
                    sign, gap, law, o, zo = -1.0, ph[P_GAPL], int(ph[P_LAWL]), PL_AT, PZL_AT
                    j_b = int(ph[P_JBL])
                else:
                    sign, gap, law, o, zo = 1.0, ph[P_GAPR], int(ph[P_LAWR]), PR_AT, PZR_AT
                    j_b = int(ph[P_JBR])
                if law_is_linear(law):
                    ledger[L_BUMPER_LOSS] += law_branch_loss(law, ph, o, j_b, sign * d0 - gap,
                                                             sign * d1 - gap, ph, zo)
    # displacement extrema (and the bumpers' maximum compression)
    for j in range(3):
        if j == 0:
            tj, dj = 0.0, d0
        elif j == 1:
            tj, dj = tau, d1
        else:
            if t_vel < 0.0:
                break
            tj = t_vel
            dj = d_vel
        if dj > extrema[0]:
            extrema[0] = dj
            extrema[1] = t0 + tj
        if dj < extrema[2]:
            extrema[2] = dj
            extrema[3] = t0 + tj
        if in_l:
            st[ACC_L + A_MAXCOMP] = max(st[ACC_L + A_MAXCOMP], -dj - ph[P_GAPL])
        if in_r:
            st[ACC_R + A_MAXCOMP] = max(st[ACC_R + A_MAXCOMP], dj - ph[P_GAPR])
    # absolute acceleration extrema
    r0 = abs_acceleration_rate(ph, d0, v0, a0)
    r1 = abs_acceleration_rate(ph, d1, v1, a1)
    if ph[P_BW] != 0.0:
        r0 += bouc_wen_aabs_rate(ph, 0.0, v0)
        r1 += bouc_wen_aabs_rate(ph, tau, v1)
    track_abs_acceleration(extrema, t0, _abs_acceleration(ph, linear, m_a0, 0.0, d0, v0, a0))
    track_abs_acceleration(extrema, t0 + tau, _abs_acceleration(ph, linear, m_a0, tau, d1, v1, a1))
    if r0 * r1 < 0.0:
        tm, xe, fe, fpe, de, ve, ae = extremum_time(W_AABS_RATE, NO_INDEX, linear, ph, evs, tau,
                                                     r0, r1)
        if not math.isnan(xe):  # from Newton's last evaluation, one small step away
            a_abs = value_at_root(tm, xe, _abs_acceleration(ph, linear, m_a0, xe, de, ve, ae), fe, fpe)
        else:
            dm, vm, am = phase_eval(ph, tm)
            a_abs = _abs_acceleration(ph, linear, m_a0, tm, dm, vm, am)
        track_abs_acceleration(extrema, t0 + tm, a_abs)
    # peak contact forces
    for side in (SIDE_L, SIDE_R):
        if (side == SIDE_L and in_l) or (side == SIDE_R and in_r):
            acc = ACC_L if side == SIDE_L else ACC_R
            fa, _, ra, _ = contact_force(ph, side, d0, v0, a0)
            fb, _, rb, _ = contact_force(ph, side, d1, v1, a1)
            peak = max(fa, fb)
            if ra * rb < 0.0:
                tm, xe, fe, fpe, de, ve, ae = extremum_time(W_FORCE_RATE, side, linear, ph, evs,
                                                             tau, ra, rb)
                if not math.isnan(xe):
                    fm = value_at_root(tm, xe, contact_force(ph, side, de, ve, ae)[0], fe, fpe)
                else:
                    dm, vm, am = phase_eval(ph, tm)
                    fm = contact_force(ph, side, dm, vm, am)[0]
                peak = max(peak, fm)
            st[acc + A_PEAK] = max(st[acc + A_PEAK], peak)


@jit
def extremum_time(what, idx, linear, ph, evs, tau, rate0, rate1):
    """Zero in ``[0, tau]`` of the rate ``what`` (values ``rate0``, ``rate1`` of opposite signs at
    the ends): Newton on the analytic jerk in a linear phase, Brent's method otherwise.

    Returns ``newton``'s tuple (the root, then its last evaluation; NaN after Brent's)."""
    if linear:
        return newton(what, idx, ph, evs, 0.0, tau, rate0, rate1, math.nan, math.nan, XTOL_EXTREMUM_S)
    nan = math.nan
    return brent(what, idx, ph, evs, 0.0, tau, rate0, rate1, XTOL_EXTREMUM_S), nan, nan, nan, nan, nan, nan


@jit
def _may_turn_back(h, v0, v1, a0, a1):
    """False when the velocity, ``v0`` and ``v1`` (same sign) at the ends of a sub-interval of
    length ``h`` with accelerations ``a0`` and ``a1`` (opposite signs), surely keeps its sign.

    The cubic through the ends' values and slopes puts the velocity's turn at ``v_c``; its
    error is ``h^4 max|v''''| / 384``, about ``1e-3 h max|a|`` on a sub-interval of 1/8 of the
    fastest period.  The sign is sure when ``v_c`` is on the ends' side by a quarter of
    ``h max(|a0|, |a1|)``.
    """
    s0 = h * a0
    s1 = h * a1
    c2 = 3.0 * (v1 - v0) - 2.0 * s0 - s1
    c3 = 2.0 * (v0 - v1) + s0 + s1
    # the turn: the root in (0, 1) of p'(x) = s0 + 2 c2 x + 3 c3 x^2 (p'(0) = s0 and p'(1) =
    # s1 have opposite signs, so there is one), by the stable quadratic formula
    disc = max(c2 * c2 - 3.0 * c3 * s0, 0.0)
    q = -(c2 + math.copysign(math.sqrt(disc), c2))
    x = s0 / q if q != 0.0 else 0.5  # (the root of the two that stays finite as c3 -> 0)
    if not 0.0 <= x <= 1.0 and c3 != 0.0:
        x = q / (3.0 * c3)
    x = min(max(x, 0.0), 1.0)
    v_c = v0 + x * (s0 + x * (c2 + x * c3))
    margin = 0.25 * max(abs(s0), abs(s1))
    return not (v_c * v0 > 0.0 and abs(v_c) > margin)


@jit
def velocity_turn(ph, evs, h, v0, v1, a0, a1):
    """Where to cut a sub-interval of length ``h`` whose velocity has two zeros, or -1.0.

    For ``v0``, ``v1`` of one sign and ``a0``, ``a1`` of opposite signs (the caller's test):
    the velocity turns inside, and where it turns it may have crossed zero and come back, a
    dip of the displacement that no end shows (a graze of a bumper's surface between two ends
    moving away from it).  Returns the turn when the velocity changed sign there; cut there,
    each part has one zero at most.
    """
    if not _may_turn_back(h, v0, v1, a0, a1):
        return -1.0
    t_a, xe, fe, fpe, _, ve, _ = extremum_time(W_ACCELERATION, NO_INDEX, ph[P_MODE] == MODE_LINEAR, ph,
                                               evs, h, a0, a1)
    if not math.isnan(xe):  # the velocity, stationary there, from Newton's last evaluation
        v_a = value_at_root(t_a, xe, ve, fe, fpe)
    else:
        v_a = phase_eval(ph, t_a)[1]
    return t_a if v_a * v0 < 0.0 and 0.0 < t_a < h else -1.0


@jit
def bouc_wen_energy(ph, z):
    """Energy (J) the Bouc-Wen spring stores at ``z``: ``k u_y^2 z^2 / (2 A)`` (the work it would
    give back unloading at its initial stiffness ``A k``)."""
    if ph[P_BW] == 0.0:
        return 0.0
    return 0.5 * ph[P_BW] * ph[P_BW + 1] * z * z / ph[P_BW + 2]


@jit
def _abs_acceleration(ph, linear, m_a0, tau, d, v, a):
    """Absolute acceleration (m/s^2) at ``tau`` given the relative motion there.

    A linear phase gives it from its equation of motion, without a sine:
    ``M a_abs = P0 + M a0 - c V - k D`` (``m_a0`` is ``P0 + M a0``; the ramp terms cancel).
    """
    if linear:
        return (m_a0 - ph[P_C] * v - ph[P_K] * d) / ph[P_M]
    return a + table_acceleration(ph, tau)


@jit
def track_abs_acceleration(extrema, t, a):
    if abs(a) > extrema[4]:
        extrema[4] = abs(a)
        extrema[5] = t
        extrema[6] = a
