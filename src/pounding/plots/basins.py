"""Basins of attraction: the plane of initial states coloured by the response each ends on."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc
from ._labels import A_G_LABEL
from .legend import place_legend


@fill_doc
def plot_basins(result: Any, ax: Any = None, **kwargs: Any) -> list:
    """Basins of attraction: each initial state (displacement in mm, velocity in m/s) coloured by
    the attractor it ends on (grey: not settled), each attractor's sample at the section marked.

    Parameters
    ----------
    result : Basins
        From :func:`pounding.basins`.
    {ax}
    **kwargs
        Passed to the image (a grid) or the scatter (random states).

    Returns
    -------
    list of matplotlib artists
        The basins, then the attractors' markers.

    Examples
    --------
    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> b = pounding.basins(osc, pounding.Harmonic(0.05, 1.8), n=(8, 8))
    >>> artists = pounding.plots.plot_basins(b)
    >>> len(artists) >= 3
    True
    """
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    if ax is None:
        ax = plt.figure(figsize=(6, 4.5), constrained_layout=True).add_subplot()
    att = result.attractors
    colors = ["0.85"] + [f"C{j % 10}" for j in range(len(att))]  # (label -1 first: not settled)
    cmap = ListedColormap(colors)
    shown = result.labels + 1
    artists: list = []
    if result.sampling == "grid":
        nx, ny = result.labels.shape
        d = result.displacement_m.reshape(nx, ny)[:, 0] * 1e3
        v = result.velocity_m_s.reshape(nx, ny)[0]
        artists.append(ax.pcolormesh(d, v, shown.T, cmap=cmap, vmin=-0.5, vmax=len(colors) - 0.5,
                                     shading="nearest", **kwargs))
    else:
        artists.append(ax.scatter(result.displacement_m * 1e3, result.velocity_m_s, c=shown, cmap=cmap,
                                  vmin=-0.5, vmax=len(colors) - 0.5, s=6, **kwargs))
    for j, row in enumerate(att.itertuples()):
        what = "impacting" if row.impacts else "free"
        artists += ax.plot([row.displacement_m * 1e3], [row.velocity_m_s], "o", mfc=colors[j + 1], mec="k",
                           ms=8, label=f"{what}, period {row.period}, alpha {row.alpha:.2f}: "
                                       f"{row.fraction:.1%} +- {row.standard_error:.1%}")
    if np.any(result.labels < 0):
        artists += ax.plot([], [], "s", color=colors[0], label=f"not settled: {result.not_settled:.1%}")
    ax.set_xlabel("initial D [mm]")
    ax.set_ylabel("initial V [m/s]")
    exc = result.excitation
    ax.set_title(f"Basins at a_G = {exc.a_g:g} g, {exc.freq_hz:g} Hz (table phase 0)", fontsize="medium")
    place_legend(ax, fontsize="small")
    return artists


@fill_doc
def plot_basin_stability(result: Any, ax: Any = None, *, curves: Any = None, **kwargs: Any) -> list:
    """The probability of pounding over frequency and a_G (colour), with ``curves`` (a
    :class:`~pounding.CoexistenceMap`: its fold and grazing curves) over it.

    Parameters
    ----------
    result : BasinStabilityMap
        From :func:`pounding.basin_stability_map`.
    {ax}
    curves : CoexistenceMap, optional
        From :func:`pounding.coexistence_map`.
    **kwargs
        Passed to the colour mesh.

    Returns
    -------
    list of matplotlib artists
        The mesh, the colour bar, the curves' lines.

    Examples
    --------
    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> m = pounding.basin_stability_map(osc, [0.04, 0.05], [1.5, 1.8, 2.1],
    ...                                  samples=10)
    >>> len(pounding.plots.plot_basin_stability(m)) >= 2
    True
    """
    import matplotlib.pyplot as plt

    if ax is None:
        ax = plt.figure(figsize=(6.5, 4.5), constrained_layout=True).add_subplot()
    ds = result.data
    mesh = ax.pcolormesh(ds["freq_hz"].values, ds["a_g"].values, ds["pounding_probability"].values,
                         shading="nearest", cmap="viridis", vmin=0.0, vmax=1.0, **kwargs)
    bar = ax.figure.colorbar(mesh, ax=ax, label="probability of pounding")
    artists: list = [mesh, bar]
    if curves is not None:
        labelled = set()
        for curve in curves.curves:
            df = curve.to_dataframe()
            fold = curve.kind == "fold"
            artists += ax.plot(df["freq_hz"], df["a_g"], color="w" if fold else "C1", lw=1.2,
                               ls="-" if fold else "--", label=None if curve.kind in labelled else curve.kind)
            labelled.add(curve.kind)
    ax.set_xlabel("f [Hz]")
    ax.set_ylabel(A_G_LABEL)
    ax.set_title(f"Probability of pounding ({int(ds.attrs['samples'])} initial states a point)",
                 fontsize="medium")
    place_legend(ax, fontsize="small")
    return artists
