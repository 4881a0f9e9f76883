"""The trajectory inside one sub-interval of a phase, and root finding on it.

Everything the event locator needs is a scalar function of the time ``tau`` since the
start of the sub-interval: an event function or its rate, the velocity (displacement
extrema), the rate of the absolute acceleration, the rate of a contact force.
:func:`traj_value` evaluates any of them by name, and :func:`brent` finds their roots.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit
from ..model.contact_laws import law_force, law_is_linear, law_relax, law_release
from ._layout import (ACT_CONTACT, E_ACTION, E_ALPHA, E_BETA, E_GAMMA, E_KIND, E_SIDE, KIND_LINEAR, KIND_ZETA,
                      MODE_LINEAR, P_BW, P_ZETA0, P_AX0, P_AX1, P_AXH, P_C, P_CBL, P_CBR, P_D0, P_DL0, P_DR0,
                      P_GAPL,
                      P_GAPR, P_H, P_K, P_KBL, P_KBR, P_LAWL, P_LAWR, P_M, P_MODE, P_NLL, P_NLR, P_P1, P_PHI,
                      P_RBL, P_RBR,
                      P_V0, P_VROUND, P_W, P_XROUND, PL_AT, PR_AT, PZL_AT, PZR_AT, SIDE_L, SIDE_NONE, SIDE_R)
from ._linear import forcing_angle, linear_eval
from ._numeric import dp5_step, phase_rhs, zeta_rate

# typed integers, not literals: one compiled root finder for all of them (see _layout.py)
W_EVENT, W_EVENT_RATE, W_VELOCITY, W_AABS_RATE, W_FORCE_RATE, W_ACCELERATION = (np.int64(k)
                                                                       for k in range(6))
NO_INDEX = np.int64(0)  # the ``idx`` argument for the functions that take none
ROUNDING = 256.0 * 2.220446049250313e-16  # relative size of rounding noise in event values


@jit
def phase_eval(ph, tau):
    """Displacement, velocity and relative acceleration ``tau`` s into the sub-interval."""
    if ph[P_MODE] == MODE_LINEAR:
        return linear_eval(ph, tau)
    if tau == 0.0:
        return ph[P_D0], ph[P_V0], phase_rhs(ph, 0.0, ph[P_D0], ph[P_V0], ph[P_ZETA0])
    d, v, a, _, _, _, _ = dp5_step(ph, tau)
    return d, v, a


@jit
def phase_zeta(ph, tau):
    """The isolator's Bouc-Wen ``z`` ``tau`` s into the sub-interval (0 without one)."""
    if ph[P_BW] == 0.0:
        return 0.0
    if tau == 0.0:
        return ph[P_ZETA0]
    return dp5_step(ph, tau)[5]


@jit
def table_acceleration(ph, tau):
    """Base acceleration (m/s^2) ``tau`` s into the sub-interval."""
    return ph[P_AX0] + ph[P_AX1] * tau + ph[P_AXH] * math.sin(ph[P_W] * tau + ph[P_PHI])


@jit
def contact_force(ph, side, d, v, a):
    """Bumper ``side`` in contact: ``(force N, elastic part N, d(force)/dt N/s, compression rate m/s)``.

    A linear law's force is its phase's branch's (``kb x + rb + cb x'``): a law with a state
    (elastic-plastic) has it from there, not from the compression alone."""
    if side == SIDE_L:
        dd, dv, da = -d - ph[P_GAPL], -v, -a
        law = int(ph[P_LAWL])
        if law_is_linear(law):
            fel = ph[P_KBL] * dd + ph[P_RBL]
            return fel + ph[P_CBL] * dv, fel, ph[P_KBL] * dv + ph[P_CBL] * da, dv
        f, fel, fd, fv = law_force(law, ph, PL_AT, dd, dv, ph, PZL_AT)
    else:
        dd, dv, da = d - ph[P_GAPR], v, a
        law = int(ph[P_LAWR])
        if law_is_linear(law):
            fel = ph[P_KBR] * dd + ph[P_RBR]
            return fel + ph[P_CBR] * dv, fel, ph[P_KBR] * dv + ph[P_CBR] * da, dv
        f, fel, fd, fv = law_force(law, ph, PR_AT, dd, dv, ph, PZR_AT)
    return f, fel, fd * dv + fv * da, dv


