"""One frequency step of a stepped-sine sweep, compiled: cycles until steady, then measure.

The step is run one forcing cycle at a time by the event-exact engine (the state carried
over is exact, so cutting at cycle ends changes nothing).  After each cycle the state at
the cycle end (the stroboscopic sample, table phase 0) is kept; the response is steady
with period multiple ``k`` when the last ``m`` strobes repeat those ``k`` cycles earlier
to within ``steady_rtol`` of the response amplitude, after allowing for how slowly the
strobes still converge.  Only arrays and scalars go in and out (it ships to workers).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit, jit_entry
from ..engine._forcing import EXC_HARMONIC
from ..engine._kernel import SUCCESS, run_kernel
from ..engine._layout import D, STATE_BASE, T, V, Z_L, Z_R, ZETA
from ..engine._system import Forcing
from ..model.contact_laws import N_LAW_STATE, law_has_memory
from ..metrics._impacts import SIDE_SUMS, add_impacts

# per-cycle record: exact extrema, then the impact sums of both sides
CY_DMAX, CY_DMIN, CY_AMAX = 0, 1, 2
CY_SUMS = 3
CYCLE_COLS = CY_SUMS + 2 * SIDE_SUMS
# the measurement window: extrema, number of cycles, impact sums (left then right)
W_DMAX, W_DMIN, W_AMAX, W_CYCLES = 0, 1, 2, 3
W_SUMS = 4
WINDOW_COLS = W_SUMS + 2 * SIDE_SUMS
AMPLITUDE_FLOOR_M = 1e-12
# Strobe differences below this fraction of the amplitude are rounding noise (each of a
# cycle's events rounds the state; measured: 1e-13 on the printed system at 1.3 Hz).  A
# transient whose lag-k differences are this small yet is farther than ``steady_rtol`` from
# its orbit would have to decay by less than 1e-6 (1e-12 / 1e-6 tolerance) in k cycles.
STROBE_NOISE = 1e-12
TYPED_ZERO = np.int64(0)  # a typed zero for arguments (a literal 0 costs a compilation)
NO_ENERGY = np.bool_(False)  # typed too: a literal False would compile run_kernel once more


@jit
def _strobe_distance(strobe, a, b, tol_d, tol_v):
    """Largest component of ``|strobe[a] - strobe[b]|`` in units of the tolerances."""
    dist = abs(strobe[a, 1] - strobe[b, 1]) / tol_v
    for q in range(strobe.shape[1]):
        if q != 1:
            dist = max(dist, abs(strobe[a, q] - strobe[b, q]) / tol_d)
    return dist


@jit
def _window_distance(strobe, n, k, first, last, tol_d, tol_v):
    """Largest lag-``k`` strobe difference over cycles ``n-1-first`` down to ``n-last``."""
    out = 0.0
    for j in range(first, last):
        out = max(out, _strobe_distance(strobe, n - 1 - j, n - 1 - j - k, tol_d, tol_v))
    return out


@jit
def periodicity(strobe, cyc, n, window, max_period, steady_rtol, omega, round_window):
    """Smallest period multiple ``k`` with which the last cycles repeat, or 0.

    Returns ``(k, m)``: ``m`` is the window of cycles that repeat (``window`` rounded up
    to a multiple of ``k`` when ``round_window``).  The lag-``k`` differences of the last
    ``m`` strobes must be within tolerance, and so must the estimated distance to the
    periodic orbit, ``d / (1 - r^k)``: ``d`` the largest of those differences and ``r``
    the per-cycle convergence ratio, from ``d`` and the largest difference of the ``m``
    strobes before (maxima over several cycles, so that a transient that rotates from
    one strobe to the next cannot pass by a lucky phase).  Differences at the level of
    rounding (``STROBE_NOISE`` of the amplitude) pass without the ratio, which noise makes
    anything between 0 and above 1.
    """
    amp = AMPLITUDE_FLOOR_M
    for j in range(max(0, n - window), n):
        amp = max(amp, 0.5 * (cyc[j, CY_DMAX] - cyc[j, CY_DMIN]))
    tol_d = steady_rtol * amp
    tol_v = tol_d * omega
    for k in range(1, max_period + 1):
        m = window
        if round_window:
            m = k * ((window + k - 1) // k)
        if n < 2 * m + k:
            continue
        recent = _window_distance(strobe, n, k, TYPED_ZERO, m, tol_d, tol_v)
        if recent > 1.0:
            continue
        if recent * steady_rtol <= STROBE_NOISE:
            # rounding noise: converged (the convergence ratio of noise means nothing)
            return _smallest_period(strobe, n, k, window, round_window, tol_d, tol_v, steady_rtol)
        older = _window_distance(strobe, n, k, m, 2 * m, tol_d, tol_v)
        ratio = recent / older if older > 0.0 else 0.0
        if ratio >= 1.0:
            continue
        if recent <= 1.0 - ratio ** (k / m):
            return _smallest_period(strobe, n, k, window, round_window, tol_d, tol_v, steady_rtol)
    return 0, window


@jit
def _smallest_period(strobe, n, k, window, round_window, tol_d, tol_v, steady_rtol):
    """The least divisor ``p`` of ``k`` with which the window also repeats, loosely.

    A transient that decays while rotating can make the lag-``k`` differences small
    before the lag-1 ones; once the orbit is within tolerance at lag ``k``, a response of
    period ``p | k`` shows lag-``p`` differences of the order of the tolerance, a true
    period-``k`` response ones of the order of its amplitude.
    """
    loose = max(1.0, min(100.0, 1e-2 / steady_rtol))
    for p in range(1, k):
        if k % p != 0:
            continue
        m = p * ((window + p - 1) // p) if round_window else window
        ok = n >= m + p
        j = 0
        while ok and j < m:
            ok = _strobe_distance(strobe, n - 1 - j, n - 1 - j - p, tol_d, tol_v) <= loose
            j += 1
        if ok:
            return p, m
    m = k * ((window + k - 1) // k) if round_window else window
    return k, m


@jit_entry
def step_kernel(sy, amp, omega, state0, steady, rtol, max_events, ctl):
    """Hold the harmonic ``amp sin(omega (t - t0))`` (m/s^2, rad/s) on the system ``sy``
    (``engine/_system.System``) from ``state0`` (time ``t0``).

    ``steady`` is ``(adaptive, n_cycles, measure_cycles, steady_rtol, max_period)``.

    ``adaptive``: stop as soon as the response is periodic (at most ``n_cycles``
    cycles); otherwise run exactly ``n_cycles``.  The last ``measure_cycles`` (rounded up
    to whole periods when adaptive and steady) are measured.

    Returns ``(state, cycles_run, period_multiple, window, window_state, window_strobes,
    status)`` with ``period_multiple`` 0 when not periodic, ``window`` of length
    ``WINDOW_COLS`` and ``window_strobes`` the window's stroboscopic samples (the state at each
    of its cycles' ends, table phase 0), shape (cycles, 2): displacement and velocity.
    ``ctl`` is the run control of ``run_kernel`` (Ctrl-C and the work budget), shared by
    every cycle.
    """
    adaptive, n_cycles, measure_cycles, steady_rtol, max_period = steady
    period = 2.0 * math.pi / omega
    t0 = state0[T]
    exc_p = np.empty(3)  # amplitude, omega, phase: A(t0) = 0 exactly, phase 0 at the step start
    exc_p[0] = amp
    exc_p[1] = omega
    exc_p[2] = -(omega * t0)
    no_record = np.zeros(1)
    n_sp = (state0.size - STATE_BASE) // 2
    strobe = np.empty((n_cycles, 3 + n_sp + 2 * N_LAW_STATE))  # D, V, the slips, the bumpers' law states, z
    starts = np.empty((n_cycles, state0.size))
    cyc = np.zeros((n_cycles, CYCLE_COLS))
    st = state0.copy()
    status = SUCCESS
    n = 0
    k = 0
    m = measure_cycles
    sums = np.zeros((1, 2 * SIDE_SUMS))
    # (a typed int, not a literal: one run_kernel for all callers)
    forcing = Forcing(np.int64(EXC_HARMONIC), exc_p, no_record, no_record)
    while n < n_cycles:
        for q in range(st.size):  # element loops, not slice assignment (less to compile)
            starts[n, q] = st[q]
        st, _, contacts, _, _, extrema, status = run_kernel(
            sy, forcing, st, t0 + (n + 1) * period, -1.0, rtol, max_events, NO_ENERGY,
            ctl)  # a step measures extrema and contacts, not the ledger
        cyc[n, CY_DMAX] = extrema[0]
        cyc[n, CY_DMIN] = extrema[2]
        cyc[n, CY_AMAX] = extrema[4]
        sums[0] = 0.0
        add_impacts(contacts, sy.mass, sums, TYPED_ZERO)
        for q in range(2 * SIDE_SUMS):
            cyc[n, CY_SUMS + q] = sums[0, q]
        strobe[n, 0] = st[D]
        strobe[n, 1] = st[V]
        for q in range(n_sp):
            strobe[n, 2 + q] = st[STATE_BASE + q]
        # a hysteretic bumper's state is memory as the slips are (m, or a line's code); a
        # stateless law's is 0, Hertzdamp's a damping that follows from the motion
        for q in range(N_LAW_STATE):
            strobe[n, 2 + n_sp + q] = st[Z_L + q] if law_has_memory(sy.law_l) else 0.0
            strobe[n, 2 + n_sp + N_LAW_STATE + q] = st[Z_R + q] if law_has_memory(sy.law_r) else 0.0
        strobe[n, 2 + n_sp + 2 * N_LAW_STATE] = st[ZETA] * sy.bw[1]  # (the Bouc-Wen z as a length)
        n += 1
        if status != SUCCESS:
            break
        if adaptive:
            k, m = periodicity(strobe, cyc, n, measure_cycles, max_period, steady_rtol, omega, adaptive)
            if k > 0:
                break
    if not adaptive or k == 0:
        # not rounded (``adaptive and k > 0`` is False here; a runtime bool, not a literal)
        k, m = periodicity(strobe, cyc, n, measure_cycles, max_period, steady_rtol, omega,
                           adaptive and k > 0)
    m = min(m, n)
    window = np.zeros(WINDOW_COLS)
    window[W_DMAX] = -np.inf
    window[W_DMIN] = np.inf
    window[W_CYCLES] = m
    for j in range(n - m, n):
        window[W_DMAX] = max(window[W_DMAX], cyc[j, CY_DMAX])
        window[W_DMIN] = min(window[W_DMIN], cyc[j, CY_DMIN])
        window[W_AMAX] = max(window[W_AMAX], cyc[j, CY_AMAX])
        for q in range(2 * SIDE_SUMS):
            window[W_SUMS + q] += cyc[j, CY_SUMS + q]
    strobes = np.empty((m, 2))
    for j in range(m):
        strobes[j, 0] = strobe[n - m + j, 0]
        strobes[j, 1] = strobe[n - m + j, 1]
    return st, n, k, window, starts[n - m].copy(), strobes, status
