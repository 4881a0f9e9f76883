"""Plots of sweeps, one for every system: alpha and eta against nu (a single mass, paper Figs. 4-5), each
level's alpha and each wall side's contacts per cycle (several levels); hysteresis loops (Figs. 7, 15)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .._docs import fill_doc
from .legend import place_legend

if TYPE_CHECKING:  # pragma: no cover
    from ..metrics import HysteresisLoop
    from ..protocols.campaign import CampaignResult
    from ..protocols.sweep_result import SweepResult

DIRECTION_STYLE = {"up": {"ls": "-", "marker": "^"}, "down": {"ls": "--", "marker": "v"}}


def plot_sweep(sweeps: "SweepResult | Sequence[SweepResult]", ax: Any = None, *,
               label: str | None = None, color: Any = None) -> list:
    """A sweep against nu, for every system: alpha (top) and eta, or e without bumpers (bottom), of a
    single mass (paper Figs. 4-5); each level's alpha (top) and each wall side's or link's contacts per
    cycle (bottom, with contacts) of a system of several levels.

    Up sweeps are drawn solid with upward markers, down sweeps dashed with downward ones.

    Parameters
    ----------
    sweeps : SweepResult or sequence of them
        E.g. ``[up, down]`` of the same system and a_G (every one of one level, or every one of several).
    ax : matplotlib Axes or pair of them, optional
        ``(ax_alpha, ax_bottom)``, or one Axes for alpha alone (several levels); a new figure if omitted.
    label : str, optional
        Legend label prefix (one level; default ``a_G = ...``), or what each line's label says in its
        brackets (several levels: with the a_G where the sweeps' differ, and the direction).
    color : optional
        One colour for all the sweeps given (default: one per a_G; several levels: one per level and
        per contact slot, the a_G told by the markers).

    Returns
    -------
    list of matplotlib artists
        The sweeps' lines in both panels (one level: the unsteady steps' circles, the line eta = 1).

    Examples
    --------
    Up and down sweeps of the damped paper system at a_G = 0.05, three frequencies of ten cycles:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> sweeps = [pounding.sweep(osc, 0.05, [1.5, 2.0, 2.5], direction,
    ...                          steady="fixed", cycles=10,
    ...                          measure_cycles=2) for direction in ("up", "down")]
    >>> artists = pounding.plots.plot_sweep(sweeps)
    >>> len(artists) > 0
    True

    A two-level building's sweep: each level's alpha (no contacts: no bottom panel).

    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=4.0e3)
    >>> b = pounding.Structure(2.0e3, iso, [pounding.Storey(1.0e3, 2.0e6, 2.0e3)])
    >>> len(pounding.plots.plot_sweep(pounding.sweep(b, 0.1, [1.0, 1.5, 2.0])))
    2
    """
    from .._errors import InputError, Problem

    if not isinstance(sweeps, Sequence):
        sweeps = [sweeps]
    several = {len(sw.levels) > 1 for sw in sweeps}
    if len(several) > 1:
        raise InputError(Problem.WRONG_MODE, "sweeps", "single masses and structures of several levels",
                         mode="sweeps of one kind",
                         fix="plot a single mass's sweeps and a building's on separate axes")
    if several == {True}:
        return _plot_levels(sweeps, ax, label, color)
    return _plot_one_level(sweeps, ax, label, color)


def _plot_one_level(sweeps: Sequence, ax: Any, label: str | None, color: Any) -> list:
    """A single mass's sweeps (``plot_sweep``): alpha and eta (e without bumpers) against nu."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
    ax_a, ax_e = ax
    artists: list = []
    colours: dict[float, Any] = {}
    for sw in sweeps:
        df = sw.to_dataframe().iloc[: sw.steps_done].sort_values("freq_hz")
        c = color if color is not None else colours.setdefault(sw.a_g, f"C{len(colours)}")
        style = DIRECTION_STYLE[sw.direction]
        text = f"{label or f'a_G = {sw.a_g:g}'} ({sw.direction})"
        has_gap = bool(sw.contact_slots)  # (a single mass's bumpers: its wall)
        y = df["eta"] if has_gap else df["e"]
        artists += ax_a.plot(df["nu"], df["alpha"], color=c, ms=4, label=text, **style)
        artists += ax_e.plot(df["nu"], y, color=c, ms=4, label=text, **style)
        unsteady = ~df["steady"].to_numpy(dtype=bool)
        if np.any(unsteady):
            artists.append(ax_a.scatter(df["nu"][unsteady], df["alpha"][unsteady], s=40,
                                        facecolors="none", edgecolors="k", lw=0.8, zorder=3))
    ax_a.set_ylabel("alpha = max|a_abs| / A_t [-]")
    kinds = {bool(sw.contact_slots) for sw in sweeps}
    ax_e.set_ylabel("eta = E / Delta [-]" if kinds == {True} else
                    "e = E / D_tmax [-]" if kinds == {False} else "eta (YBs) / e (NBs) [-]")
    ax_e.set_xlabel("nu = f / f_R [-]")
    if any(sw.contact_slots for sw in sweeps):
        artists.append(ax_e.axhline(1.0, color="0.5", lw=0.8, ls=":"))
    place_legend(ax_a, fontsize="small")
    return artists


