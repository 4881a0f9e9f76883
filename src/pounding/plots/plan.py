"""A building in plan's run: the orbit in plan of its corners (or its bearings) with the moat drawn."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from .._checks import non_negative
from .._docs import fill_doc


@fill_doc
def plot_plan_orbit(run: Any, ax: Any = None) -> list:
    """The orbit in plan of a :class:`~pounding.engine.plan_result.PlanRun`: each corner of the moat's
    floor as it moved (its displacement, mm: every corner starts at the origin), inside the moat's
    clearance (the rectangle each corner may move in before it meets a wall: ``-gap_x-`` to ``+gap_x+``,
    ``-gap_y-`` to ``+gap_y+``; a circular moat's ring as each corner meets it, an arc ``gap_m`` beyond
    its start along its diagonal, in its colour), the contacts marked where they began; without a moat,
    each bearing's orbit.
    A circle marks the largest bearing displacement in plan (exact).

    Parameters
    ----------
    run : PlanRun
        What :func:`pounding.simulate` returned for a building in plan.
    {ax}

    Returns
    -------
    list of matplotlib artists
        The orbits, the moat's rectangle, the contacts' markers and the circle.

    Examples
    --------
    >>> import pounding
    >>> from pounding import Bearing, Floor, PlanBuilding, RectangularMoat
    >>> iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01])
    >>> bearings = [Bearing((sx * 10.0, sy * 6.0), iso)
    ...             for sx in (-1, 1) for sy in (-1, 1)]
    >>> moat = RectangularMoat(0.08, pounding.KelvinVoigt(5.0e8, 1.0e6))
    >>> b = PlanBuilding([Floor(6.0e5, (24.0, 16.0), centre_m=(1.2, 0.0))],
    ...                  bearings, moat=moat)
    >>> quake = pounding.RecordPair.of_direction(
    ...     pounding.records.el_centro().scaled(pga_g=0.5), 30.0)
    >>> run = pounding.simulate(b, quake, 10.0, sample_rate_hz=100.0)
    >>> artists = pounding.plots.plot_plan_orbit(run)
    >>> len(artists)  # four corners, the moat, the contacts, the circle
    7
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Rectangle

    if ax is None:
        _, ax = plt.subplots(figsize=(8.0, 5.0), constrained_layout=True)
    building = run.building
    artists: list = []
    mm = 1e3
    moat = building.moat
    if moat is not None:
        level = moat.level
        floor = building.placed_floors[level]
        u = run.displacement[:, level]
        for k, (px, py) in enumerate(building.floors[level].corners_m()):
            x = u[:, 0] - (py - floor.centre_m[1]) * u[:, 2]
            y = u[:, 1] + (px - floor.centre_m[0]) * u[:, 2]
            artists += ax.plot(x * mm, y * mm, lw=0.8, label=f"corner ({px:g}, {py:g}) m")
        if np.ndim(moat.gap_m) == 0:  # (a ring: where each corner meets it, an arc about its own start)
            colours = [a.get_color() for a in artists]
            artists += _ring_arcs(ax, moat, building.floors[level], u, colours)
        else:
            g = np.asarray(moat.gap_m) * mm
            artists.append(ax.add_patch(Rectangle((-g[0], -g[2]), g[0] + g[1], g[2] + g[3], fill=False,
                                                  lw=1.5, color="k", label="moat clearance")))
        contacts = run.contacts
        if len(contacts):
            q = np.minimum(np.searchsorted(run.t, contacts["t_start_s"].to_numpy()), run.t.size - 1)
            corners = building.floors[level].corners_m()
            xs, ys = [], []
            for row, k in zip(q, contacts["corner"].to_numpy()):
                px, py = corners[k]
                xs.append(u[row, 0] - (py - floor.centre_m[1]) * u[row, 2])
                ys.append(u[row, 1] + (px - floor.centre_m[0]) * u[row, 2])
            artists += ax.plot(np.array(xs) * mm, np.array(ys) * mm, "x", color="C3", ms=6,
                               label=f"contacts ({len(contacts)})")
    else:
        for b, bearing in enumerate(building.bearings):
            artists += ax.plot(run.bearing_displacement[:, b, 0] * mm, run.bearing_displacement[:, b, 1] * mm,
                               lw=0.8, label=f"bearing at ({bearing.at_m[0]:g}, {bearing.at_m[1]:g}) m")
    r = float(np.max(run.bearing_displacement_max_m)) * mm
    artists.append(ax.add_patch(Circle((0.0, 0.0), r, fill=False, ls="--", color="0.4",
                                       label=f"largest bearing displacement {r:.4g} mm")))
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)
    ring = moat is not None and np.ndim(moat.gap_m) == 0
    ax.set_title("orbit in plan" + (" (each corner meets the ring along its arc)" if ring else
                                    " (each corner meets only the two walls on its sides)" if moat is not None
                                    else ""), fontsize=9)
    return artists


