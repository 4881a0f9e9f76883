"""Basins of attraction: the plane of initial states coloured by the response each ends on."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._legend import place_legend


def plot_basins(result: Any, ax: Any = None, **kwargs: Any) -> list:
    """Basins of attraction: each initial state (displacement in mm, velocity in m/s) coloured by
    the attractor it ends on (grey: not settled), each attractor's sample at the section marked.

    Parameters
    ----------
    result : Basins
        From :func:`pounding.basins`.
    ax : matplotlib Axes, optional
        Where to draw (a new figure if omitted).
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
    >>> artists = b.plot()
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
    ax.set_xlabel("initial D, mm")
    ax.set_ylabel("initial V, m/s")
    exc = result.excitation
    ax.set_title(f"Basins at a_G = {exc.a_g:g} g, {exc.freq_hz:g} Hz (table phase 0)", fontsize="medium")
    place_legend(ax, fontsize="small")
    return artists
