"""``pounding design``: from a site to a gap, in one HTML report."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from .._errors import Interrupted
from .._io import interrupts_deferred
from ._app import command, console, folder, interrupted


@command("design")
def design(
    plan: Path = typer.Argument(..., metavar="DESIGN.toml",
                                help="The design: [system], [bumpers], [site], [records], [design] (see "
                                     "examples/design_ups.toml)."),
    out: Path = typer.Option(Path("design_report"), "--out", help="Directory for index.html, tables and "
                             "figures."),
    store: Optional[str] = typer.Option(None, "--store",
                                        help="The runs' Zarr store (default: [run] store, or runs.zarr in "
                                             "--out); rerun to resume it."),
    scheduler: Optional[str] = typer.Option(None, "--scheduler",
                                            help="threads, serial, processes, local or a Dask scheduler's "
                                                 "address (default: [run] scheduler, or threads)."),
    workers: Optional[int] = typer.Option(None, "--workers",
                                          help="Threads or processes (default: every core)."),
    restart: bool = typer.Option(False, "--restart", help="Overwrite the store instead of resuming it."),
) -> None:
    """Which gap keeps pounding rare at a site: stripes of a scaled suite over a design grid, fragility
    curves, the decision, and a report."""
    from dataclasses import replace

    from .._checks import integer
    from .._runner import scheduler_kind
    from ..design.plan import DesignPlan, free_store, run_plan, typed_store
    from ..reports.design import write_report

    parsed = DesignPlan.from_toml(plan)  # (a bad file fails here, before any work)
    out = folder("--out", out)
    if workers is not None:
        integer("--workers", workers, 1, 4096)
    if scheduler is not None:
        scheduler_kind(scheduler)
    if scheduler is not None or workers is not None:
        parsed = replace(parsed, scheduler=parsed.scheduler if scheduler is None else scheduler,
                         workers=parsed.workers if workers is None else workers)
    where = store or (str(parsed.store) if parsed.store is not None else str(out / "runs.zarr"))
    n_design = 0
    for kind in parsed.kinds:
        n_kind = 1
        for values in kind.grid.values():
            n_kind *= len(values)
        n_design += n_kind
    per_design = len(parsed.records) * len(parsed.levels_g)
    stores = (where if len(parsed.kinds) == 1 else
              ", ".join(typed_store(where, kind.name) for kind in parsed.kinds))
    types = "" if len(parsed.kinds) == 1 else f" of {len(parsed.kinds)} bumper types"
    what = "pairs" if parsed.in_plan else "records"
    console.print(f"{parsed.title}: {len(parsed.records)} {what} x {len(parsed.levels_g)} stripes x "
                  f"{n_design} designs{types} = {per_design * n_design} runs -> {stores}, and {per_design} "
                  f"without {'the moat' if parsed.in_plan else 'bumpers'} -> {free_store(where)}")
    out.mkdir(parents=True, exist_ok=True)
    try:
        outcome = run_plan(parsed, where, progress=True, resume=not restart)
    except Interrupted as stop:
        interrupted(f"{stop.done} of {stop.total} runs of the part under way are kept in {stores} and "
                    f"{free_store(where)}; run the same command again to resume")
        return
    with interrupts_deferred() as held:  # (the runs are in their store: the report is written whole or not)
        page = write_report(outcome, out)
        console.print(outcome.decision.verdict())
        console.print(f"report -> {page}")
    if held:
        interrupted(f"after the report was written: {page}")
