"""From a stepped-sine recording to the paper's measurements (issue 17): ``analyse_stepped_sine``.

(Steps 3-5 and the contacts, per window, are :func:`pounding.metrics.measured.measure_window`, shared
with the metrics "as measured" of :func:`pounding.sweep`.)

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
4. **Peaks.** The signals smoothed by a cubic Savitzky-Golay filter 10 ms wide
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

from .._checks import float_array, instance_of, integer, non_negative, positive
from .._errors import InputError, PoundingWarning, Problem
from ..data import PAPER_F_REF_HZ, PAPER_OMEGA_MIN_RAD_S
from ._sanity import fundamental, warn_inconsistent, warn_time_scale
from ..metrics.measured import measure_window, smooth
from ..metrics.measured_contacts import IMPACT_COLUMNS
from .lab_sweep import LabSweep
from .record import LabRecord
from .._units import GRAVITY_M_S2

TABLE_LOWPASS_FACTOR = 5.0  # the table signal's low-pass corner, times the highest step frequency
SCHMITT = 1.0 / 3.0  # a zero crossing counts after the signal went below -SCHMITT x its amplitude
STEP_RTOL = 0.03  # cycles within 3 % in frequency belong to one step
MIN_CONTACT_SAMPLES = 15  # fewer samples a contact than this: a warning to sample faster (at 10, 500 Hz
GOOD_CONTACT_SAMPLES = 20  # for 20 ms contacts, the mean force was 7 % off; at 20, 2 %): the rate advised


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


def analyse_stepped_sine(record: LabRecord, *, mass_kg: float, gap_total_m: float | None = None,
                         freqs_hz: Any = None, measure_cycles: int = 5, steady_rtol: float = 0.02,
                         f_ref_hz: float = PAPER_F_REF_HZ, omega_min_rad_s: float = PAPER_OMEGA_MIN_RAD_S,
                         g: float = GRAVITY_M_S2) -> LabSweep:
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
    instance_of("record", record, LabRecord, "pounding.lab.LabRecord (read_test or synthetic_test)")
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
    acc = np.column_stack([smooth(a, fs) for a in raw_acc.T])
    disp = smooth(record.displacement_m, fs)
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
        noise = float(np.nanstd(record.displacement_m[in_step] - disp[in_step]))  # (what smoothing removes)
        shape, contacts, found, unconfirmed = measure_window(
            t, table, raw_acc, acc, record.displacement_m, disp, crossings[i1 - measure_cycles:i1 + 1],
            period, amp, fs, names=names, mass_kg=mass_kg, gap=gap, steady_rtol=steady_rtol,
            omega_min_rad_s=omega_min_rad_s, noise=noise)
        fundamentals.append([fundamental(t[in_win], table[in_win], 1.0 / period),
                             (2.0 * math.pi / period) ** 2 * fundamental(t[in_win],
                                                                         record.displacement_m[in_win],
                                                                         1.0 / period),
                             *(fundamental(t[in_win], raw_acc[in_win, j], 1.0 / period)
                               for j in range(1, raw_acc.shape[1]))])
        row = {"freq_hz": f, "nu": f / f_ref_hz, "a_g": amp / g, **shape, "cycles_run": n_cyc,
               "window_start_s": w0, "window_end_s": float(s1), **contacts}
        if found is not None:
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
