"""A structure's run: each level's response against time, and its peak envelopes over the height."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .._units import GRAVITY_M_S2

if TYPE_CHECKING:
    from ..engine.structure_result import StructureRun


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
    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02],
    ...                         damping_n_s_m=2.0e4)
    >>> moat = pounding.Wall(0, 0.05, 0.05, pounding.KelvinVoigt(2.0e8, 1.0e5))
    >>> b = pounding.Structure(3.0e4, iso, [pounding.Storey(2.0e4, 4.0e7)] * 3,
    ...                        [moat])
    >>> run = pounding.simulate(b, pounding.Harmonic(0.3, 1.2), 5.0)
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
