"""The stepped-sine protocol restated on top of the solve_ivp reference (fixed cycles).

Each step starts at table phase 0 with the state carried over; the last ``measure``
cycles are measured: extrema of D and |a_abs|, and the contacts that end in them.
"""

from __future__ import annotations

import math

import numpy as np

import pounding as pd_
from reference import reference


def reference_sweep(osc, a_g, freqs_hz, cycles, measure, rtol=1e-12, atol=1e-16):
    state = None
    t = 0.0
    rows = []
    for f in freqs_hz:
        exc = pd_.Harmonic(a_g, f, phase=-(2 * math.pi * f * t))
        period = 1.0 / f
        t_window = t + (cycles - measure) * period
        t_end = t + cycles * period
        kw = dict(rtol=rtol, atol=atol)
        if cycles > measure:
            state = reference(osc, exc, t_window, state=state, **kw).state
        res = reference(osc, exc, t_end, state=state, measure=True, **kw)
        state, t = res.state, t_end
        done = [c for c in res.completed if c[3] > t_window]
        rows.append({
            "freq_hz": f,
            "alpha": res.a_abs_max / exc.peak_m_s2,
            "excursion_m": res.d_max - res.d_min,
            "contacts": len(done),
            "restitution": np.mean([-c[4] / c[2] for c in done]) if done else math.nan,
            "contact_time_s": np.mean([c[3] - c[1] for c in done]) if done else math.nan,
        })
    return rows