def _ring_arcs(ax: Any, moat: Any, outline: Any, u: np.ndarray, colours: list) -> list:
    """A circular moat as each corner meets it, in that corner's displacement (mm): the ring's arc
    ``|p + d| = R`` about where the corner started, wide enough for its orbit, in the corner's colour."""
    radius, mm = moat.radius_m(outline), 1e3
    reach = max(float(np.max(np.abs(u[:, :2]))) if u.size else 0.0, moat.gap_m) * 2.0 + 1e-3
    artists: list = []
    for k, (px, py) in enumerate(outline.corners_m()):
        at = np.arctan2(py, px)
        phi = at + np.linspace(-1.0, 1.0, 121) * min(np.pi, reach / radius)
        dx, dy = radius * np.cos(phi) - px, radius * np.sin(phi) - py
        artists += ax.plot(dx * mm, dy * mm, lw=1.5, color=colours[k] if k < len(colours) else "k",
                           ls="-", alpha=0.9, label="ring, as each corner meets it" if k == 0 else None)
    return artists


@fill_doc
def plot_moat_design(design: Any, ax: Any = None, gap_m: Optional[float] = None) -> list:
    """A :class:`~pounding.design.MoatDesign`: each pair's largest bearing displacement in plan at its most
    critical orientation (bars, the angle on each), the design value (the suite's mean or largest), the
    moat's demand (each pair's, dots, and the suite's, where the runs have it), when given the code's
    total maximum displacement with torsion, and a moat's gap to compare them with.

    Parameters
    ----------
    design : MoatDesign
        What :func:`pounding.design.moat_design` returned.
    {ax}
    gap_m : float, optional
        A moat's gap (its smallest), m, drawn across: the building's own, say.

    Returns
    -------
    list of matplotlib artists
        The bars and the lines.

    Examples
    --------
    >>> import pandas as pd
    >>> import pounding
    >>> from pounding.design import MoatDesign
    >>> runs = [("a", 0.0), ("a", 90.0), ("b", 0.0), ("b", 90.0)]
    >>> index = pd.MultiIndex.from_tuples(runs, names=["pair", "angle_deg"])
    >>> data = pd.DataFrame({"disp_max_m": [0.2, 0.3, 0.25, 0.22]}, index=index)
    >>> artists = pounding.plots.plot_moat_design(MoatDesign.of(data, None))
    >>> len(artists)  # two bars, the design value
    3
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(9.0, 3.8), constrained_layout=True)
    critical = design.critical
    mm = 1e3
    x = np.arange(len(critical))
    artists: list = list(ax.bar(x, critical["disp_max_m"].to_numpy() * mm, 0.6, color="C0",
                                label="largest bearing displacement in plan, its critical angle"))
    cases = critical["eccentricity"] if "eccentricity" in critical else [None] * len(critical)
    for k, (angle, value, case) in enumerate(zip(critical["angle_deg"], critical["disp_max_m"], cases)):
        label = f"{angle:g} deg" if case is None else f"{angle:g} deg\n{case}"
        ax.annotate(label, (k, value * mm), ha="center", va="bottom", fontsize=7)
    rule = design.attrs.get("rule", "")
    artists.append(ax.axhline(design.design_displacement_m * mm, color="C3", lw=1.5,
                              label=f"design ({rule}): {design.design_displacement_m * mm:.4g} mm"))
    if "moat_demand_m" in critical:
        artists.append(ax.plot(x, critical["moat_demand_m"].to_numpy() * mm, "o", color="C1", ms=5,
                               label="the moat's demand (its corners towards a wall)")[0])
        artists.append(ax.axhline(design.moat_demand_m * mm, color="C1", lw=1.2, ls=":",
                                  label=f"the moat's demand ({rule}): {design.moat_demand_m * mm:.4g} mm"))
    if design.code:
        d_tm = design.code["d_tm_m"] * mm
        artists.append(ax.axhline(d_tm, color="k", ls="--", lw=1.2,
                                  label=f"code D_TM with torsion: {d_tm:.4g} mm"))
    if gap_m is not None:
        gap = non_negative("gap_m", gap_m, "m") * mm
        artists.append(ax.axhline(gap, color="C2", lw=2.0, label=f"the moat's gap: {gap:.4g} mm"))
    ax.set_xticks(x, [str(name) for name in critical.index], rotation=30, ha="right", fontsize=7)
    ax.set_ylabel("displacement (mm)")
    ax.set_ylim(0.0, ax.get_ylim()[1] * 1.08)  # (room for the angles above the bars)
    ax.legend(fontsize=7, frameon=False, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # (beside the axes)
    return artists


__all__ = ["plot_moat_design", "plot_plan_orbit"]
