"""A virtual shaking-table test: the simulator's exact motion through realistic sensors (issue 17).

:func:`synthetic_test` runs a stepped sine on a system (each frequency held for a number of
cycles, the state carried from step to step, as :func:`pounding.sweep` does with a fixed
schedule) and records it as a lab would: the engine's exact histories at ``oversample`` times
the sampling rate, an analogue anti-alias filter (a causal Butterworth low-pass, as a data
acquisition card applies it), sampling, accelerometer gain errors and offsets, noise and the
laser's resolution.  It is how the lab pipeline is tested, and how a test is planned (which
sampling rate resolves a 10 ms contact?).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._checks import float_array, instance_of, integer, non_negative, plausible, positive, real_tuple
from .._errors import InputError, Problem, renamed_keyword
from ..engine import State, simulate
from ..excitation import MAX_A_G, GRAVITY_M_S2, Harmonic
from ..model import Oscillator
from ..model.measurement import MeasurementChain, Sensor
from .record import LabRecord

ANTI_ALIAS_ORDER = 4  # poles of the Butterworth anti-alias filter
MAX_OUTPUT_SAMPLES = 50_000_000  # a recording longer than this is refused (memory grows with it)


@renamed_keyword("oscillator", "system")
def synthetic_test(system: Oscillator, a_g: float, freqs_hz: Any, *, cycles: int = 30,
                   sample_rate_hz: float | None = None, noise: float = 0.01,
                   anti_alias_hz: float | None = None, gains: Any = (1.0, 1.0), offsets_m_s2: Any = None,
                   laser_resolution_m: float | None = None,
                   oversample: int | None = None, seed: int = 0, state: State | None = None,
                   g: float = GRAVITY_M_S2, measurement: MeasurementChain | None = None) -> LabRecord:
    """Record a stepped-sine test of ``system`` through realistic sensors.

    Parameters
    ----------
    system : Oscillator
        The system on the table.
    a_g : float
        Table acceleration amplitude, g.
    freqs_hz : array_like, shape (n_steps,)
        The steps in the order they are run, Hz.
    cycles : int
        Cycles per step (each step lasts ``cycles / f`` rounded to the internal sampling).
    sample_rate_hz : float, optional
        The recording's sampling rate, Hz (1000; or the chain's).
    noise : float
        Gaussian noise on every channel, its standard deviation a fraction of the channel's
        largest absolute value over the last quarter of each step (0.01: 1 % of what the sensor
        reads once the step has settled).
    anti_alias_hz : float, optional
        Corner of an anti-alias low-pass (order 4 Butterworth, causal) on every channel; default
        none (ideal sampling).  Must be below half the internal rate.  (Shorthand for a chain.)
    gains : sequence of float
        One per accelerometer on the mass (their number): the factor each one's reading is off
        by (1.02: reads 2 % high).
    offsets_m_s2 : sequence of float, optional
        Each accelerometer's zero offset, m/s^2 (default 0).
    laser_resolution_m : float, optional
        The displacement's quantum, m (0: none).
    oversample : int, optional
        The engine's histories are taken at this many times ``sample_rate_hz`` before
        filtering and sampling (10; or the chain's).
    seed : int
        Of the noise.
    state : State, optional
        Where the test starts (default at rest).
    g : float
        m/s^2 per g.
    measurement : MeasurementChain, optional
        The instruments: filters, sampling and quanta per channel (instead of
        ``sample_rate_hz``, ``anti_alias_hz``, ``laser_resolution_m`` and ``oversample``).  The
        accelerometers' gains, offsets and the noise come after sampling, before a zero-phase
        filter (software filters the record as read).

    Returns
    -------
    LabRecord
        ``source`` "synthetic"; ``meta`` holds the schedule (``freqs_hz``, ``step_start_s``), ``a_g``,
        ``g`` and the sensor settings.

    Examples
    --------
    The damped printed system at a_G = 0.05 g, three steps of 10 cycles, recorded at 1 kHz through a
    200 Hz anti-alias filter, two accelerometers 2 % off and a laser of 0.01 mm resolution:

    >>> import pounding
    >>> rec = pounding.lab.synthetic_test(pounding.presets.paper_damped(), 0.05,
    ...                                   [1.0, 1.5, 2.0], cycles=10,
    ...                                   anti_alias_hz=200.0, gains=(1.02, 0.98),
    ...                                   laser_resolution_m=1e-5)
    >>> rec.n_samples, rec.mass_channels
    (21667, ('accelerometer_1', 'accelerometer_2'))
    >>> rec.meta["step_start_s"].round(3).tolist()  # s: when each step starts
    [0.0, 10.0, 16.667]
    """
    instance_of("system", system, Oscillator, "pounding.Oscillator")
    a_g = positive("a_g", a_g, "g")
    if a_g > MAX_A_G:
        raise InputError(Problem.TOO_LARGE, "a_g", a_g, maximum=MAX_A_G, what=" g",
                         fix="a_g is in g: 0.05 is 5 % of g")
    freqs = float_array("freqs_hz", freqs_hz)
    if (freqs <= 0.0).any():
        i = int(np.flatnonzero(freqs <= 0.0)[0])
        raise InputError(Problem.NOT_POSITIVE, f"freqs_hz[{i}]", freqs[i], unit="Hz")
    cycles = integer("cycles", cycles, 1, 100_000)
    chain = _chain(measurement, sample_rate_hz, anti_alias_hz, laser_resolution_m, oversample)
    fs, oversample, fs_int = chain.sample_rate_hz, chain.oversample, chain.internal_rate_hz
    noise = non_negative("noise", noise, "(a fraction of each channel's peak)")
    plausible("noise", noise, 0.0, 0.2, "noise is a fraction: 0.01 is 1 %")
    gains_t = real_tuple("gains", gains)
    if not gains_t:
        raise InputError(Problem.EMPTY, "gains", gains)
    for i, k in enumerate(gains_t):
        positive(f"gains[{i}]", k, "(a factor, 1 for an exact accelerometer)")
    offsets_t = (0.0,) * len(gains_t) if offsets_m_s2 is None else real_tuple("offsets_m_s2", offsets_m_s2)
    if len(offsets_t) != len(gains_t):
        raise InputError(Problem.LENGTH_MISMATCH, "offsets_m_s2", offsets_m_s2, got=len(offsets_t),
                         expected=len(gains_t), hint=" (one per accelerometer, as gains)")
    seed = integer("seed", seed, 0, 2**32 - 1)
    g = positive("g", g, "m/s^2")
    steps_int = [round(cycles / f * fs_int) for f in freqs]
    if sum(steps_int) / oversample > MAX_OUTPUT_SAMPLES:
        raise InputError(Problem.TOO_MUCH_WORK, "freqs_hz", f"{freqs.size} steps",
                         estimate=f"{sum(steps_int) / oversample:.3g}", unit="samples",
                         budget=f"{MAX_OUTPUT_SAMPLES:.3g}",
                         fix="fewer steps or cycles, or a lower sample_rate_hz")
    if state is None:
        state = State.at_rest(system)
    instance_of("state", state, State, "pounding.State")

    zi = None  # (the causal filters' states, carried from step to step: the test does not stop)
    rng = np.random.default_rng(seed)
    t0 = float(state.vector[0])
    parts: list[np.ndarray] = []
    starts = []
    m_next = 0  # internal samples so far (the record keeps every oversample-th)
    for k, (f, n_int) in enumerate(zip(freqs, steps_int)):
        t_start = t0 + m_next / fs_int
        starts.append(t_start)
        exc = Harmonic(a_g, float(f), phase=-(2.0 * math.pi * f * t_start), g=g)
        run = simulate(system, exc, n_int / fs_int, state, sample_rate_hz=fs_int)
        if not run.success:
            raise InputError(Problem.BAD_STATE, "system", system, why=f"the step at {f:g} Hz failed: "
                             f"{run.message}", fix="check the system; a shorter or milder test may run")
        uniform = run.to_dataframe()["event"].to_numpy() == ""
        t = run.t[uniform]
        last = k == freqs.size - 1
        keep = slice(0, t.size if last else t.size - 1)  # (the next step starts at this one's last sample)
        block = np.vstack([exc.peak_m_s2 * np.sin(2.0 * math.pi * f * t + exc.phase),
                           run.abs_acceleration[uniform], run.displacement[uniform]])[:, keep]
        t = t[keep]
        block, zi = chain.analogue(block, zi)
        take = (np.arange(m_next, m_next + t.size) % oversample) == 0
        table, mass, disp = block[:, take]
        parts.append(chain.quantize(np.vstack([
            _noisy(table, noise, rng),
            *(_noisy(gain * mass + o, noise, rng) for gain, o in zip(gains_t, offsets_t)),
            _noisy(disp, noise, rng)])))
        m_next += t.size
        state = run.final_state
    data = chain.digital(np.hstack(parts))
    time_s = t0 + np.arange(data.shape[1]) / fs  # the sampling clock
    table_rec, mass_rec, disp_rec = data[0], data[1:-1].T, data[-1]
    channels = tuple(f"accelerometer_{j + 1}" for j in range(len(gains_t)))
    meta = {"freqs_hz": freqs.copy(), "step_start_s": np.array(starts), "cycles": cycles, "a_g": a_g, "g": g,
            "sample_rate_hz": fs, "noise": noise, "anti_alias_hz": anti_alias_hz, "gains": gains_t,
            "offsets_m_s2": offsets_t, "laser_resolution_m": chain.laser.resolution, "seed": seed,
            "measurement": chain}
    return LabRecord(time_s, table_rec, mass_rec, disp_rec, channels, source="synthetic", meta=meta)


def _chain(measurement: Any, sample_rate_hz: Any, anti_alias_hz: Any, laser_resolution_m: Any,
           oversample: Any) -> MeasurementChain:
    """The test's chain: ``measurement``, or the one its shorthands state (not both)."""
    shorthands = {"sample_rate_hz": sample_rate_hz, "anti_alias_hz": anti_alias_hz,
                  "laser_resolution_m": laser_resolution_m, "oversample": oversample}
    if measurement is not None:
        instance_of("measurement", measurement, MeasurementChain, "pounding.MeasurementChain or None")
        given = [k for k, v in shorthands.items() if v is not None]
        if given:
            raise InputError(Problem.DUPLICATE, given[0], shorthands[given[0]],
                             repeated="measurement (give the sampling, filters and quanta in the chain)")
        return measurement
    fs = positive("sample_rate_hz", 1000.0 if sample_rate_hz is None else sample_rate_hz, "Hz")
    over = integer("oversample", 10 if oversample is None else oversample, 1, 1000)
    resolution = non_negative("laser_resolution_m", laser_resolution_m or 0.0, "m")
    sensor = Sensor()
    if anti_alias_hz is not None:
        anti_alias_hz = positive("anti_alias_hz", anti_alias_hz, "Hz")
        if anti_alias_hz >= 0.5 * fs * over:
            raise InputError(Problem.OUT_OF_RANGE, "anti_alias_hz", anti_alias_hz,
                             range=f"(0, {0.5 * fs * over:g}) Hz, below half the internal rate",
                             hint=" (raise oversample, or lower the corner)")
        sensor = Sensor(anti_alias_hz, ANTI_ALIAS_ORDER, zero_phase=False)
    return MeasurementChain(fs, sensor, sensor, Sensor(sensor.lowpass_hz, sensor.order, False, resolution),
                            over)


def _noisy(x: np.ndarray, noise: float, rng: np.random.Generator) -> np.ndarray:
    """``x`` plus Gaussian noise of ``noise`` times its largest absolute value over its last quarter."""
    scale = noise * float(np.max(np.abs(x[3 * x.size // 4:]))) if x.size else 0.0
    return x + rng.normal(0.0, scale, x.size) if scale > 0.0 else x.copy()
