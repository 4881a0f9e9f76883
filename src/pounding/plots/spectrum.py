"""Plots of pounding spectra."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc
from .legend import place_legend

KINDS = ("curves", "map")


@fill_doc
def plot_pounding_spectrum(spectrum: Any, ax: Any = None, *, kind: str = "curves",
                           quantity: str = "amplification") -> list:
    """A pounding spectrum (:func:`pounding.pounding_spectrum`) over the isolation period.

    Parameters
    ----------
    spectrum : PoundingSpectrum
        From :func:`pounding.pounding_spectrum`.
    {ax}
    kind : {"curves", "map"}
        "curves": the median over the records against the period, one line per gap, the 16-84 %
        band shaded (one record: its curves); "map": the median over period (x) and gap (y).
    quantity : str
        A variable of ``spectrum.data`` with the gap dimension (``amplification``, ``acc_max_g``,
        ``disp_max_m``, ``impacts``, ``impact_force_max_n``, ``impact_speed_max_m_s``, ``disp_ratio``).

    Returns
    -------
    list of matplotlib artists
        "curves": one line per gap (and its band); "map": the colour mesh.

    Examples
    --------
    El Centro on isolators of 2 and 3 s with gaps of 50 and 100 mm:

    >>> import pounding
    >>> spectrum = pounding.pounding_spectrum(pounding.records.el_centro(),
    ...                                       [2.0, 3.0], gaps_m=[0.05, 0.1])
    >>> artists = pounding.plots.plot_pounding_spectrum(spectrum)
    >>> len(artists)  # two gaps, and the line amplification = 1
    3
    """
    import matplotlib.pyplot as plt

    from .._checks import one_of
    from .._errors import InputError, Problem

    kind = one_of("kind", kind, KINDS)
    ds = spectrum.data
    if quantity not in ds or "gap_m" not in ds[quantity].dims:
        choices = ", ".join(v for v in ds.data_vars if "gap_m" in ds[v].dims and v != "status")
        raise InputError(Problem.NOT_IN_RESULT, "quantity", quantity, choices=choices)
    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 3.8), constrained_layout=True)
    stats = spectrum.summary()[quantity]
    median = stats.sel(percentile=50.0)
    units = ds[quantity].attrs.get("units", "")
    label = f"{quantity} [{units}]" if units and units != "1" else quantity
    n = ds.sizes["record"]
    x_label = ("isolated period T on the bearings' initial stiffness [s]"
               if "isolated" in ds.attrs.get("period", "")
               else "superstructure's fixed-base period T [s]" if "structure" in ds.attrs
               else "isolation period T [s]")
    artists: list = []
    if kind == "curves":
        for gap in ds["gap_m"].values:
            line, = ax.plot(ds["period_s"], median.sel(gap_m=gap), lw=1.2, label=f"gap {gap * 1e3:g} mm")
            artists.append(line)
            if n > 1:
                artists.append(ax.fill_between(ds["period_s"], stats.sel(percentile=16.0, gap_m=gap),
                                               stats.sel(percentile=84.0, gap_m=gap), color=line.get_color(),
                                               alpha=0.15, lw=0))
        if quantity == "amplification":
            artists.append(ax.axhline(1.0, color="0.5", lw=0.8, ls=":"))
        ax.set_xlabel(x_label)
        ax.set_ylabel(label)
        place_legend(ax, fontsize=8)
    else:
        # one band per gap computed, of equal height, labelled with its gap (with shading="nearest" on the
        # gaps themselves, 10, 20 and 50 mm were drawn as the bands 5-15, 15-35 and 35-65 mm)
        gaps_mm = np.asarray(ds["gap_m"], dtype=float) * 1e3
        mesh = ax.pcolormesh(ds["period_s"], np.arange(gaps_mm.size), np.asarray(median).T, shading="nearest")
        artists.append(mesh)
        ax.figure.colorbar(mesh, ax=ax, label=label)
        ax.set_yticks(np.arange(gaps_mm.size), [f"{g:g}" for g in gaps_mm])
        ax.set_xlabel(x_label)
        ax.set_ylabel("gap [mm] (one band per gap computed)")
    what = "median over " + (f"{n} records (16-84 % shaded)" if n > 1 and kind == "curves"
                             else f"{n} record(s)")
    unbounded = "" if np.isfinite(np.asarray(median)[~np.isnan(np.asarray(median))]).all() else (
        "; inf (a rigid stop's impulse) not drawn")
    ax.set_title(f"{quantity}: {what}{unbounded}", fontsize=9)
    return artists
