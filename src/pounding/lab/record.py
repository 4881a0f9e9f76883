"""Shaking-table recordings: :class:`LabRecord` and :func:`read_test` (issue 17).

A recording holds the table's acceleration, one or more accelerometers on the mass and a laser
measuring the mass's displacement relative to the table, sampled together.  ``read_test``
reads them from delimited text in the units the lab used and checks what later steps rely on:
time strictly increasing, a sampling rate, and where samples are missing (gaps in time, runs
of NaN), which it reports instead of hiding.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._checks import instance_of, one_of, positive
from .._delimited import as_columns, read_columns
from .._errors import InputError, PoundingWarning, Problem
from .._units import ACC_UNITS, LENGTH_UNITS, TIME_UNITS
from .._units import GRAVITY_M_S2

ROLES = ("time", "table_acc", "mass_acc", "displacement")
# unit -> factor to SI, per kind of channel
DEFAULT_UNITS = {"time": "s", "table_acc": "m/s2", "mass_acc": "m/s2", "displacement": "m"}
GAP_FACTOR = 1.5  # a time step longer than this many median steps is a gap in the recording
MIN_SAMPLES = 16


@dataclass(frozen=True, eq=False)
class LabRecord:
    """A shaking-table recording in SI units.

    Attributes
    ----------
    time_s : ndarray, shape (n,)
        Sample times, s, strictly increasing.
    table_acc_m_s2 : ndarray, shape (n,)
        The table's acceleration, m/s^2.
    mass_acc_m_s2 : ndarray, shape (n, k)
        The mass's absolute acceleration from each of ``k`` accelerometers, m/s^2.
    displacement_m : ndarray, shape (n,)
        The mass's displacement relative to the table, m.
    mass_channels : tuple of str
        The accelerometers' names (their columns), length ``k``.
    source : str
        Where it came from (the file, or "synthetic").
    gaps : DataFrame
        Gaps in time: ``start_s``, ``end_s``, ``missing_samples`` (at the median rate).
    nan_runs : DataFrame
        Runs of missing values: ``channel``, ``start_s``, ``end_s``, ``samples``.
    meta : dict
        What is known of the test besides the samples (a synthetic test's schedule and sensors).

    Examples
    --------
    :func:`read_test` and :func:`synthetic_test` return one; built from arrays it runs the same
    checks.  A steady 1.5 Hz cycle of 10 mm at a_G = 0.05 g, two accelerometers, and 10 ms the
    laser lost:

    >>> import pounding
    >>> import numpy as np
    >>> # s (1 kHz), rad/s (1.5 Hz)
    >>> t, w = np.arange(0.0, 2.0, 0.001), 3.0 * np.pi
    >>> # m/s^2, m
    >>> table, laser = 0.05 * 9.81 * np.sin(w * t), -0.01 * np.sin(w * t)
    >>> # m/s^2: absolute
    >>> mass = table - w**2 * laser
    >>> laser[500:510] = np.nan
    >>> rec = pounding.lab.LabRecord(t, table, np.column_stack([mass, mass]), laser,
    ...                              ("acc_1", "acc_2"))
    >>> rec.mass_acc_m_s2.shape, round(rec.sample_rate_hz)
    ((2000, 2), 1000)
    >>> rec.nan_runs[["channel", "samples"]].values.tolist()  # reported, not hidden
    [['displacement', 10]]
    """

    time_s: np.ndarray
    table_acc_m_s2: np.ndarray
    mass_acc_m_s2: np.ndarray
    displacement_m: np.ndarray
    mass_channels: tuple[str, ...]
    source: str = "arrays"
    gaps: pd.DataFrame = field(default=None, repr=False)  # type: ignore[assignment]
    nan_runs: pd.DataFrame = field(default=None, repr=False)  # type: ignore[assignment]
    meta: dict = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        t = np.asarray(self.time_s, dtype=float)
        n = t.size
        if t.ndim != 1 or n < MIN_SAMPLES:
            raise InputError(Problem.TOO_SHORT, "time_s", f"{n} samples", got=n, expected=MIN_SAMPLES)
        if not np.isfinite(t).all():
            i = int(np.flatnonzero(~np.isfinite(t))[0])
            raise InputError(Problem.NOT_FINITE, f"time_s[{i}]", t[i])
        step = np.diff(t)
        if (step <= 0.0).any():
            i = int(np.flatnonzero(step <= 0.0)[0])
            raise InputError(Problem.TIME_NOT_INCREASING, "time_s", f"samples {i} and {i + 1}",
                             where=f"sample {i + 1}", before=float(t[i]), after=float(t[i + 1]))
        acc = np.asarray(self.mass_acc_m_s2, dtype=float)
        if acc.ndim == 1:
            acc = acc[:, None]
        arrays = {"table_acc_m_s2": np.asarray(self.table_acc_m_s2, dtype=float),
                  "displacement_m": np.asarray(self.displacement_m, dtype=float)}
        for name, a in arrays.items():
            if a.shape != (n,):
                raise InputError(Problem.SIZE_MISMATCH, name, f"shape {a.shape}", got=a.size, expected=n,
                                 other="time_s")
        if acc.ndim != 2 or acc.shape[0] != n or acc.shape[1] < 1:
            raise InputError(Problem.SIZE_MISMATCH, "mass_acc_m_s2", f"shape {acc.shape}", got=acc.shape[0],
                             expected=n, other="time_s (one column per accelerometer)")
        channels = tuple(str(c) for c in self.mass_channels)
        if len(channels) != acc.shape[1]:
            raise InputError(Problem.LENGTH_MISMATCH, "mass_channels", channels, got=len(channels),
                             expected=acc.shape[1], hint=" (one name per accelerometer column)")
        for name, a in (("time_s", t), ("mass_acc_m_s2", acc), *arrays.items()):
            a.setflags(write=False)
            object.__setattr__(self, name, a)
        object.__setattr__(self, "mass_channels", channels)
        if self.gaps is None:
            object.__setattr__(self, "gaps", _gaps(t))
        if self.nan_runs is None:
            object.__setattr__(self, "nan_runs", _nan_runs(t, {"table_acc": arrays["table_acc_m_s2"],
                                                                 "displacement": arrays["displacement_m"],
                                                                 **{c: acc[:, j] for j,
                                                                    c in enumerate(channels)}}))

    @property
    def n_samples(self) -> int:
        """Samples per channel."""
        return int(self.time_s.size)

    @property
    def sample_rate_hz(self) -> float:
        """The sampling rate, Hz: one over the median time step."""
        return float(1.0 / np.median(np.diff(self.time_s)))

    @property
    def duration_s(self) -> float:
        """Recorded time, s."""
        return float(self.time_s[-1] - self.time_s[0])

    @property
    def mass_acc_mean_m_s2(self) -> np.ndarray:
        """The mean of the accelerometers (as the paper averages its two), shape (n,)."""
        return self.mass_acc_m_s2.mean(axis=1)

    def to_xarray(self) -> Any:
        """The channels of :meth:`to_dataframe` as a Dataset along ``sample``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "sample")

    def to_dataframe(self) -> pd.DataFrame:
        """One row per sample: ``time_s``, ``table_acc_m_s2``, the accelerometers (by name, m/s^2)
        and ``displacement_m``."""
        df = pd.DataFrame({"time_s": self.time_s, "table_acc_m_s2": self.table_acc_m_s2})
        for j, c in enumerate(self.mass_channels):
            df[c] = self.mass_acc_m_s2[:, j]
        df["displacement_m"] = self.displacement_m
        return df


