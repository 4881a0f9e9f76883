"""``pounding bifurcation``, ``pounding basins`` and ``pounding lyapunov``: which response a system
ends on, by sweeping (a brute-force bifurcation diagram, up and down, over the branch of periodic
orbits), from every initial state of a box (basins of attraction), and whether it is chaotic (its
Lyapunov exponents)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from .._errors import Interrupted, Status
from .._io import atomic_write, interrupts_deferred
from ._app import (ARG_SYSTEM, OPT_A_G, OPT_FMAX, OPT_FMIN, OPT_FREQ, OPT_NO_BUMPERS, OPT_PRESET,
                   OPT_SCHEDULER, command, console, err_console, figure_path, files,
                   frequencies, interrupted, kv_table, several_masses, save_figure, system, working,
                   write_csv)

CSV = (".csv",)
NETCDF = (".nc", ".nc4", ".netcdf")


@command("bifurcation")
def bifurcation(
    system_file: Optional[Path] = ARG_SYSTEM,
    a_g: float = OPT_A_G,
    preset: Optional[str] = OPT_PRESET,
    no_bumpers: bool = OPT_NO_BUMPERS,
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = typer.Option(0.01, "--fstep", help="Frequency step, Hz."),
    direction: str = typer.Option("both", "--direction", help="both (up, then down), up or down."),
    transient_cycles: int = typer.Option(100, "--transient-cycles",
                                         help="Cycles held at each frequency before recording."),
    record_cycles: int = typer.Option(20, "--record-cycles", help="Cycles recorded at each frequency."),
    max_period: int = typer.Option(8, "--max-period", help="Largest period multiple looked for."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the samples, one row per recorded cycle "
                                       "(CSV)."),
    netcdf: Optional[Path] = typer.Option(None, "--netcdf", help="Write the dataset (.nc)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Draw the diagram (PNG, PDF...)."),
    branch: bool = typer.Option(False, "--branch", help="Also follow the branch of periodic orbits over "
                                "the range and draw it under the diagram."),
) -> None:
    """Bifurcation diagram: each frequency held, the state carried over, and the state at table
    phase 0 recorded cycle after cycle (one point: period 1; k points: period k; a cloud: no
    period); up, then down."""
    from ..protocols.bifurcation_diagram import bifurcation_diagram

    paths = files(out=(out, CSV), netcdf=(netcdf, NETCDF))
    plot = figure_path("--plot", plot)
    osc = system(system_file, preset, bumpers=not no_bumpers)
    several = several_masses(osc)
    freqs = frequencies(fmin, fmax, fstep)
    kwargs = dict(direction=direction, transient_cycles=transient_cycles, record_cycles=record_cycles,
                  max_period=max_period)
    try:
        result = bifurcation_diagram(osc, a_g, freqs, progress=True, **kwargs)
    except Interrupted as stop:
        result = stop.partial
    table, add = kv_table(f"bifurcation diagram, a_G = {a_g:g}", system_file or preset)
    add("status", result.message)
    steps = result.to_dataframe(cycles=False)
    for sw in result.sweeps if not several else ():  # (a structure's sweeps: no jumps table yet)
        jumps = sw.jumps()
        pairs = zip(jumps["freq_from_hz"], jumps["freq_to_hz"], jumps["kind"])
        add(f"jumps {sw.direction} [Hz]", ", ".join(f"{a:g}->{b:g} ({k})" for a, b, k in pairs) or "none")
    not_periodic = steps.loc[steps["period"] == 0]
    if len(not_periodic):  # (each frequency once, in order, with the directions that did not settle)
        where = [f"{f:g}" + ("" if part["direction"].nunique() > 1 or steps["direction"].nunique() == 1
                             else f" ({part['direction'].iloc[0]})")
                 for f, part in not_periodic.groupby("freq_hz", sort=True)]
        add("not periodic [Hz]", ", ".join(where[:16]) + (" ..." if len(where) > 16 else ""))
    else:
        add("not periodic [Hz]", "none")
    if several:
        top = steps.groupby("freq_hz")["alpha"].max()
        add("largest alpha (any level)", f"{top.max():.3g} at {top.idxmax():g} Hz" if len(top) else "none")
    console.print(table)
    with interrupts_deferred() as held:
        if paths["out"] is not None:
            write_csv(result.to_dataframe(), paths["out"])
            console.print(f"samples -> {paths['out']}")
        if paths["netcdf"] is not None:
            atomic_write(paths["netcdf"], lambda tmp: result.to_xarray().to_netcdf(tmp))
            console.print(f"dataset -> {paths['netcdf']}")
    if plot is not None and len(steps) and not held:
        # (followed after the files are written: its failure or a Ctrl-C loses nothing)
        branches = _branch(osc, a_g, fmin, fmax) if branch else None
        # (a structure's branch: its first moving mass's section, the level drawn with it)
        level = {"level": 1 if _first_fixed(osc) else 0} if several and branches is not None else {}
        with interrupts_deferred() as more:
            save_figure(lambda: result.plot(branches=branches, **level), plot)
        held += more
    if result.status == Status.INTERRUPTED or held:
        interrupted(f"{len(steps)} steps finished; they are in the summary"
                    + (" and the files written" if any(paths.values()) or plot else ""))
    if not result.success:
        raise typer.Exit(code=1)


def _first_fixed(model) -> bool:
    """Whether a structure's (a pair's first) base is fixed: its first moving level is then 1."""
    return (model.structures[0] if hasattr(model, "structures") else model).fixed


def _branch(osc, a_g: float, fmin: float, fmax: float):
    """The branch over the range, or None (with a warning saying why) where it cannot be followed:
    the diagram's files are written already."""
    from .._errors import InputError
    from ..analysis.continuation import continuation

    try:
        with working(f"following the branch from {fmin:g} to {fmax:g} Hz ..."):
            return continuation(osc, a_g, (fmin, fmax))
    except (InputError, Interrupted) as exc:
        err_console.print(f"[yellow]warning:[/] the branch was not drawn: {exc}")
        return None


