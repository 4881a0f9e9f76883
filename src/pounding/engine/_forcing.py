"""The excitation as the kernel sees it: its piece from a given instant, and the run's scales."""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit

EXC_HARMONIC = 0
TWO_PI = 2.0 * math.pi
# relative to the run's scales (run_scales): a contact whose added compression and impulse are
# both below it is no impact (not recorded), and an incoming velocity below it is zero
RESOLUTION = 1e-9


@jit
def excitation_piece(kind, exc_p, rec_t, rec_a, t, j_hint):
    """Base acceleration from ``t`` on: ``(a0, a1, amp, omega, phase, t_next, j)`` such that
    ``A(t + tau) = a0 + a1 tau + amp sin(omega tau + phase)`` until ``t_next``; for a record,
    ``j`` is the sample interval holding ``t``, looked for from ``j_hint`` on (the one the
    last call returned: a run goes through the intervals in order), else ``j_hint``."""
    if kind == EXC_HARMONIC:
        omega = exc_p[1]
        # the angle reduced to [0, 2 pi): as exact as the angle itself (np.fmod is a call into
        # Numba's C helpers, 2 % of a run)
        angle = omega * t + exc_p[2]
        phase = angle - TWO_PI * math.floor(angle / TWO_PI)
        return 0.0, 0.0, exc_p[0], omega, phase, np.inf, j_hint
    n = rec_t.size
    if t < rec_t[0]:
        return 0.0, 0.0, 0.0, 0.0, 0.0, rec_t[0], j_hint
    if t >= rec_t[n - 1]:
        return 0.0, 0.0, 0.0, 0.0, 0.0, np.inf, j_hint
    # the sample interval holding t: rec_t[j] <= t < rec_t[j + 1] (rec_t increases): the hint's
    # or the next one's, else by bisection
    j = min(max(j_hint, 0), n - 2)
    if not (rec_t[j] <= t < rec_t[j + 1]):
        if j + 2 < n and rec_t[j + 1] <= t < rec_t[j + 2]:
            j += 1
        else:
            j = 0
            hi = n - 1
            while hi - j > 1:
                mid = (j + hi) // 2
                if rec_t[mid] <= t:
                    j = mid
                else:
                    hi = mid
    slope = (rec_a[j + 1] - rec_a[j]) / (rec_t[j + 1] - rec_t[j])
    return rec_a[j] + slope * (t - rec_t[j]), slope, 0.0, 0.0, 0.0, rec_t[j + 1], j


@jit
def run_scales(mass, slopes, exc_kind, exc_p, rec_a, gap_l, gap_r, breaks):
    """The run's length (m) and velocity (m/s) scales: the largest of the total gap, the first
    breakpoint and the table's peak acceleration over ``w^2``, with ``w`` the faster of the
    forcing and the isolator's first branch; the velocity scale is the length scale times
    ``w``.  What the run's displacements are rounded against, and what its resolution
    (``RESOLUTION``) is relative to.  The system's and the excitation's, not the start's: a
    run continued from a final state has the scales of the run it continues."""
    w = math.sqrt(slopes[0] / mass)
    amp = 0.0
    if exc_kind == EXC_HARMONIC:
        amp = abs(exc_p[0])
        w = max(w, exc_p[1])
    else:
        for a in rec_a:
            amp = max(amp, abs(a))
    x = max(gap_l + gap_r, amp / (w * w))
    if breaks.size > 0:
        x = max(x, breaks[0])
    return x, x * w
