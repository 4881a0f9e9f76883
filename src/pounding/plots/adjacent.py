"""Two adjacent structures' run: the linked levels' motion and their separation against each gap."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..engine.adjacent_result import AdjacentRun


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
    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02],
    ...                         damping_n_s_m=2.0e4)
    >>> isolated = pounding.Structure(3.0e4, iso,
    ...                               [pounding.Storey(2.0e4, 4.0e7)] * 3)
    >>> old = pounding.Structure.fixed_base(
    ...     [pounding.Storey(2.5e4, 3.0e7, 5.0e4)] * 3)
    >>> roof = pounding.Link(3, 3, 0.15, pounding.KelvinVoigt(5.0e8, 2.0e5))
    >>> run = pounding.simulate(pounding.Adjacent(isolated, old, [roof]),
    ...                         pounding.Harmonic(a_g=0.4, freq_hz=1.0), 10.0)
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
