"""The peak of a system's response against the orientation of the pair that shakes it."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc


@fill_doc
def plot_orientations(result: Any, quantity: str = "disp_max_m", ax: Any = None) -> list:
    """``quantity`` of :func:`pounding.orientations` against the angle, on a polar axes (0 degrees along x,
    counter-clockwise towards y), the most critical orientation marked.

    Parameters
    ----------
    result : Orientations
        What :func:`pounding.orientations` returned.
    quantity : str
        A column of its ``data`` (``disp_max_m``, ``acc_max_g``, ``drift_ratio_max``, ...).
    {ax}
        A polar one (made when None).

    Returns
    -------
    list of matplotlib artists
        The curve and the critical orientation's marker.

    Examples
    --------
    >>> import pandas as pd
    >>> import pounding
    >>> from pounding.protocols.orientations import Orientations
    >>> table = pd.DataFrame({"disp_max_m": [0.1, 0.2, 0.15]},
    ...                      index=pd.Index([0.0, 120.0, 240.0], name="angle_deg"))
    >>> artists = pounding.plots.plot_orientations(Orientations(table, "a pair"))
    >>> len(artists)
    2
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(4.5, 4.5), subplot_kw={"projection": "polar"}, constrained_layout=True)
    angle, value = result.critical(quantity)  # (an unknown quantity refused by name)
    angles = np.radians(result.angles_deg)
    values = result.data[quantity].to_numpy(dtype=float)
    closed = np.append(angles, angles[:1]), np.append(values, values[:1])  # (round the circle)
    artists = list(ax.plot(*closed, "-o", lw=1.2, ms=3, label=quantity))
    if np.isfinite(value):
        artists += ax.plot([np.radians(angle)], [value], "*", ms=12, color="C3",
                           label=f"critical: {value:.4g} at {angle:g} deg")
    ax.set_title(f"{quantity}, {result.pair_name}" if result.pair_name else quantity, fontsize=9)
    ax.legend(loc="lower left", bbox_to_anchor=(-0.1, -0.15), fontsize=8, frameon=False)
    return artists