def plot_lab_sweep(lab: Any, ax: Any = None, *, label: str | None = None, color: Any = None) -> list:
    """A measured sweep (:class:`pounding.lab.LabSweep`) as :func:`plot_sweep` draws a model's:
    alpha (top) and eta, or e without a gap (bottom), against nu; markers only (measured
    points), hollow where the step was not steady.

    Parameters
    ----------
    lab : LabSweep
        From :func:`pounding.lab.analyse_stepped_sine`.
    ax : pair of matplotlib Axes, optional
        ``(ax_alpha, ax_excursion)``, e.g. those of :func:`plot_sweep` to overlay the model.
    label : str, optional
        Legend label (default ``lab, a_G = ...``).
    color : matplotlib color, optional
        The markers' colour (default black).

    Returns
    -------
    list of matplotlib artists
        The measured points in both panels, the unsteady steps' circles.

    Examples
    --------
    A synthetic stepped-sine test of the damped paper system (three steps of ten cycles),
    analysed as a measured one:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> record = pounding.lab.synthetic_test(osc, 0.05, [1.5, 2.0, 2.5], cycles=10)
    >>> lab = pounding.lab.analyse_stepped_sine(record, mass_kg=500.0,
    ...                                         gap_total_m=0.03)
    >>> artists = pounding.plots.plot_lab_sweep(lab)
    >>> len(lab.steps), len(artists) > 0
    (3, True)
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
    ax_a, ax_e = ax
    df = lab.steps.sort_values("freq_hz")
    style = {"ls": "none", "marker": "o", "ms": 5, "color": color if color is not None else "k"}
    text = label or f"lab, a_G = {lab.a_g:.3g} ({lab.direction})"
    y = df["eta"] if lab.gap_total_m is not None else df["e"]
    artists = list(ax_a.plot(df["nu"], df["alpha"], label=text, **style))
    artists += ax_e.plot(df["nu"], y, label=text, **style)
    unsteady = ~df["steady"].to_numpy(dtype=bool)
    if np.any(unsteady):
        artists.append(ax_a.scatter(df["nu"][unsteady], df["alpha"][unsteady], s=60, facecolors="white",
                                    edgecolors=style["color"], zorder=3))
    ax_a.set_ylabel("alpha = max|a_abs| / A_t [-]")
    ax_e.set_ylabel("eta = E / Delta [-]" if lab.gap_total_m is not None else "e = E / D_tmax [-]")
    ax_e.set_xlabel("nu = f / f_R [-]")
    place_legend(ax_a, fontsize="small")
    return artists


@fill_doc
def plot_hysteresis(loop: "HysteresisLoop", ax: Any = None, *, per: str = "total_gap",
                    **line_kwargs: Any) -> list:
    """``r = F_I / (M g)`` against ``d`` (paper Figs. 7 and 15).

    Parameters
    ----------
    loop : HysteresisLoop
        From :meth:`SweepResult.hysteresis_loop`.
    {ax}
    per : {"total_gap", "half_gap"}
        ``d = D / Delta`` (the paper's definition, Sect. 3.3: symmetric bumpers at +-0.5), or
        ``d = D / (Delta / 2)`` (bumpers at +-1, where the paper's Figs. 7 and 15 draw them).
    **line_kwargs
        Passed to ``ax.plot``.

    Returns
    -------
    list of matplotlib artists
        The loop's line, the bumpers' surfaces.

    Examples
    --------
    The loop of the damped paper system at a_G = 0.05 and 1.5 Hz, where it hits both bumpers:

    >>> import pounding
    >>> up = pounding.sweep(pounding.presets.paper_damped(), 0.05, [1.5],
    ...                     steady="fixed", cycles=10, measure_cycles=2)
    >>> artists = pounding.plots.plot_hysteresis(up.hysteresis_loop(1.5),
    ...                                          per="half_gap")
    >>> len(artists)  # the loop and the two bumpers' surfaces
    3
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(5, 4), constrained_layout=True)
    line_kwargs.setdefault("lw", 1.0)
    line_kwargs.setdefault("label", f"a_G = {loop.a_g:g}, f = {loop.freq_hz:g} Hz")
    from .._checks import one_of

    scale = {"total_gap": 1.0, "half_gap": 2.0}[one_of("per", per, ("total_gap", "half_gap"))]
    artists = list(ax.plot(scale * loop.d, loop.r, **line_kwargs))
    for x in loop.bumper_surfaces_d or ():  # where contact begins with relaxed bumpers
        artists.append(ax.axvline(scale * x, color="0.6", lw=0.6, ls=":"))
    ax.set_xlabel("d = D / Delta [-]" if per == "total_gap"
                  else "d = 2 D / Delta [-] (bumpers at +-1, as the paper's figures)")
    ax.set_ylabel("r = F_I / (M g) [-]")
    place_legend(ax, fontsize="small")
    return artists


def plot_campaign(result: "CampaignResult", ax: Any = None) -> list:
    """alpha (top) and eta or e (bottom) against nu, NBs left and YBs right (Figs. 4-5).

    Parameters
    ----------
    result : CampaignResult
        From :func:`pounding.campaign`.
    ax : 2-by-n array of matplotlib Axes, optional
        One column per configuration in the campaign; a new figure if omitted.

    Returns
    -------
    list of matplotlib artists
        Those of :func:`plot_sweep`, for every sweep.

    Examples
    --------
    A tiny campaign of the damped paper system without and with bumpers: one a_G, up only, two
    frequencies of ten cycles:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> result = pounding.campaign(osc.without_bumpers(), osc, nbs_a_g=[0.05],
    ...                            ybs_a_g=[0.05],
    ...                            freqs_hz=[1.5, 2.0], directions=["up"],
    ...                            steady="fixed", cycles=10, measure_cycles=2)
    >>> artists = pounding.plots.plot_campaign(result)
    >>> len(artists) > 0
    True
    """
    import matplotlib.pyplot as plt

    confs = list(dict.fromkeys(key[0] for key in result.sweeps))
    if ax is None:
        _, ax = plt.subplots(2, len(confs), figsize=(6 * len(confs), 6), sharex=True,
                             squeeze=False, constrained_layout=True)
    ax = np.asarray(ax).reshape(2, len(confs))
    a_gs = sorted({key[1] for key in result.sweeps})
    artists: list = []
    for j, conf in enumerate(confs):
        for (c, ag, d), sw in result.sweeps.items():
            if c != conf:
                continue
            if len(sw.levels) > 1:  # (a structure's sweep: its top floor above, its base below)
                order = np.argsort(sw.freqs_hz)
                style = {"color": f"C{a_gs.index(ag)}", "marker": ".", "ls": "-" if d == "up" else "--",
                         "label": f"{ag:g} g {d}"}
                artists += ax[0, j].plot(sw.nu[order], sw.alpha_top[order], **style)
                artists += ax[1, j].plot(sw.nu[order], sw.alpha_base[order], **style)
                ax[0, j].set_ylabel("alpha of the top floor")
                ax[1, j].set_ylabel("alpha of the base")
                ax[1, j].set_xlabel("nu = f / f_R")
                ax[0, j].legend(fontsize="small")
            else:
                artists += plot_sweep(sw, ax=(ax[0, j], ax[1, j]), color=f"C{a_gs.index(ag)}")
        ax[0, j].set_title(conf)
    return artists


def plot_structure_sweep_levels(result: "SweepResult", ax: Any = None) -> list:
    """``plot_structure_sweep``, :func:`plot_sweep`'s name before for a structure's sweep (for one release,
    through ``pounding.plots``): each level's alpha and each contact slot's contacts per cycle, as it drew
    them, a one-level structure's too."""
    return _plot_levels([result], ax)


def _plot_levels(sweeps: Sequence, ax: Any, label: str | None = None, color: Any = None) -> list:
    """Sweeps of several levels (``plot_sweep``): each level's alpha against nu and, with contacts, each
    wall side's (or link's) contacts per cycle; each sweep's direction in its line style."""
    import matplotlib.pyplot as plt

    from ..protocols.sweep_window import level_name, slot_name

    slots = any(sw.contact_slots for sw in sweeps)
    if ax is None:
        if slots:
            _, (ax_a, ax_c) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
        else:
            _, ax_a = plt.subplots(figsize=(7, 4), constrained_layout=True)
            ax_c = None
    elif isinstance(ax, (list, tuple, np.ndarray)):
        ax_a, ax_c = ax
    else:
        ax_a, ax_c = ax, None
    artists: list = []
    a_gs = len({sw.a_g for sw in sweeps}) > 1
    for sw in sweeps:
        order = np.argsort(sw.freqs_hz)
        nu = sw.nu[order]
        ls = DIRECTION_STYLE[sw.direction]["ls"] if len(sweeps) > 1 else "-"
        marker = "." if not a_gs else "os^vD<>"[sorted({w.a_g for w in sweeps}).index(sw.a_g) % 7]
        said = [x for x in (label, f"a_G = {sw.a_g:g}" if a_gs else None,
                            sw.direction if len(sweeps) > 1 else None) if x]
        tag = f" ({', '.join(said)})" if said else ""
        for q in range(len(sw.levels)):
            artists += ax_a.plot(nu, sw.alpha[order, q], marker=marker, ls=ls,
                                 color=color if color is not None else f"C{q % 10}",
                                 label=level_name(sw.levels, q) + tag)
        if ax_c is not None:
            for c in range(len(sw.contact_slots)):
                artists += ax_c.plot(nu, sw.contacts_per_cycle[order, c], marker=marker, ls=ls,
                                     color=color if color is not None else f"C{c % 10}",
                                     label=slot_name(sw.contact_slots, c) + tag)
    first = sweeps[0]
    ax_a.set_ylabel("alpha = max|a_abs| / A_t")
    ax_a.set_title(f"Sweep {' and '.join(dict.fromkeys(sw.direction for sw in sweeps))}, "
                   f"a_G = {', '.join(dict.fromkeys(f'{sw.a_g:g}' for sw in sweeps))} g"
                   if len(sweeps) > 1 else f"Sweep {first.direction}, a_G = {first.a_g:g} g")
    ax_a.legend(fontsize="small")
    ax_a.grid(True, alpha=0.3)
    if ax_c is not None:
        ax_c.set_ylabel("contacts per cycle")
        ax_c.legend(fontsize="small")
        ax_c.grid(True, alpha=0.3)
        ax_c.set_xlabel("nu = f / f_R")
    else:
        ax_a.set_xlabel("nu = f / f_R")
    return artists
