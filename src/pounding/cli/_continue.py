"""``pounding continue``: a branch of periodic orbits over a frequency range, its folds and
bifurcations, optionally with the sweeps that jump at them."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import typer

from .._errors import Interrupted
from .._io import interrupts_deferred
from ._app import (ARG_SYSTEM, OPT_A_G, OPT_NO_BUMPERS, OPT_PRESET, command, console, err_console,
                   figure_path, files, interrupted, kv_table, several_masses, save_figure, system, working,
                   write_csv)

CSV = (".csv",)


@command("continue")
def continue_branch(
    system_file: Optional[Path] = ARG_SYSTEM,
    a_g: float = OPT_A_G,
    start: float = typer.Option(..., "--from", help="The branch's first frequency, Hz."),
    end: float = typer.Option(..., "--to", help="Its last frequency, Hz."),
    preset: Optional[str] = OPT_PRESET,
    no_bumpers: bool = OPT_NO_BUMPERS,
    out: Optional[Path] = typer.Option(None, "--out", help="Write the branch, one row per orbit (CSV)."),
    bifurcations: Optional[Path] = typer.Option(None, "--bifurcations", help="Write the bifurcations (CSV)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Draw alpha against nu (PNG, PDF...)."),
    sweeps: bool = typer.Option(False, "--sweeps", help="Also run an up and a down sweep (0.1 Hz steps) "
                                "and draw them over the branch."),
    period_multiple: int = typer.Option(1, "--period-multiple",
                                        help="The orbits' period, in forcing periods."),
    max_step: float = typer.Option(0.02, "--max-step", help="Largest step along the branch, as a fraction "
                                   "of the range."),
) -> None:
    """Follow the periodic response over a frequency range through its folds; locate its folds,
    branch points, period-doublings, Neimark-Sacker points and grazings."""
    from ..analysis.continuation import continuation

    paths = files(out=(out, CSV), bifurcations=(bifurcations, CSV))
    plot = figure_path("--plot", plot)
    osc = system(system_file, preset, bumpers=not no_bumpers)
    several = several_masses(osc)
    if several and sweeps:
        err_console.print("[yellow]warning:[/] --sweeps draws one mass's sweeps over its branch; a "
                          "structure's branch is drawn alone")
        sweeps = False
    complete = True
    with working(f"following the branch from {start:g} to {end:g} Hz ..."):
        try:
            branch = continuation(osc, a_g, (start, end), period_multiple=period_multiple, max_step=max_step)
        except Interrupted as stop:
            branch, complete = stop.partial, False
    table, add = kv_table(f"branch at a_G = {a_g:g}, {start:g} to {end:g} Hz", system_file or preset)
    add("status", branch.message)
    add("orbits", f"{len(branch)} ({int((~branch.data['stable']).sum())} unstable)")
    gap = _not_covered(branch, start, end)
    if gap:
        add("not covered", gap)
    for label, bif in _one_line_each(branch.bifurcations):
        add(label, f"f = {bif.freq_hz:.6g} Hz, alpha = {bif.alpha:.4g}"
            + ("" if bif.located else " (not located to tolerance)")
            + (f", the map goes as depth^{bif.scaling_exponent:.3f}" if math.isfinite(bif.scaling_exponent)
               else ""))
    console.print(table)
    runs = []
    if sweeps and complete and plot is not None:
        import numpy as np

        from ..protocols import sweep

        lo, hi = sorted((start, end))
        freqs = np.round(np.arange(lo, hi + 1e-9, 0.1), 10)
        with working("running the sweeps ..."):
            runs = [sweep(osc, a_g, freqs, direction) for direction in ("up", "down")]
    with interrupts_deferred() as held:
        if paths["out"] is not None:
            write_csv(branch.to_dataframe(), paths["out"])
            console.print(f"branch -> {paths['out']}")
        if paths["bifurcations"] is not None:
            write_csv(branch.bifurcation_table(), paths["bifurcations"])
            console.print(f"bifurcations -> {paths['bifurcations']}")
        if plot is not None and len(branch):
            save_figure(lambda: branch.plot(sweeps=runs or None), plot)
    if not complete or held:
        interrupted(f"{len(branch)} orbits followed; they are in the summary"
                    + (" and the files written" if any(paths.values()) or plot else ""))
    if not branch.success or gap:
        if gap:
            err_console.print(f"the branch did not cover {gap}")
        raise typer.Exit(code=1)


def _not_covered(branch, start: float, end: float) -> str:
    """The part of ``[start, end]`` the branch's orbits never reached (it turned back at a fold, or stopped
    short), with how to follow it; "" when it covered the whole range."""
    if not len(branch):
        return f"{min(start, end):g}-{max(start, end):g} Hz (no orbit)"
    f = branch.data["freq_hz"].to_numpy(float)
    lo, hi = float(f.min()), float(f.max())
    tol = 1e-9 * max(abs(end - start), 1.0)
    missing = [(a, b) for a, b in ((min(start, end), lo), (hi, max(start, end))) if b - a > tol]
    if not missing:
        return ""
    a, b = missing[0]
    far = b if abs(b - end) <= tol else a  # (the range's far end, where another branch can start)
    near = a if far == b else b
    return (f"{a:.6g}-{b:.6g} Hz of {min(start, end):g}-{max(start, end):g} Hz (the branch turned back "
            f"or stopped at {near:.6g} Hz; follow the rest from the other end: --from {far:g} "
            f"--to {near:.6g})")


def _freq_list(freqs) -> str:
    """``1.7-2.0, 2.4 Hz``: a test matrix's frequencies as runs (of its step) and single values."""
    f = sorted(float(x) for x in freqs)
    step = min((b - a for a, b in zip(f, f[1:])), default=0.0)
    runs: list[list[float]] = []
    for x in f:
        if runs and x - runs[-1][-1] <= step * (1 + 1e-6):
            runs[-1].append(x)
        else:
            runs.append([x])
    return ", ".join(f"{r[0]:g}-{r[-1]:g}" if len(r) > 1 else f"{r[0]:g}" for r in runs) + " Hz"


