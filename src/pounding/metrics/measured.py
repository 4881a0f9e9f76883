"""Metrics as a lab measures them: from sampled, noisy histories of one window of whole cycles.

:func:`measure_window` is the per-window half of :func:`pounding.lab.analyse_stepped_sine` (whose
module states the method: offsets, smoothed peaks, synchronous averaging, contacts from force
pulses), kept here so that :func:`pounding.sweep` with a :class:`pounding.MeasurementChain` measures
its windows the same way: one implementation.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .measured_contacts import FLIGHT_FIT_S, IMPACT_COLUMNS, window_contacts

SMOOTH_S = 0.010  # the Savitzky-Golay window: 10 ms (a 1 kHz record: 11 samples)
UNCERTAIN = ("contact_time_s", "restitution", "mean_force_n")  # contact means given with a standard error
STEADY_NOISE_FLOOR = 3.0  # steadiness tolerates this many noise standard deviations
PERIODIC_NOISE = 5.0  # aligned cycles repeat within this many noise standard deviations (see _in_phase)


def smooth(x: np.ndarray, fs: float) -> np.ndarray:
    """A Savitzky-Golay smoothing (cubic, :data:`SMOOTH_S` wide): noise down, short peaks kept."""
    from scipy import signal

    n = max(5, 2 * round(0.5 * SMOOTH_S * fs) + 1)
    if n >= x.size:
        return x.copy()
    return signal.savgol_filter(np.nan_to_num(x), n, 3)


def _peak(t: np.ndarray, x: np.ndarray, i: int) -> float:
    """The extreme of the smoothed ``x`` at its sample ``i``, between the samples: the vertex of the
    parabola through ``i - 1, i, i + 1``."""
    if i == 0 or i == x.size - 1:
        return float(x[i])
    y0, y1, y2 = x[i - 1], x[i], x[i + 1]
    den = y0 - 2.0 * y1 + y2
    if den == 0.0:
        return float(y1)
    shift = 0.5 * (y0 - y2) / den
    return float(y1 - 0.25 * (y0 - y2) * shift) if abs(shift) <= 1.0 else float(y1)


def _cycles_in_phase(t: np.ndarray, x: np.ndarray, start_s: float, period_s: float,
                     cycles: int) -> np.ndarray:
    """``x`` over ``cycles`` periods from ``start_s``, cut into periods and aligned in phase: its cubic
    spline read at ``t_j + k period_s`` (``t_j`` the samples of the first period), shape (cycles, samples
    of a period)."""
    from scipy.interpolate import CubicSpline

    lo = max(int(np.searchsorted(t, start_s)) - 3, 0)
    hi = min(int(np.searchsorted(t, start_s + cycles * period_s)) + 3, t.size)
    spline = CubicSpline(t[lo:hi], x[lo:hi])
    phase = t[(t >= start_s) & (t < start_s + period_s)]
    return np.stack([spline(phase + k * period_s) for k in range(cycles)])


def _cycle_mean(t: np.ndarray, x: np.ndarray, start_s: float, period_s: float, cycles: int) -> np.ndarray:
    """The mean of ``x`` (shape (n, k)) over exactly ``cycles`` periods from ``start_s``: its cubic spline's
    integral over them (zeros where the samples there are not all finite), shape (k,)."""
    from scipy.interpolate import CubicSpline

    lo = max(int(np.searchsorted(t, start_s)) - 3, 0)
    hi = min(int(np.searchsorted(t, start_s + cycles * period_s)) + 3, t.size)
    if not np.isfinite(x[lo:hi]).all():
        return np.zeros(x.shape[1])
    end = start_s + cycles * period_s
    return CubicSpline(t[lo:hi], x[lo:hi]).integrate(start_s, end) / (end - start_s)


def _in_phase(cycles: np.ndarray, fs: float, rtol: float) -> bool:
    """Whether aligned cycles (shape (k, n)) repeat: every smoothed cycle within the larger of
    :data:`PERIODIC_NOISE` noise standard deviations and ``rtol`` of the peak of their average. The noise
    is the robust spread (1.4826 MAD) of the smoothed differences from the average: a pulse that some
    cycles have and others not (a graze) is an outlier of it, and fails the test."""
    from scipy import signal

    n = max(5, 2 * round(0.5 * SMOOTH_S * fs) + 1)
    if n >= cycles.shape[1]:
        return False
    resid = signal.savgol_filter(cycles - cycles.mean(axis=0), n, 3, axis=1, mode="wrap")
    noise = 1.4826 * float(np.median(np.abs(resid)))
    peak = float(np.abs(cycles.mean(axis=0)).max())
    return float(np.abs(resid).max()) <= max(PERIODIC_NOISE * noise, rtol * peak)


def _periodic_peak(x: np.ndarray, fs: float, sign: float) -> float:
    """The largest ``sign * x`` of one period of samples, smoothed as :func:`smooth` (wrapping round the
    period) and between the samples by the parabola through the three around it: signed as ``x``."""
    from scipy import signal

    n = max(5, 2 * round(0.5 * SMOOTH_S * fs) + 1)
    y = sign * (signal.savgol_filter(x, n, 3, mode="wrap") if n < x.size else x)
    i = int(np.argmax(y))
    y0, y1, y2 = y[i - 1], y[i], y[(i + 1) % y.size]
    den = y0 - 2.0 * y1 + y2
    shift = 0.5 * (y0 - y2) / den if den != 0.0 else 0.0
    return sign * float(y1 - 0.25 * (y0 - y2) * shift if abs(shift) <= 1.0 else y1)


def _standard_error(x: np.ndarray) -> float:
    """The standard error of the mean of ``x``'s finite values (NaN with fewer than two)."""
    x = x[np.isfinite(x)]
    return float(np.std(x, ddof=1) / math.sqrt(x.size)) if x.size >= 2 else math.nan


