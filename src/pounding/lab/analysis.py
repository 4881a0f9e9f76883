"""From a stepped-sine recording to the paper's measurements (issue 17): ``analyse_stepped_sine``.

The method, step by step (each a SciPy tool, not a hand-written one):

1. **Cycles.** The table's acceleration, low-passed without phase (``sosfiltfilt``, a Butterworth
   at :data:`TABLE_LOWPASS_FACTOR` times the highest step frequency), crosses zero upwards once a
   cycle; a crossing counts only after the signal went below minus a third of its amplitude (a
   Schmitt trigger: noise near zero makes no extra cycles), its instant interpolated linearly.
2. **Steps.** Consecutive cycles of the same frequency (within :data:`STEP_RTOL`, or nearest the
   same frequency of a given schedule) form a step.  The step's table amplitude ``A_t`` and
   frequency come from a least-squares sine fit to its table acceleration.
3. **Window.** The last ``measure_cycles`` whole cycles of each step; ``steady`` when their
   excursions agree within ``steady_rtol`` (the sweep's periodicity criterion on the measured
   cycle peaks, with a noise floor).
4. **Peaks.** The signals smoothed by a cubic Savitzky-Golay filter :data:`SMOOTH_S` wide
   (``savgol_filter``: the noise down, a 10 ms contact pulse kept); each cycle's largest
   ``|a|`` (per accelerometer and of their mean) and its displacement extremes, between the
   samples by the parabola through the three around each.  An accelerometer's offset is
   removed first: its mean over the window's whole cycles (a periodic motion's acceleration
   averages to zero over a cycle).
5. **Synchronous average.** The largest of noisy peaks is biased high (by about half the noise at
   1 % noise: the round trip through ``identify`` felt it).  A steady window is periodic, so its
   cycles are averaged sample by sample in phase (each signal a cubic spline, read at
   ``t + k T`` for the window's ``k``-th cycle, ``T`` from the table's fitted frequency): the
   noise falls by the square root of the window's cycles, the response does not.  alpha is the
   largest ``|a|`` of the averaged cycle over ``A_t``, ``E`` its ``D_max - D_min``.  A window that
   is not steady is not averaged: alpha is the largest of its cycles' peaks and ``E`` its
   largest ``D_max`` less its smallest ``D_min`` (what the sweep measures on the simulator's
   exact histories, and what the averaged cycle gives for a steady one).
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pandas as pd

from .._checks import float_array, integer, non_negative, positive
from .._errors import InputError, PoundingWarning, Problem
from ..data import PAPER_F_REF_HZ, PAPER_OMEGA_MIN_RAD_S
from ._sanity import fundamental, warn_inconsistent, warn_time_scale
from .contacts import FLIGHT_FIT_S, IMPACT_COLUMNS, window_contacts
from .lab_sweep import LabSweep
from .record import LabRecord

TABLE_LOWPASS_FACTOR = 5.0  # the table signal's low-pass corner, times the highest step frequency
SCHMITT = 1.0 / 3.0  # a zero crossing counts after the signal went below -SCHMITT x its amplitude
STEP_RTOL = 0.03  # cycles within 3 % in frequency belong to one step
SMOOTH_S = 0.010  # the Savitzky-Golay window: 10 ms (a 1 kHz record: 11 samples)
UNCERTAIN = ("contact_time_s", "restitution", "mean_force_n")  # contact means given with a standard error
MIN_CONTACT_SAMPLES = 15  # fewer samples a contact than this: a warning to sample faster (at 10, 500 Hz
GOOD_CONTACT_SAMPLES = 20  # for 20 ms contacts, the mean force was 7 % off; at 20, 2 %): the rate advised
STEADY_NOISE_FLOOR = 3.0  # steadiness tolerates this many noise standard deviations
PERIODIC_NOISE = 5.0  # aligned cycles repeat within this many noise standard deviations (see _in_phase)


def table_cycles(time_s: np.ndarray, table: np.ndarray, f_max_hz: float) -> np.ndarray:
    """Instants (s) where the table's acceleration crosses zero upwards, one per cycle."""
    from scipy import signal

    fs = 1.0 / float(np.median(np.diff(time_s)))
    corner = min(TABLE_LOWPASS_FACTOR * f_max_hz, 0.45 * fs)
    ok = np.isfinite(table)  # (missing samples bridged linearly: a crossing in a short run is kept)
    filled = np.interp(time_s, time_s[ok], table[ok]) if ok.any() and not ok.all() else np.nan_to_num(table)
    x = signal.sosfiltfilt(signal.butter(4, corner, fs=fs, output="sos"), filled)
    level = SCHMITT * float(np.percentile(np.abs(x), 99))
    out = []
    armed = False
    for i in range(1, x.size):  # (a Schmitt trigger: a loop over samples, bounded by the record)
        if x[i] < -level:
            armed = True
        elif armed and x[i - 1] < 0.0 <= x[i]:
            out.append(time_s[i - 1] + (time_s[i] - time_s[i - 1]) * (-x[i - 1]) / (x[i] - x[i - 1]))
            armed = False
    return np.asarray(out)


