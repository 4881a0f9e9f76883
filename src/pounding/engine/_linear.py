"""Closed-form solution of one linear phase of motion.

Within a phase the motion obeys ``M D'' + c D' + k D = P0 + P1 tau + H sin(w tau + phi)``
with constant coefficients (``tau`` is the time since the phase start).  The solution is a
particular solution (polynomial plus sinusoid) plus the free response
``exp(A tau) y0`` of the 2x2 system, written so that every damping regime (under-,
critically and over-damped, ``k = 0``, ``c = 0``) is evaluated without cancellation.
"""

from __future__ import annotations

import math

from .._jit import jit
from ._hermite import hermite_end
from ._layout import (N_ENDS, P_AX0, P_AX1, P_AXH, P_B0, P_B1, P_B2, P_B3, P_C, P_CPHI, P_D0, P_ENDS,
                      P_ENDS_NEXT, P_H, P_K, P_M, P_NKEY, P_NODE, P_P0, P_P1, P_PHI, P_Q2, P_ROOT, P_S,
                      P_SPHI, P_V0, P_VROUND, P_VRUN, P_W, P_XROUND, P_XRUN, P_Y0, P_Y1, P_ZI, P_ZR)


@jit
def linear_setup(ph):
    """Fill the derived coefficients of ``ph`` from M, c, k, forcing, D0 and V0.

    Returns False when the phase has no bounded closed form (undamped, exactly resonant).
    """
    m, c, k = ph[P_M], ph[P_C], ph[P_K]
    s = -0.5 * c / m
    q2 = s * s - k / m
    ph[P_S] = s
    ph[P_Q2] = q2
    ph[P_ROOT] = math.sqrt(abs(q2))
    if not linear_forcing(ph):
        return False
    linear_start(ph, math.sin(ph[P_PHI]), math.cos(ph[P_PHI]))
    return True


@jit
def linear_forcing(ph):
    """Fill the particular solution of ``ph`` (and its rounding scales) from M, c, k and the
    forcing: all :func:`linear_setup` redoes when only the forcing's polynomial changed (a
    phase continuing into the next piece of a record).

    Returns False when the phase has no bounded closed form (undamped, exactly resonant).
    """
    m, c, k = ph[P_M], ph[P_C], ph[P_K]
    p0, p1, h, w = ph[P_P0], ph[P_P1], ph[P_H], ph[P_W]
    # polynomial particular solution b0 + b1 t + b2 t^2 + b3 t^3
    if k != 0.0:
        b1 = p1 / k
        ph[P_B0], ph[P_B1], ph[P_B2], ph[P_B3] = (p0 - c * b1) / k, b1, 0.0, 0.0
    elif c != 0.0:
        b2 = 0.5 * p1 / c
        ph[P_B0], ph[P_B1], ph[P_B2], ph[P_B3] = 0.0, (p0 - 2.0 * m * b2) / c, b2, 0.0
    else:
        ph[P_B0], ph[P_B1], ph[P_B2], ph[P_B3] = 0.0, 0.0, 0.5 * p0 / m, p1 / (6.0 * m)
    # harmonic particular solution Im(Z exp(i(w t + phi))), Z = H / (k - m w^2 + i c w)
    zr = 0.0
    zi = 0.0
    if h != 0.0:
        re = k - m * w * w
        im = c * w
        den = re * re + im * im
        scale = k * k + (m * w * w) ** 2
        if den <= 1e-24 * scale:
            return False
        zr = h * re / den
        zi = -h * im / den
    ph[P_ZR] = zr
    ph[P_ZI] = zi
    # the rounding scales of the displacement and velocity the closed form adds up (|zr| + |zi|
    # for the particular solution's amplitude: a scale, no square root needed)
    amp = abs(zr) + abs(zi)
    ph[P_XROUND] = max(ph[P_XRUN], abs(ph[P_B0]) + amp)
    ph[P_VROUND] = max(ph[P_VRUN], abs(ph[P_B1]) + w * amp)
    return True


