"""Plots of records and their response spectra."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .._docs import fill_doc
from .legend import place_legend

if TYPE_CHECKING:  # pragma: no cover
    from ..excitation import Record


@fill_doc
def plot_record(record: "Record", ax: Any = None) -> list:
    """The acceleration (g) against time (s), its peak marked.

    Parameters
    ----------
    record : Record
        A ground motion, e.g. from :mod:`pounding.records`.
    {ax}

    Returns
    -------
    list of matplotlib artists
        The record's line, the peak's marker and its label.

    Examples
    --------
    >>> import pounding
    >>> artists = pounding.plots.plot_record(pounding.records.el_centro())
    >>> len(artists)
    3
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 2.8), constrained_layout=True)
    a_g = record.accel / record.g
    label = record.name or "record"
    artists = list(ax.plot(record.t, a_g, lw=0.8, label=label))
    i = int(np.argmax(np.abs(a_g)))
    artists += ax.plot([record.t[i]], [a_g[i]], "o", color=artists[0].get_color(), ms=4)
    artists.append(ax.annotate(f"PGA {abs(a_g[i]):.3g} g at {record.t[i]:.2f} s", (record.t[i], a_g[i]),
                               textcoords="offset points", xytext=(6, 4), fontsize=8))
    ax.set_xlabel("t [s]")
    ax.set_ylabel("table acceleration [g]")
    ax.set_title(label)
    return artists


@fill_doc
def plot_response_spectrum(spectrum: Any, ax: Any = None, *, quantity: str = "psa_g") -> list:
    """One curve per record of an elastic response spectrum (:func:`pounding.response_spectrum`).

    Parameters
    ----------
    spectrum : xarray.Dataset
        From :func:`pounding.response_spectrum` (dims ``record`` and ``period_s``).
    {ax}
    quantity : str
        The variable drawn: ``psa_g`` (default), ``sa_g``, ``sd_m``, ``sv_m_s``, ``psv_m_s``, ...

    Returns
    -------
    list of matplotlib artists
        One line per record.

    Examples
    --------
    The 5 % damped spectrum of El Centro at three periods:

    >>> import pounding
    >>> spectrum = pounding.response_spectrum(pounding.records.el_centro(),
    ...                                       [0.5, 1.0, 2.0])
    >>> artists = pounding.plots.plot_response_spectrum(spectrum, quantity="sd_m")
    >>> len(artists)
    1
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 3.5), constrained_layout=True)
    da = spectrum[quantity]
    artists = []
    for name in da["record"].values:
        artists += ax.plot(da["period_s"], da.sel(record=name), lw=1.0, label=str(name))
    ax.set_xlabel("period T [s]")
    units = da.attrs.get("units", "")
    ax.set_ylabel(f"{quantity} [{units}]" if units else quantity)
    ax.set_title(f"{spectrum.attrs.get('damping_ratio', 0.05):.0%} damped")
    if len(artists) <= 10:
        place_legend(ax, fontsize=8)
    return artists


@fill_doc
def plot_pair(pair: Any, ax: Any = None) -> list:
    """A pair's two components (g) against time, on one axes, each one's peak in the legend.

    Parameters
    ----------
    pair : RecordPair
        A ground motion's two components, e.g. from :func:`pounding.records.fema_p695_pairs`.
    {ax}

    Returns
    -------
    list of matplotlib artists
        The two lines.

    Examples
    --------
    >>> import pounding
    >>> quake = pounding.records.el_centro()
    >>> pair = pounding.RecordPair(quake, quake.negated())
    >>> artists = pounding.plots.plot_pair(pair)
    >>> len(artists)
    2
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 2.8), constrained_layout=True)
    artists = []
    for axis, rec in (("x", pair.x), ("y", pair.y)):
        label = f"{axis}: {rec.name}" if rec.name else axis
        artists += ax.plot(rec.t, rec.accel / rec.g, lw=0.7, label=f"{label} (PGA {rec.pga_g:.3g} g)")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("table acceleration [g]")
    ax.set_title(pair.name or "pair")
    place_legend(ax, fontsize=8)
    return artists


@fill_doc
def plot_rotd_spectrum(spectrum: Any, ax: Any = None) -> list:
    """RotD50 and RotD100 pseudo-accelerations (:func:`pounding.rotd_spectrum`) against the period: each
    pair's two curves and its components' (x at 0, y at 90 degrees) for up to four pairs; for more, each
    pair's RotD50 thin and the median over the pairs of both.

    Parameters
    ----------
    spectrum : xarray.Dataset
        What :func:`pounding.rotd_spectrum` returned.
    {ax}

    Returns
    -------
    list of matplotlib artists
        The curves.

    Examples
    --------
    >>> import pounding
    >>> quake = pounding.records.el_centro()
    >>> pair = pounding.RecordPair(quake, quake.negated())
    >>> spec = pounding.rotd_spectrum(pair, [0.5, 1.0, 2.0],
    ...                               angle_step_deg=15.0)
    >>> len(pounding.plots.plot_rotd_spectrum(spec))
    4
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 3.5), constrained_layout=True)
    periods = spectrum["period_s"]
    artists = []
    names = spectrum["pair"].values
    if names.size <= 4:
        angles = spectrum["angle_deg"].values
        for name in names:
            one = spectrum.sel(pair=name)
            line = ax.plot(periods, one["rotd100_psa_g"], lw=1.2, label=f"{name}: RotD100")[0]
            artists += [line] + ax.plot(periods, one["rotd50_psa_g"], lw=1.2, ls="--", color=line.get_color(),
                                        label=f"{name}: RotD50")
            for axis, angle in (("x", 0.0), ("y", 90.0)):
                if np.any(angles == angle):
                    artists += ax.plot(periods, one["psa_g"].sel(angle_deg=angle), lw=0.7, ls=":",
                                       color=line.get_color(), label=f"{name}: {axis}")
    else:
        for name in names:
            artists += ax.plot(periods, spectrum["rotd50_psa_g"].sel(pair=name), lw=0.5, color="0.75")
        artists += ax.plot(periods, spectrum["rotd100_psa_g"].median("pair"), lw=1.6, color="C3",
                           label=f"median RotD100 of {names.size}")
        artists += ax.plot(periods, spectrum["rotd50_psa_g"].median("pair"), lw=1.6, color="C0",
                           label=f"median RotD50 (thin: each of {names.size})")
    ax.set_xlabel("period T [s]")
    ax.set_ylabel("pseudo-acceleration [g]")
    ax.set_title(f"{spectrum.attrs.get('damping_ratio', 0.05):.0%} damped, orientation-independent")
    place_legend(ax, fontsize=8)
    return artists