def _steps(crossings: np.ndarray, freqs_hz: np.ndarray | None) -> list[tuple[int, int]]:
    """Runs of cycles ``[i0, i1)`` (indices into the cycles between crossings) of one frequency."""
    f = 1.0 / np.diff(crossings)
    if freqs_hz is not None:
        label = np.abs(f[:, None] / freqs_hz[None, :] - 1.0).argmin(axis=1)
        near = np.abs(f / freqs_hz[label] - 1.0) <= 0.1
        label = np.where(near, label, -1)
    else:
        label = np.empty(f.size, dtype=int)
        current, start = 0, 0
        for i in range(f.size):
            if i > start and abs(f[i] / np.median(f[start:i]) - 1.0) > STEP_RTOL:
                current, start = current + 1, i
            label[i] = current
    runs = []
    i = 0
    while i < f.size:
        j = i
        while j < f.size and label[j] == label[i]:
            j += 1
        if label[i] >= 0:
            runs.append((i, j))
        i = j
    return runs


def _sine_fit(t: np.ndarray, x: np.ndarray, f: float) -> tuple[float, float]:
    """Least-squares ``x ~ a sin + b cos + c`` at ``f``, refined in frequency: (amplitude, frequency)."""
    from scipy.optimize import least_squares

    ok = np.isfinite(x)
    t, x = t[ok] - t[ok][0], x[ok]

    def resid(p):
        w = 2.0 * math.pi * p[3]
        return p[0] * np.sin(w * t) + p[1] * np.cos(w * t) + p[2] - x

    w = 2.0 * math.pi * f
    design = np.column_stack([np.sin(w * t), np.cos(w * t), np.ones_like(t)])
    a, b, c = np.linalg.lstsq(design, x, rcond=None)[0]
    fit = least_squares(resid, [a, b, c, f], x_scale=[abs(a) + abs(b) + 1e-12] * 3 + [f])
    return float(math.hypot(fit.x[0], fit.x[1])), float(fit.x[3])