@command("basins")
def basins_command(
    system_file: Optional[Path] = ARG_SYSTEM,
    a_g: float = OPT_A_G,
    freq: float = OPT_FREQ,
    preset: Optional[str] = OPT_PRESET,
    no_bumpers: bool = OPT_NO_BUMPERS,
    dmin: Optional[float] = typer.Option(None, "--dmin", help="Lowest initial displacement, m (default: "
                                         "the left bumper's surface)."),
    dmax: Optional[float] = typer.Option(None, "--dmax", help="Highest initial displacement, m (default: "
                                         "the right bumper's surface)."),
    vmin: float = typer.Option(-1.0, "--vmin", help="Lowest initial velocity, m/s."),
    vmax: float = typer.Option(1.0, "--vmax", help="Highest initial velocity, m/s."),
    n: int = typer.Option(50, "--n", help="Grid points along each axis (n x n states)."),
    random: Optional[int] = typer.Option(None, "--random", help="Instead of a grid, this many states drawn "
                                         "uniformly in the box (basin stability)."),
    seed: int = typer.Option(0, "--seed", help="The random states' seed."),
    max_cycles: int = typer.Option(500, "--max-cycles", help="Most cycles a state runs before it is called "
                                   "not settled."),
    scheduler: str = OPT_SCHEDULER,
    workers: Optional[int] = typer.Option(None, "--workers", help="Parallel workers (default: all cores)."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the attractors, one row each (CSV)."),
    netcdf: Optional[Path] = typer.Option(None, "--netcdf", help="Write every state's label (.nc)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Draw the basins (PNG, PDF...)."),
) -> None:
    """Basins of attraction: every initial state of a box (at table phase 0) run until it settles;
    the responses it settles on (attractors) found, and the share of states that end on each."""
    from ..excitation import Harmonic
    from ..protocols.basins import basins, open_range

    paths = files(out=(out, CSV), netcdf=(netcdf, NETCDF))
    plot = figure_path("--plot", plot)
    osc = system(system_file, preset, bumpers=not no_bumpers)
    lo, hi = open_range(osc)  # (a structure's: the shifts of it as one body that leave it open)
    d_box = None if dmin is None and dmax is None else (
        dmin if dmin is not None else (lo if lo > -float("inf") else -0.05),
        dmax if dmax is not None else (hi if hi < float("inf") else 0.05))
    kwargs = dict(displacement_m=d_box, velocity_m_s=(vmin, vmax), max_cycles=max_cycles,
                  scheduler=scheduler, workers=workers, seed=seed)
    kwargs.update(dict(n=random, sampling="random") if random is not None else dict(n=(n, n)))
    try:
        result = basins(osc, Harmonic(a_g, freq), progress=True, **kwargs)
    except Interrupted as stop:
        result = stop.partial
    table, add = kv_table(f"basins at a_G = {a_g:g}, {freq:g} Hz", system_file or preset)
    for j, row in enumerate(result.attractors.itertuples()):
        what = "impacting" if row.impacts else "free"
        add(f"attractor {j}", f"{what}, period {row.period}, alpha {row.alpha:.4g}, excursion "
                              f"{row.excursion_m * 1e3:.3g} mm: {row.fraction:.1%} "
                              f"+- {row.standard_error:.1%}")
    add("not settled", f"{result.not_settled:.1%} (in {max_cycles} cycles)")
    console.print(table)
    with interrupts_deferred() as held:
        if paths["out"] is not None:
            write_csv(result.attractors, paths["out"])
            console.print(f"attractors -> {paths['out']}")
        if paths["netcdf"] is not None:
            atomic_write(paths["netcdf"], lambda tmp: result.to_xarray().to_netcdf(tmp))
            console.print(f"dataset -> {paths['netcdf']}")
        if plot is not None:
            save_figure(result.plot, plot)
    if not result.complete or held:
        interrupted("the states finished are in the summary"
                    + (" and the files written" if any(paths.values()) or plot else ""))


@command("lyapunov")
def lyapunov_command(
    system_file: Optional[Path] = ARG_SYSTEM,
    a_g: float = OPT_A_G,
    freq: float = OPT_FREQ,
    preset: Optional[str] = OPT_PRESET,
    no_bumpers: bool = OPT_NO_BUMPERS,
    cycles: int = typer.Option(1000, "--cycles", help="Forcing periods counted."),
    transient_cycles: int = typer.Option(200, "--transient-cycles", help="Periods run first, for the "
                                         "response to settle (from rest)."),
    align_cycles: int = typer.Option(20, "--align-cycles", help="Periods the tangent frame is carried "
                                     "before the count starts."),
    method: str = typer.Option("auto", "--method", help="The Jacobian: auto, exact or finite-difference."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the running estimates, one row per period "
                                       "(CSV)."),
    netcdf: Optional[Path] = typer.Option(None, "--netcdf", help="Write the exponents and their history "
                                          "(.nc)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Draw the running estimates (PNG, PDF...)."),
) -> None:
    """Lyapunov exponents of the response to a harmonic table motion, from the exact tangent dynamics
    through every impact: a positive largest exponent is chaos."""
    from ..analysis.lyapunov import lyapunov
    from ..excitation import Harmonic

    paths = files(out=(out, CSV), netcdf=(netcdf, NETCDF))
    plot = figure_path("--plot", plot)
    osc = system(system_file, preset, bumpers=not no_bumpers)
    try:
        spec = lyapunov(osc, Harmonic(a_g, freq), cycles=cycles, transient_cycles=transient_cycles,
                        align_cycles=align_cycles, method=method, progress=True)
    except Interrupted as stop:
        spec = stop.partial
    table, add = kv_table(f"Lyapunov exponents at a_G = {a_g:g}, {freq:g} Hz", system_file or preset)
    for i, value in enumerate(spec.exponents):
        add(f"lambda_{i + 1}", "-inf: a direction the map erases (a contact or a slip holds the state "
            "there), not a number to average" if value == float("-inf") else f"{value:.6g} 1/s")
    add("of the state", ", ".join(spec.coordinates))
    verdict = (f"periodic (period {spec.period})" if spec.period else
               f"chaotic (Kaplan-Yorke dimension {spec.kaplan_yorke_dimension:.3g})" if spec.chaotic else
               "not chaotic" if spec.largest < 0.0 else "not settled: count more periods")
    add("response", verdict)
    add("method", f"{spec.method}, {spec.cycles} periods counted")
    console.print(table)
    console.print(spec.message)
    with interrupts_deferred() as held:
        if paths["out"] is not None:
            hist = spec.to_xarray()["history"].to_pandas()
            hist.columns = [f"lambda_{i + 1}_1_s" for i in range(len(spec.coordinates))]
            write_csv(hist.reset_index(), paths["out"])
            console.print(f"running estimates -> {paths['out']}")
        if paths["netcdf"] is not None:
            atomic_write(paths["netcdf"], lambda tmp: spec.to_xarray().to_netcdf(tmp))
            console.print(f"dataset -> {paths['netcdf']}")
        if plot is not None:
            save_figure(spec.plot, plot)
    if spec.status == Status.INTERRUPTED or held:
        interrupted("the periods counted are in the summary"
                    + (" and the files written" if any(paths.values()) or plot else ""))
    if not spec.success:
        err_console.print(f"[red]stopped early:[/] {spec.message}")
        raise typer.Exit(code=1)
