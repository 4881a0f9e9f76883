"""``pounding simulate`` of a building in plan (a SYSTEM.toml with ``[[floors]]``): its summary, its floors'
and bearings' tables, its files."""

from __future__ import annotations

import math

from pathlib import Path
from typing import Any, Optional

import typer
from rich.markup import escape

from .._errors import Interrupted
from ._app import console, kv_table, run_files, working


def simulate_plan(building: Any, exc: Any, what: str, duration: float, velocity: float,
                  sample_rate: Optional[float], out: dict, plot: Optional[Path], system_file: Any) -> None:
    """Run ``building`` under ``exc`` and say what it did, as ``pounding simulate`` does for every system."""
    from rich.table import Table

    from ..engine import simulate as run_simulation

    if velocity != 0.0:
        raise typer.BadParameter("--velocity is for a structure on a line: a building in plan starts at rest")
    wants_history = out["history"] is not None or plot is not None
    rate = sample_rate if wants_history else 0.0  # (the events only: every extremum is exact without samples)
    complete = True
    try:
        with working(f"simulating {duration:g} s of {what} on {building.n_levels} floors in plan ..."):
            run = run_simulation(building, exc, duration, sample_rate_hz=rate)
    except Interrupted as stop:
        run, complete = stop.partial, False
    s = run.summary()
    table, add_row = kv_table(f"{what}, {s['t_end_s']:g} s", system_file)
    add_row("status", run.message)
    add_row("largest bearing displacement in plan [mm]",
            f"{s['bearing_displacement_max_m'] * 1e3:.2f} (bearing {s['bearing_of_max']})")
    add_row("base's largest rotation [mrad]", f"{s['theta_max_rad'] * 1e3:.3f}")
    if building.moat is not None:
        add_row("contacts with the moat", str(s["contacts"]))
        add_row("smallest clearance [mm]", f"{s['clearance_min_m'] * 1e3:.2f}"
                + (" (struck)" if s["clearance_min_m"] < 0 else ""))
        if s["contacts"] and math.isinf(s["peak_force_max_n"]):
            add_row("max peak force [kN]", "inf (the rigid impacts' impulses: see the contacts' impulse_n_s)")
        elif s["contacts"]:
            add_row("max peak force [kN]", f"{s['peak_force_max_n'] / 1e3:.3f}")
    add_row("energy in / residual [J]", f"{s['input_work_j']:.6g} / {s['energy_residual_j']:.2e}")
    console.print(table)
    floors = Table(title="each floor (extrema exact)")
    for head in ("floor", "x max / min [mm]", "y max / min [mm]", "rotation max / min [mrad]"):
        floors.add_column(escape(head), justify="right")
    for level, row in run.peaks().iterrows():
        floors.add_row("base" if level == 0 else str(level),
                       *(f"{row[f'{q}_max_{u}'] * 1e3:.2f} / {row[f'{q}_min_{u}'] * 1e3:.2f}"
                         for q, u in (("x", "m"), ("y", "m"), ("theta", "rad"))))
    console.print(floors)
    bearings = Table(title="each bearing (its largest displacement in plan: the vector sum, exact)")
    for head in ("bearing", "at x, y [m]", "largest [mm]", "at t [s]"):
        bearings.add_column(escape(head), justify="right")
    for b, row in run.bearings().iterrows():
        bearings.add_row(str(b), f"{row['at_x_m']:g}, {row['at_y_m']:g}",
                         f"{row['displacement_max_m'] * 1e3:.2f}", f"{row['displacement_max_time_s']:.3f}")
    console.print(bearings)
    run_files(run, out, plot, duration, complete)
