"""Two horizontal components of one ground motion, applied together: :class:`RecordPair`, rotated or
projected on a direction, scaled, read from a pair of AT2 files or two columns of a table."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._checks import instance_of, plausible, positive, real
from .._errors import InputError, Problem
from .harmonic import GRAVITY_M_S2
from .record import UNIFORM_RTOL, Record


@dataclass(frozen=True, eq=False)
class RecordPair:
    """The two horizontal components of one ground motion, on one time base.

    Parameters
    ----------
    x, y : Record
        The components along the plan's x and y axes (m/s^2).  Sampled at the same step from the same
        start; a component that ends sooner is at rest after its end (zeros added).  Their ``g`` must agree.
    name : str
        What the motion is called (default: the components' names, ``"x / y"``).
    meta : mapping
        Anything known about it (event, station, the rotation applied, a scale factor).

    Notes
    -----
    Compared by identity, as :class:`Record`.  A direction is an angle from x towards y, in degrees: the
    motion along it is ``cos(a) x + sin(a) y`` (:meth:`along`).

    Examples
    --------
    Two components, the pair turned by 30 degrees, and its motion along 45 degrees:

    >>> import numpy as np
    >>> import pounding
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> north = pounding.Record.from_g(t, 0.3 * np.sin(2 * np.pi * t), name="N")
    >>> east = pounding.Record.from_g(t, 0.2 * np.cos(2 * np.pi * t), name="E")
    >>> pair = pounding.RecordPair(north, east)
    >>> pair
    RecordPair('N / E', n=101, t=[0, 1] s, pga=0.3 g, 0.2 g)
    >>> turned = pair.rotated(30.0)
    >>> round(turned.meta["rotation_deg"], 1), round(pair.along(45.0).pga_g, 3)
    (30.0, 0.255)
    """

    x: Record
    y: Record
    name: str = ""
    meta: Mapping[str, Any] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        instance_of("pair.x", self.x, Record, "pounding.Record")
        instance_of("pair.y", self.y, Record, "pounding.Record")
        instance_of("pair.name", self.name, str, "str")
        instance_of("pair.meta", self.meta, Mapping, "dict")
        x, y = self.x, self.y
        if x.g != y.g:
            raise InputError(Problem.BAD_STATE, "pair.y.g", y.g,
                             why=f"differs from pair.x.g = {x.g!r}: one motion has one g",
                             fix="give both components the same g")
        if not (x.t.size == y.t.size and np.array_equal(x.t, y.t)):
            x, y = _on_one_base(x, y)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)
        object.__setattr__(self, "name", self.name or " / ".join(n for n in (x.name, y.name) if n))
        object.__setattr__(self, "meta", dict(self.meta))

    # ---- making one ------------------------------------------------------------------------
    @classmethod
    def from_at2(cls, path_x: str | Path, path_y: str | Path, *, g: float = GRAVITY_M_S2,
                 name: str | None = None) -> "RecordPair":
        """Two PEER NGA ``.AT2`` files, one component each (:meth:`Record.from_at2`): x from ``path_x``, y
        from ``path_y``.  ``name`` defaults to the event and station the first file's header gives, else
        the two files' stems."""
        x, y = Record.from_at2(path_x, g=g), Record.from_at2(path_y, g=g)
        if name is None:
            name = ", ".join(str(x.meta[k]) for k in ("event", "station") if x.meta.get(k)) or ""
        return cls(x, y, name, {"source": [str(path_x), str(path_y)]})

    @classmethod
    def from_csv(cls, path: str | Path, *, x: Any = None, y: Any = None, time: Any = None,
                 dt: float | None = None, units: str = "g", g: float = GRAVITY_M_S2,
                 name: str | None = None) -> "RecordPair":
        """Two acceleration columns of one delimited text file (:meth:`Record.from_csv`'s formats): ``x``
        and ``y`` their header names or 0-based indices, with a ``time`` column (s) or a step ``dt``."""
        if x is None or y is None:
            missing = "x" if x is None else "y"
            raise InputError(Problem.MISSING_INPUT, missing, None,
                             what=f"the {missing} component's column ({missing}=): its header name or "
                                  "0-based index")
        rx = Record.from_csv(path, accel=x, time=time, dt=dt, units=units, g=g, name=str(x))
        ry = Record.from_csv(path, accel=y, time=time, dt=dt, units=units, g=g, name=str(y))
        return cls(rx, ry, Path(path).stem if name is None else name, {"source": str(path)})

    @classmethod
    def of_direction(cls, record: Record, angle_deg: float) -> "RecordPair":
        """One component ``record`` along the direction ``angle_deg`` (from x towards y, degrees): the pair
        ``(cos(a) record, sin(a) record)``; ``meta["direction_deg"]`` says which.

        Examples
        --------
        >>> import pounding
        >>> quake = pounding.records.el_centro()
        >>> pair = pounding.RecordPair.of_direction(quake, 30.0)
        >>> [round(p / quake.pga_g, 3) for p in pair.pga_g]  # cos 30, sin 30
        [0.866, 0.5]
        """
        instance_of("record", record, Record, "pounding.Record")
        a = math.radians(real("angle_deg", angle_deg))
        meta = {**record.meta, "direction_deg": float(angle_deg)}
        x = record._derived(math.cos(a) * record.accel, record.meta)
        y = record._derived(math.sin(a) * record.accel, record.meta)
        return _pair(x, y, f"{record.name} at {float(angle_deg):g} deg".strip(), meta)

    # ---- what it is --------------------------------------------------------------------------
    @property
    def t(self) -> np.ndarray:
        """The samples' times, s, shape (n,)."""
        return self.x.t

    @property
    def g(self) -> float:
        """Gravity's acceleration, m/s^2."""
        return self.x.g

    @property
    def dt_s(self) -> float:
        """The time step, s."""
        return self.x.dt_s

    @property
    def duration_s(self) -> float:
        """``t[-1] - t[0]``, s."""
        return self.x.duration_s

    @property
    def pga_g(self) -> tuple[float, float]:
        """Each component's peak ground acceleration, g: ``(x, y)``."""
        return self.x.pga_g, self.y.pga_g

    @property
    def peak_vector_g(self) -> float:
        """The largest ``|(a_x, a_y)|`` over the samples, g: the peak along the direction where it is
        largest (the motion is linear between samples, so its largest length is at a sample)."""
        return float(np.hypot(self.x.accel, self.y.accel).max()) / self.g

    # ---- new pairs, one direction --------------------------------------------------------------
    def rotated(self, angle_deg: float) -> "RecordPair":
        """The same motion in axes turned by ``angle_deg`` (from x towards y): the new x is the motion
        along ``angle_deg``, the new y along ``angle_deg + 90``.  ``meta["rotation_deg"]`` adds up."""
        a = math.radians(real("angle_deg", angle_deg))
        c, s = math.cos(a), math.sin(a)
        x = self.x._derived(c * self.x.accel + s * self.y.accel, self.x.meta)
        y = self.y._derived(-s * self.x.accel + c * self.y.accel, self.y.meta)
        meta = {**self.meta, "rotation_deg": self.meta.get("rotation_deg", 0.0) + float(angle_deg)}
        return _pair(x, y, self.name, meta)

    def along(self, angle_deg: float) -> Record:
        """The motion along the direction ``angle_deg`` (from x towards y, degrees): the one-component
        record ``cos(a) x + sin(a) y``, named after the pair and the direction."""
        a = math.radians(real("angle_deg", angle_deg))
        rec = self.x._derived(math.cos(a) * self.x.accel + math.sin(a) * self.y.accel,
                              {**self.meta, "direction_deg": float(angle_deg)})
        object.__setattr__(rec, "name", f"{self.name} at {float(angle_deg):g} deg".strip())
        return rec

    def scaled(self, factor: float | None = None, *, pga_g: float | None = None) -> "RecordPair":
        """Both components times one ``factor`` (> 0), as codes and FEMA P695 scale a pair, or by the one
        factor that brings its peak vector (:attr:`peak_vector_g`, the largest direction's PGA) to ``pga_g``;
        ``meta["scale_factor"]`` multiplies any earlier one."""
        if (factor is None) == (pga_g is None):
            raise InputError(Problem.MISSING_INPUT, "factor", factor,
                             what="one of factor= (both components times it) or pga_g= (the peak vector's)")
        if pga_g is not None:
            factor = positive("pga_g", pga_g, "g") / self.peak_vector_g
        f = positive("factor", factor, "(a factor)")
        plausible("factor", f, 0.01, 100.0, "a record scaled that far no longer resembles shaking")
        meta = {**self.meta, "scale_factor": self.meta.get("scale_factor", 1.0) * f}
        x = self.x._derived(f * self.x.accel, self.x.meta)
        return _pair(x, self.y._derived(f * self.y.accel, self.y.meta), self.name, meta)

    def to_dataframe(self) -> pd.DataFrame:
        """``time_s``, ``accel_x_m_s2``, ``accel_y_m_s2``: one row per sample."""
        return pd.DataFrame({"time_s": self.t, "accel_x_m_s2": self.x.accel, "accel_y_m_s2": self.y.accel})

    def to_xarray(self) -> Any:
        """The samples of :meth:`to_dataframe` as a Dataset along ``sample``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "sample", {"name": self.name})

    def plot(self, ax: Any = None) -> Any:
        """The two components (g) against time on one axes, their peaks in the legend; returns the Figure."""
        from ..plots import figure_of
        from ..plots.record import plot_pair

        return figure_of(plot_pair(self, ax=ax), ax)

    def __repr__(self) -> str:
        name = f"{self.name!r}, " if self.name else ""
        px, py = self.pga_g
        return (f"RecordPair({name}n={self.t.size}, t=[{self.t[0]:g}, {self.t[-1]:g}] s, "
                f"pga={px:.3g} g, {py:.3g} g)")


def _pair(x: Record, y: Record, name: str, meta: Mapping[str, Any]) -> RecordPair:
    """A pair of components known to share their time base (no checks again)."""
    out = object.__new__(RecordPair)
    for key, value in (("x", x), ("y", y), ("name", name), ("meta", dict(meta))):
        object.__setattr__(out, key, value)
    return out


def _on_one_base(x: Record, y: Record) -> tuple[Record, Record]:
    """The two components on one time base: the same step from the same start, the shorter one at rest
    after its end; else an InputError that says how to make them so."""
    step = x.dt_s
    same = (x.uniform and y.uniform and abs(y.dt_s - step) <= UNIFORM_RTOL * step
            and abs(float(y.t[0] - x.t[0])) <= UNIFORM_RTOL * step)
    if not same:
        raise InputError(Problem.BAD_STATE, "pair.y.t",
                         f"{y.t.size} samples at {y.dt_s:g} s from {y.t[0]:g} s",
                         why=f"is not pair.x's time base ({x.t.size} samples at {step:g} s from "
                             f"{x.t[0]:g} s)",
                         fix="resample both components at one step from one start (np.interp)")
    n = max(x.t.size, y.t.size)
    longer = x if x.t.size == n else y

    def padded(r: Record) -> Record:
        if r.t.size == n:
            return r
        accel = np.zeros(n)
        accel[:r.t.size] = r.accel
        out = r._derived(accel, r.meta)
        object.__setattr__(out, "t", longer.t)
        return out

    return padded(x), padded(y)
