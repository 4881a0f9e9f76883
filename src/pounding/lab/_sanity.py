"""Checks that a recording's channels are what they are said to be: units, signs, time scale.

Kinematics ties the channels together whatever the forces: the mass's acceleration relative to
the table is the second derivative of the laser's displacement, so over whole cycles of a step the
fundamentals (the components at the table's frequency ``f``, complex amplitudes) obey
``F(a_abs) = F(A) - omega^2 F(D)`` exactly, contacts or not.  Taking the table channel as right, an
accelerometer read as ``s_a`` times the truth and a laser as ``s_D`` times it give
``F(a) = s_a F(A) - (s_a / s_D) omega^2 F(D)``: two real unknowns, found by least squares over the
steps (at different frequencies the two terms point different ways).  Both are 1 for a consistent
recording; -1 for a channel of the opposite sign, 1/9.81 or 9.81 for g and m/s^2 mixed up, 1e3 or
1e-3 for millimetres and metres.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .._errors import PoundingWarning
from .._units import GRAVITY_M_S2

RATIO_RTOL = 0.25  # a ratio further than this from 1 is warned about
F_LOW_HZ, F_HIGH_HZ = 0.05, 200.0  # stepped-sine frequencies outside this look like a time-unit error


def fundamental(t: np.ndarray, x: np.ndarray, f: float) -> complex:
    """The complex amplitude ``X`` of ``x ~ Re(X exp(i 2 pi f t)) + c`` (least squares, finite samples)."""
    ok = np.isfinite(x)
    if ok.sum() < 4:
        return complex(math.nan, math.nan)
    w = 2.0 * math.pi * f * (t[ok] - t[ok][0])
    design = np.column_stack([np.cos(w), -np.sin(w), np.ones(w.size)])
    re, im, _ = np.linalg.lstsq(design, x[ok], rcond=None)[0]
    return complex(re, im)


def channel_scales(table: np.ndarray, disp_w2: np.ndarray, acc: np.ndarray) -> tuple[float, float]:
    """``(s_a, s_D)`` from the steps' fundamentals ``table = F(A)``, ``disp_w2 = omega^2 F(D)``, ``acc =
    F(a)``
    (complex, shape (steps,)); NaN where the steps cannot tell them apart."""
    ok = np.isfinite(table) & np.isfinite(disp_w2) & np.isfinite(acc)
    if ok.sum() < 1:
        return math.nan, math.nan
    scale = np.abs(table[ok]) + np.abs(disp_w2[ok])  # (each step weighs the same)
    p, q, z = table[ok] / scale, disp_w2[ok] / scale, acc[ok] / scale
    design = np.vstack([np.column_stack([p.real, -q.real]), np.column_stack([p.imag, -q.imag])])
    rhs = np.concatenate([z.real, z.imag])
    if np.linalg.cond(design) > 1e6:
        return math.nan, math.nan
    x, ratio = np.linalg.lstsq(design, rhs, rcond=None)[0]
    return float(x), float(x / ratio) if ratio != 0.0 else math.inf


def _near(value: float, target: float) -> bool:
    return abs(value / target - 1.0) < RATIO_RTOL


def _diagnosis(s_a: float, s_d: float) -> str | None:
    """What scales far from 1 most likely mean (None when they are near 1)."""
    if _near(s_a, 1.0) and _near(s_d, 1.0):
        return None
    if _near(s_a, -1.0) and _near(s_d, 1.0):
        return "it reads the opposite sign of the table's and the laser's: negate that accelerometer"
    if _near(s_a, 1.0) and _near(s_d, -1.0):
        return ("the laser reads the opposite sign (pounding takes D positive in the direction of the "
                "table's positive acceleration): negate the displacement")
    for factor, why in ((1.0 / GRAVITY_M_S2, "it looks like g read as m/s^2: give its unit as g"),
                        (GRAVITY_M_S2, "it looks like m/s^2 read as g: give its unit as m/s2"),
                        (1e-2, "it looks like cm/s^2 read as m/s^2: give its unit as cm/s2")):
        if _near(s_a, factor) and _near(s_d, 1.0):
            return why
    for factor, why in ((1e3, "the displacement looks like mm read as m: give its unit as mm"),
                        (1e-3, "the displacement looks like m read as mm: give its unit as m"),
                        (GRAVITY_M_S2,
                         "the accelerations (table and mass) look like g read as m/s^2: give their "
                         "unit as g"),
                        (1.0 / GRAVITY_M_S2, "the accelerations (table and mass) look like m/s^2 read as g")):
        if _near(s_a, 1.0) and _near(s_d, factor):
            return why
    return "check the channels' units, signs and columns (and that the table channel is the table's)"


def warn_inconsistent(source: str, channels: tuple[str, ...], table: np.ndarray, disp_w2: np.ndarray,
                      acc: np.ndarray) -> None:
    """Warn for each accelerometer (``acc`` shape (steps, channels)) whose scales are not 1."""
    for j, name in enumerate(channels):
        s_a, s_d = channel_scales(table, disp_w2, acc[:, j])
        why = _diagnosis(s_a, s_d) if np.isfinite(s_a) and np.isfinite(s_d) else None
        if why is not None:
            warnings.warn(f"{source}: the channels disagree: against the table, accelerometer {name!r} reads "
                          f"{s_a:.3g} times the mass's acceleration and the laser {s_d:.3g} times its "
                          "displacement (kinematics, whatever the forces; 1 and 1 for a consistent "
                          f"recording); {why}",
                          PoundingWarning, stacklevel=3)


def warn_time_scale(source: str, sample_rate_hz: float, freqs_hz: np.ndarray) -> None:
    """Warn when the steps' frequencies are outside what shaking tables run (a time unit error)."""
    if freqs_hz.size == 0:
        return
    f = float(np.median(freqs_hz))
    if f < F_LOW_HZ:
        warnings.warn(f"{source}: the steps are at {f:.3g} Hz and the record samples at {sample_rate_hz:.3g} "
                      "Hz: is the time in ms read as s? give units time=ms", PoundingWarning, stacklevel=3)
    elif f > F_HIGH_HZ:
        warnings.warn(f"{source}: the steps are at {f:.3g} Hz: is the time in s read as ms? give "
                      "units time=s",
                      PoundingWarning, stacklevel=3)