def read_test(path: str | Path, *, time: Any, table_acc: Any, mass_acc: Any, displacement: Any,
              units: dict[str, str] | None = None, g: float = GRAVITY_M_S2) -> LabRecord:
    """Read a shaking-table recording from delimited text (CSV, TSV, semicolons, whitespace).

    Parameters
    ----------
    path : str or Path
        The file; lines starting with ``#`` are comments; a first line with a non-number is
        the header.
    time, table_acc, displacement : str or int
        Their columns, by header name or 0-based index.
    mass_acc : str, int or list of them
        One or more accelerometers on the mass.
    units : dict, optional
        Per role (``time``: "s" or "ms"; ``table_acc`` and ``mass_acc``: "m/s2", "cm/s2" or "g";
        ``displacement``: "m" or "mm"); roles left out are SI (:data:`DEFAULT_UNITS`).
    g : float
        m/s^2 per g, for channels in g.

    Returns
    -------
    LabRecord
        In SI units, with the gaps in time and the runs of missing values it found (a
        :class:`~pounding.PoundingWarning` says where, when there are any).

    Raises
    ------
    InputError
        A missing file, a column not in the file, a truncated line, a field that is not a number
        (naming its line and column), time that does not increase (naming the line), too few
        samples, an unknown unit.

    Examples
    --------
    A file in the lab's units (time in ms, accelerations in g, the laser in mm), one accelerometer:

    >>> import pounding
    >>> import numpy as np
    >>> t = np.arange(0.0, 4.0, 0.002)  # s: 4 s at 500 Hz
    >>> table = 0.05 * np.sin(3.0 * np.pi * t)  # g (1.5 Hz)
    >>> laser = -10.0 * np.sin(3.0 * np.pi * t)  # mm
    >>> columns = np.column_stack([1e3 * t, table, 2.81 * table, laser])
    >>> np.savetxt("run.csv", columns, delimiter=",", comments="",
    ...            header="time_ms,table_g,mass_g,laser_mm")
    >>> units = {"time": "ms", "table_acc": "g", "mass_acc": "g",
    ...          "displacement": "mm"}
    >>> rec = pounding.lab.read_test("run.csv", time="time_ms", table_acc="table_g",
    ...                              mass_acc="mass_g", displacement="laser_mm",
    ...                              units=units)
    >>> round(rec.sample_rate_hz), rec.mass_channels  # Hz
    (500, ('mass_g',))
    >>> round(float(rec.displacement_m.max()), 4)  # m
    0.01
    """
    g = positive("g", g, "m/s^2")
    units = _units(units)
    acc_cols = as_columns("mass_acc", mass_acc)
    columns = {"time": time, "table_acc": table_acc, "displacement": displacement}
    columns.update({f"mass_acc[{j}]": c for j, c in enumerate(acc_cols)})
    values, names, line_of = read_columns("path", path, columns)
    t = values["time"] * TIME_UNITS[units["time"]]
    bad = ~np.isfinite(t)
    if bad.any():
        raise InputError(Problem.BAD_CELL, "path", str(path), line=int(line_of[np.flatnonzero(bad)[0]]),
                         column=names["time"], token="", hint=" (every sample needs its time)")
    step = np.diff(t)
    if (step <= 0.0).any():
        i = int(np.flatnonzero(step <= 0.0)[0])
        raise InputError(Problem.TIME_NOT_INCREASING, names["time"], str(path),
                         where=f"line {int(line_of[i + 1])}", before=float(values["time"][i]),
                         after=float(values["time"][i + 1]))
    acc_si = {k: _acc_factor(units[k], g) for k in ("table_acc", "mass_acc")}
    disp = values["displacement"] * LENGTH_UNITS[units["displacement"]]
    _plausible_displacement(disp, units["displacement"])
    record = LabRecord(t, values["table_acc"] * acc_si["table_acc"],
                       np.column_stack([values[f"mass_acc[{j}]"]
                                        for j in range(len(acc_cols))]) * acc_si["mass_acc"],
                       disp, tuple(names[f"mass_acc[{j}]"] for j in range(len(acc_cols))), source=str(path))
    _warn_missing(record)
    return record


