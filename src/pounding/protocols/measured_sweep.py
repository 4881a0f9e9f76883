"""A sweep's metrics as the lab would measure them: each window through a :class:`MeasurementChain`.

For each step, the motion from the exact state at the start of its measured window is simulated
again (``lead`` cycles, the window's cycles, ``lead`` more), sampled at the chain's internal rate,
passed through the chain and measured by :func:`pounding.metrics.measured.measure_window`: the lab
pipeline's own per-window method (``lab.analyse_stepped_sine``). The window measured is the one
``lead`` cycles after the exact window, so that the filters have settled on both sides; a steady
step repeats itself (the window is whole periods of it), so that is the exact window's motion
again, and a step that did not settle is measured ``lead`` cycles on.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd

from .._errors import InputError, Problem, Status
from ..engine import State, simulate
from ..engine.simulate import kernel_system
from ..excitation import GRAVITY_M_S2, Harmonic
from ..metrics.measured import measure_window, smooth
from ..metrics.measured_contacts import FLIGHT_FIT_S
from ..model import MeasurementChain, Oscillator

# what a measured window gives (the rest of a sweep's table stays exact)
MEASURED_COLUMNS = ("alpha", "excursion_m", "displacement_max_m", "displacement_min_m", "eta", "e", "contact",
                    "contacts_per_cycle", "restitution", "contact_time_s", "impulse_n_s", "mean_force_n",
                    "peak_force_n", "dissipated_energy_j")
MAX_SAMPLES_PER_STEP = 20_000_000  # internal samples of one re-simulated window: beyond, refused


def lead_cycles(chain: MeasurementChain, freq_hz: float) -> int:
    """Cycles simulated before (and after) a measured window: the filters' settling and the flight a
    contact's velocities are fitted on, at least one."""
    return 1 + math.ceil((chain.settle_s + FLIGHT_FIT_S) * freq_hz)


def check_window_samples(chain: MeasurementChain, freqs_hz: np.ndarray, window_cycles: int) -> None:
    """Refuse a chain whose re-simulated windows (at the lowest frequency, the longest window) would
    hold more than :data:`MAX_SAMPLES_PER_STEP` samples: before the sweep runs, not after."""
    f = float(np.min(freqs_hz))
    samples = (2 * lead_cycles(chain, f) + window_cycles) / f * chain.simulation_rate_hz
    if samples > MAX_SAMPLES_PER_STEP:
        raise InputError(Problem.TOO_MUCH_WORK, "measurement", chain.describe(),
                         estimate=f"{samples:.3g}", unit=f"samples in the window at {f:g} Hz",
                         budget=f"{MAX_SAMPLES_PER_STEP:.3g}",
                         fix="a lower sample_rate_hz or oversample, or fewer measure_cycles")


def measure_steps(oscillator: Oscillator, a_g: float, freqs_hz: np.ndarray, window_states: np.ndarray,
                  window_cycles: np.ndarray, steps_done: int, chain: MeasurementChain, *,
                  omega_min_rad_s: float, steady_rtol: float, rtol: float, max_events_per_cycle: int,
                  max_steps: int, stop: Any = None,
                  g: float = GRAVITY_M_S2) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Per step (those done and finished), the metrics of its window as measured through ``chain``.

    ``stop()`` is polled between windows: when it is true, ``KeyboardInterrupt`` is raised (the
    sweep's Ctrl-C). A window whose simulation fails, or the step that stopped the sweep (give
    ``steps_done`` without it), has NaN metrics.

    Returns
    -------
    steps : DataFrame
        One row per step of ``freqs_hz`` (NaN past ``steps_done``): :data:`MEASURED_COLUMNS` and
        ``window_start_s`` (of the window measured).
    impacts : DataFrame
        Every contact read in the windows (the lab's columns, with ``freq_hz``).
    """
    bumpers = oscillator.bumpers
    gap = None if bumpers is None else bumpers.total_gap
    # the lab reads symmetric gaps about the laser's zero: an off-centre mass is centred
    centre = 0.0 if bumpers is None else 0.5 * (bumpers.gap_right_m - bumpers.gap_left_m)
    rows, impacts = [], []
    layout = kernel_system(oscillator).layout  # (the window states')
    fs = chain.sample_rate_hz
    missing = {q: math.nan for q in MEASURED_COLUMNS} | {"window_start_s": math.nan}
    for i, f in enumerate(np.asarray(freqs_hz, dtype=float)):
        if stop is not None and stop():
            raise KeyboardInterrupt
        if i >= steps_done:
            rows.append(dict(missing))
            continue
        cycles = int(window_cycles[i])
        lead = lead_cycles(chain, f)
        total = 2 * lead + cycles
        period = 1.0 / f
        start = State._from_kernel(window_states[i], layout)
        t0 = float(start.time_s)
        exc = Harmonic(a_g, float(f), phase=-(2.0 * math.pi * f * t0), g=g)
        # (within the sweep's own limits: a window it could not run is not measured)
        run = simulate(oscillator, exc, total * period, start, sample_rate_hz=chain.simulation_rate_hz,
                       rtol=rtol, max_events=max_events_per_cycle * total, max_steps=max_steps)
        if run.status != Status.SUCCESS:
            rows.append(dict(missing))
            continue
        uniform = run.to_dataframe()["event"].to_numpy() == ""
        t = run.t[uniform]
        t_s, table, mass, disp = chain.measure(t, exc.acceleration(t), run.abs_acceleration[uniform],
                                               run.displacement[uniform] - centre, stride=chain.stride)
        raw_acc = np.column_stack([mass, mass])  # (the mean of the accelerometers, and the one)
        acc = np.column_stack([smooth(a, fs) for a in raw_acc.T])
        d = smooth(disp, fs)
        bounds = t0 + (lead + np.arange(cycles + 1)) * period
        in_win = (t_s >= bounds[0]) & (t_s < bounds[-1])
        noise = float(np.nanstd(disp[in_win] - d[in_win]))
        amp = table_amplitude(t_s[in_win], table[in_win], f)  # (A_t as the table's accelerometer reads it)
        shape, contacts, found, _ = measure_window(
            t_s, table, raw_acc, acc, disp, d, bounds, period, amp, fs, names=("alpha", "alpha_1"),
            mass_kg=oscillator.mass_kg, gap=gap, steady_rtol=steady_rtol, omega_min_rad_s=omega_min_rad_s,
            noise=noise, contact_timing=chain.contact_timing)
        row = {q: shape.get(q, contacts.get(q, math.nan)) for q in MEASURED_COLUMNS}
        row["displacement_max_m"] += centre
        row["displacement_min_m"] += centre
        if gap is None:
            row["contact"] = False
            row["contacts_per_cycle"] = 0.0
        row["window_start_s"] = float(bounds[0])
        rows.append(row)
        if found is not None and len(found):
            impacts.append(found.assign(freq_hz=float(f)))
    table = pd.concat(impacts, ignore_index=True) if impacts else pd.DataFrame()
    return pd.DataFrame(rows), table


def table_amplitude(t: np.ndarray, table: np.ndarray, freq_hz: float) -> float:
    """The amplitude of the table's acceleration at ``freq_hz`` (least squares: sine, cosine and an
    offset over whole cycles), as the lab fits it."""
    w = 2.0 * math.pi * freq_hz
    design = np.column_stack([np.sin(w * t), np.cos(w * t), np.ones_like(t)])
    a, b, _ = np.linalg.lstsq(design, table, rcond=None)[0]
    return float(math.hypot(a, b))
