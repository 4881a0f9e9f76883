"""The compiled elastic response of a record, exact: the peaks of ``u``, ``u'`` and ``a_abs`` over time.

Between two samples the record is ``A = g0 + g1 tau`` and the oscillator's motion has the closed form
``u = exp(-sigma tau) (C cos wd tau + S sin wd tau) + p0 + p1 tau`` (Nigam and Jennings' recurrence
is its value at the samples).  Its peaks between samples are found, not sampled: every quantity
``f`` here (``u``, ``u'``, ``a_abs``) is a damped sinusoid plus a straight line, so ``f''`` is a pure
damped sinusoid whose zeros are known in closed form; between them ``f'`` is monotone and has at
most one root, bracketed by a sign change and found by safeguarded Newton iteration.  An interval
is searched only where ``f'`` or ``f''`` changes sign across it, or where it spans half a period
(which could hide a pair of roots): a peak cannot hide anywhere else.
"""

from __future__ import annotations

import math

import numpy as np

from .._control import CTL_BUDGET as BUDGET
from .._control import CTL_STOP as STOP
from .._control import CTL_WORK as WORK
from .._errors import Status
from .._jit import jit, jit_entry

# how the spectrum ended: pounding.Status's codes
DONE, INTERRUPTED, OVER_BUDGET = int(Status.SUCCESS), int(Status.INTERRUPTED), int(Status.BUDGET)
NEWTON_ITERATIONS = 100


@jit
def _value(a: float, b: float, d0: float, d1: float, sig: float, wd: float, tau: float) -> float:
    """``exp(-sig tau) (a cos wd tau + b sin wd tau) + d0 + d1 tau``."""
    return math.exp(-sig * tau) * (a * math.cos(wd * tau) + b * math.sin(wd * tau)) + d0 + d1 * tau


@jit
def _deriv_a(a: float, b: float, sig: float, wd: float) -> float:
    """The cosine coefficient of the derivative of ``exp(-sig tau) (a cos + b sin)``."""
    return -sig * a + wd * b


@jit
def _deriv_b(a: float, b: float, sig: float, wd: float) -> float:
    """Its sine coefficient."""
    return -wd * a - sig * b


@jit
def _root(a1: float, b1: float, d1: float, a2: float, b2: float, sig: float, wd: float, lo: float, hi: float,
          f_lo: float) -> float:
    """The root of ``f' = exp(-sig tau)(a1 cos + b1 sin) + d1``, monotone on ``[lo, hi]`` with a sign change
    there (``f_lo = f'(lo)``): Newton's steps, bisection where one would leave the bracket."""
    x = 0.5 * (lo + hi)
    for _ in range(NEWTON_ITERATIONS):  # (bounded; it converges in a handful)
        fx = _value(a1, b1, d1, 0.0, sig, wd, x)
        if fx == 0.0:
            return x
        if (fx < 0.0) == (f_lo < 0.0):
            lo, f_lo = x, fx
        else:
            hi = x
        dfx = _value(a2, b2, 0.0, 0.0, sig, wd, x)
        step = fx / dfx if dfx != 0.0 else 0.0
        nx = x - step
        if not (lo < nx < hi) or dfx == 0.0:
            nx = 0.5 * (lo + hi)
        if abs(nx - x) <= 1e-15 * (1.0 + abs(x)) or hi - lo <= 1e-15 * (1.0 + abs(x)):
            return nx
        x = nx
    return x


@jit
def _interior_peak(a: float, b: float, d0: float, d1: float, sig: float, wd: float, h: float) -> float:
    """The largest ``|f|`` at the critical points of ``f = exp(-sig tau)(a cos + b sin) + d0 + d1 tau`` inside
    ``(0, h)`` (0 if it has none)."""
    a1, b1 = _deriv_a(a, b, sig, wd), _deriv_b(a, b, sig, wd)
    a2, b2 = _deriv_a(a1, b1, sig, wd), _deriv_b(a1, b1, sig, wd)
    peak = 0.0
    # the zeros of f'' (a pure damped sinusoid: a2 cos x + b2 sin x = R sin(x + phi)) cut (0, h) into
    # pieces on which f' is monotone
    phi = math.atan2(a2, b2)
    k = math.floor(phi / math.pi) + 1.0
    lo = 0.0
    f_lo = _value(a1, b1, d1, 0.0, sig, wd, 0.0)
    while True:  # (bounded: one pass per half period inside the interval, and one more)
        cut = (k * math.pi - phi) / wd
        last = cut >= h
        if last:
            cut = h
        f_hi = _value(a1, b1, d1, 0.0, sig, wd, cut)
        if f_hi == 0.0 and not last:
            peak = max(peak, abs(_value(a, b, d0, d1, sig, wd, cut)))
        elif (f_lo < 0.0) != (f_hi < 0.0) and f_lo != 0.0 and f_hi != 0.0:
            x = _root(a1, b1, d1, a2, b2, sig, wd, lo, cut, f_lo)
            peak = max(peak, abs(_value(a, b, d0, d1, sig, wd, x)))
        if last:
            break
        lo, f_lo = cut, f_hi
        k += 1.0
    return peak