@jit
def abs_acceleration_rate(ph, d, v, a):
    """Time derivative of the absolute acceleration (m/s^3): ``-(d/dt restoring force) / M``
    (less a Bouc-Wen spring's: :func:`bouc_wen_aabs_rate`)."""
    rate = ph[P_C] * a + ph[P_K] * v
    if ph[P_NLR] != 0.0:
        rate += contact_force(ph, SIDE_R, d, v, a)[2]
    if ph[P_NLL] != 0.0:
        rate -= contact_force(ph, SIDE_L, d, v, a)[2]
    return -rate / ph[P_M]


@jit
def bouc_wen_aabs_rate(ph, tau, v):
    """A Bouc-Wen spring's part of :func:`abs_acceleration_rate` ``tau`` s into the sub-interval
    (apart: its integration kept out of the closed-form phases' path)."""
    return -ph[P_BW] * zeta_rate(ph, v, phase_zeta(ph, tau)) / ph[P_M]


@jit
def event_value(evs, i, ph, tau, d, v, a):
    """Event ``i`` at ``tau``: ``(value, rate, scale)``; it fires when value crosses zero downwards.

    ``scale`` is the size of the terms summed, so that ``ROUNDING * scale`` is the noise level.
    """
    if evs[i, E_KIND] == KIND_LINEAR and int(evs[i, E_SIDE]) == SIDE_NONE:
        # the isolator's events (most of them): linear in the motion, small enough to inline
        alpha, beta, gamma = evs[i, E_ALPHA], evs[i, E_BETA], evs[i, E_GAMMA]
        return (alpha + beta * d + gamma * v, beta * v + gamma * a,
                abs(alpha) + abs(beta * d) + abs(gamma * v))
    return _bumper_event_value(evs, i, ph, tau, d, v, a)


@jit
def _bumper_event_value(evs, i, ph, tau, d, v, a):
    """:func:`event_value` of a bumper's event: contact (the surface relaxing) or release; and the
    Bouc-Wen z crossing zero (kept out of :func:`event_value`'s fast path, with its integration)."""
    if evs[i, E_KIND] == KIND_ZETA:  # (alpha: minus z's sign at the phase start)
        z = phase_zeta(ph, tau)
        return -evs[i, E_ALPHA] * z, -evs[i, E_ALPHA] * zeta_rate(ph, v, z), 1.0
    side = int(evs[i, E_SIDE])
    if evs[i, E_KIND] == KIND_LINEAR:
        alpha, beta, gamma = evs[i, E_ALPHA], evs[i, E_BETA], evs[i, E_GAMMA]
        g = alpha + beta * d + gamma * v
        gp = beta * v + gamma * a
        # the mass's displacement is rounded relative to the run's and the phase's lengths
        # (ph[P_XROUND]), not to its own size: at gap 0, after a release near D = 0, it is 1e-8 m
        # made of terms of 1e-2 m
        scale = abs(alpha) + abs(beta * d) + abs(gamma * v) + ph[P_XROUND]
        if evs[i, E_ACTION] != ACT_CONTACT:  # the compression back to zero: no surface relaxing
            return g, gp, scale
        if side == SIDE_L:
            r, rr = law_relax(int(ph[P_LAWL]), ph, PL_AT, ph[P_DL0], tau, ph, PZL_AT)
        else:
            r, rr = law_relax(int(ph[P_LAWR]), ph, PR_AT, ph[P_DR0], tau, ph, PZR_AT)
        return g + r, gp + rr, scale + r
    if side == SIDE_L:
        law, o, zo = int(ph[P_LAWL]), PL_AT, PZL_AT
        dd, dv, da = -d - ph[P_GAPL], -v, -a
        kb, cb, rb = ph[P_KBL], ph[P_CBL], ph[P_RBL]
    else:
        law, o, zo = int(ph[P_LAWR]), PR_AT, PZR_AT
        dd, dv, da = d - ph[P_GAPR], v, a
        kb, cb, rb = ph[P_KBR], ph[P_CBR], ph[P_RBR]
    if law_is_linear(law):
        # the phase's own branch (kb x + rb + cb x'), not the one the compression is in: at a
        # breakpoint that branch's slope is the one the motion heads into (with the slope of the
        # branch above, a release right after coming down to a breakpoint had the wrong rate,
        # and the bumper pulled 14 N, unseen)
        g, gp = kb * dd + rb + cb * dv, kb * dv + cb * da
    else:
        g, gp = law_release(law, ph, o, dd, dv, da, ph, zo)
    scale = law_release(law, ph, o, abs(dd) + ph[P_XROUND], abs(dv) + ph[P_VROUND], 0.0, ph, zo)[0]
    return g, gp, scale


