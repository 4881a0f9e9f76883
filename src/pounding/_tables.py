"""Result data as tables and labelled arrays: one way for every result class to give its ``to_xarray``
from its table (and its ``to_dataframe`` from its Dataset)."""

from __future__ import annotations

from typing import Any

import pandas as pd

from ._errors import warn_renamed


def frame_to_xarray(df: Any, dim: str, attrs: dict | None = None, index: str | None = None) -> Any:
    """A table as an ``xarray.Dataset``: its columns as variables along ``dim`` (one per row), or along
    the column ``index`` when its values are unique; ``attrs`` added."""
    import xarray as xr

    if index is not None and index in df.columns and df[index].is_unique:
        ds = xr.Dataset.from_dataframe(df.set_index(index))
    else:
        ds = xr.Dataset.from_dataframe(df.reset_index(drop=True).rename_axis(dim))
    ds.attrs.update({k: v for k, v in (attrs or {}).items() if v is not None})
    return ds


def xarray_to_frame(ds: Any) -> Any:
    """A Dataset as a long table: one row per point of its dimensions, their coordinates as columns."""
    return ds.to_dataframe().reset_index()


def percentiles(values: Any, qs: Any, axis: int = -1) -> Any:
    """The percentiles ``qs`` (0-100) of ``values`` along ``axis``, NaN left out, inf kept (a rigid stop's
    impulse: an unbounded acceleration or force).  Shape: ``qs``'s, then ``values``' without ``axis``.

    NumPy's interpolation between two infs gives inf - inf = NaN, so inf goes in as a finite stand-in and a
    percentile above every finite value of its slice, which only the stand-in can give, comes back as inf."""
    import warnings

    import numpy as np

    v = np.asarray(values, dtype=float)
    big = np.finfo(float).max / 4.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # (a slice with no value: NaN, said by the NaN)
        finite_max = np.nanmax(np.where(np.isfinite(v), v, np.nan), axis=axis)
        out = np.nanpercentile(np.minimum(v, big), qs, axis=axis)
    return np.where(out > np.where(np.isnan(finite_max), -np.inf, finite_max), np.inf, out)


class RenamedColumns(pd.DataFrame):
    """A table that still answers to its columns' old names for one release (``OLD``: old name -> new),
    with a ``FutureWarning`` naming the new one; its subclasses say which names."""

    OLD: dict = {}
    WHY: dict = {}  # (old name -> why it changed, where not for its unit)

    @property
    def _constructor(self) -> Any:
        return type(self)

    def _renamed(self, key: Any) -> Any:
        if isinstance(key, str) and key in self.OLD and key not in self.columns:
            warn_renamed(key, self.OLD[key], stacklevel=4, why=self.WHY.get(key, "with its unit"))
            return self.OLD[key]
        if isinstance(key, list) and any(isinstance(k, str) and k in self.OLD for k in key):
            return [self._renamed(k) for k in key]
        return key

    def __getitem__(self, key: Any) -> Any:
        return super().__getitem__(self._renamed(key))

    def __getattr__(self, name: str) -> Any:
        if name in type(self).OLD:
            return self[name]
        return super().__getattr__(name)


class ContactTable(RenamedColumns):
    """A run's contacts (:attr:`Run.contacts`, :attr:`StructureRun.contacts`, :attr:`AdjacentRun.links`):
    each column named with its unit; the names without units (0.1's: ``work`` is ``bumper_dissipation_j``,
    the name of that column in every run's tables) still answer, with a ``FutureWarning``."""

    OLD = {"t_start": "t_start_s", "t_end": "t_end_s", "v_in": "v_in_m_s", "v_out": "v_out_m_s",
           "impulse": "impulse_n_s", "peak_force": "peak_force_n", "max_compression": "max_compression_m",
           "work": "bumper_dissipation_j", "work_j": "bumper_dissipation_j"}
    WHY = {"work_j": "one name in every run's tables", "work": "one name in every run's tables"}


class HistoryTable(RenamedColumns):
    """A single mass's sampled histories (:meth:`Run.to_dataframe`): each column named with its unit; 0.1's
    names without units (``t``, ``displacement``, ...) still answer, with a ``FutureWarning``."""

    OLD = {"t": "t_s", "displacement": "displacement_m", "velocity": "velocity_m_s",
           "abs_acceleration": "abs_acceleration_m_s2", "isolator_force": "isolator_force_n",
           "bumper_force_left": "bumper_force_left_n", "bumper_force_right": "bumper_force_right_n"}


class EventTable(RenamedColumns):
    """A run's events (``t_s``, ``kind``, ``index``); a structure's names of 0.1 (``t``, ``event``) still
    answer, with a ``FutureWarning``."""

    OLD = {"t": "t_s", "event": "kind"}


class RenamedKeys(dict):
    """A dict of named numbers that still answers to its keys' old names for one release (``OLD``: old name
    -> new; ``WHY``: why), by ``[]`` and ``get``, with a ``FutureWarning`` naming the new one; its subclasses
    say which names.  ``in``, iteration and copies know the new names only."""

    OLD: dict = {}
    WHY: str = "one name for every system"

    @classmethod
    def name_now(cls, key: Any) -> Any:
        """``key``'s name now: itself, or (a name before) its new name, with a ``FutureWarning``."""
        if isinstance(key, str) and key in cls.OLD:
            warn_renamed(key, cls.OLD[key], stacklevel=4, why=cls.WHY)
            return cls.OLD[key]
        return key

    def __missing__(self, key: Any) -> Any:
        if isinstance(key, str) and key in self.OLD and self.OLD[key] in self:
            warn_renamed(key, self.OLD[key], why=self.WHY)
            return self[self.OLD[key]]
        raise KeyError(key)

    def get(self, key: Any, default: Any = None) -> Any:
        """``self[key]`` (an old name answering, with its warning), or ``default``."""
        if key in self or (isinstance(key, str) and self.OLD.get(key) in self):
            return self[key]
        return default


class RunQuantities(RenamedKeys):
    """A run's point (``quantities()`` of every run): the names of every system's; a building's
    ``base_disp_max_m`` of before is ``disp_max_m`` (a single mass's, the base's: the moat's demand)."""

    OLD = {"base_disp_max_m": "disp_max_m"}
