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
    if not complete or held:
        interrupted(f"the finished angles are in {out} (NaN where a run did not finish)")