@jit
def traj_value(what, idx, ph, evs, tau):
    """The scalar function ``what`` (a ``W_*`` constant) of the trajectory at ``tau``."""
    d, v, a = phase_eval(ph, tau)
    if what == W_EVENT:
        return event_value(evs, idx, ph, tau, d, v, a)[0]
    if what == W_EVENT_RATE:
        return event_value(evs, idx, ph, tau, d, v, a)[1]
    if what == W_VELOCITY:
        return v
    if what == W_AABS_RATE:
        if ph[P_BW] != 0.0:
            return abs_acceleration_rate(ph, d, v, a) + bouc_wen_aabs_rate(ph, tau, v)
        return abs_acceleration_rate(ph, d, v, a)
    if what == W_ACCELERATION:
        return a
    return contact_force(ph, idx, d, v, a)[2]


@jit
def _value_and_rate(what, idx, ph, evs, tau):
    """``newton``'s function and its rate at ``tau``, then the motion there ``(d, v, a)``."""
    d, v, a = phase_eval(ph, tau)
    if what == W_EVENT:
        g, gp, _ = event_value(evs, idx, ph, tau, d, v, a)
        return g, gp, d, v, a
    if what == W_VELOCITY:
        return v, a, d, v, a
    # a linear phase's acceleration and rates (W_AABS_RATE, W_FORCE_RATE) and their
    # derivatives, from the jerk: M j = P1 + H w cos(w tau + phi) - c a - k v
    jerk = (ph[P_P1] + ph[P_H] * ph[P_W] * forcing_angle(ph, tau)[1] - ph[P_C] * a
            - ph[P_K] * v) / ph[P_M]
    if what == W_ACCELERATION:
        return a, jerk, d, v, a
    if what == W_AABS_RATE:
        return (-(ph[P_C] * a + ph[P_K] * v) / ph[P_M], -(ph[P_C] * jerk + ph[P_K] * a) / ph[P_M],
                d, v, a)
    # W_FORCE_RATE of a Kelvin-Voigt bumper: F = k_b x + c_b x' with x' = +-V
    sign, k_b, c_b = 1.0, ph[P_KBR], ph[P_CBR]  # (the linear law's branch in this phase)
    if idx == SIDE_L:
        sign, k_b, c_b = -1.0, ph[P_KBL], ph[P_CBL]
    return sign * (k_b * v + c_b * a), sign * (k_b * a + c_b * jerk), d, v, a


@jit
def _root_guess(fa, fb, sa, sb):
    """First guess in ``(0, 1)`` at the root of a function with values ``fa``, ``fb`` (of
    opposite signs) and slopes ``sa``, ``sb`` (per unit of the interval) at 0 and 1.

    Inverse cubic Hermite interpolation: the instant as a cubic in the function's value,
    through both ends with slopes ``1 / sa`` and ``1 / sb``, at value 0.  For a smooth
    function monotone on an interval of length ``h`` it is within ``O(h^4)`` of the root,
    the secant's within ``O(h^2)``.  The secant's root when a slope is NaN or of the wrong
    sign (not monotone), or the guess falls outside the interval.
    """
    df = fb - fa
    x = -fa / df  # the secant's root
    ra = df / sa
    rb = df / sb
    if not (ra > 0.0 and rb > 0.0):  # (False for NaN)
        return x
    x2 = x * x
    t = x2 * (3.0 - 2.0 * x) + ra * x * (1.0 - x) * (1.0 - x) + rb * x2 * (x - 1.0)
    if 0.0 < t < 1.0:
        return t
    return x


