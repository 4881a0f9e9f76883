"""``pounding bifurcation``: a brute-force bifurcation diagram, up and down, optionally over the
branch of periodic orbits."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from .._errors import Interrupted, Status
from .._io import atomic_write, interrupts_deferred
from ._app import (OPT_FMAX, OPT_FMIN, OPT_NO_BUMPERS, OPT_PRESET, command, compile_notice, console,
                   figure_path, files, frequencies, interrupted, kv_table, save_figure, system, write_csv)

CSV = (".csv",)
NETCDF = (".nc", ".nc4", ".netcdf")


@command("bifurcation")
def bifurcation(
    system_file: Optional[Path] = typer.Argument(
        None, metavar="SYSTEM.toml", help="System TOML (see examples/). Omit to use --preset."),
    a_g: float = typer.Option(..., "--a-g", help="Peak table acceleration in g (the paper's a_G)."),
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
    freqs = frequencies(fmin, fmax, fstep)
    kwargs = dict(direction=direction, transient_cycles=transient_cycles, record_cycles=record_cycles,
                  max_period=max_period)
    compile_notice()
    try:
        result = bifurcation_diagram(osc, a_g, freqs, progress=True, **kwargs)
    except Interrupted as stop:
        result = stop.partial
    branches = None
    if branch and result.success:
        from ..analysis.continuation import continuation

        with console.status(f"following the branch from {fmin:g} to {fmax:g} Hz ..."):
            branches = continuation(osc, a_g, (fmin, fmax))
    table, add = kv_table(f"bifurcation diagram, a_G = {a_g:g}", system_file or preset)
    add("status", result.message)
    steps = result.to_dataframe(cycles=False)
    for sw in result.sweeps:
        jumps = sw.jumps()
        pairs = zip(jumps["freq_from_hz"], jumps["freq_to_hz"], jumps["kind"])
        add(f"jumps {sw.direction} [Hz]", ", ".join(f"{a:g}->{b:g} ({k})" for a, b, k in pairs) or "none")
    not_periodic = steps.loc[steps["period"] == 0, "freq_hz"]
    add("not periodic [Hz]", ", ".join(f"{f:g}" for f in not_periodic.unique()[:12])
        + (" ..." if not_periodic.nunique() > 12 else "") or "none")
    console.print(table)
    with interrupts_deferred() as held:
        if paths["out"] is not None:
            write_csv(result.to_dataframe(), paths["out"])
            console.print(f"samples -> {paths['out']}")
        if paths["netcdf"] is not None:
            atomic_write(paths["netcdf"], lambda tmp: result.to_xarray().to_netcdf(tmp))
            console.print(f"dataset -> {paths['netcdf']}")
        if plot is not None and len(steps):
            save_figure(lambda: result.plot(branches=branches), plot)
    if result.status == Status.INTERRUPTED or held:
        interrupted(f"{len(steps)} steps finished; they are in the summary"
                    + (" and the files written" if any(paths.values()) or plot else ""))
    if not result.success:
        raise typer.Exit(code=1)