@jit_entry
def spectrum_kernel(t: np.ndarray, acc: np.ndarray, omegas: np.ndarray, zeta: float, out: np.ndarray,
                    ctl: np.ndarray) -> int:
    """Peaks ``out[j] = (max |u|, max |u'|, max |a_abs|)`` of the oscillator ``omegas[j]`` (rad/s, > 0),
    damping ratio ``zeta`` (0 <= zeta < 1), at rest at ``t[0]``, under the record ``acc`` (m/s^2, linear
    between the samples ``t``) up to ``t[-1]``.  Polls ``ctl[STOP]`` once per oscillator and counts the
    intervals and the half periods inside them against ``ctl[BUDGET]``.  Returns DONE, INTERRUPTED or
    OVER_BUDGET."""
    n = t.size
    root = math.sqrt(1.0 - zeta * zeta)
    for j in range(omegas.size):
        if ctl[STOP] != 0:
            return INTERRUPTED
        w = omegas[j]
        # (intervals, and half periods searched)
        ctl[WORK] += n - 1 + int(w * root * (t[n - 1] - t[0]) / math.pi)
        if ctl[WORK] > ctl[BUDGET]:
            return OVER_BUDGET
        w2 = w * w
        sig = zeta * w
        wd = w * root
        u = 0.0
        v = 0.0
        u_max = 0.0
        v_max = 0.0
        a_max = 0.0
        h_prev = -1.0
        e = c = s = 0.0
        for k in range(n - 1):
            h = t[k + 1] - t[k]
            g0 = acc[k]
            g1 = (acc[k + 1] - g0) / h
            p1 = -g1 / w2
            p0 = (-g0 - 2.0 * sig * p1) / w2
            cu = u - p0  # u's homogeneous part: exp(-sig tau)(cu cos + su sin)
            su = (v - p1 + sig * cu) / wd
            if h != h_prev:
                e = math.exp(-sig * h)
                c = math.cos(wd * h)
                s = math.sin(wd * h)
                h_prev = h
            cv, sv = _deriv_a(cu, su, sig, wd), _deriv_b(cu, su, sig, wd)  # u'
            ca, sa = _deriv_a(cv, sv, sig, wd), _deriv_b(cv, sv, sig, wd)  # u'' (a_abs = u'' + A)
            cj, sj = _deriv_a(ca, sa, sig, wd), _deriv_b(ca, sa, sig, wd)  # u'''
            cs, ss = _deriv_a(cj, sj, sig, wd), _deriv_b(cj, sj, sig, wd)  # u''''
            u1 = e * (cu * c + su * s) + p0 + p1 * h
            v1 = e * (cv * c + sv * s) + p1
            acc0 = -2.0 * sig * v - w2 * u  # a_abs at both ends
            acc1 = -2.0 * sig * v1 - w2 * u1
            long = wd * h >= math.pi  # (half a period or more: a pair of roots could hide)
            ddu0 = acc0 - g0  # u'' at both ends
            ddu1 = acc1 - acc[k + 1]
            bend = (ddu0 < 0.0) != (ddu1 < 0.0)
            if long or bend or (v < 0.0) != (v1 < 0.0):
                u_max = max(u_max, _interior_peak(cu, su, p0, p1, sig, wd, h))
            if long or bend:
                v_max = max(v_max, _interior_peak(cv, sv, p1, 0.0, sig, wd, h))
            j0 = cj + g1  # a_abs' = u''' + g1 at both ends, a_abs'' = u'''' at both ends
            j1 = e * (cj * c + sj * s) + g1
            q0 = cs
            q1 = e * (cs * c + ss * s)
            if long or (j0 < 0.0) != (j1 < 0.0) or (q0 < 0.0) != (q1 < 0.0):
                a_max = max(a_max, _interior_peak(ca, sa, g0, g1, sig, wd, h))
            u_max = max(u_max, abs(u1))
            v_max = max(v_max, abs(v1))
            a_max = max(a_max, abs(acc1))
            u = u1
            v = v1
        out[j, 0] = u_max
        out[j, 1] = v_max
        out[j, 2] = a_max
    return DONE
