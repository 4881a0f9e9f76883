"""Plots of parameter studies."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc
from .legend import place_legend


@fill_doc
def plot_study(result: Any, quantity: str, *, x: str | None = None, hue: str | None = None, ax: Any = None,
               where: dict | None = None) -> list:
    """A study's quantity against one grid axis, one line per value of another.

    Parameters
    ----------
    result : StudyResult
        From :func:`pounding.open_study`.
    quantity : str
        One of the study's quantities (``result.data`` variables but ``done`` and ``session``).
    x : str, optional
        The grid axis along the horizontal (default: the first one longer than 1).
    hue : str, optional
        The axis whose values make the lines (default: the next one longer than 1, if any).
    {ax}
    where : dict, optional
        A value for each other axis longer than 1 (the nearest is taken): ``{"a_g": 0.05}``.

    Returns
    -------
    list of matplotlib Line2D
        Points not done are gaps in the lines.

    Examples
    --------
    Three left gaps at two a_G, one 5 s run at 1.5 Hz each, written to ``gaps.zarr``; the peak
    acceleration against the gap, a line per a_G:

    >>> import pounding
    >>> grid = {"bumpers.gap_left_m": [0.010, 0.015, 0.020], "a_g": [0.03, 0.05]}
    >>> compute = {"kind": "simulate", "freq_hz": 1.5, "duration_s": 5.0}
    >>> spec = pounding.StudySpec(pounding.presets.paper_damped(), compute, grid)
    >>> _ = pounding.study(spec, "gaps.zarr", progress=False)
    >>> artists = pounding.plots.plot_study(pounding.open_study("gaps.zarr"),
    ...                                     "acc_max_g", hue="a_g")
    >>> len(artists)
    2
    """
    import matplotlib.pyplot as plt

    from .._errors import InputError, Problem
    from .._tables import RunQuantities

    ds = result.data
    quantities = [v for v in ds.data_vars if v not in ("done", "session")]
    quantity = RunQuantities.name_now(quantity) if quantity not in quantities else quantity
    if quantity not in quantities:
        raise InputError(Problem.NOT_IN_RESULT, "quantity", quantity, choices=", ".join(quantities))
    long = [d for d in ds[quantity].dims if ds.sizes[d] > 1]
    for name, value in (("x", x), ("hue", hue)):
        if value is not None and value not in ds.dims:
            raise InputError(Problem.NOT_IN_RESULT, name, value, choices=", ".join(ds.dims))
    where = dict(where or {})
    for name in where:
        if name not in ds.dims or name in (x, hue):
            raise InputError(Problem.NOT_IN_RESULT, "where", name,
                             choices=", ".join(d for d in ds.dims if d not in (x, hue)) or "no other axis")
    free = [d for d in long if d not in where]
    x = x or (free[0] if free else ds[quantity].dims[0])
    if hue is None:
        rest = [d for d in free if d != x]
        hue = rest[0] if rest else None
    elif hue == x:
        raise InputError(Problem.DUPLICATE, "hue", hue, repeated="x (give two different axes)")
    da = ds[quantity].where(ds["done"])
    for d in ds[quantity].dims:
        if d in (x, hue):
            continue
        if d in where:
            value = where[d]
            if isinstance(value, str):
                if value not in list(ds[d].values):
                    raise InputError(Problem.NOT_ONE_OF, f"where[{d!r}]", value,
                                     choices=", ".join(map(str, ds[d].values)))
                da = da.sel({d: value})
            else:
                da = da.sel({d: value}, method="nearest")
        elif ds.sizes[d] == 1:
            da = da.isel({d: 0})
        else:
            raise InputError(Problem.MISSING_INPUT, "where", where,
                             what=f"a value for the axis {d!r} (where={{{d!r}: ...}}), or choose it as x or "
                                  "hue")
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.8), constrained_layout=True)
    units = ds[quantity].attrs.get("units", "1")
    xs = ds[x].values
    artists = []
    for value in ([None] if hue is None else ds[hue].values):
        line = da if value is None else da.sel({hue: value})
        (art,) = ax.plot(xs, np.asarray(line.transpose(x).values, dtype=float), marker="o", ms=3, lw=1.2,
                         label=None if value is None else f"{hue} = {value}{_unit(ds, hue, ' ')}")
        artists.append(art)
    ax.set_xlabel(f"{x}{_unit(ds, x)}")
    ax.set_ylabel(quantity if units in ("1", "") else f"{quantity} [{units}]")
    if hue is not None:
        place_legend(ax, fontsize=8)
    ax.grid(alpha=0.3)
    return artists


def _unit(ds: Any, dim: str, sep: str = " [") -> str:
    """`` [m]`` (or `` m`` with ``sep=" "``) for a grid axis the store gives a unit; ``""`` otherwise."""
    from ..model.dotted import unit_of

    unit = ds[dim].attrs.get("units") or unit_of(dim)
    if not unit or unit in ("1", "-"):
        return ""
    return f" [{unit}]" if sep == " [" else f" {unit}"
