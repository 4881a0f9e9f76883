"""The bifurcation diagram: the section's samples against the frequency, up and down, over the
branches of periodic orbits at the same section."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc
from .._checks import integer, one_of
from .._errors import InputError, Problem
from .legend import place_legend

DIRECTION_COLOR = {"up": "C0", "down": "C3"}
DIRECTION_MARKER = {"up": "^", "down": "v"}


@fill_doc
def plot_bifurcation_diagram(diagram: Any, ax: Any = None, *, branches: Any = None, y: str = "displacement",
                             level: int = -1, **kwargs: Any) -> list:
    """A bifurcation diagram: each recorded stroboscopic sample (table phase 0) against the
    frequency, up and down in two colours; branches of periodic orbits under it at the same
    section, stable solid, unstable dashed.

    Parameters
    ----------
    diagram : BifurcationDiagram
        From :func:`pounding.bifurcation_diagram`.
    {ax}
    branches : Branch or sequence of Branch, optional
        From :func:`pounding.continuation` in ``freq_hz`` (their orbits' crossings of the section,
        ``Branch.section()``).
    y : {"displacement", "velocity"}
        What to draw of the section's state: displacement in mm (default) or velocity in m/s.
    level : int
        A structure's level drawn: its place along the diagram's ``level`` (default -1, the top;
        for a pair, the second's top).
    **kwargs
        Passed to the samples' markers (``ms``, ``alpha``, ...).

    Returns
    -------
    list of matplotlib artists
        The samples' markers (one per direction), then the branches' lines.

    Examples
    --------
    >>> import numpy as np, pounding
    >>> osc = pounding.presets.paper_damped()
    >>> freqs = np.arange(1.4, 2.05, 0.1)
    >>> diagram = pounding.bifurcation_diagram(osc, 0.05, freqs,
    ...     transient_cycles=30, record_cycles=10)
    >>> branch = pounding.continuation(osc, 0.05, (1.4, 2.0))
    >>> artists = pounding.plots.plot_bifurcation_diagram(diagram, branches=branch)
    >>> len(artists) > 2
    True
    """
    import matplotlib.pyplot as plt

    one_of("y", y, ("displacement", "velocity"))
    column, scale, label = {"displacement": ("strobe_displacement_m", 1e3, "D at table phase 0, mm"),
                            "velocity": ("strobe_velocity_m_s", 1.0, "V at table phase 0, m/s")}[y]
    if ax is None:
        ax = plt.figure(figsize=(7, 4), constrained_layout=True).add_subplot()
    ds = diagram.data
    where = ""
    if "level" in ds.dims:
        level = integer("level", level, -ds.sizes["level"], ds.sizes["level"] - 1,
                        "give a level's place along the diagram's level")
        if branches is not None:  # (a branch's section is its first moving mass's)
            model = diagram.oscillator
            fixed = (model.structures[0] if hasattr(model, "structures") else model).fixed
            first = 1 if fixed else 0  # (the first structure's levels come first along level)
            if level % ds.sizes["level"] != first:
                raise InputError(Problem.BAD_STATE, "level", level,
                                 why="is not the mass the branches' section is of (the first structure's "
                                     "first moving level)", fix=f"draw the branches with level={first}")
        ds = ds.isel(level=level)
        prefix = "" if len(set(diagram.data["level_structure"].values.tolist())) == 1 else \
            f"{ds['level_structure'].item()}'s "
        where = f", {prefix}level {int(ds['level_number'])}"
        label = label.replace("D at", "x at").replace("V at", "v at")
    style = dict(ms=3, alpha=0.8, linestyle="none") | kwargs
    artists: list = []
    for d in ds["direction"].values.tolist():
        values = ds[column].sel(direction=d).values * scale  # (freq_hz, cycle)
        freqs = np.broadcast_to(ds["freq_hz"].values[:, None], values.shape)
        keep = np.isfinite(values)
        artists += ax.plot(freqs[keep], values[keep], DIRECTION_MARKER[d], color=DIRECTION_COLOR[d],
                           mfc="none", label=f"sweep {d}", **style)
    if branches is not None:
        for k, br in enumerate([branches] if hasattr(branches, "section") else list(branches)):
            sec = br.section(0.0)
            values = sec[f"{y}_m" if y == "displacement" else "velocity_m_s"].to_numpy() * scale
            for stable, ls in ((True, "-"), (False, "--")):
                # (a period-k orbit crosses the section k times: its crossings as dots, not a line)
                fmt = ls if br.period_multiple == 1 else ("." if stable else "x")
                shown = np.where(sec["stable"].to_numpy() == stable, values, np.nan)
                artists += ax.plot(sec["freq_hz"], shown, fmt, color="0.35", lw=1.0, ms=2,
                                   label=f"branch, {'stable' if stable else 'unstable'}" if k == 0 else None)
    ax.set_xlabel("f [Hz]")
    ax.set_ylabel(label)
    ax.set_title(f"Bifurcation diagram, a_G = {diagram.a_g:g} g{where}", fontsize="medium")
    place_legend(ax, fontsize="small")
    return artists