def _smooth(x: np.ndarray, fs: float) -> np.ndarray:
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
    """The largest ``sign * x`` of one period of samples, smoothed as :func:`_smooth` (wrapping round the
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


def analyse_stepped_sine(record: LabRecord, *, mass_kg: float, gap_total_m: float | None = None,
                         freqs_hz: Any = None, measure_cycles: int = 5, steady_rtol: float = 0.02,
                         f_ref_hz: float = PAPER_F_REF_HZ, omega_min_rad_s: float = PAPER_OMEGA_MIN_RAD_S,
                         g: float = 9.81) -> LabSweep:
    """Per step of a stepped-sine recording, the paper's Table 2 quantities (see the module's method).

    Parameters
    ----------
    record : LabRecord
        The recording (:func:`read_test`, or :func:`synthetic_test`).
    mass_kg : float
        The mass on the table, kg.
    gap_total_m : float, optional
        ``Delta = g_L + g_R``, m (YBs): gives ``eta``.
    freqs_hz : array_like, optional
        The schedule's frequencies (each cycle is given the nearest within 10 %); default: found
        from the table signal.
    measure_cycles : int
        Whole cycles at the end of each step that are measured.
    steady_rtol : float
        How far the window's cycle excursions may differ (relative) for ``steady``.
    f_ref_hz, omega_min_rad_s, g : float
        ``nu = f / f_ref``; ``e = E / D_tmax`` with ``D_tmax = A_t / omega_min^2``; m/s^2 per g.

    Returns
    -------
    LabSweep
        Its ``steps``: one row per step in the order run: ``freq_hz``, ``nu``, ``a_g`` (the fitted table
        amplitude, g), ``alpha`` (of the accelerometers' mean) and ``alpha_<channel>``,
        ``excursion_m``, ``displacement_max_m``, ``displacement_min_m``, ``eta``, ``e``,
        ``steady``, ``averaged`` (measured on the window's cycles averaged in phase: see the module's
        method), ``cycles_run``, ``window_start_s``, ``window_end_s``, ``missing_samples`` (in the
        window: NaN values and gaps in time; where there are any, the step's quantities are NaN:
        they cannot be measured there), and with ``gap_total_m`` the contacts' means: ``contact``,
        ``contacts_per_cycle``, ``contact_time_s``, ``v_in_m_s``, ``v_out_m_s`` (speeds: means of the
        absolute values; ``impacts`` has them signed), ``restitution``,
        ``impulse_n_s``, ``mean_force_n``, ``peak_force_n``, ``dissipated_energy_j``.  Uncertainties:
        ``alpha_se`` (the standard error of the window's cycle peaks, over ``A_t``) and
        ``contact_time_s_se``, ``restitution_se``, ``mean_force_n_se`` (of the contacts' values):
        the scatter noise and sampling leave from cycle to cycle; a bias they share (a gain
        error) is not in them.

    Examples
    --------
    A virtual YBs test (1 % noise, 1 kHz) of three steps at a_G = 0.05 g, measured as the lab would:

    >>> import pounding
    >>> rec = pounding.lab.synthetic_test(pounding.presets.paper_damped(), 0.05,
    ...                                   [1.0, 1.5, 2.0], cycles=10)
    >>> sweep = pounding.lab.analyse_stepped_sine(rec, mass_kg=500.0,
    ...                                           gap_total_m=0.03,
    ...                                           freqs_hz=[1.0, 1.5, 2.0])
    >>> # Hz, -, Hz
    >>> sweep.resonance_hz, round(sweep.alpha_max, 1), sweep.contact_range_hz
    (1.5, 8.3, (1.5, 1.5))
    >>> at = sweep.steps.iloc[1]  # the resonance step
    >>> f"{1e3 * at['contact_time_s']:.0f} ms, restitution {at['restitution']:.2f}"
    '50 ms, restitution 0.97'
    """
    if not isinstance(record, LabRecord):
        raise InputError(Problem.WRONG_TYPE, "record", record, got=type(record).__name__,
                         expected="pounding.lab.LabRecord (read_test or synthetic_test)")
    mass_kg = positive("mass_kg", mass_kg, "kg")
    gap = None if gap_total_m is None else positive("gap_total_m", gap_total_m, "m")
    sched = None if freqs_hz is None else float_array("freqs_hz", freqs_hz)
    if sched is not None and (sched <= 0.0).any():
        raise InputError(Problem.NOT_POSITIVE, "freqs_hz", freqs_hz, unit="Hz")
    # (one cycle cannot show steadiness)
    measure_cycles = integer("measure_cycles", measure_cycles, 2, 10_000)
    steady_rtol = non_negative("steady_rtol", steady_rtol, "(relative)")
    f_ref_hz = positive("f_ref_hz", f_ref_hz, "Hz")
    omega_min_rad_s = positive("omega_min_rad_s", omega_min_rad_s, "rad/s")
    g = positive("g", g, "m/s^2")
    t, table = record.time_s, record.table_acc_m_s2
    f_max = float(sched.max()) if sched is not None else 0.45 * record.sample_rate_hz / TABLE_LOWPASS_FACTOR
    crossings = table_cycles(t, table, f_max)
    if crossings.size < measure_cycles + 2:
        raise InputError(Problem.TOO_SHORT, "record", f"{crossings.size} table cycles", got=crossings.size,
                         expected=measure_cycles + 2)
    fs = record.sample_rate_hz
    raw_acc = np.column_stack([record.mass_acc_mean_m_s2, record.mass_acc_m_s2])
    acc = np.column_stack([_smooth(a, fs) for a in raw_acc.T])
    disp = _smooth(record.displacement_m, fs)
    names = ("alpha", *(f"alpha_{c}" for c in record.mass_channels))
    rows = []
    impacts = []
    crossings_without_force = 0
    short = []
    fundamentals = []  # per step: F(A), omega^2 F(D), F(a_j) (the channels' consistency)
    for i0, i1 in _steps(crossings, sched):
        n_cyc = i1 - i0
        if n_cyc < measure_cycles + 1:  # (the first cycle of a step is a transient)
            short.append((float(crossings[i0]), n_cyc))
            continue
        s0, s1 = crossings[i0], crossings[i1]
        in_step = (t >= s0) & (t < s1)
        amp, f = _sine_fit(t[in_step], table[in_step], 1.0 / float(np.median(np.diff(crossings[i0:i1 + 1]))))
        period = 1.0 / f  # (the table's own period, fitted: what a steady response repeats with)
        if sched is not None:
            f = float(sched[np.abs(sched / f - 1.0).argmin()])
        w0 = float(crossings[i1 - measure_cycles])
        in_win = (t >= w0) & (t < s1)
        # the accelerometers' offsets: over whole cycles of a periodic motion the acceleration
        # averages to zero, so the window's mean is the offset
        zero = _cycle_mean(t, raw_acc, w0, period, measure_cycles)
        peaks = np.empty((measure_cycles, acc.shape[1]))
        dmax = np.empty(measure_cycles)
        dmin = np.empty(measure_cycles)
        for k, c in enumerate(range(i1 - measure_cycles, i1)):
            w = np.flatnonzero((t >= crossings[c]) & (t < crossings[c + 1]))
            for j in range(acc.shape[1]):
                i = int(w[int(np.argmax(np.abs(acc[w, j] - zero[j])))])
                peaks[k, j] = abs(_peak(t, acc[:, j], i) - zero[j])
            dmax[k] = _peak(t, disp, int(w[int(np.argmax(disp[w]))]))
            dmin[k] = _peak(t, disp, int(w[int(np.argmin(disp[w]))]))
        exc = dmax - dmin
        excursion = float(dmax.max() - dmin.min())  # (over the window, as the sweep measures it)
        spread = float(exc.max() - exc.min()) / excursion if excursion > 0.0 else 0.0
        noise = float(np.nanstd(record.displacement_m[in_step] - disp[in_step]))  # (what smoothing removes)
        steady = bool(spread <= steady_rtol + STEADY_NOISE_FLOOR * noise / max(excursion, 1e-300))
        alphas = peaks.max(axis=0)
        fundamentals.append([fundamental(t[in_win], table[in_win], 1.0 / period),
                             (2.0 * math.pi / period) ** 2 * fundamental(t[in_win],
                                                                         record.displacement_m[in_win],
                                                                         1.0 / period),
                             *(fundamental(t[in_win], raw_acc[in_win, j], 1.0 / period)
                               for j in range(1, raw_acc.shape[1]))])
        aligned = (_cycles_in_phase(t, raw_acc[:, 0], w0, period, measure_cycles)
                   if steady and np.isfinite(raw_acc[in_win]).all()
                   and np.isfinite(record.displacement_m[in_win]).all() else None)
        if aligned is not None and _in_phase(aligned, fs, steady_rtol):
            # the window's cycles averaged in phase: the noise down by sqrt(measure_cycles)
            for j in range(acc.shape[1]):
                avg = _cycles_in_phase(t, raw_acc[:, j], w0, period, measure_cycles).mean(axis=0) - zero[j]
                alphas[j] = max(_periodic_peak(avg, fs, 1.0), -_periodic_peak(avg, fs, -1.0))
            avg = _cycles_in_phase(t, record.displacement_m, w0, period, measure_cycles).mean(axis=0)
            dmax_avg, dmin_avg = _periodic_peak(avg, fs, 1.0), _periodic_peak(avg, fs, -1.0)
            excursion = dmax_avg - dmin_avg
        else:
            aligned = None
            dmax_avg, dmin_avg = float(dmax.max()), float(dmin.min())
        row = {"freq_hz": f, "nu": f / f_ref_hz, "a_g": amp / g}
        row.update({name: float(alphas[j]) / amp for j, name in enumerate(names)})
        # the scatter of the window's cycles: what noise (and an unsteady response) leaves uncertain
        row["alpha_se"] = _standard_error(peaks[:, 0]) / amp
        row.update({"excursion_m": excursion, "displacement_max_m": dmax_avg, "displacement_min_m": dmin_avg,
                    "eta": excursion / gap if gap is not None else math.nan,
                    "e": excursion / (amp / omega_min_rad_s ** 2), "steady": steady,
                    "averaged": aligned is not None,
                    "cycles_run": n_cyc, "window_start_s": w0,
                    "window_end_s": float(s1)})
        if gap is not None:
            # (the flight beside the window's contacts)
            win = (t >= w0 - FLIGHT_FIT_S) & (t < s1 + FLIGHT_FIT_S)
            found, unconfirmed = window_contacts(t[win], record.displacement_m[win], disp[win],
                                                 acc[win, 0] - zero[0],
                                                 raw_acc[win, 0] - zero[0], table[win], mass_kg, 0.5 * gap,
                                                 fs, (w0, s1))
            row["contact"] = len(found) > 0
            row["contacts_per_cycle"] = len(found) / measure_cycles
            for q in IMPACT_COLUMNS[3:]:  # (the velocities as speeds: the sides' signs differ)
                x = found[q].abs() if q in ("v_in_m_s", "v_out_m_s") else found[q]
                row[q] = float(x.mean()) if len(found) else math.nan
            for q in UNCERTAIN:
                row[f"{q}_se"] = _standard_error(found[q].to_numpy(dtype=float)) if len(found) else math.nan
            impacts.append(found.assign(freq_hz=f))
            crossings_without_force += unconfirmed
        # a window with missing samples (NaN, or a gap in time) is not measured: say so
        missing = int(np.isnan(record.displacement_m[in_win]).sum()
                      + np.isnan(record.mass_acc_m_s2[in_win]).sum() + np.isnan(table[in_win]).sum())
        gaps = record.gaps
        missing += int(gaps.loc[(gaps["end_s"] > row["window_start_s"]) & (gaps["start_s"] < s1),
                                "missing_samples"].sum())
        row["missing_samples"] = missing
        if missing:
            for q in row:
                if q not in ("freq_hz", "nu", "a_g", "cycles_run", "window_start_s", "window_end_s",
                             "missing_samples", "steady", "averaged"):
                    row[q] = math.nan
        rows.append(row)
    for start, n_cyc in short:
        warnings.warn(f"{record.source}: the step at {start:.3g} s ran {n_cyc} cycle(s), fewer than "
                      f"measure_cycles + 1 = {measure_cycles + 1}: not measured (lower measure_cycles to "
                      "measure it)",
                      PoundingWarning, stacklevel=2)
    if not rows:
        longest = max((n for _, n in short), default=0)
        raise InputError(Problem.BAD_STATE, "measure_cycles", measure_cycles,
                         why=f"no step ran more than {measure_cycles} cycles (the longest ran {longest})",
                         fix=f"lower measure_cycles to {max(longest - 1, 2)} or less, or check freqs_hz")
    warn_time_scale(record.source, fs, np.array([r["freq_hz"] for r in rows]))
    fund = np.array(fundamentals, dtype=complex)
    warn_inconsistent(record.source, record.mass_channels, fund[:, 0], fund[:, 1], fund[:, 2:])
    if crossings_without_force:
        warnings.warn(f"{record.source}: the displacement crossed the gap (gap_total_m = {gap:g} m, half of "
                      f"it each side of the laser's zero) {crossings_without_force} time(s) in the measured "
                      "windows without a bumper force pulse in the accelerations: not counted as contacts. "
                      "Check that gap_total_m is the rig's and that the laser reads 0 at the centre between "
                      "the bumpers",
                      PoundingWarning, stacklevel=2)
    table = pd.concat(impacts, ignore_index=True) if impacts else pd.DataFrame(columns=["freq_hz",
                                                                                        *IMPACT_COLUMNS])
    if len(table):
        samples = float(table["contact_time_s"].median()) * fs
        if 0.0 < samples < MIN_CONTACT_SAMPLES:
            warnings.warn(f"{record.source}: contacts last about {samples:.1f} samples at {fs:g} Hz: their "
                          "times, velocities and forces are uncertain by a sample or more; record at "
                          f"{GOOD_CONTACT_SAMPLES / float(table['contact_time_s'].median()):.0f} Hz or more",
                          PoundingWarning, stacklevel=2)
    return LabSweep(pd.DataFrame(rows), record, mass_kg, gap, f_ref_hz, impacts=table)
