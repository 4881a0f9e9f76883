"""Plots of one run of any system: a single mass's, a structure's (every level, the peak envelopes over
the height) and two adjacent structures' (the linked levels and their separation against each gap)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from .._units import GRAVITY_M_S2

if TYPE_CHECKING:  # pragma: no cover
    from ..engine.adjacent_result import AdjacentRun
    from ..engine.result import Run
    from ..engine.structure_result import StructureRun


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


def plot_structure_run(run: "StructureRun", axes: Any = None, *, levels: Any = None) -> list:
    """Displacements (mm) and absolute accelerations (g) of the levels against time, the contacts marked,
    and the exact peak envelopes over the height.

    Parameters
    ----------
    run : StructureRun
        A result of :func:`pounding.simulate` for a :class:`~pounding.Structure`.
    axes : sequence of three matplotlib Axes, optional
        Where to draw the displacements, the accelerations and the envelopes (a new figure if omitted).
    levels : sequence of int, optional
        The levels whose histories are drawn (default: every level, at most 6: the base, the top and
        those between, evenly).

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    The paper's rig as a structure, its bumpers each on a steel stand of its own (the mass, level 0, and
    the two stands):

    >>> import pounding
    >>> rig = pounding.presets.paper_rig_stands()
    >>> run = pounding.simulate(rig, pounding.Harmonic(0.05, 2.0), 3.0)
    >>> len(pounding.plots.plot_structure_run(run)) > 0
    True
    """
    import matplotlib.lines
    import matplotlib.pyplot as plt

    n = run.structure.n_levels
    if axes is None:
        fig = plt.figure(figsize=(10, 5.5), constrained_layout=True)
        grid = fig.add_gridspec(2, 2, width_ratios=(3, 1))
        axes = [fig.add_subplot(grid[0, 0]), None, fig.add_subplot(grid[:, 1])]
        axes[1] = fig.add_subplot(grid[1, 0], sharex=axes[0])
    ax_d, ax_a, ax_e = axes
    if levels is None:
        levels = sorted({int(round(x)) for x in np.linspace(0, n - 1, min(n, 6))})
    else:
        from .._checks import integer

        levels = [integer(f"levels[{k}]", lv, 0, n - 1, fix=f"give levels from 0 to {n - 1}")
                  for k, lv in enumerate(levels)]
    ground = "ground" if run.structure.fixed else "base"
    artists: list = []
    for i in levels:
        name = ground if i == 0 else f"floor {i}"
        artists += ax_d.plot(run.t, run.displacement[:, i] * 1e3, lw=0.9, label=name)
        artists += ax_a.plot(run.t, run.abs_acceleration[:, i] / GRAVITY_M_S2, lw=0.8, label=name)
    starts = run.contacts["t_start_s"].to_numpy()
    for t in starts:
        artists.append(ax_d.axvline(t, color="0.6", lw=0.5, ls=":"))
    ax_d.set_ylabel("displacement [mm]")
    ax_a.set_ylabel("absolute acceleration [g]")
    ax_a.set_xlabel("t [s]")
    handles, labels = ax_d.get_legend_handles_labels()
    if len(starts):
        handles.append(matplotlib.lines.Line2D([], [], color="0.6", lw=0.8, ls=":"))
        labels.append(f"contact starts ({len(starts)})")
    ax_d.legend(handles, labels, fontsize="small", ncol=min(len(labels), 4), loc="lower center",
                bbox_to_anchor=(0.5, 1.0), frameon=False)
    height = np.concatenate([[0.0], np.cumsum([s.height_m for s in run.structure.storeys])])
    peak_d = np.maximum(np.abs(run.displacement_max), np.abs(run.displacement_min))
    artists += ax_e.plot(peak_d * 1e3, height, "o-", color="C0", label="|displacement| [mm]")
    twin = ax_e.twiny()
    artists += twin.plot(run.abs_acceleration_max / GRAVITY_M_S2, height, "s--", color="C3",
                         label="|absolute acceleration| [g]")
    ax_e.set_xlabel("peak |displacement| [mm]", color="C0")
    twin.set_xlabel("peak |absolute acceleration| [g]", color="C3")
    ax_e.set_ylabel("level (at its height)")
    ax_e.set_yticks(height, [ground] + [f"{i}" for i in range(1, n)] if n <= 12 else None)
    ax_e.set_xlim(left=0.0)
    twin.set_xlim(left=0.0)
    return artists


def plot_adjacent_run(run: "AdjacentRun", axes: Any = None) -> list:
    """For each link: the two levels' displacements against time (mm), and below, the first's less the
    second's against the gap (dashed), the contacts marked.

    Parameters
    ----------
    run : AdjacentRun
        A result of :func:`pounding.simulate` for :class:`~pounding.Adjacent` structures.
    axes : sequence of two matplotlib Axes, optional
        Where to draw (a new figure if omitted).

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    A one-storey isolated building beside a one-storey fixed-base one, 5 cm apart at their roofs:

    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[4.0e6], breakpoints_m=[],
    ...                         damping_n_s_m=2.0e4)
    >>> pair = pounding.Adjacent(
    ...     pounding.Structure(3.0e4, iso, [pounding.Storey(2.0e4, 4.0e7)]),
    ...     pounding.Structure.fixed_base([pounding.Storey(2.5e4, 3.0e7, 5.0e4)]),
    ...     [pounding.Link(1, 1, 0.05, pounding.KelvinVoigt(5.0e8, 2.0e5))])
    >>> run = pounding.simulate(pair, pounding.Harmonic(0.4, 1.0), 5.0)
    >>> len(pounding.plots.plot_adjacent_run(run)) > 0
    True
    """
    import matplotlib.pyplot as plt

    if axes is None:
        _, axes = plt.subplots(2, 1, figsize=(8, 5), sharex=True, constrained_layout=True)
    ax_x, ax_s = axes
    artists: list = []
    for j, link in enumerate(run.adjacent.links):
        first = run.first.displacement[:, link.level_first] * 1e3
        second = run.second.displacement[:, link.level_second] * 1e3
        artists += ax_x.plot(run.t, first, lw=0.9, color=f"C{2 * j}",
                             label=f"first, level {link.level_first}")
        artists += ax_x.plot(run.t, second, lw=0.9, color=f"C{2 * j + 1}",
                             label=f"second, level {link.level_second}")
        artists += ax_s.plot(run.t, first - second, lw=0.9, color=f"C{2 * j}",
                             label=f"link {j}: first less second")
        artists.append(ax_s.axhline(link.gap_m * 1e3, color=f"C{2 * j}", ls="--", lw=0.8))
    hits = run.links
    if len(hits):
        gaps_mm = [run.adjacent.links[k].gap_m * 1e3 for k in hits["link"]]
        artists += ax_s.plot(hits["t_start_s"], gaps_mm, "v",
                             color="k", ms=4, label=f"contacts ({len(hits)})")
    ax_x.set_ylabel("displacement [mm]")
    ax_s.set_ylabel("separation closed [mm]")
    ax_s.set_xlabel("t [s]")
    ax_x.legend(fontsize="small", ncol=2, loc="upper right")
    ax_s.legend(fontsize="small", loc="lower right")
    ax_s.set_title("the levels' relative displacement; dashed: the gap, where they meet", fontsize="medium")
    return artists