def measure_window(t: np.ndarray, table: np.ndarray, raw_acc: np.ndarray, acc: np.ndarray, d_raw: np.ndarray,
                   d: np.ndarray, bounds: np.ndarray, period: float, amp: float, fs: float, *,
                   names: tuple[str, ...], mass_kg: float, gap: float | None, steady_rtol: float,
                   omega_min_rad_s: float, noise: float,
                   contact_timing: str = "pulse") -> tuple[dict, dict, Any, int]:
    """The paper's quantities over one window of whole cycles of a sampled record.

    Parameters
    ----------
    t : ndarray, shape (n,)
        Sample times, s (uniform at ``fs``), covering the window and the flight beside it.
    table : ndarray, shape (n,)
        The table's acceleration, m/s^2.
    raw_acc, acc : ndarray, shape (n, k)
        The mass's accelerations as recorded and smoothed (:func:`smooth`), m/s^2: the
        accelerometers' mean first, then each (their names ``names``, alpha's columns).
    d_raw, d : ndarray, shape (n,)
        The displacement as recorded and smoothed, m (symmetric gaps about its zero).
    bounds : ndarray, shape (cycles + 1,)
        The window's cycle boundaries, s (the table's upward zero crossings).
    period, amp, fs : float
        The table's period (s), amplitude ``A_t`` (m/s^2) and the sampling rate (Hz).
    names : tuple of str
        alpha's column names, one per column of ``raw_acc``.
    mass_kg : float
    gap : float or None
        ``Delta = g_L + g_R``, m (None: no contacts are looked for).
    steady_rtol, omega_min_rad_s : float
        As :func:`pounding.lab.analyse_stepped_sine`'s.
    noise : float
        The displacement's noise (standard deviation of the recorded less the smoothed), m.
    contact_timing : str
        ``"pulse"``: contacts timed by their force pulses; ``"laser"``: by the displacement's gap
        crossings (:func:`pounding.metrics.measured_contacts.window_contacts`).

    Returns
    -------
    shape : dict
        alpha per column, ``alpha_se``, ``excursion_m``, ``displacement_max_m``,
        ``displacement_min_m``, ``eta``, ``e``, ``steady``, ``averaged``.
    contacts : dict
        With ``gap``: ``contact``, ``contacts_per_cycle``, the contacts' means and their standard
        errors (empty without).
    found : DataFrame or None
        The contacts (with ``gap``).
    unconfirmed : int
        Gap crossings without a force pulse (with ``"laser"`` timing, contacts still).
    """
    measure_cycles = bounds.size - 1
    w0, s1 = float(bounds[0]), float(bounds[-1])
    in_win = (t >= w0) & (t < s1)
    # the accelerometers' offsets: over whole cycles of a periodic motion the acceleration
    # averages to zero, so the window's mean is the offset
    zero = _cycle_mean(t, raw_acc, w0, period, measure_cycles)
    peaks = np.empty((measure_cycles, acc.shape[1]))
    dmax = np.empty(measure_cycles)
    dmin = np.empty(measure_cycles)
    for k in range(measure_cycles):
        w = np.flatnonzero((t >= bounds[k]) & (t < bounds[k + 1]))
        for j in range(acc.shape[1]):
            i = int(w[int(np.argmax(np.abs(acc[w, j] - zero[j])))])
            peaks[k, j] = abs(_peak(t, acc[:, j], i) - zero[j])
        dmax[k] = _peak(t, d, int(w[int(np.argmax(d[w]))]))
        dmin[k] = _peak(t, d, int(w[int(np.argmin(d[w]))]))
    exc = dmax - dmin
    excursion = float(dmax.max() - dmin.min())  # (over the window, as the sweep measures it)
    spread = float(exc.max() - exc.min()) / excursion if excursion > 0.0 else 0.0
    steady = bool(spread <= steady_rtol + STEADY_NOISE_FLOOR * noise / max(excursion, 1e-300))
    alphas = peaks.max(axis=0)
    aligned = (_cycles_in_phase(t, raw_acc[:, 0], w0, period, measure_cycles)
               if steady and np.isfinite(raw_acc[in_win]).all()
               and np.isfinite(d_raw[in_win]).all() else None)
    if aligned is not None and _in_phase(aligned, fs, steady_rtol):
        # the window's cycles averaged in phase: the noise down by sqrt(measure_cycles)
        for j in range(acc.shape[1]):
            avg = _cycles_in_phase(t, raw_acc[:, j], w0, period, measure_cycles).mean(axis=0) - zero[j]
            alphas[j] = max(_periodic_peak(avg, fs, 1.0), -_periodic_peak(avg, fs, -1.0))
        avg = _cycles_in_phase(t, d_raw, w0, period, measure_cycles).mean(axis=0)
        dmax_avg, dmin_avg = _periodic_peak(avg, fs, 1.0), _periodic_peak(avg, fs, -1.0)
        excursion = dmax_avg - dmin_avg
    else:
        aligned = None
        dmax_avg, dmin_avg = float(dmax.max()), float(dmin.min())
    row = {name: float(alphas[j]) / amp for j, name in enumerate(names)}
    # the scatter of the window's cycles: what noise (and an unsteady response) leaves uncertain
    row["alpha_se"] = _standard_error(peaks[:, 0]) / amp
    row.update({"excursion_m": excursion, "displacement_max_m": dmax_avg, "displacement_min_m": dmin_avg,
                "eta": excursion / gap if gap else math.nan,
                "e": excursion / (amp / omega_min_rad_s ** 2), "steady": steady,
                "averaged": aligned is not None})
    contacts: dict[str, Any] = {}
    found, unconfirmed = None, 0
    if gap is not None:
        # (the flight beside the window's contacts)
        win = (t >= w0 - FLIGHT_FIT_S) & (t < s1 + FLIGHT_FIT_S)
        found, unconfirmed = window_contacts(t[win], d_raw[win], d[win],
                                             acc[win, 0] - zero[0],
                                             raw_acc[win, 0] - zero[0], table[win], mass_kg, 0.5 * gap,
                                             fs, (w0, s1), contact_timing)
        contacts["contact"] = len(found) > 0
        contacts["contacts_per_cycle"] = len(found) / measure_cycles
        contacts.update(contact_means(found))
    return row, contacts, found, unconfirmed


def contact_means(found: Any) -> dict[str, float]:
    """The contacts' means (speeds for the velocities: the sides' signs differ) and the standard
    errors of :data:`UNCERTAIN` (NaN without contacts)."""
    out = {}
    for q in IMPACT_COLUMNS[3:]:
        x = found[q].abs() if q in ("v_in_m_s", "v_out_m_s") else found[q]
        out[q] = float(x.mean()) if len(found) else math.nan
    for q in UNCERTAIN:
        out[f"{q}_se"] = _standard_error(found[q].to_numpy(dtype=float)) if len(found) else math.nan
    return out
