"""A study's results, read back from its store: :func:`open_study`."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .spec import StudySpec
from .store import SPEC_ATTR, check_store, open_checked, open_dataset

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd
    import xarray as xr


@dataclass(frozen=True, eq=False)
class StudyResult:
    """A study store, opened.

    Attributes
    ----------
    data : xarray.Dataset
        Lazily read (Dask arrays): dims the grid's axes; the quantities, ``done``, ``session``.
    spec : StudySpec
        The study that made the store.

    Examples
    --------
    Both gaps at once (``bumpers.gap_m``), each point 5 s at 1.5 Hz and a_G = 0.05 from rest:

    >>> import pounding
    >>> spec = pounding.StudySpec(pounding.presets.paper_damped(),
    ...                           {"kind": "simulate", "freq_hz": 1.5, "a_g": 0.05,
    ...                            "duration_s": 5.0},
    ...                           {"bumpers.gap_m": [0.01, 0.02, 0.03]})
    >>> _ = pounding.study(spec, "both_gaps.zarr", progress=False)
    >>> res = pounding.open_study("both_gaps.zarr")
    >>> res.done, res.complete, res.spec.dims
    (3, True, ('bumpers.gap_m',))
    >>> df = res.to_dataframe()  # one row per point done
    >>> cols = ["bumpers.gap_m", "acc_max_g", "impacts"]
    >>> print(df[cols].round(3).to_string(index=False))
     bumpers.gap_m  acc_max_g  impacts
              0.01      0.591     14.0
              0.02      0.135      0.0
              0.03      0.135      0.0
    """

    data: "xr.Dataset" = field(repr=False)
    spec: StudySpec = field(repr=False)

    @property
    def done(self) -> int:
        """Points computed."""
        return int(self.data["done"].sum())

    @property
    def complete(self) -> bool:
        """True when every point of the grid is done."""
        return self.done == self.spec.size

    def to_xarray(self) -> "xr.Dataset":
        """The study's store (:attr:`data`, read lazily)."""
        return self.data

    def to_dataframe(self, only_done: bool = True) -> "pd.DataFrame":
        """One row per point: the grid's values, then the quantities (the points done only, unless
        ``only_done`` is False)."""
        df = self.data.drop_vars("session").to_dataframe().reset_index()
        if only_done:
            df = df[df["done"]].reset_index(drop=True)
        return df.drop(columns="done")

    def plot(self, quantity: str, x: str | None = None, hue: str | None = None, ax: Any = None,
             where: dict | None = None) -> Any:
        """``quantity`` against the axis ``x``, one line per value of ``hue``; see
        :func:`pounding.plots.plot_study`.

        Returns its Figure.
        """
        from ..plots import plot_study, figure_of

        return figure_of(plot_study(self, quantity, x=x, hue=hue, ax=ax, where=where), ax)


def open_study(store: str | Path) -> StudyResult:
    """Open the store of :func:`pounding.study` (``xarray.open_zarr(store)`` reads it too).

    Parameters
    ----------
    store : str or Path
        The study's Zarr folder, or its fsspec URL (``s3://...``); a folder that is not a
        study's store is refused.

    Returns
    -------
    StudyResult
        ``.data`` (read lazily), ``.spec`` (the study that made it), ``.done`` and
        ``.complete``, ``.to_dataframe()`` and ``.plot()``.  Works on a study still running or
        interrupted: the points not done are NaN, with ``done`` False.

    Examples
    --------
    >>> import pounding
    >>> spec = pounding.StudySpec(pounding.presets.paper_damped(),
    ...                           {"kind": "sweep", "freqs_hz": [1.5, 2.0],
    ...                            "cycles": 10},
    ...                           {"a_g": [0.03, 0.05]})
    >>> _ = pounding.study(spec, "sweeps.zarr", progress=False)
    >>> res = pounding.open_study("sweeps.zarr")
    >>> res.spec.kind, res.done, res.complete
    ('sweep', 2, True)
    >>> print(res.data["alpha"].round(2).to_pandas())  # max alpha of each sweep
    a_g
    0.03    3.55
    0.05    8.39
    Name: alpha, dtype: float64
    """
    store = check_store(store)
    group = open_checked(store, None)
    spec = StudySpec._from_store(json.loads(dict(group.attrs)[SPEC_ATTR]))
    return StudyResult(open_dataset(store), spec)
