"""Plots of periodic orbits: the phase plane."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._legend import place_legend


def plot_orbit(orbit: Any, ax: Any = None, **kwargs: Any) -> list:
    """A periodic orbit in the phase plane, displacement (mm) against velocity (m/s).

    Parameters
    ----------
    orbit : PeriodicOrbit
        From :func:`pounding.periodic_orbit`.
    ax : matplotlib Axes, optional
        Where to draw (a new figure if omitted).
    **kwargs
        Passed to the orbit's line (solid when stable, dashed when not).

    Returns
    -------
    list of matplotlib artists
        The orbit's line, the mark of its section state, those of its contacts' starts, the
        bumpers' surfaces.

    Examples
    --------
    The damped paper system's orbit at a_G = 0.05 and 1.5 Hz, which hits both bumpers:

    >>> import pounding
    >>> orbit = pounding.periodic_orbit(pounding.presets.paper_damped(),
    ...                                 pounding.Harmonic(0.05, 1.5))
    >>> artists = pounding.plots.plot_orbit(orbit)
    >>> # the orbit, its section state, the contacts' starts, two bumpers
    >>> len(artists)
    5
    """
    import matplotlib.pyplot as plt
    from matplotlib import cbook
    from matplotlib.lines import Line2D

    kwargs = cbook.normalize_kwargs(kwargs, Line2D)  # (c, ls, lw: the long names)
    if ax is None:
        ax = plt.figure().add_subplot()
    run = orbit.run
    style = {"color": "C0", "linestyle": "-" if orbit.stable else "--",
             "label": f"{'stable' if orbit.stable else 'unstable'}, "
                      f"max |mu| = {orbit.max_abs_multiplier:.3g}"}
    style.update(kwargs)
    artists = list(ax.plot(run.displacement * 1e3, run.velocity, **style))
    artists += ax.plot([orbit.state.displacement_m * 1e3], [orbit.state.velocity_m_s], "o",
                       color=style["color"], markersize=4, label="section state")
    contacts = orbit._contacts()
    if contacts.size:  # where each contact starts: the mass at the bumper's surface
        t0 = run.t[0]
        starts = (contacts[:, 1] - t0) % orbit.period_s + t0
        artists += ax.plot(np.interp(starts, run.t, run.displacement) * 1e3,
                           np.interp(starts, run.t, run.velocity),
                           "v", color="C3", markersize=5, label="contact starts")
    b = run.oscillator.bumpers
    if b is not None:
        for x_mm in (-b.gap_left * 1e3, b.gap_right * 1e3):
            artists.append(ax.axvline(x_mm, color="0.6", linewidth=0.8))
    ax.set_xlabel("displacement D [mm]")
    ax.set_ylabel("velocity V [m/s]")
    ax.set_title(f"periodic orbit, f = {run.excitation.freq_hz:g} Hz, a_G = {run.excitation.a_g:g}, "
                 f"{orbit.contacts_per_period} contacts per period")
    place_legend(ax, fontsize="small")
    return artists
