"""``pounding study``: a parameter study into a resumable Zarr store."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from .._errors import Interrupted
from .._io import interrupts_deferred
from ._app import OPT_SCHEDULER, command, console, interrupted


@command("study")
def study(
    spec: Path = typer.Argument(..., help="The study: a TOML file with [system], [compute] and [grid]."),
    store: str = typer.Option(..., "--store",
                              help="The Zarr folder (created; rerun to resume it), or an fsspec URL "
                              "(s3://bucket/study.zarr)."),
    scheduler: str = OPT_SCHEDULER,
    workers: Optional[int] = typer.Option(None, "--workers",
                                          help="Threads or processes (default: every core)."),
    restart: bool = typer.Option(False, "--restart", help="Overwrite the store instead of resuming it."),
) -> None:
    """Run a parameter study; a rerun computes only the points not done yet."""
    from ..studies import study as run_study
    from ..studies import StudyResult
    from ..studies import StudySpec

    parsed = StudySpec.from_toml(spec)  # (bad specs fail here, before any work)
    console.print(f"{parsed.size} points "
                  f"({' x '.join(f'{d} {n}' for d, n in zip(parsed.dims, parsed.shape))}), kind "
                  f"{parsed.kind} -> {store}")
    try:
        ds = run_study(parsed, store, scheduler=scheduler, workers=workers, resume=not restart, progress=True)
    except Interrupted as stop:
        interrupted(f"{stop.done} of {stop.total} points are in {store}; run the same command again "
                    "to resume")
        return
    with interrupts_deferred() as held:  # (the study is in its store: a Ctrl-C now changes nothing)
        result = StudyResult(ds, parsed)
        console.print(f"{result.done} of {parsed.size} points done; read with "
                      f"pounding.open_study({str(store)!r}) or xarray.open_zarr")
    if held:
        interrupted(f"after the study had finished: all {result.done} points are in {store}")
