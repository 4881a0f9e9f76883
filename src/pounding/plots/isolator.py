"""The isolator's loop of one run of any system: its force against the base's displacement."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from .._checks import real
from .._errors import InputError, Problem
from .legend import place_legend


def plot_isolator_loop(run: Any, ax: Any = None, *, t_start_s: Optional[float] = None,
                       t_end_s: Optional[float] = None, **line: Any) -> list:
    """The isolator's force (kN) against the base's displacement (mm) over a run: its hysteresis loop.

    A friction isolator's slips run along its slip lines, ``+-mu W`` off the pendulum's ``(W / R) D``
    (dotted; with a velocity dependence ``+-mu_fast W`` dashed too), and its sticks are vertical: the force
    changes while the base stays put.  The walls at the base (a single mass's bumpers, a building's moat)
    are drawn where their gaps close.

    Parameters
    ----------
    run : Run or StructureRun
        A result of :func:`pounding.simulate` with samples (``sample_rate_hz > 0``), of a system with an
        isolated base.
    ax : matplotlib Axes, optional
        Where to draw (a new figure if omitted).
    t_start_s, t_end_s : float, optional
        The part of the run drawn, s (default: all of it; a steady cycle's loop is the last period).
    **line
        Passed to ``ax.plot`` for the loop.

    Returns
    -------
    list of matplotlib artists
        The loop's line, then the slip lines (two, or four with ``mu_fast``) and the walls' gaps where there
        are any.

    Examples
    --------
    A mass on a friction pendulum shaken at 0.2 g, 0.6 Hz, its last two cycles:

    >>> import pounding
    >>> osc = pounding.Oscillator(500.0, pounding.FrictionIsolator(mu=0.1,
    ...                                                             radius_m=1.5))
    >>> run = pounding.simulate(osc, pounding.Harmonic(0.2, 0.6), duration=20.0)
    >>> artists = pounding.plots.plot_isolator_loop(run, t_start_s=20.0 - 2 / 0.6)
    >>> len(artists)  # the loop and the two slip lines
    3
    """
    import matplotlib.pyplot as plt

    levels = getattr(run, "levels", run)  # (a single mass's run: its one-level structure's)
    structure = getattr(levels, "structure", None)
    if structure is None or not hasattr(levels, "isolator_force"):
        raise InputError(Problem.WRONG_MODE, "run", type(run).__name__,
                         mode="one structure's or one mass's run",
                         fix="plot run.first or run.second of a pair")
    if structure.fixed:
        raise InputError(Problem.WRONG_MODE, "run", "a fixed base", mode="an isolated base",
                         fix="a fixed-base building has no isolator to draw")
    t = np.asarray(levels.t, dtype=float)
    if t.size < 2:
        raise InputError(Problem.BAD_STATE, "run", f"{t.size} samples", why="has no histories to draw",
                         fix="simulate with sample_rate_hz > 0 (the default samples at 1 kHz)")
    t0 = float(t[0]) if t_start_s is None else real("t_start_s", t_start_s)
    t1 = float(t[-1]) if t_end_s is None else real("t_end_s", t_end_s)
    inside = (t >= t0) & (t <= t1)
    if inside.sum() < 2:
        raise InputError(Problem.BAD_STATE, "t_start_s", t_start_s,
                         why=f"leaves fewer than 2 samples in [{t0:g}, {t1:g}] s",
                         fix=f"give a window inside the run's [{t[0]:g}, {t[-1]:g}] s")
    d_mm = np.asarray(levels.displacement, dtype=float)[inside, 0] * 1e3
    f_kn = np.asarray(levels.isolator_force, dtype=float)[inside] / 1e3
    if ax is None:
        _, ax = plt.subplots(figsize=(5.5, 4.5), constrained_layout=True)
    line.setdefault("lw", 1.0)
    line.setdefault("label", "isolator")
    artists = list(ax.plot(d_mm, f_kn, **line))
    iso = structure.isolator
    friction = getattr(iso, "friction_force_n", None)
    if hasattr(iso, "travel_m"):  # (a triple friction pendulum: its stages in a slide from rest, both ways)
        reach = iso.travel_m if iso.ring_stiffness_n_m is None else np.inf  # (stiff rings: on past it)
        lo, hi = max(d_mm.min() * 1e-3, -reach), min(d_mm.max() * 1e-3, reach)
        for a, b in ((lo, 0.0), (0.0, hi)):
            u = np.linspace(a, b, 400) if b > a else np.zeros(0)
            artists += ax.plot(u * 1e3, iso.backbone(u) / 1e3, color="0.5", lw=0.8, ls=":",
                               label="slide from rest (stages)" if a == 0.0 else None)
    elif friction is not None:  # (a friction isolator: its slip lines, at rest and fast)
        span = np.array([d_mm.min(), d_mm.max()])
        k = iso.restoring_stiffness_n_m
        lines = [(friction, "slip at +-mu W", ":")]
        if iso.mu_fast is not None:
            lines.append((iso.friction_fast_force_n, "slip at +-mu_fast W", "--"))
        for force, label, style in lines:
            for sign in (1.0, -1.0):
                artists += ax.plot(span, (k * span * 1e-3 + sign * force) / 1e3, color="0.5", lw=0.8,
                                   ls=style, label=label if sign > 0 else None)
    for wall in structure.walls:
        if wall.level != 0:
            continue
        for x in (wall.gap_right_m, -wall.gap_left_m):
            artists.append(ax.axvline(x * 1e3, color="k", lw=1.2, label=None))
    ax.set_xlabel("base displacement [mm]")
    ax.set_ylabel("isolator force [kN]")
    place_legend(ax, fontsize="small")
    return artists