def _one_line_each(bifurcations: list) -> list:
    """``(label, bifurcation)`` per line of the summary: a grazing of both sides at one orbit (a
    symmetric system's: a wall's two sides, a single mass's two bumpers) is one line,
    "grazing (wall0_left and wall0_right)", not two."""
    out: list = []
    for bif in bifurcations:
        prev = out[-1][1] if out else None
        sides = sorted((bif.side, prev.side)) if prev is not None else []
        if (prev is not None and bif.kind == prev.kind == "grazing"
                and sides[0].endswith("left") and sides[1] == sides[0][:-4] + "right"
                and abs(bif.freq_hz - prev.freq_hz) <= 1e-7 * max(1.0, abs(bif.freq_hz))
                and abs(bif.a_g - prev.a_g) <= 1e-12 * max(1.0, abs(bif.a_g))):
            out[-1] = (f"grazing ({sides[0]} and {sides[1]})", prev)
            continue
        out.append((f"{bif.kind}{f' ({bif.side})' if bif.side else ''}", bif))
    return out


@command("coexistence")
def coexistence(
    system_file: Optional[Path] = ARG_SYSTEM,
    a_g_min: float = typer.Option(0.02, "--a-g-min", help="The map's lowest a_G, g."),
    a_g_max: float = typer.Option(0.12, "--a-g-max", help="Its highest a_G, g."),
    start: float = typer.Option(0.5, "--from", help="Its lowest frequency, Hz."),
    end: float = typer.Option(5.0, "--to", help="Its highest frequency, Hz."),
    levels: Optional[str] = typer.Option(None, "--levels",
                                         help="The branches' a_G, comma-separated (default: "
                                         "the paper's 0.03, 0.05, 0.075, 0.1 within the range)."),
    grazings: bool = typer.Option(False, "--grazings", help="Also follow the grazings (contacts appearing)."),
    basin_sample: int = typer.Option(4, "--basin-sample", help="Points per axis of the basin sample run at "
                                     "each test point (0: none, and a branch's one stable orbit is only "
                                     "that)."),
    preset: Optional[str] = OPT_PRESET,
    no_bumpers: bool = OPT_NO_BUMPERS,
    out: Optional[Path] = typer.Option(None, "--out", help="Write the curves' points (CSV)."),
    matrix: Optional[Path] = typer.Option(None, "--matrix", help="Write the test matrix: each point's "
                                          "witnesses, responses and verdict (CSV)."),
    plot: Optional[Path] = typer.Option(None, "--plot",
                                        help="Draw the curves over the test matrix (PNG, PDF...)."),
) -> None:
    """Where two responses coexist (where up and down sweeps must differ): branches at a_G levels,
    their folds followed in (a_G, f), and each test point judged by the branch and a basin sample
    (coexisting, one response, or not assessed). SYSTEM.toml may be a building's or a pair's file.
    Exits 1 when a branch stopped short of the range or left test points unreached (the map is then
    incomplete)."""
    from ..analysis.curves import coexistence_map

    paths = files(out=(out, CSV), matrix=(matrix, CSV))
    plot = figure_path("--plot", plot)
    chosen = None
    if levels is not None:
        try:
            chosen = [float(v) for v in levels.split(",") if v.strip()]
        except ValueError:
            chosen = []
        if not chosen:
            raise typer.BadParameter(f"--levels {levels!r}: give numbers separated by commas, e.g. 0.03,0.05")
    osc = system(system_file, preset, bumpers=not no_bumpers)
    complete = True
    kinds = ("fold", "grazing") if grazings else ("fold",)
    with working(f"branches and {' and '.join(kinds)} curves, a_G {a_g_min:g} to {a_g_max:g} ..."):
        try:
            cmap = coexistence_map(osc, a_g=(a_g_min, a_g_max), freqs_hz=(start, end), levels=chosen,
                                   kinds=kinds, basin_sample=basin_sample)
        except Interrupted as stop:
            cmap, complete = stop.partial, False
    table, add = kv_table(f"coexistence, a_G {a_g_min:g}-{a_g_max:g}, {start:g}-{end:g} Hz", system_file
                          or preset)
    for br in cmap.branches:
        folds = ", ".join(f"{b.freq_hz:.4g}" for b in br.folds())
        add(f"branch a_G = {br.a_g:g}", f"{len(br)} orbits, "
            + (f"folds at {folds} Hz" if folds else "no fold") + f" ({br.status.name})")
    for i, c in enumerate(cmap.curves):
        df = c.to_dataframe()
        add(f"curve {i}: {c.kind}{' ' + c.side if c.side else ''}",
            f"{len(c)} points, a_G {df.a_g.min():.4g}-{df.a_g.max():.4g}; {c.status.name}: {c.message}")
    for note in cmap.notes:
        add("note", note)
    for verdict, words in (("coexist", "coexisting"), ("one", "one response"),
                           ("one on the branch", "one on the branch"), ("not assessed", "not assessed")):
        rows = cmap.matrix[cmap.matrix["verdict"] == verdict]
        if verdict == "coexist" or len(rows):
            add(words, f"{len(rows)} of {len(cmap.matrix)} test points"
                + (": " + "; ".join(f"a_G {a:g}: {_freq_list(g.freq_hz)}" for a, g in rows.groupby("a_g"))
                   if len(rows) else ""))
    console.print(table)
    with interrupts_deferred() as held:
        if paths["out"] is not None:
            write_csv(cmap.to_dataframe(), paths["out"])
            console.print(f"curves -> {paths['out']}")
        if paths["matrix"] is not None:
            write_csv(cmap.matrix, paths["matrix"])
            console.print(f"test matrix -> {paths['matrix']}")
        if plot is not None:
            save_figure(lambda: cmap.plot(), plot)
    if not complete or held:
        interrupted(f"{len(cmap.curves)} curves followed; they are in the summary"
                    + (" and the files written" if any(paths.values()) or plot else ""))
    short = cmap.matrix[~cmap.matrix["branch_reached"].astype(bool)]
    if not all(br.success for br in cmap.branches) or len(short):
        if len(short):  # (a branch that turned back, or started at the other end, and never came here)
            console.print(f"{len(short)} test point(s) no branch reached: "
                          + "; ".join(f"a_G {a:g}: {_freq_list(g.freq_hz)}" for a, g in short.groupby("a_g")))
        raise typer.Exit(code=1)  # (the map is incomplete; the summary says where)
