"""Plots of branches of periodic orbits: a quantity against the continued parameter, stable
orbits solid and unstable ones dashed, bifurcations marked, sweeps over it."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Optional

import numpy as np

from .._docs import fill_doc
from .._errors import InputError, Problem
from ._labels import A_G_LABEL
from .legend import place_legend

# marker and short label of each bifurcation kind
MARKS = {"fold": ("s", "F"), "branch-point": ("D", "BP"), "period-doubling": ("o", "PD"),
         "neimark-sacker": ("*", "NS"), "grazing": ("x", "G")}


@fill_doc
def plot_branch(branch: Any, ax: Any = None, *, y: str = "alpha", x: Optional[str] = None,
                sweeps: Any = None, **kwargs: Any) -> list:
    """A branch: ``y`` against the parameter, stable solid, unstable dashed, bifurcations marked.

    Parameters
    ----------
    branch : Branch or sequence of Branch
        From :func:`pounding.continuation` (several: e.g. a branch and its period-doubled one).
    {ax}
    y : str
        A column of ``Branch.to_dataframe()``: ``"alpha"`` (default), ``"eta"``,
        ``"excursion_m"``, ``"max_abs_multiplier"``, ...
    x : str, optional
        The abscissa: default ``"nu"`` for a frequency branch (as the sweeps' plots), else the
        parameter's column.
    sweeps : SweepResult or sequence of them, optional
        Drawn over the branch as markers (up sweeps ``^``, down sweeps ``v``), to compare.
    **kwargs
        Passed to the branch's lines (``color``, ``lw``, ...).

    Returns
    -------
    list of matplotlib artists
        The branch's lines, the bifurcations' markers and labels, the sweeps' markers.

    Examples
    --------
    The damped paper system's branch at a_G = 0.05, its folds and grazings marked, with an up
    sweep over it:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> branch = pounding.continuation(osc, 0.05, (1.5, 2.5))
    >>> up = pounding.sweep(osc, 0.05, [1.5, 2.0, 2.5], steady="fixed", cycles=10,
    ...                     measure_cycles=2)
    >>> artists = pounding.plots.plot_branch(branch, sweeps=up)
    >>> len(artists) > 0
    True
    """
    import matplotlib.pyplot as plt
    from matplotlib import cbook
    from matplotlib.lines import Line2D

    kwargs = cbook.normalize_kwargs(kwargs, Line2D)
    branches = list(branch) if isinstance(branch, Sequence) else [branch]
    if ax is None:
        ax = plt.figure(figsize=(7, 4), constrained_layout=True).add_subplot()
    artists: list = []
    for k, br in enumerate(branches):
        df = br.to_dataframe()
        xcol = x or ("nu" if br.parameter == "freq_hz" else br.parameter)
        for col in (xcol, y):
            if col not in df.columns:
                raise InputError(Problem.NOT_IN_RESULT, "y" if col == y else "x", col,
                                 choices=", ".join(df.columns))
        xs, ys = df[xcol].to_numpy(float), df[y].to_numpy(float)
        stable = df["stable"].to_numpy(bool)
        color = kwargs.pop("color", None) or f"C{k}"
        label = f"period {br.period_multiple} branch" if len(branches) > 1 else "branch"
        # runs of equal stability, each drawn with its neighbour's point so the line is unbroken
        cuts = np.flatnonzero(np.diff(stable.astype(int))) + 1
        starts = np.concatenate(([0], cuts))
        ends = np.concatenate((cuts, [stable.size]))
        seen = set()
        for s, e in zip(starts, ends):
            st = bool(stable[s])
            lab = f"{label}, {'stable' if st else 'unstable'}" if st not in seen else None
            seen.add(st)
            sl = slice(s, min(e + 1, stable.size))
            artists += ax.plot(xs[sl], ys[sl], color=color, linestyle="-" if st else "--", label=lab,
                               **kwargs)
        col_of = {"nu": lambda b: b.freq_hz / br.f_ref_hz, "freq_hz": lambda b: b.freq_hz,
                  "a_g": lambda b: b.a_g}
        labelled = set()
        for bif in br.bifurcations:
            marker, short = MARKS.get(bif.kind, ("o", bif.kind))
            bx = col_of[xcol](bif) if xcol in col_of else bif.value
            by = bif.alpha if y == "alpha" else np.interp(bif.index - 0.5, np.arange(len(ys)), ys)
            artists += ax.plot([bx], [by], marker, color="k", mfc="none" if bif.kind != "grazing" else "k",
                               ms=7, label=bif.kind if bif.kind not in labelled else None)
            labelled.add(bif.kind)
            artists.append(ax.annotate(short, (bx, by), textcoords="offset points", xytext=(4, 4),
                                       fontsize="x-small"))
        ax.set_xlabel({"nu": "nu = f / f_R [-]", "freq_hz": "f [Hz]", "a_g": A_G_LABEL}.get(xcol, xcol))
    ax.set_ylabel({"alpha": "alpha = max|a_abs| / A_t [-]", "eta": "eta = E / Delta [-]"}.get(y, y))
    if sweeps is not None:
        from .sweep import DIRECTION_STYLE

        for sw in (list(sweeps) if isinstance(sweeps, Sequence) else [sweeps]):
            df = sw.to_dataframe().iloc[: sw.steps_done]
            if y not in df.columns:
                raise InputError(Problem.NOT_IN_RESULT, "y", y, choices=", ".join(df.columns))
            xcol = x or "nu"
            artists += ax.plot(df[xcol] if xcol in df.columns else df["freq_hz"], df[y],
                               DIRECTION_STYLE[sw.direction]["marker"], color="0.3", ms=5, mfc="none",
                               label=f"sweep {sw.direction}, a_G = {sw.a_g:g}")
    place_legend(ax, fontsize="small")
    return artists
