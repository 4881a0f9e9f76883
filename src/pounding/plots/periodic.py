"""Plots of periodic orbits: the phase plane."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..engine.layout import C_T_START
from .legend import place_legend


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


def plot_structure_orbit(orbit: Any, ax: Any = None, **kwargs: Any) -> Any:
    """A structure's periodic orbit: each level in its phase plane, displacement (mm) against velocity
    (m/s), the section state marked.

    Parameters
    ----------
    orbit : StructurePeriodicOrbit
        From :func:`pounding.periodic_orbit` of a structure or an adjacent pair.
    ax : matplotlib Axes, optional
        Where to draw (a new figure if omitted).
    **kwargs
        Passed to every level's line (solid when stable, dashed when not).

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=4.0e3)
    >>> stop = pounding.Wall(0, 0.02, 0.02, pounding.KelvinVoigt(1.0e8, 2.0e4))
    >>> b = pounding.Structure(2.0e3, iso,
    ...                        [pounding.Storey(1.0e3, 2.0e6, 2.0e3)], [stop])
    >>> orbit = pounding.periodic_orbit(b, pounding.Harmonic(0.1, 1.5))
    >>> ax = pounding.plots.plot_structure_orbit(orbit)
    >>> len(ax.get_lines())  # two levels, each its orbit and its section state
    4
    """
    import matplotlib.pyplot as plt

    if ax is None:
        ax = plt.figure().add_subplot()
    run = orbit.run
    parts = [("first.", run.first), ("second.", run.second)] if hasattr(run, "first") else [("", run)]
    k = 0
    for prefix, part in parts:
        x0, v0 = part.displacement[0], part.velocity[0]
        for level in range(part.displacement.shape[1]):
            if not np.any(part.displacement[:, level]) and not np.any(part.velocity[:, level]):
                continue  # (a fixed base's ground)
            style = {"color": f"C{k % 10}", "linestyle": "-" if orbit.stable else "--",
                     "label": f"{prefix}level {level}"}
            style.update(kwargs)
            ax.plot(part.displacement[:, level] * 1e3, part.velocity[:, level], **style)
            ax.plot([x0[level] * 1e3], [v0[level]], "o", color=style["color"], markersize=4)
            k += 1
    ax.set_xlabel("displacement x [mm]")
    ax.set_ylabel("velocity v [m/s]")
    exc = run.excitation
    ax.set_title(f"periodic orbit, f = {exc.freq_hz:g} Hz, a_G = {exc.a_g:g}, max |mu| = "
                 f"{orbit.max_abs_multiplier:.3g} ({'stable' if orbit.stable else 'unstable'}), "
                 f"{orbit.contacts_per_period} contacts per period", fontsize="small")
    place_legend(ax, fontsize="small")
    return ax
