"""``pounding campaign``: the paper's matrix of sweeps, its tables, figure and netCDF file."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer
from rich.markup import escape

from .._errors import Interrupted
from .._io import interrupts_deferred
from ._app import (
    OPT_CYCLES,
    OPT_FMAX,
    OPT_FMIN,
    OPT_FSTEP,
    OPT_MAX_CYCLES,
    OPT_MEASURE_CYCLES,
    OPT_NBS,
    OPT_SCHEDULER,
    OPT_STEADY,
    OPT_WORKERS,
    OPT_YBS,
    PRESET_LIST,
    cell,
    command,
    console,
    data_table,
    err_console,
    folder,
    frequencies,
    interrupted,
    save_figure,
    steady_options,
    system,
    write_csv,
)


@command()
def campaign(
    out: Path = typer.Option(
        ..., "--out", help="Directory for campaign.nc, steps.csv, table2-4.csv, campaign.png."
    ),
    preset: Optional[str] = typer.Option(
        None,
        "--preset",
        help=f"Built-in system for both configurations: {PRESET_LIST}.",
    ),
    nbs: Optional[Path] = OPT_NBS,
    ybs: Optional[Path] = OPT_YBS,
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = OPT_FSTEP,
    steady: str = OPT_STEADY,
    cycles: Optional[int] = OPT_CYCLES,
    measure_cycles: int = OPT_MEASURE_CYCLES,
    max_cycles: Optional[int] = OPT_MAX_CYCLES,
    workers: Optional[int] = OPT_WORKERS,
    scheduler: str = OPT_SCHEDULER,
) -> None:
    """The paper's matrix: NBs at a_G 0.03, 0.05, 0.1 and YBs at 0.03, 0.05, 0.075, 0.1, up and down."""
    from .. import presets
    from ..protocols import campaign as run_campaign

    out = folder("--out", out)
    if preset is not None and (nbs or ybs):
        raise typer.BadParameter("give --preset or --nbs/--ybs, not both")
    if preset is not None:
        nbs_osc, ybs_osc = presets.by_name(preset, bumpers=False), presets.by_name(preset)
    elif nbs or ybs:  # (an oscillator's file, or a structure's: without its walls, and with them)
        nbs_osc = system(nbs, None) if nbs else None
        ybs_osc = system(ybs, None) if ybs else None
    else:
        raise typer.BadParameter("give --preset NAME, or --nbs and/or --ybs TOML files")
    complete = True
    try:
        result = run_campaign(
            nbs_osc,
            ybs_osc,
            freqs_hz=frequencies(fmin, fmax, fstep),
            measure_cycles=measure_cycles,
            workers=workers,
            scheduler=scheduler,
            progress=True,
            **steady_options(steady, cycles, max_cycles),
        )
    except Interrupted as stop:
        err_console.print(f"[yellow]{escape(str(stop))}; saving them[/]")
        result, complete = stop.partial, False
    with interrupts_deferred() as held:  # every file whole, whatever Ctrl-C comes meanwhile
        _save_campaign(result, out)
    columns = ("configuration", "a_g", "direction", "nu_r", "alpha", "eta", "e", "contact_nu_min",
               "contact_nu_max")
    if not result.of_one_mass:  # (a structure's campaign: its table 2 per level)
        columns = ("configuration", "a_g", "direction", "nu_r_top", "alpha_top_max", "alpha_base_max",
                   "drift_ratio_max", "contact_nu_min", "contact_nu_max")
    summary = data_table("Table 2 analogue (model)", columns)
    for _, row in result.table2().iterrows():
        summary.add_row(*(cell(row[c]) for c in columns))
    console.print(summary)
    tables = "table2-4.csv" if result.of_one_mass else "table2.csv"
    console.print(f"campaign.nc, steps.csv, {tables}, campaign.png -> {out}")
    if not complete or held:
        done = sum(sw.steps_done for sw in result.sweeps.values())
        interrupted(
            f"{done} steps finished; they are in {out} (campaign.nc has complete = 0, the tables a "
            "'complete' column)" if not complete else
            f"after the campaign had finished: all {done} steps are in {out}, complete"
        )


def _save_campaign(result, out: Path) -> None:
    """The campaign's files; each table says per sweep whether it finished (``complete``)."""
    out.mkdir(parents=True, exist_ok=True)
    result.to_netcdf(out / "campaign.nc")
    steps = result.data.to_dataframe().reset_index()
    write_csv(steps[steps["ran"]].drop(columns=["ran"]), out / "steps.csv")
    finished = {key: sw.steps_done == sw.freqs_hz.size for key, sw in result.sweeps.items()}
    tables = [("table2", result.table2)] + ([("table3", result.table3), ("table4", result.table4)]
                                            if result.of_one_mass else [])
    for name, make in tables:
        df = make()
        df = df.copy()
        df["complete"] = [
            finished[(c, a, d)] for c, a, d in zip(df["configuration"], df["a_g"], df["direction"])
        ]
        write_csv(df, out / f"{name}.csv")
    if result.sweeps:
        save_figure(result.plot, out / "campaign.png")
