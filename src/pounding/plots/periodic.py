"""Plots of periodic orbits: the phase plane."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc
from ..engine.layout import C_T_START
from .legend import place_legend


@fill_doc
def plot_orbit(orbit: Any, ax: Any = None, **kwargs: Any) -> list:
    """A periodic orbit in the phase plane, displacement (mm) against velocity (m/s): a single mass's with
    its contacts' starts and its bumpers' surfaces, or each level's of a system of several.

    Parameters
    ----------
    orbit : PeriodicOrbit
        From :func:`pounding.periodic_orbit`.
    {ax}
    **kwargs
        Passed to the orbit's lines (solid when stable, dashed when not).

    Returns
    -------
    list of matplotlib artists
        A single mass's: the orbit's line, the mark of its section state, those of its contacts'
        starts, the bumpers' surfaces.  Several levels: each moving level's line and section state.

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

    from ..engine import Run

    kwargs = cbook.normalize_kwargs(kwargs, Line2D)  # (c, ls, lw: the long names)
    if ax is None:
        ax = plt.figure().add_subplot()
    run = orbit.run
    if not isinstance(run, Run):  # (several levels)
        return _plot_levels(orbit, ax, kwargs)
    style = {"color": "C0", "linestyle": "-" if orbit.stable else "--",
             "label": f"{'stable' if orbit.stable else 'unstable'}, "
                      f"max |mu| = {orbit.max_abs_multiplier:.3g}"}
    style.update(kwargs)
    artists = list(ax.plot(run.displacement * 1e3, run.velocity, **style))
    artists += ax.plot([orbit.state.displacement_m * 1e3], [orbit.state.velocity_m_s], "o",
                       color=style["color"], markersize=4, label="section state")
    contacts = orbit.period_contact_table
    if contacts.size:  # where each contact starts: the mass at the bumper's surface
        t0 = run.t[0]
        starts = (contacts[:, C_T_START] - t0) % orbit.period_s + t0
        artists += ax.plot(np.interp(starts, run.t, run.displacement) * 1e3,
                           np.interp(starts, run.t, run.velocity),
                           "v", color="C3", markersize=5, label="contact starts")
    b = run.oscillator.bumpers
    if b is not None:
        for x_mm in (-b.gap_left_m * 1e3, b.gap_right_m * 1e3):
            artists.append(ax.axvline(x_mm, color="0.6", linewidth=0.8))
    ax.set_xlabel("displacement D [mm]")
    ax.set_ylabel("velocity V [m/s]")
    ax.set_title(f"periodic orbit, f = {run.excitation.freq_hz:g} Hz, a_G = {run.excitation.a_g:g}, "
                 f"{orbit.contacts_per_period} contacts per period")
    place_legend(ax, fontsize="small")
    return artists


def _plot_levels(orbit: Any, ax: Any, kwargs: dict) -> list:
    """A structure's (or a pair's) periodic orbit (``plot_orbit``): each moving level's line in its phase
    plane and its section state."""
    from ..engine import structure_runs

    run = orbit.run
    parts = structure_runs(run)
    prefixes = ("first.", "second.") if len(parts) > 1 else ("",)
    artists: list = []
    k = 0
    for prefix, part in zip(prefixes, parts):
        x0, v0 = part.displacement[0], part.velocity[0]
        for level in range(part.displacement.shape[1]):
            if not np.any(part.displacement[:, level]) and not np.any(part.velocity[:, level]):
                continue  # (a fixed base's ground)
            style = {"color": f"C{k % 10}", "linestyle": "-" if orbit.stable else "--",
                     "label": f"{prefix}level {level}"}
            style.update(kwargs)
            artists += ax.plot(part.displacement[:, level] * 1e3, part.velocity[:, level], **style)
            artists += ax.plot([x0[level] * 1e3], [v0[level]], "o", color=style["color"], markersize=4)
            k += 1
    ax.set_xlabel("displacement x [mm]")
    ax.set_ylabel("velocity v [m/s]")
    exc = run.excitation
    ax.set_title(f"periodic orbit, f = {exc.freq_hz:g} Hz, a_G = {exc.a_g:g}, max |mu| = "
                 f"{orbit.max_abs_multiplier:.3g} ({'stable' if orbit.stable else 'unstable'}), "
                 f"{orbit.contacts_per_period} contacts per period", fontsize="small")
    place_legend(ax, fontsize="small")
    return artists


def plot_structure_orbit_axes(orbit: Any, ax: Any = None, **kwargs: Any) -> Any:
    """``plot_structure_orbit``, :func:`plot_orbit`'s name before for a structure's orbit (for one release,
    through ``pounding.plots``): the same drawing, its Axes returned as that function did."""
    import matplotlib.pyplot as plt

    if ax is None:
        ax = plt.figure().add_subplot()
    plot_orbit(orbit, ax=ax, **kwargs)
    return ax
