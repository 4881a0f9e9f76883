"""Result data as tables and labelled arrays: one way for every result class to give its ``to_xarray``
from its table (and its ``to_dataframe`` from its Dataset)."""

from __future__ import annotations

from typing import Any


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