@jit
def linear_start(ph, sp, cp):
    """The free response's initial values from ``P_D0``, ``P_V0`` and the sine ``sp`` and
    cosine ``cp`` of the forcing phase ``P_PHI``: all :func:`linear_setup` redoes when only
    those changed (a sub-interval continuing a phase under harmonic forcing, which passes
    the previous sub-interval's end values: its forcing angle by angle addition, equal to
    ``P_PHI``'s sine and cosine but for rounding)."""
    zr, zi, w = ph[P_ZR], ph[P_ZI], ph[P_W]
    ph[P_SPHI] = sp
    ph[P_CPHI] = cp
    ph[P_Y0] = ph[P_D0] - (ph[P_B0] + zr * sp + zi * cp)
    ph[P_Y1] = ph[P_V0] - (ph[P_B1] + w * (zr * cp - zi * sp))


@jit
def _free_response(ph, tau):
    """``exp(s tau) * (C(tau), S(tau))`` with ``exp(A tau) = e^{s tau}(C I + S (A - s I))``."""
    s = ph[P_S]
    q2 = ph[P_Q2]
    r = ph[P_ROOT]
    z = q2 * tau * tau
    if abs(z) < 1e-3:
        cc = 1.0 + z * (0.5 + z * (1.0 / 24.0 + z / 720.0))
        ss = tau * (1.0 + z * (1.0 / 6.0 + z * (1.0 / 120.0 + z / 5040.0)))
        e = math.exp(s * tau)
        return e * cc, e * ss
    if q2 < 0.0:
        e = math.exp(s * tau)
        return e * math.cos(r * tau), e * math.sin(r * tau) / r
    ep = math.exp((s + r) * tau)
    em = math.exp((s - r) * tau)
    return 0.5 * (ep + em), 0.5 * (ep - em) / r


@jit
def linear_eval(ph, tau):
    """Displacement (m), velocity (m/s) and relative acceleration (m/s^2) at ``tau`` (s)."""
    d, v, a, _, _ = linear_eval_angle(ph, tau)
    return d, v, a


@jit
def end_valid(ph, h):
    """True when the end values of ``ph`` were computed for this phase and sub-interval ``h``."""
    return (ph[P_NKEY] == h and ph[P_NKEY + 1] == ph[P_W] and ph[P_NKEY + 2] == ph[P_S]
            and ph[P_NKEY + 3] == ph[P_Q2])


@jit
def reset_ends(ph):
    """Forget every phase's end values (at the start of a run)."""
    ph[P_NKEY] = math.nan
    for j in range(N_ENDS):
        ph[P_ENDS + 8 * j] = math.nan
    ph[P_ENDS_NEXT] = 0.0


@jit
def fill_end(ph, h):
    """Compute the transcendental values at ``tau = h`` unless they are those of this phase.

    A full sub-interval of a phase has the same length ``h`` as the one before it (the
    length depends on the phase's frequencies only), so the sines and exponentials at its
    end are the same: only the forcing phase changes, which :func:`linear_eval_end` adds
    by angle addition.  A steady motion goes through the same few phases again and again:
    the values of the last ``N_ENDS`` phases are kept.
    """
    if end_valid(ph, h):
        return
    w, s, q2 = ph[P_W], ph[P_S], ph[P_Q2]
    for j in range(N_ENDS):
        o = P_ENDS + 8 * j
        if ph[o] == h and ph[o + 1] == w and ph[o + 2] == s and ph[o + 3] == q2:
            for i in range(8):
                ph[P_NKEY + i] = ph[o + i]  # key and values: P_NODE follows P_NKEY
            return
    ph[P_NKEY] = h
    ph[P_NKEY + 1] = w
    ph[P_NKEY + 2] = s
    ph[P_NKEY + 3] = q2
    ec, es = _free_response(ph, h)
    ph[P_NODE] = math.sin(w * h)
    ph[P_NODE + 1] = math.cos(w * h)
    ph[P_NODE + 2] = ec
    ph[P_NODE + 3] = es
    o = P_ENDS + 8 * int(ph[P_ENDS_NEXT])
    for i in range(8):
        ph[o + i] = ph[P_NKEY + i]
    ph[P_ENDS_NEXT] = (ph[P_ENDS_NEXT] + 1.0) % N_ENDS


@jit
def forcing_angle(ph, tau):
    """Sine and cosine of the forcing angle ``tau`` s into a linear phase's sub-interval."""
    wt = ph[P_W] * tau
    sw, cw = math.sin(wt), math.cos(wt)
    sp, cp = ph[P_SPHI], ph[P_CPHI]
    return sw * cp + cw * sp, cw * cp - sw * sp


