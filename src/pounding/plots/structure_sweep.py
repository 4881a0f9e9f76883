"""A structure's sweep: each level's alpha against the frequency ratio, and the contacts per cycle."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..protocols.structure_sweep_result import StructureSweepResult


def plot_structure_sweep(result: "StructureSweepResult", ax: Any = None) -> list:
    """Each level's alpha (its absolute acceleration peak over the table's) against ``nu``, and below it,
    when the structure has contacts, each wall side's (or link's) contacts per cycle.

    Parameters
    ----------
    result : StructureSweepResult
        A result of :func:`pounding.sweep` for a :class:`~pounding.Structure` or :class:`~pounding.Adjacent`.
    ax : matplotlib Axes or sequence of two, optional
        Where to draw alpha (and the contacts); a new figure if omitted.

    Returns
    -------
    list of matplotlib artists

    Examples
    --------
    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=4.0e3)
    >>> b = pounding.Structure(2.0e3, iso, [pounding.Storey(1.0e3, 2.0e6, 2.0e3)])
    >>> res = pounding.sweep(b, 0.1, [1.0, 1.5, 2.0])
    >>> len(pounding.plots.plot_structure_sweep(res)) > 0
    True
    """
    import matplotlib.pyplot as plt
    import numpy as np

    from ..protocols.structure_sweep_result import level_name, slot_name

    order = np.argsort(result.freqs_hz)
    nu = result.nu[order]
    slots = result.contact_slots
    if ax is None:
        if slots:
            _, (ax_a, ax_c) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
        else:
            _, ax_a = plt.subplots(figsize=(7, 4), constrained_layout=True)
            ax_c = None
    elif isinstance(ax, (list, tuple)):
        ax_a, ax_c = ax
    else:
        ax_a, ax_c = ax, None
    artists: list = []
    for q in range(len(result.levels)):
        artists += ax_a.plot(nu, result.alpha[order, q], marker=".", label=level_name(result.levels, q))
    ax_a.set_ylabel("alpha = max|a_abs| / A_t")
    ax_a.set_title(f"Sweep {result.direction}, a_G = {result.a_g:g} g")
    ax_a.legend(fontsize="small")
    ax_a.grid(True, alpha=0.3)
    if ax_c is not None:
        for c in range(len(slots)):
            artists += ax_c.plot(nu, result.contact_metrics[order, c, 0], marker=".",
                                 label=slot_name(slots, c))
        ax_c.set_ylabel("contacts per cycle")
        ax_c.legend(fontsize="small")
        ax_c.grid(True, alpha=0.3)
        ax_c.set_xlabel("nu = f / f_R")
    else:
        ax_a.set_xlabel("nu = f / f_R")
    return artists
