"""Earthquake (or any sampled) table accelerations: :class:`Record`, read from AT2 and CSV, scaled."""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._checks import at_most, float_array, instance_of, one_of, plausible, positive
from .._errors import InputError, PoundingWarning, Problem
from .._units import ACC_UNITS
from .harmonic import MAX_A_G, MAX_ACCEL_M_S2, MAX_TIME_S, RECORD, GRAVITY_M_S2

UNIFORM_RTOL = 1e-6  # time steps equal within this are a uniform sampling
MIN_STEP_S = 1e-9  # the shortest time step accepted, s (records are sampled at 1 kHz and slower)
# a record's PGA as read in its stated unit is plausible within this, g (the strongest recorded shaking is
# about 4 g, the weakest worth a pounding analysis some hundredths of g); outside it, a reading in another
# unit that lands inside is named in a warning (El Centro's m/s^2 read as g: 3.13 g; its g read as m/s^2:
# 0.0325 g)
PLAUSIBLE_PGA_G = (0.05, 2.0)


@dataclass(frozen=True, eq=False)
class Record:
    """Sampled table acceleration, linear between samples and zero outside ``[t[0], t[-1]]``.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times in s, strictly increasing, n >= 2.
    accel : array_like, shape (n,)
        Table acceleration in m/s^2 at those times (:meth:`from_g` takes units of g).
    name : str
        What the record is called (a file's stem, an NGA sequence number); shown in plots and tables.
    meta : mapping
        Anything known about it (event, year, station, magnitude, component, scale factor, source).
    g : float
        Gravity's acceleration in m/s^2, for the values given in g (``pga_g``, ``scaled(pga_g=)``).

    Notes
    -----
    Records compare by identity (``==`` is ``is``: comparing arrays element by element is rarely
    what is meant); ``meta`` is a copy made at construction, to be read, not changed.

    Examples
    --------
    A record from samples in g (files: :meth:`from_at2`, :meth:`from_csv`), and the shipped El
    Centro record scaled to a PGA of 0.3 g, shaking the paper's YBs system for its first 10 s:

    >>> import pounding
    >>> pulse = pounding.Record.from_g([0.0, 0.1, 0.2, 0.3, 0.4],
    ...                                [0.0, 0.1, -0.2, 0.05, 0.0], name="pulse")
    >>> # m/s^2 (0 after the end)
    >>> pulse, pulse.acceleration([0.05, 1.0]).round(4).tolist()
    (Record('pulse', n=5, t=[0, 0.4] s, pga=0.2 g), [0.4905, 0.0])
    >>> quake = pounding.records.el_centro().scaled(pga_g=0.3)
    >>> # -, s, s
    >>> round(quake.meta["scale_factor"], 3), round(quake.dt_s, 3), quake.duration_s
    (0.941, 0.02, 31.16)
    >>> run = pounding.simulate(pounding.presets.paper_damped(), quake,
    ...                         duration=10.0)
    >>> # impacts, peak acceleration in g
    >>> len(run.contacts), round(run.abs_acceleration_max / 9.81, 2)
    (14, 1.75)
    """

    t: np.ndarray = field(repr=False)
    accel: np.ndarray = field(repr=False)
    name: str = ""
    meta: Mapping[str, Any] = field(default_factory=dict, repr=False)
    g: float = GRAVITY_M_S2

    def __post_init__(self) -> None:
        t = float_array("record.t", self.t, min_len=2)
        accel = float_array("record.accel", self.accel, min_len=2)
        if accel.size != t.size:
            raise InputError(Problem.LENGTH_MISMATCH, "record.accel", f"array of {accel.size}",
                             got=accel.size, expected=t.size, hint=" (one acceleration per time in record.t)")
        steps = np.diff(t)
        if np.any(steps <= 0.0):
            i = int(np.flatnonzero(steps <= 0.0)[0])
            raise InputError(Problem.NOT_INCREASING, f"record.t[{i}:{i + 2}]", t[i:i + 2].tolist())
        i = int(np.argmax(np.abs(t)))
        at_most(f"record.t[{i}]", float(t[i]), MAX_TIME_S, " s", "give the times in s")
        # steps the engine can resolve: at least 1 ns, and a million times the rounding of the times
        # (a record at 1e-300 s steps was taken, and its run met no sample of it)
        least = max(MIN_STEP_S, 1e6 * np.spacing(abs(float(t[i]))))
        j = int(np.argmin(steps))
        if steps[j] < least:
            raise InputError(Problem.TOO_SMALL, f"record.t[{j + 1}] - record.t[{j}]", float(steps[j]),
                             minimum=f"{least:.3g} s", hint=" (steps this small cannot be resolved: give the "
                                                            "times in s; 100 Hz sampling is 0.01)")
        i = int(np.argmax(np.abs(accel)))
        at_most(f"record.accel[{i}]", float(accel[i]), MAX_ACCEL_M_S2, " m/s^2 (1000 g)",
                "give the acceleration in m/s^2 (Record.from_g takes units of g)")
        plausible(f"record.accel[{i}]", abs(float(accel[i])), 0.0, 5.0 * GRAVITY_M_S2,
                  f"{abs(float(accel[i])) / GRAVITY_M_S2:.3g} g; the acceleration is in m/s^2 (use "
                  "Record.from_g for units of g)")
        instance_of("record.name", self.name, str, "str")
        instance_of("record.meta", self.meta, Mapping, "dict")
        g = at_most("record.g", positive("record.g", self.g, "m/s^2"), MAX_A_G, " m/s^2", "give g in m/s^2")
        t.setflags(write=False)
        accel.setflags(write=False)
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "accel", accel)
        object.__setattr__(self, "meta", dict(self.meta))
        object.__setattr__(self, "g", g)

    # ---- making one -------------------------------------------------------------------------
    @classmethod
    def from_g(cls, t: np.ndarray, accel_g: np.ndarray, g: float = GRAVITY_M_S2, *, name: str = "",
               meta: Mapping[str, Any] | None = None) -> "Record":
        """A record given in units of ``g``."""
        g = positive("g", g, "m/s^2")
        return cls(t, float_array("accel_g", accel_g, min_len=2) * g, name, meta or {}, g).check_units(
            "g", "Record.from_g; Record takes m/s^2")

    @classmethod
    def from_at2(cls, path: str | Path, *, g: float = GRAVITY_M_S2) -> "Record":
        """A PEER NGA ``.AT2`` file (header variants: see :mod:`pounding.excitation._at2`).

        Its name is the file's stem; ``meta`` has the header lines and, where line 2 reads
        ``EVENT[, DATE], STATION, COMPONENT``, those (and ``date``).  UTF-8 or Latin-1 text.
        Truncated files (fewer values than ``NPTS``), extra values, non-numbers and headers without
        ``NPTS``/``DT`` are errors naming the line.
        """
        from .._checks import input_path
        from ._at2 import parse_at2

        raw = input_path("path", path).read_bytes()
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError:  # (station names with accents, in older files' Latin-1)
            text = raw.decode("latin-1")
        values, dt, unit, meta = parse_at2(text, "path", str(path))
        g = positive("g", g, "m/s^2")
        factor = g if unit == "g" else 1e-2
        meta.update(source=str(path))
        return cls(dt * np.arange(values.size), values * factor, Path(path).stem, meta, g).check_units(
            "g" if unit == "g" else "cm/s2", "the file's unit")

    @classmethod
    def from_csv(cls, path: str | Path, *, accel: Any = None, time: Any = None, dt: float | None = None,
                 units: str = "g", g: float = GRAVITY_M_S2, name: str | None = None) -> "Record":
        """Delimited text (CSV, TSV, semicolons or whitespace; a header line or none).

        Parameters
        ----------
        path : str or Path
            The file.
        accel : str or int
            The acceleration column: its header name or 0-based index.
        time : str or int, optional
            The time column (s); or give ``dt``.
        dt : float, optional
            The time step (s) of a file without a time column.
        units : {"g", "m/s2", "cm/s2"}
            The acceleration's unit.
        g : float
            m/s^2 per g.
        name : str, optional
            Default: the file's stem.
        """
        from .._checks import input_path
        from .._delimited import read_columns

        input_path("path", path)  # (the file first: a path that is wrong is the first thing to say)
        if accel is None:
            raise InputError(Problem.MISSING_INPUT, "accel", accel,
                             what="the acceleration column (accel=): its header name or 0-based index")
        units = one_of("units", units, tuple(ACC_UNITS))
        g = positive("g", g, "m/s^2")
        if (time is None) == (dt is None):
            raise InputError(Problem.MISSING_INPUT, "time", time,
                             what="either the time column (time=) or the time step (dt=), not both")
        columns = {"accel": accel} if time is None else {"time": time, "accel": accel}
        # (a record cannot miss a sample: an empty field or a nan is refused, quoted as written)
        values, names, lines = read_columns("path", path, columns, required=tuple(columns))
        a = values["accel"]
        if time is None:
            step = positive("dt", dt, "s")
            t = step * np.arange(a.size)
        else:
            t = values["time"]
            steps = np.diff(t)
            if not np.all(np.isfinite(t)) or np.any(steps <= 0.0):
                i = int(np.flatnonzero(~(np.isfinite(steps) & (steps > 0.0)))[0]) if np.any(
                    ~(np.isfinite(steps) & (steps > 0.0))) else 0
                raise InputError(Problem.TIME_NOT_INCREASING, "path", str(path), where=f"line {lines[i + 1]}",
                                 before=float(t[i]), after=float(t[i + 1]))
        factor = g if units == "g" else ACC_UNITS[units]
        meta = {"source": str(path), "unit": units, "columns": names}
        return cls(t, a * factor, Path(path).stem if name is None else name, meta, g).check_units(units)

    def scaled(self, *, pga_g: float | None = None, sa_g: float | None = None, period_s: float | None = None,
               damping_ratio: float | None = None, factor: float | None = None) -> "Record":
        """The record times a factor: to a peak ground acceleration, or to a spectral acceleration,
        or a factor given.

        Give ``pga_g`` (g), or ``sa_g`` (g) with ``period_s``: the pseudo-spectral acceleration
        ``PSa = omega^2 Sd`` at that period and ``damping_ratio`` (default 0.05; as codes and FEMA P695
        scale), or ``factor`` (> 0; e.g. from :func:`pounding.design.stripe_factors`).
        ``meta["scale_factor"]`` multiplies any earlier one.
        """
        if sum(v is not None for v in (pga_g, sa_g, factor)) != 1:
            raise InputError(Problem.MISSING_INPUT, "pga_g", pga_g,
                             what="one of pga_g=, sa_g= (with period_s=) or factor=")
        if sa_g is None:  # (period_s and damping_ratio are sa_g's alone)
            for name, value in (("period_s", period_s), ("damping_ratio", damping_ratio)):
                if value is not None:
                    raise InputError(Problem.WRONG_MODE, name, value, mode="sa_g",
                                     fix=f"leave {name} out when scaling "
                                         + ("by a factor" if factor is not None else "to pga_g"))
        if factor is not None:
            target = positive("factor", factor, "(a factor)")
            plausible("factor", target, 0.01, 100.0, "a record scaled that far no longer resembles shaking")
            now = 1.0
        elif pga_g is not None:
            target = positive("pga_g", pga_g, "g")
            plausible("pga_g", target, 0.0, 5.0, "pga_g is in g (0.3 is 30 % of g)")
            now = self.pga_g
        else:
            target = positive("sa_g", sa_g, "g")
            plausible("sa_g", target, 0.0, 10.0, "sa_g is in g")
            if period_s is None:
                raise InputError(Problem.MISSING_INPUT, "period_s", period_s, what="the period (s) of sa_g")
            from ._spectrum_run import damping_ratio_value, spectrum_peaks

            period = positive("period_s", period_s, "s")
            zeta = damping_ratio_value(0.05 if damping_ratio is None else damping_ratio)
            peaks, done = spectrum_peaks([(self.t, self.accel)], np.array([period]), zeta)
            if done < 1:
                raise KeyboardInterrupt
            now = float((2.0 * math.pi / period) ** 2 * peaks[0, 0, 0] / self.g)  # (the pseudo-acceleration)
        if now == 0.0:
            raise InputError(Problem.BAD_STATE, "record", self.name or "record",
                             why="the record is all zeros", fix="give a record that moves")
        factor = target / now
        meta = {**self.meta, "scale_factor": self.meta.get("scale_factor", 1.0) * factor}
        return self._derived(self.accel * factor, meta)

    def negated(self) -> "Record":
        """The same record with the opposite sign."""
        return self._derived(-self.accel, self.meta)

    def _derived(self, accel: np.ndarray, meta: Mapping[str, Any]) -> "Record":
        """This record's times with other accelerations (scaled, negated): its times and unit checked
        already, and a level scaled to on purpose is no unit mistake (the scale factor's plausibility
        is checked where it is asked for), so only the hard bound is checked again."""
        accel = np.array(accel, dtype=float)
        i = int(np.argmax(np.abs(accel)))
        at_most(f"record.accel[{i}]", float(accel[i]), MAX_ACCEL_M_S2, " m/s^2 (1000 g)",
                "scale the record less")
        accel.setflags(write=False)
        out = object.__new__(Record)
        for name, value in (("t", self.t), ("accel", accel), ("name", self.name), ("meta", dict(meta)),
                            ("g", self.g)):
            object.__setattr__(out, name, value)
        return out

    def check_units(self, unit: str, field: str = "units") -> "Record":
        """Warn when the record's PGA, read in ``unit`` ("g", "m/s2", "cm/s2"), is implausible for
        shaking and another of those units would make it plausible: a file in m/s^2 read as g (El Centro
        at 3.13 g) or one in g read as m/s^2 (El Centro at 0.0325 g).  ``field`` names where the unit
        was given.  Returns the record."""
        lo, hi = PLAUSIBLE_PGA_G
        pga = self.pga_g
        if lo <= pga <= hi or pga == 0.0:
            return self
        to_si = {u: (self.g if f is None else f) for u, f in ACC_UNITS.items()}
        raw = pga * self.g / to_si[unit]  # (the file's own numbers)
        other = [(u, raw * f / self.g) for u, f in to_si.items()
                 if u != unit and lo <= raw * f / self.g <= hi]
        if other:
            u, reading = other[0]
            name = f" {self.name!r}" if self.name else ""
            warnings.warn(f"read in {unit} ({field}), the record{name} has a PGA of {pga:.3g} g, "
                          f"outside the plausible [{lo:g}, {hi:g}] g of strong shaking: if its values are in "
                          f"{u}, its PGA is {reading:.3g} g (give that unit)", PoundingWarning, stacklevel=3)
        return self

    # ---- what it is -------------------------------------------------------------------------
    @property
    def pga_g(self) -> float:
        """The peak ground acceleration, ``max |a|``, in g."""
        return float(np.abs(self.accel).max()) / self.g

    @property
    def peak_m_s2(self) -> float:
        """The peak ground acceleration, ``max |a|``, in m/s^2 (as a sine's ``Harmonic.peak_m_s2``)."""
        return float(np.abs(self.accel).max())

    @property
    def duration_s(self) -> float:
        """``t[-1] - t[0]`` in s."""
        return float(self.t[-1] - self.t[0])

    @property
    def dt_s(self) -> float:
        """The time step in s (the median one; :attr:`uniform` says whether all are equal)."""
        return float(np.median(np.diff(self.t)))

    @property
    def uniform(self) -> bool:
        """Whether the samples are equally spaced (within 1e-6 of the step)."""
        steps = np.diff(self.t)
        return bool(np.ptp(steps) <= UNIFORM_RTOL * float(np.median(steps)))

    def acceleration(self, t: np.ndarray) -> np.ndarray:
        """Table acceleration (m/s^2) at times ``t`` (s)."""
        return np.interp(np.asarray(t, dtype=float), self.t, self.accel, left=0.0, right=0.0)

    def to_xarray(self) -> Any:
        """The samples of :meth:`to_dataframe` as a Dataset along ``sample``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "sample", {"name": self.name})

    def to_dataframe(self) -> pd.DataFrame:
        """``time_s``, ``accel_m_s2``, ``accel_g``: one row per sample."""
        return pd.DataFrame({"time_s": self.t, "accel_m_s2": self.accel, "accel_g": self.accel / self.g})

    def plot(self, ax: Any = None) -> Any:
        """The acceleration (g) against time, its peak marked; returns its Figure."""
        from ..plots.record import plot_record
        from ..plots import figure_of

        return figure_of(plot_record(self, ax=ax), ax)

    def __repr__(self) -> str:
        name = f"{self.name!r}, " if self.name else ""
        return (f"Record({name}n={self.t.size}, t=[{self.t[0]:g}, {self.t[-1]:g}] s, "
                f"pga={self.pga_g:.3g} g)")

    def __getstate__(self) -> dict:
        # the cached kernel arrays are copies of t and accel: not shipped to workers
        state = dict(self.__dict__)
        state.pop("_kernel_arrays", None)
        return state

    def kernel_arrays(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The excitation as the compiled engine takes it: a kind code and three float arrays
        (internal; made once per record, never written to)."""
        return self._kernel_arrays

    @cached_property
    def _kernel_arrays(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        # the first parameter: the record's uniform step (steps equal within 1e-9 of it; else 0), each of
        # whose intervals goes by its phase's transition (the core's transition.cpp)
        steps = np.diff(self.t)
        step = float(np.median(steps))
        uniform = float(np.max(np.abs(steps - step))) <= 1e-9 * step
        return (RECORD, np.array([step if uniform else 0.0, 0.0, 0.0]), np.array(self.t, dtype=float),
                np.array(self.accel, dtype=float))

