"""What the lab's instruments do to the motion before anything is measured: the measurement chain.

A shaking-table test does not read the exact motion. Each channel (the table's accelerometer, the
mass's accelerometers, the laser on the displacement) passes an analogue low-pass before it is
sampled (causal, as a data acquisition card's anti-alias filter), is sampled and quantized, and
may be low-passed again in software after the test (often without phase: ``filtfilt``).
:class:`MeasurementChain` states all of it, per channel, as plain data; the simulator's exact
histories go through it in :meth:`MeasurementChain.measure` (and :meth:`MeasurementChain.apply`
for a :class:`pounding.Run`), and so do :func:`pounding.lab.synthetic_test`'s virtual tests and
the metrics "as measured" of :func:`pounding.sweep` (``measurement=``): one implementation.

The default chain is ideal sampling at 1 kHz: no filter, no quantum.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .._checks import boolean, instance_of, integer, non_negative, one_of, positive
from .._errors import InputError, Problem

CHANNELS = ("table", "mass", "laser")
# how a measured window's contacts are timed: by the flanks of the bumper's force pulse in the
# accelerations, or by the laser's gap crossings (see pounding.metrics.measured_contacts)
CONTACT_TIMINGS = ("pulse", "laser")
MAX_ORDER = 10  # Butterworth poles at most (beyond, second-order sections lose their accuracy)


@dataclass(frozen=True)
class Sensor:
    """One channel of a :class:`MeasurementChain`.

    Parameters
    ----------
    lowpass_hz : float or None
        The low-pass's corner, Hz (a Butterworth; None: no filter).
    order : int
        Its poles (1-10; 4 by default).
    zero_phase : bool
        False: causal, applied before sampling (an analogue anti-alias filter). True: applied
        after sampling, forwards and backwards (``scipy.signal.sosfiltfilt``: no phase lag, the
        magnitude squared), as software filters a record after the test.
    resolution : float
        The quantum of the sampled values, in the channel's unit (m/s^2 or m; 0: none).

    Examples
    --------
    >>> from pounding import Sensor
    >>> sensor = Sensor(lowpass_hz=15.0, zero_phase=True)
    >>> round(sensor.gain(15.0), 6)  # -6 dB at the corner: twice -3 dB
    0.5
    """

    lowpass_hz: float | None = None
    order: int = 4
    zero_phase: bool = False
    resolution: float = 0.0

    def __post_init__(self) -> None:
        if self.lowpass_hz is not None:
            object.__setattr__(self, "lowpass_hz", positive("lowpass_hz", self.lowpass_hz, "Hz"))
        object.__setattr__(self, "order", integer("order", self.order, 1, MAX_ORDER))
        object.__setattr__(self, "zero_phase", boolean("zero_phase", self.zero_phase))
        object.__setattr__(self, "resolution", non_negative("resolution", self.resolution, "(the quantum)"))

    def gain(self, freq_hz: Any, rate_hz: float | None = None) -> Any:
        """The filter's magnitude at ``freq_hz`` (1 without a filter): ``1 / sqrt(1 + r^(2n))``
        causal, its square zero-phase (the filter runs twice), with ``r = f / f_c`` (the analogue
        Butterworth) or, run digitally at ``rate_hz``, ``r = tan(pi f / rate) / tan(pi f_c / rate)``
        (the bilinear transform's, exact for the filter the chain runs). Float or array as given."""
        f = np.asarray(freq_hz, dtype=float)
        if self.lowpass_hz is None:
            out = np.ones_like(f)
        else:
            if rate_hz is None:
                ratio = f / self.lowpass_hz
            else:
                ratio = np.tan(np.pi * f / rate_hz) / math.tan(math.pi * self.lowpass_hz / rate_hz)
            once = 1.0 / np.sqrt(1.0 + ratio ** (2 * self.order))
            out = once**2 if self.zero_phase else once
        return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class MeasurementChain:
    """The lab's instruments, channel by channel: what a test records of the exact motion.

    Parameters
    ----------
    sample_rate_hz : float
        The recording's sampling rate, Hz (1000).
    table, mass, laser : Sensor
        The table's accelerometer, the mass's accelerometers (all alike) and the laser on the
        displacement (default: no filter, no quantum).
    oversample : int
        The exact histories are taken at this many times ``sample_rate_hz`` for the causal
        (analogue) filters before sampling (10).
    contact_timing : str
        How a measured window's contacts are timed (and their velocities read): ``"pulse"`` (the
        default), by the flanks of the bumper's force pulse in the accelerations, the velocities from
        the displacement's free flight fitted with the measured acceleration; ``"laser"``, where the
        laser's displacement crosses the gap, the velocities from the laser alone
        (:mod:`pounding.metrics.measured_contacts`). What the instruments record does not depend on
        it.

    Examples
    --------
    The hypothesis of a 15 Hz zero-phase low-pass on the accelerations (the laser as read):

    >>> import pounding
    >>> chain = pounding.MeasurementChain.lowpass(15.0)
    >>> chain.mass.lowpass_hz, chain.laser.lowpass_hz
    (15.0, None)
    >>> run = pounding.simulate(pounding.presets.paper_damped(),
    ...                         pounding.Harmonic(0.05, 1.5), 4.0)
    >>> rec = chain.apply(run)
    >>> list(rec.columns)
    ['time_s', 'table_acc_m_s2', 'mass_acc_m_s2', 'displacement_m']
    >>> len(rec)  # 4 s at 1 kHz
    4001
    """

    sample_rate_hz: float = 1000.0
    table: Sensor = field(default_factory=Sensor)
    mass: Sensor = field(default_factory=Sensor)
    laser: Sensor = field(default_factory=Sensor)
    oversample: int = 10
    contact_timing: str = "pulse"

    def __post_init__(self) -> None:
        fs = positive("sample_rate_hz", self.sample_rate_hz, "Hz")
        object.__setattr__(self, "sample_rate_hz", fs)
        object.__setattr__(self, "oversample", integer("oversample", self.oversample, 1, 1000))
        timing = one_of("contact_timing", self.contact_timing, CONTACT_TIMINGS)
        object.__setattr__(self, "contact_timing", timing)
        for name in CHANNELS:
            sensor = getattr(self, name)
            instance_of(name, sensor, Sensor, "pounding.Sensor")
            if sensor.lowpass_hz is not None:
                nyquist = 0.5 * fs * (1 if sensor.zero_phase else self.oversample)
                if sensor.lowpass_hz >= nyquist:
                    raise InputError(
                        Problem.OUT_OF_RANGE,
                        f"{name}.lowpass_hz",
                        sensor.lowpass_hz,
                        range=f"(0, {nyquist:g}) Hz, below half the rate it runs at",
                        hint=" (a zero-phase filter runs on the samples: raise sample_rate_hz, or lower "
                        "the corner)",
                    )

    @classmethod
    def lowpass(
        cls,
        cutoff_hz: float,
        *,
        order: int = 4,
        zero_phase: bool = True,
        sample_rate_hz: float = 1000.0,
        laser: bool = False,
        contact_timing: str = "pulse",
    ) -> "MeasurementChain":
        """The accelerometers (table and mass) through one Butterworth low-pass, the laser as read
        (or through it too, ``laser=True``): the chain the paper's accelerations are tested against.

        Parameters
        ----------
        cutoff_hz : float
            The corner, Hz.
        order : int
            Poles (4).
        zero_phase : bool
            Forwards and backwards after sampling (True), or causal before it.
        sample_rate_hz : float
            The recording's rate, Hz (1000).
        laser : bool
            Filter the displacement too.
        contact_timing : str
            ``"pulse"`` (contacts timed by the force pulses in the filtered accelerations) or
            ``"laser"`` (by the laser's gap crossings): see :class:`MeasurementChain`.

        Returns
        -------
        MeasurementChain

        Examples
        --------
        >>> import pounding
        >>> chain = pounding.MeasurementChain.lowpass(20.0, zero_phase=False)
        >>> round(chain.mass.gain(20.0), 4)  # -3 dB at the corner, causal
        0.7071
        >>> laser = pounding.MeasurementChain.lowpass(15.0, contact_timing="laser")
        >>> laser.describe().endswith("contacts timed by the laser's gap crossings")
        True
        """
        sensor = Sensor(cutoff_hz, order, zero_phase)
        return cls(sample_rate_hz, sensor, sensor, sensor if boolean("laser", laser) else Sensor(),
                   contact_timing=contact_timing)

    def gain(self, freq_hz: Any, channel: str = "mass") -> Any:
        """A channel's magnitude at ``freq_hz`` as the chain runs its filter (causal at the internal
        rate, zero-phase at the recording's): :meth:`Sensor.gain`. Float or array as given."""
        name = one_of("channel", channel, CHANNELS)
        sensor = getattr(self, name)
        return sensor.gain(freq_hz, self.sample_rate_hz if sensor.zero_phase else self.internal_rate_hz)

    @property
    def internal_rate_hz(self) -> float:
        """The rate the exact histories are taken at, Hz (``oversample`` x ``sample_rate_hz``)."""
        return self.sample_rate_hz * self.oversample

    @property
    def stride(self) -> int:
        """Every how many samples of :attr:`simulation_rate_hz` the recording keeps: ``oversample``
        with a causal filter (it runs between the samples), else 1."""
        causal = any(s.lowpass_hz is not None and not s.zero_phase for s in self.sensors)
        return self.oversample if causal else 1

    @property
    def simulation_rate_hz(self) -> float:
        """The rate exact histories need for this chain, Hz: :attr:`internal_rate_hz` with a causal
        filter, else ``sample_rate_hz`` (the same samples, ten times fewer to compute)."""
        return self.sample_rate_hz * self.stride

    @property
    def settle_s(self) -> float:
        """How long the slowest filter takes to forget where it started, s (0 without one):
        ``5 n / (2 pi f_c)`` for ``n`` poles at ``f_c`` (ten time constants of the corner per pole
        pair)."""
        corners = [(s.lowpass_hz, s.order) for s in self.sensors if s.lowpass_hz is not None]
        return max((5.0 * order / (2.0 * math.pi * fc) for fc, order in corners), default=0.0)

    @property
    def sensors(self) -> tuple[Sensor, Sensor, Sensor]:
        """``(table, mass, laser)``."""
        return (self.table, self.mass, self.laser)

    def with_cutoff(self, cutoff_hz: float | None) -> "MeasurementChain":
        """The same chain with the accelerometers' (table and mass) low-pass corner at ``cutoff_hz``
        (None: none); their order and phase kept."""
        table, mass = (replace(s, lowpass_hz=cutoff_hz) for s in (self.table, self.mass))
        return replace(self, table=table, mass=mass)

    def describe(self) -> str:
        """The chain in words (one line; contacts timed by their force pulses unless it says they are
        timed by the laser's gap crossings)."""
        parts = [f"sampled at {self.sample_rate_hz:g} Hz"]
        for name, sensor in zip(CHANNELS, self.sensors):
            if sensor.lowpass_hz is not None:
                kind = "zero-phase" if sensor.zero_phase else "causal"
                corner = f"{sensor.order} poles at {sensor.lowpass_hz:g} Hz"
                parts.append(f"{name}: {kind} Butterworth low-pass, {corner}")
            if sensor.resolution > 0.0:
                parts.append(f"{name}: quantum {sensor.resolution:g}")
        text = "; ".join(parts) if len(parts) > 1 else parts[0] + ", no filter (ideal sampling)"
        laser = self.contact_timing == "laser"
        return text + ("; contacts timed by the laser's gap crossings" if laser else "")

    # ---- the pipeline, in the order the lab's instruments apply it
    def analogue_sos(self) -> list[np.ndarray | None]:
        """Per channel, the causal filter's second-order sections at the internal rate (None: none)."""
        from scipy import signal

        return [
            None
            if s.lowpass_hz is None or s.zero_phase
            else signal.butter(s.order, s.lowpass_hz, fs=self.internal_rate_hz, output="sos")
            for s in self.sensors
        ]

    def analogue(self, block: np.ndarray, zi: list | None = None) -> tuple[np.ndarray, list]:
        """The causal filters over ``block`` (shape (3, n): table, mass, displacement at the internal
        rate), continuing from ``zi`` (None: at rest, each at the block's first value); returns the
        filtered block and the filters' states to continue with."""
        from scipy import signal

        out = np.array(block, dtype=float, copy=True)
        sos_all = self.analogue_sos()
        zi = [None] * 3 if zi is None else list(zi)
        for j, sos in enumerate(sos_all):
            if sos is None or out.shape[1] == 0:
                continue
            if zi[j] is None:
                zi[j] = signal.sosfilt_zi(sos) * out[j, 0]
            out[j], zi[j] = signal.sosfilt(sos, out[j], zi=zi[j])
        return out, zi

    def quantize(self, sampled: np.ndarray) -> np.ndarray:
        """Each channel (rows: table, mass..., displacement) rounded to its quantum."""
        out = np.array(sampled, dtype=float, copy=True)
        rows = (0, *range(1, out.shape[0] - 1), out.shape[0] - 1)
        for j in rows:
            sensor = self.table if j == 0 else self.laser if j == out.shape[0] - 1 else self.mass
            if sensor.resolution > 0.0:
                out[j] = np.round(out[j] / sensor.resolution) * sensor.resolution
        return out

    def digital(self, sampled: np.ndarray) -> np.ndarray:
        """The zero-phase filters over the sampled channels (rows: table, mass..., displacement)."""
        from scipy import signal

        out = np.array(sampled, dtype=float, copy=True)
        for j in range(out.shape[0]):
            sensor = self.table if j == 0 else self.laser if j == out.shape[0] - 1 else self.mass
            if sensor.lowpass_hz is None or not sensor.zero_phase:
                continue
            sos = signal.butter(sensor.order, sensor.lowpass_hz, fs=self.sample_rate_hz, output="sos")
            least = 3 * (2 * sos.shape[0] + 1) + 1  # (sosfiltfilt's padding needs more samples than this)
            if out.shape[1] < least:
                raise InputError(Problem.TOO_SHORT, "samples", f"{out.shape[1]} samples", got=out.shape[1],
                                 expected=least)
            out[j] = signal.sosfiltfilt(sos, out[j])
        return out

    def measure(self, time_s: Any, table: Any, mass: Any, displacement: Any, *,
                stride: int | None = None) -> tuple[np.ndarray, ...]:
        """The chain over exact histories on the internal grid: causal filters, sampling (every
        ``stride``-th sample from the first), quanta, zero-phase filters.

        Parameters
        ----------
        time_s : array_like, shape (n,)
            Uniform at ``sample_rate_hz`` times ``stride``, s.
        table, mass : array_like, shape (n,)
            The table's and the mass's absolute accelerations, m/s^2.
        displacement : array_like, shape (n,)
            The mass's displacement relative to the table, m.
        stride : int, optional
            ``oversample`` (default) or :attr:`stride` (histories at :attr:`simulation_rate_hz`).

        Returns
        -------
        tuple of ndarray, each shape (m,)
            ``(time_s, table, mass, displacement)`` as recorded, ``m = ceil(n / stride)``.
        """
        stride = self.oversample if stride is None else stride
        if stride not in (self.oversample, self.stride):
            raise InputError(Problem.NOT_ONE_OF, "stride", stride,
                             choices=f"{self.oversample}, {self.stride}")
        arrays = [np.asarray(x, dtype=float) for x in (time_s, table, mass, displacement)]
        for name, x in zip(("table", "mass", "displacement"), arrays[1:]):
            if x.shape != arrays[0].shape or x.ndim != 1:
                raise InputError(Problem.LENGTH_MISMATCH, name, f"shape {x.shape}", got=x.shape,
                                 expected=arrays[0].shape, hint=" (one value per sample of time_s)")
        block = np.vstack(arrays[1:])
        filtered, _ = self.analogue(block)  # (none at a stride of 1 unless oversample is 1: refused above)
        sampled = self.digital(self.quantize(filtered[:, ::stride]))
        return (np.asarray(time_s, dtype=float)[::stride], *sampled)

    def apply(self, run: Any) -> Any:
        """A :class:`pounding.Run` as the lab would record it.

        Parameters
        ----------
        run : Run
            From :func:`pounding.simulate`, with uniform samples at :attr:`internal_rate_hz`
            (``sample_rate_hz=chain.internal_rate_hz``: the chain resamples otherwise, linearly
            between the run's samples, and warns nothing; give the rate for an exact chain).

        Returns
        -------
        pandas.DataFrame
            ``time_s``, ``table_acc_m_s2``, ``mass_acc_m_s2``, ``displacement_m`` at
            ``sample_rate_hz``.
        """
        import pandas as pd

        for name in ("t", "abs_acceleration", "displacement", "excitation"):
            if not hasattr(run, name):
                raise InputError(
                    Problem.WRONG_TYPE, "run", run, got=type(run).__name__, expected="pounding.Run (simulate)"
                )
        t_run = np.asarray(run.t, dtype=float)
        if t_run.size < 2:
            raise InputError(Problem.TOO_SHORT, "run", f"{t_run.size} samples", got=t_run.size, expected=2)
        n = int(math.floor((t_run[-1] - t_run[0]) * self.internal_rate_hz + 1e-9)) + 1
        grid = t_run[0] + np.arange(n) / self.internal_rate_hz
        # (an event's row repeats its time: the uniform samples are read where they are, the rest
        # linearly between the run's samples, from the last row at each time)
        keep = np.append(np.diff(t_run) > 0.0, True)
        tt = t_run[keep]
        mass = np.interp(grid, tt, np.asarray(run.abs_acceleration, dtype=float)[keep])
        disp = np.interp(grid, tt, np.asarray(run.displacement, dtype=float)[keep])
        table = run.excitation.acceleration(grid)
        t, tab, acc, d = self.measure(grid, table, mass, disp)
        return pd.DataFrame({"time_s": t, "table_acc_m_s2": tab, "mass_acc_m_s2": acc, "displacement_m": d})

