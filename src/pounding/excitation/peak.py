"""The largest ground acceleration of an excitation over a window, exact: a sine's crest, or a record's
sample (linear between them)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def ground_peak(excitation: Any, t0: float, t1: float) -> tuple[float, float]:
    """The largest absolute ground acceleration over [t0, t1], m/s^2, and when: exact (a sine's crest, or a
    record's sample, linear between them)."""
    from .harmonic import Harmonic

    ends = np.array([t0, t1])
    candidates = [ends]
    if isinstance(excitation, Harmonic):  # crests where omega t + phase = pi/2 + k pi
        w, phi = excitation.omega_rad_s, excitation.phase
        first = math.ceil(((w * t0 + phi) - 0.5 * math.pi) / math.pi)
        last = math.floor(((w * t1 + phi) - 0.5 * math.pi) / math.pi)
        if last >= first:
            candidates.append(np.array([(0.5 * math.pi + first * math.pi - phi) / w]))
    else:
        inside = excitation.t[(excitation.t >= t0) & (excitation.t <= t1)]
        candidates.append(inside)
    times = np.concatenate(candidates)
    values = np.abs(excitation.acceleration(times))
    j = int(np.argmax(values))
    return float(values[j]), float(times[j])
