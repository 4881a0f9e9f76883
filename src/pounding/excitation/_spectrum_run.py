"""The exact elastic spectrum's computation on arrays: what ``response_spectrum`` and
``Record.scaled(sa_g=...)`` share (a module of its own, so that neither imports the other)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._checks import float_array, real
from .._errors import InputError, Problem
from .._core import spectrum as spectrum_kernel
from .._core import spectrum_pair as spectrum_pair_kernel
from .._errors import Status

DONE, INTERRUPTED = int(Status.SUCCESS), int(Status.INTERRUPTED)

MAX_INTERVALS = 2_000_000_000  # periods x record intervals: about a minute of one core


MAX_PERIOD_S = 1000.0  # the longest period: beyond it the closed form's particular solution loses digits


def periods_array(periods_s: Any) -> np.ndarray:
    """Validated periods (s): finite, in [0, 1000], strictly increasing, shape (p,)."""
    periods = float_array("periods_s", periods_s)
    if (periods < 0.0).any():
        i = int(np.flatnonzero(periods < 0.0)[0])
        raise InputError(Problem.NEGATIVE, f"periods_s[{i}]", float(periods[i]), unit="s")
    if (periods > MAX_PERIOD_S).any():
        i = int(np.flatnonzero(periods > MAX_PERIOD_S)[0])
        raise InputError(Problem.OUT_OF_RANGE, f"periods_s[{i}]", float(periods[i]),
                         range=f"[0, {MAX_PERIOD_S:g}] s",
                         hint=" (the closed form subtracts a / omega^2 terms that cancel: at 1e4 s it keeps "
                              "four digits, at 1e5 s none)")
    if periods.size > 1 and (np.diff(periods) <= 0.0).any():
        raise InputError(Problem.NOT_INCREASING, "periods_s", periods.tolist()[:6])
    return periods


def damping_ratio_value(damping_ratio: Any) -> float:
    """A validated damping ratio in [0, 1)."""
    zeta = real("damping_ratio", damping_ratio)
    if not 0.0 <= zeta < 1.0:
        raise InputError(Problem.OUT_OF_RANGE, "damping_ratio", zeta, range="[0, 1)",
                         hint=" (a fraction of critical: 0.05 is 5 %)")
    return zeta


def spectrum_peaks(series: Sequence[tuple[np.ndarray, np.ndarray]], periods: np.ndarray,
                   zeta: float) -> tuple[np.ndarray, int]:
    """Peak relative displacement, relative velocity and absolute acceleration (SI) of each
    ``(t, accel)`` series at each period (checked ones): shape (records, periods, 3), and how many
    series were done (fewer on Ctrl-C: the rest NaN).  A period 0 is the rigid oscillator."""
    from .._control import new_control, run_interruptibly

    # the kernel's work: every record interval, and every half period inside them (searched for peaks)
    half_periods = float(np.sum(2.0 / periods[periods > 0.0])) * math.sqrt(1.0 - zeta * zeta)
    work = sum(periods.size * (t.size - 1) + half_periods * (t[-1] - t[0]) for t, _ in series)
    if work > MAX_INTERVALS:
        raise InputError(Problem.TOO_MUCH_WORK, "periods_s", f"{periods.size} periods down to "
                         f"{periods[periods > 0.0].min() if (periods > 0.0).any() else 0.0:g} s",
                         estimate=f"{work:.3g}", unit="intervals and half periods",
                         budget=f"{MAX_INTERVALS:.3g}",
                         fix="fewer periods or records, or no periods far below the record's time step")
    rigid = periods == 0.0
    omegas = 2.0 * math.pi / periods[~rigid]
    peaks = np.full((len(series), periods.size, 3), np.nan)
    ctl = new_control(MAX_INTERVALS)
    for i, (t_s, accel) in enumerate(series):
        out = np.zeros((omegas.size, 3))
        t, a = np.array(t_s, dtype=float), np.array(accel, dtype=float)
        status = run_interruptibly(lambda t=t, a=a, out=out: spectrum_kernel(t, a, omegas, zeta, out, ctl),
                                   [ctl])
        if status == INTERRUPTED:
            return peaks, i
        if status != DONE:  # (the budget was checked above)
            raise RuntimeError(f"response_spectrum: the kernel stopped with status {status}")
        peaks[i, ~rigid] = out
        peaks[i, rigid] = (0.0, 0.0, float(np.abs(a).max()))
    return peaks, len(series)


def pair_peaks(pairs: Sequence[tuple[np.ndarray, np.ndarray, np.ndarray]], periods: np.ndarray, zeta: float,
               angles_rad: np.ndarray) -> tuple[np.ndarray, int]:
    """Peak relative displacement (m) of each ``(t, accel_x, accel_y)`` pair at each period (checked ones)
    in each direction ``cos(a) x + sin(a) y``: shape (pairs, periods, angles), and how many pairs were done
    (fewer on Ctrl-C: the rest NaN).  At a period 0 (the rigid oscillator): the peak ground acceleration
    along each direction (m/s^2), at a sample (the motion is linear between them)."""
    from .._control import new_control, run_interruptibly

    positive = periods > 0.0
    half_periods = (float(np.sum(2.0 / periods[positive])) * math.sqrt(1.0 - zeta * zeta)
                    * 4 * (1 + angles_rad.size))  # (each direction's, at about four intervals' cost)
    per_interval = positive.sum() * (1 + angles_rad.size // 8)  # (the kernel's own count)
    work = sum(per_interval * (t.size - 1) + half_periods * (t[-1] - t[0]) for t, _, _ in pairs)
    if work > MAX_INTERVALS:
        raise InputError(Problem.TOO_MUCH_WORK, "periods_s", f"{periods.size} periods and {angles_rad.size} "
                         "directions", estimate=f"{work:.3g}", unit="intervals and half periods",
                         budget=f"{MAX_INTERVALS:.3g}",
                         fix="fewer periods, directions (a larger angle step) or pairs")
    omegas = 2.0 * math.pi / periods[positive]
    cos_a, sin_a = np.cos(angles_rad), np.sin(angles_rad)
    peaks = np.full((len(pairs), periods.size, angles_rad.size), np.nan)
    ctl = new_control(MAX_INTERVALS)
    for i, (t_s, ax, ay) in enumerate(pairs):
        out = np.zeros((omegas.size, angles_rad.size))
        t, a_x, a_y = (np.array(v, dtype=float) for v in (t_s, ax, ay))
        # (the accelerations by a power of two of their size, the peaks back by it: the same numbers, none of
        # the kernel's squares under- or overflowing)
        largest = max(float(np.abs(a_x).max()), float(np.abs(a_y).max()))
        scale = 2.0 ** round(math.log2(largest)) if largest > 0.0 else 1.0
        x_unit, y_unit = a_x / scale, a_y / scale
        status = run_interruptibly(
            lambda: spectrum_pair_kernel(t, x_unit, y_unit, omegas, zeta, angles_rad, out, ctl), [ctl])
        if status == INTERRUPTED:
            return peaks, i
        if status != DONE:  # (the budget was checked above)
            raise RuntimeError(f"rotd_spectrum: the kernel stopped with status {status}")
        peaks[i, positive] = out * scale
        for k in range(0, angles_rad.size, 64):  # (64 directions at a time: a record's samples each)
            along = np.outer(cos_a[k:k + 64], a_x) + np.outer(sin_a[k:k + 64], a_y)
            peaks[i, ~positive, k:k + 64] = np.abs(along).max(axis=1)
    return peaks, len(pairs)
