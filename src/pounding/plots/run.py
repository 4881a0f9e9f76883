"""Plots of one run."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from .._units import GRAVITY_M_S2

if TYPE_CHECKING:  # pragma: no cover
    from ..engine.result import Run


def plot_run(run: "Run", ax: Any = None, *, contacts: bool = True) -> list:
    """Displacement (left axis, mm) and absolute acceleration (right axis, g) against time.

    Parameters
    ----------
    run : Run
        A result of :func:`pounding.simulate`.
    ax : matplotlib Axes, optional
        Where to draw (a new figure if omitted); a twin axis is added for the acceleration.
    contacts : bool
        Shade the contact intervals.

    Returns
    -------
    list of matplotlib artists
        The displacement's and the acceleration's lines, the contacts' shading, the bumpers'
        surfaces.

    Examples
    --------
    Ten seconds of the damped paper system shaken at a_G = 0.05 and 1.5 Hz, from rest:

    >>> import pounding
    >>> run = pounding.simulate(pounding.presets.paper_damped(),
    ...                         pounding.Harmonic(0.05, 1.5), 10.0)
    >>> artists = pounding.plots.plot_run(run)
    >>> len(artists) > 0
    True
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 3.5), constrained_layout=True)
    artists = list(ax.plot(run.t, run.displacement * 1e3, color="C0", lw=1.0, label="D"))
    ax.set_xlabel("t [s]")
    ax.set_ylabel("D [mm]", color="C0")
    twin = ax.twinx()
    artists += twin.plot(run.t, run.abs_acceleration / GRAVITY_M_S2, color="C3", lw=0.8, label="a_abs")
    twin.set_ylabel("absolute acceleration [g]", color="C3")
    if contacts and len(run.contacts):
        ends = run.contacts["t_end_s"].fillna(run.t[-1]).to_numpy()
        for start, end in zip(run.contacts["t_start_s"].to_numpy(), ends):
            artists.append(ax.axvspan(start, end, color="0.85", lw=0))
    b = run.oscillator.bumpers
    if b is not None:
        for y in (-b.gap_left_m, b.gap_right_m):
            artists.append(ax.axhline(y * 1e3, color="0.4", ls=":", lw=0.8))
    ax.set_xlim(float(np.min(run.t)), float(np.max(run.t)))
    return artists