@jit
def linear_eval_end(ph, h):
    """:func:`linear_eval_angle` at ``tau = h`` from the values of :func:`fill_end`."""
    sw, cw = ph[P_NODE], ph[P_NODE + 1]
    sp, cp = ph[P_SPHI], ph[P_CPHI]
    st, ct = sw * cp + cw * sp, cw * cp - sw * sp
    d, v, a = _combine(ph, h, st, ct, ph[P_NODE + 2], ph[P_NODE + 3])
    return d, v, a, st, ct


@jit
def linear_eval_angle(ph, tau):
    """:func:`linear_eval`, and the sine and cosine of the forcing angle at ``tau``.

    The angle is ``P_SPHI``, ``P_CPHI``'s plus ``w tau`` by angle addition, as at the end
    (:func:`linear_eval_end`): the start's sine and cosine are the phase's reference (a
    continuing sub-interval carries them over from the last one's end, so they can differ
    from those of ``P_PHI``, the clock's angle, by its rounding: 1e-14 after 3 s at 30 rad/s).
    """
    st, ct = forcing_angle(ph, tau)
    ec, es = _free_response(ph, tau)
    d, v, a = _combine(ph, tau, st, ct, ec, es)
    return d, v, a, st, ct


@jit
def _combine(ph, tau, st, ct, ec, es):
    """The solution at ``tau`` given ``sin``/``cos`` of the forcing angle and the free response."""
    m, c, k = ph[P_M], ph[P_C], ph[P_K]
    w = ph[P_W]
    b1, b2, b3 = ph[P_B1], ph[P_B2], ph[P_B3]
    zr, zi = ph[P_ZR], ph[P_ZI]
    dp = ph[P_B0] + tau * (b1 + tau * (b2 + tau * b3)) + zr * st + zi * ct
    vp = b1 + tau * (2.0 * b2 + 3.0 * b3 * tau) + w * (zr * ct - zi * st)
    s = ph[P_S]
    y0, y1 = ph[P_Y0], ph[P_Y1]
    d = dp + ec * y0 + es * (y1 - s * y0)
    v = vp + ec * y1 + es * (s * y1 - (k / m) * y0)
    a = (ph[P_P0] + ph[P_P1] * tau + ph[P_H] * st - c * v - k * d) / m
    return d, v, a


@jit
def linear_integrals(ph, tau, d0, v0, a0, d1, v1, a1, s1, c1):
    """``(int V^2, int D, int A_g V)`` over the sub-interval ``[0, tau]`` of a linear phase
    (m^2/s, m s, m^2/s^2): the two-point Hermite rule of ``_hermite``, on the derivatives at
    both ends (no evaluation inside); ``s1``, ``c1``: sine and cosine of the forcing angle at
    ``tau``.

    The rule of order p = 8 is exact to degree 17; its error is
    ``((p+1)!)^2 / ((2p+2)! (2p+3)!) T^(2p+3) f^(2p+2) = 1.7e-22 T^19 f^(18)``.  A sub-interval
    is at most 1/8 of the phase's fastest period and the integrands (products) oscillate at
    most twice as fast, so ``|f^(18)| <= (pi / (2 T))^18 max|f|`` and the error is below
    ``6e-19 T max|f|``: rounding decides.  (The 7-point Gauss-Lobatto rule used with nonlinear
    laws: 5e-14 T max|f|, from 5 evaluations inside the sub-interval.)
    """
    inv_m = 1.0 / ph[P_M]
    cm, km, w = ph[P_C] * inv_m, ph[P_K] * inv_m, ph[P_W]
    hm, p1m = ph[P_H] * inv_m, ph[P_P1] * inv_m
    axh, ax0, ax1 = ph[P_AXH], ph[P_AX0], ph[P_AX1]
    vv0, dd0, gv0 = hermite_end(cm, km, w, hm, p1m, axh, ax0, ax1, 0.0, d0, v0, a0,
                                ph[P_SPHI], ph[P_CPHI], tau, 1.0)
    vv1, dd1, gv1 = hermite_end(cm, km, w, hm, p1m, axh, ax0, ax1, tau, d1, v1, a1, s1, c1, tau, -1.0)
    return vv0 + vv1, dd0 + dd1, gv0 + gv1