@jit
def newton(what, idx, ph, evs, xa, xb, fa, fb, ra, rb, xtol):
    """Root of an event function (``W_EVENT``), of the velocity (``W_VELOCITY``) or, in a
    linear phase with Kelvin-Voigt contacts, of the acceleration (``W_ACCELERATION``), the
    absolute acceleration's or a contact force's rate (``W_AABS_RATE``, ``W_FORCE_RATE``) in
    ``[xa, xb]`` given values ``fa``,
    ``fb`` of opposite sign: Newton's method on the analytic rate, kept inside the
    shrinking bracket by bisection (``rtsafe``).

    ``ra``, ``rb``: the function's rates at ``xa`` and ``xb`` when known (NaN otherwise);
    then the first guess is an inverse cubic interpolation (:func:`_root_guess`) instead of
    the secant's root, and an event instant takes one evaluation fewer.

    Returns ``(root, x, f, fp, d, v, a)``: the root, and the last point evaluated with the
    function, its rate and the motion there (``x`` NaN when none was).  The root is one
    small step ``root - x`` from it, so a value stationary at the root (an extremum: the
    displacement at a velocity zero) follows from a second-order Taylor step
    (:func:`value_at_root`) without evaluating the closed form again.
    """
    nan = math.nan
    if fa == 0.0:
        return xa, nan, nan, nan, nan, nan, nan
    if fb == 0.0:
        return xb, nan, nan, nan, nan, nan, nan
    lo, hi = (xa, xb) if fa < 0.0 else (xb, xa)  # f(lo) < 0 < f(hi)
    x = xa + (xb - xa) * _root_guess(fa, fb, ra * (xb - xa), rb * (xb - xa))
    dx_old = abs(xb - xa)
    dx = dx_old
    prev_newton = 0.0  # the previous Newton step's size (0: it was a bisection)
    xe = f = fp = d = v = a = nan
    for _ in range(100):
        xe = x
        f, fp, d, v, a = _value_and_rate(what, idx, ph, evs, x)
        if f == 0.0:
            break
        if f < 0.0:
            lo = x
        else:
            hi = x
        newton_ok = fp != 0.0
        if newton_ok:
            step = f / fp
            x_new = x - step
            newton_ok = ((x_new - lo) * (x_new - hi) < 0.0) and abs(2.0 * step) <= dx_old
        dx_old = dx
        if newton_ok:
            dx = abs(step)
            x = x_new
            tol = xtol + 4.0 * 2.220446049250313e-16 * abs(x)
            # converging quadratically (dx = C prev^2), the next step would be C dx^2 =
            # dx^3 / prev^2: when that is below the tolerance, x is the root to it already
            if dx < prev_newton and dx * dx * dx < tol * prev_newton * prev_newton:
                break
            prev_newton = dx
        else:
            x_new = 0.5 * (lo + hi)
            dx = abs(x_new - x)
            x = x_new
            tol = xtol + 4.0 * 2.220446049250313e-16 * abs(x)
            prev_newton = 0.0
        if dx < tol:
            break
    return x, xe, f, fp, d, v, a


@jit
def value_at_root(root, x, value, f, fp):
    """A quantity stationary at ``newton``'s root, from its value at the last point ``x``
    evaluated, where its rate ``f`` and the rate's derivative ``fp`` were: second-order
    Taylor, exact to ``O((root - x)^3)`` (``root - x`` is Newton's last step, below its
    tolerance or ``tol^(1/3) step^(2/3)`` by the quadratic stopping rule)."""
    dt = root - x
    return value + dt * (f + 0.5 * dt * fp)


@jit
def brent(what, idx, ph, evs, xa, xb, fa, fb, xtol):
    """Root of ``traj_value(what, idx, ...)`` in ``[xa, xb]`` given values of opposite sign.

    Brent's method (as scipy's ``brentq``); returns the end of the bracket closest to the root.
    """
    if fa == 0.0:
        return xa
    if fb == 0.0:
        return xb
    xpre, xcur = xa, xb
    fpre, fcur = fa, fb
    xblk = xpre
    fblk = fpre
    spre = 0.0
    scur = 0.0
    for _ in range(200):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk = xpre
            fblk = fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = 0.5 * (xtol + 4.0 * 2.220446049250313e-16 * abs(xcur))
        sbis = 0.5 * (xblk - xcur)
        if fcur == 0.0 or abs(sbis) < delta:
            break
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre = scur
                scur = stry
            else:
                spre = sbis
                scur = sbis
        else:
            spre = sbis
            scur = sbis
        xpre = xcur
        fpre = fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0.0 else -delta
        fcur = traj_value(what, idx, ph, evs, xcur)
    return xcur