def _units(units: Any) -> dict[str, str]:
    if units is None:
        return dict(DEFAULT_UNITS)
    instance_of("units", units, dict,
                'dict such as {"time": "ms", "table_acc": "g", "mass_acc": "g", '
                                  '"displacement": "mm"}')
    out = dict(DEFAULT_UNITS)
    choices = {"time": TIME_UNITS, "table_acc": ACC_UNITS, "mass_acc": ACC_UNITS,
               "displacement": LENGTH_UNITS}
    for role, unit in units.items():
        one_of("units key", role, ROLES)
        out[role] = one_of(f"units.{role}", unit, choices[role])
    return out


def _acc_factor(unit: str, g: float) -> float:
    factor = ACC_UNITS[unit]
    return g if factor is None else factor


def _plausible_displacement(disp: np.ndarray, unit: str) -> None:
    peak = float(np.nanmax(np.abs(disp))) if np.isfinite(disp).any() else 0.0
    if unit == "m" and peak > 1.0:
        warnings.warn(f"displacement reaches {peak:g} m: a shaking-table laser reads mm; "
                      'if the file is in mm, say units={"displacement": "mm"}', PoundingWarning, stacklevel=3)


def _gaps(t: np.ndarray) -> pd.DataFrame:
    step = np.diff(t)
    dt = float(np.median(step))
    at = np.flatnonzero(step > GAP_FACTOR * dt)
    return pd.DataFrame({"start_s": t[at], "end_s": t[at + 1],
                         "missing_samples": np.rint(step[at] / dt).astype(int) - 1})


def _nan_runs(t: np.ndarray, channels: dict[str, np.ndarray]) -> pd.DataFrame:
    rows = []
    for name, a in channels.items():
        bad = np.isnan(a).astype(np.int8)
        edges = np.diff(np.concatenate(([0], bad, [0])))
        for start, end in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):
            rows.append({"channel": name, "start_s": float(t[start]), "end_s": float(t[end - 1]),
                         "samples": int(end - start)})
    return pd.DataFrame(rows, columns=["channel", "start_s", "end_s", "samples"])


def _warn_missing(record: LabRecord) -> None:
    parts = []
    if len(record.gaps):
        g = record.gaps.iloc[0]
        parts.append(f"{len(record.gaps)} gap(s) in time (the first {g.start_s:g} to {g.end_s:g} s, "
                     f"{g.missing_samples} samples missing)")
    if len(record.nan_runs):
        r = record.nan_runs.iloc[0]
        parts.append(f"{len(record.nan_runs)} run(s) of missing values (the first in {r.channel}, "
                     f"{r.start_s:g} to {r.end_s:g} s, {r.samples} samples)")
    if parts:
        warnings.warn(f"{record.source}: " + "; ".join(parts) + ": see the record's .gaps and .nan_runs; the "
                      "steps they fall in cannot be measured", PoundingWarning, stacklevel=3)