@jit
def _velocity_only(evs, i):
    """True when event ``i`` is ``gamma V`` alone: its root is the velocity's zero."""
    return (evs[i, E_KIND] == KIND_LINEAR and evs[i, E_ALPHA] == 0.0 and evs[i, E_BETA] == 0.0
            and int(evs[i, E_SIDE]) == SIDE_NONE)


@jit
def _displacement_only(evs, i, ph):
    """True when event ``i`` depends on the displacement alone (its extremum is the velocity's
    zero): the isolator's, a bumper's compression or branch end, a contact start against a
    bumper at rest."""
    side = int(evs[i, E_SIDE])
    return evs[i, E_KIND] == KIND_LINEAR and evs[i, E_GAMMA] == 0.0 and (
        side == SIDE_NONE or evs[i, E_ACTION] != ACT_CONTACT
        or (side == SIDE_L and ph[P_DL0] == 0.0) or (side == SIDE_R and ph[P_DR0] == 0.0))


@jit
def locate_event(i, ph, evs, h, g0, gp0, tol0, g1, gp1, tol1, xtol, t_vel, d_vel):
    """First time in ``[0, h]`` at which event ``i`` fires, or -1.0.

    ``g`` and ``gp`` are the event's value and rate at both ends.  A value within ``tol0`` of
    zero at the start means the trajectory has just left (or sits on) that boundary: it
    fires only if the value then clearly goes negative.  A dip below zero between two
    positive ends (a graze) is found from the zero of the rate; for events that depend on
    the displacement alone that zero is the velocity's, ``t_vel`` (displacement ``d_vel``;
    -1 if the velocity keeps its sign).
    """
    if g0 > tol0 and g1 <= 0.0:
        if t_vel >= 0.0 and _velocity_only(evs, i):
            return t_vel  # (a slip reversal: the velocity's zero, located already)
        return newton(W_EVENT, i, ph, evs, 0.0, h, g0, g1, gp0, gp1, xtol)[0]
    if g0 <= tol0 and g1 < -tol1:
        tp = h
        for _ in range(60):
            tp *= 0.5
            d, v, a = phase_eval(ph, tp)
            gt, gpt, sc = event_value(evs, i, ph, tp, d, v, a)
            if gt > ROUNDING * sc:
                return newton(W_EVENT, i, ph, evs, tp, h, gt, g1, gpt, gp1, xtol)[0]
        if gp0 > 0.0 and gp1 < 0.0:
            # it first rose, by less than the rounding, and came back: where it turned (a mass at
            # a bumper's surface moving away at 1e-9 m/s and turned back within 1e-5 s, 8e-15 m
            # out: started at once, the contact released at once, and again, ZENO)
            if _displacement_only(evs, i, ph) and t_vel >= 0.0:
                return t_vel
            return brent(W_EVENT_RATE, i, ph, evs, 0.0, h, gp0, gp1, xtol)
        return 0.0
    if not (gp0 < 0.0 and gp1 > 0.0):
        return -1.0
    # a local minimum inside: does it dip below zero?
    displacement_only = _displacement_only(evs, i, ph)
    if displacement_only:
        if t_vel < 0.0:
            return -1.0
        tm = t_vel
        gm = evs[i, E_ALPHA] + evs[i, E_BETA] * d_vel
        # the displacement at the velocity's zero is rounded against the phase's lengths, for the
        # isolator's events too (a reversal 24 um from the yield of two springs at once: a
        # rounding-level dip of 1e-17 m into a yield, yield and reversal again and again, ZENO)
        sc = abs(evs[i, E_ALPHA]) + abs(evs[i, E_BETA]) * (abs(d_vel) + ph[P_XROUND])
    else:
        tm = brent(W_EVENT_RATE, i, ph, evs, 0.0, h, gp0, gp1, xtol)
        d, v, a = phase_eval(ph, tm)
        gm, _, sc = event_value(evs, i, ph, tm, d, v, a)
    if gm >= -ROUNDING * sc:
        return -1.0
    if g0 <= tol0:
        return 0.0  # it leaves the boundary on the wrong side at once
    return newton(W_EVENT, i, ph, evs, 0.0, tm, g0, gm, gp0, 0.0, xtol)[0]  # (tm: the rate's zero)
