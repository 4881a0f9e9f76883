"""``pounding reproduce``, ``identify`` and ``warm-up`` (a no-op, kept for scripts)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer
from rich.markup import escape

from .._errors import Interrupted
from .._io import interrupts_deferred
from ._app import (
    OPT_SCHEDULER,
    PRESET_LIST,
    cell,
    data_table,
    NO_METAVAR,
    OPT_FMAX,
    OPT_FMIN,
    OPT_FSTEP,
    OPT_NBS,
    OPT_WORKERS,
    OPT_YBS,
    command,
    console,
    err_console,
    files,
    folder,
    frequencies,
    interrupted,
    write_csv,
)


@command()
def reproduce(
    preset: Optional[str] = typer.Option(
        None, "--preset", help=f"Built-in system: {PRESET_LIST} (default: the package's best, "
        "paper-calibrated)."
    ),
    nbs: Optional[Path] = OPT_NBS,
    ybs: Optional[Path] = OPT_YBS,
    out: Path = typer.Option(Path("report"), "--out", help="Directory for index.html, tables and figures."),
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = OPT_FSTEP,
    workers: Optional[int] = OPT_WORKERS,
    lowpass_hz: Optional[float] = typer.Option(
        None, "--lowpass-hz", help="Also tell the story as measured: the report's system with its "
        "accelerations through a 4-pole zero-phase low-pass at this cutoff (Hz)."),
    exact_only: bool = typer.Option(
        False, "--exact-only", metavar=NO_METAVAR, help="Only the exact metrics (the default preset "
        "otherwise adds paper-calibrated-measured, its metrics measured through its fitted low-pass, and "
        "paper-calibrated-laser, its contacts timed by the laser)."),
    laser: bool = typer.Option(
        True, "--laser/--no-laser", help="With a measured story, also tell the story with the contacts "
        "timed by the laser's gap crossings (the default preset: paper-calibrated-laser; with --lowpass-hz: "
        "the same system and low-pass)."),
    stands: bool = typer.Option(True, "--stands/--no-stands", help="Test whether stands under the "
                                "bumpers explain the YBs accelerations (the YBs system on four stands, a few "
                                "seconds)."),
) -> None:
    """The paper's tables and figures from the model, beside the measurements, in one HTML report."""
    from .. import presets
    from ..model import MeasurementChain, Oscillator
    from ..reports import reproduce as write_report

    out = folder("--out", out)
    if preset is not None and (nbs or ybs):
        raise typer.BadParameter("give --preset or --nbs and --ybs, not both")
    if nbs or ybs:
        if not (nbs and ybs):
            raise typer.BadParameter("give both --nbs and --ybs (the report compares the two configurations)")
        nbs_osc, ybs_osc = Oscillator.from_toml(nbs), Oscillator.from_toml(ybs)
        label = f"{nbs} (NBs) and {ybs} (YBs)"
    else:
        name = preset or presets.BEST_PRESET
        nbs_osc, ybs_osc = presets.by_name(name, bumpers=False), presets.by_name(name)
        label = f"preset {name}" + ("" if preset else " (the default: the package's best)")
    if lowpass_hz is not None and exact_only:
        raise typer.BadParameter("give --lowpass-hz or --exact-only, not both")
    measured, profile, by_laser, laser_profile = None, None, None, None
    if lowpass_hz is not None:
        measured = (ybs_osc, MeasurementChain.lowpass(lowpass_hz))
        by_laser = (ybs_osc, MeasurementChain.lowpass(lowpass_hz, contact_timing="laser"))
    elif not exact_only and not (nbs or ybs) and (preset or presets.BEST_PRESET) in (
            presets.BEST_PRESET, "paper-calibrated-measured", "paper-calibrated-laser"):
        measured, profile = presets.paper_calibrated_measured(), presets.measurement_profile()
        by_laser, laser_profile = presets.paper_calibrated_laser(), presets.measurement_profile("laser")
    if not laser:
        by_laser, laser_profile = None, None
    beside = {"paper-printed": presets.paper_printed()}
    beside[label if (nbs or ybs) else (preset or presets.BEST_PRESET)] = ybs_osc
    freqs = frequencies(fmin, fmax, fstep)
    try:
        report = write_report(
            nbs_osc,
            ybs_osc,
            out,
            system_label=label,
            beside=beside,
            freqs_hz=freqs,
            workers=workers,
            progress=True,
            measured=measured,
            profile=profile,
            stands=stands,
            laser=by_laser,
            laser_profile=laser_profile,
        )
    except Interrupted as stop:
        interrupted(f"{stop}; no report written (a report of part of the campaign would mislead)")
    t2 = report.comparisons["2"]
    summary = data_table(f"Table 2, model ({label}) beside measured (paper)",
                         ("cfg", "a_G", "dir", "nu_R model", "nu_R meas.", "alpha model", "alpha meas.",
                          "eta|e model", "eta|e meas."))
    for _, row in t2.iterrows():
        q = "eta" if row["configuration"] == "YBs" else "e"
        summary.add_row(row["configuration"], cell(row["a_g"], "g"), row["direction"],
                        *(cell(row[c], ".3g") for c in ("nu_r_model", "nu_r_measured", "alpha_model",
                                                        "alpha_measured", f"{q}_model", f"{q}_measured")))
    console.print(summary)
    console.print(f"verdict: {escape(label)} {escape(report.verdict.summary())}")
    if report.measured is not None:
        console.print(f"as measured ({escape(report.measured.chain.describe())}): "
                      f"{escape(report.measured.verdict.summary())}")
    if report.laser is not None:
        console.print(f"as measured, timed by the laser ({escape(report.laser.chain.describe())}): "
                      f"{escape(report.laser.verdict.summary())}")
    if report.stands is not None:
        console.print(f"stands under the bumpers: {escape(report.stands.verdict)}")
    console.print(f"report -> {report.index_html} (tables CSV, {len(report.figures)} figures PNG)")


@command()
def identify(
    targets: Optional[Path] = typer.Argument(
        None, metavar="TARGETS.toml", help="Targets TOML (see examples/). Omit for --paper."
    ),
    family: Path = typer.Option(..., "--family", help="Model family TOML: mass, branches, law, fixed "
                                "numbers, bounds (or any system's numbers by their paths: system = "
                                "\"rig.toml\" and [bounds] of dotted names)."),
    out: Path = typer.Option(Path("calibrated.toml"), "--out", help="Write the fitted YBs system (TOML)."),
    paper: bool = typer.Option(
        False, "--paper", metavar=NO_METAVAR, help="Fit the paper's Tables 2-4 (instead of TARGETS.toml)."
    ),
    residuals: Optional[Path] = typer.Option(
        None, "--residuals", help="Also write the residual table (CSV)."
    ),
    seed: int = typer.Option(0, "--seed", help="Seed of the global search (same seed, same result)."),
    maxiter: int = typer.Option(30, "--maxiter", help="Generations of differential evolution."),
    popsize: int = typer.Option(10, "--popsize", help="Population per free number."),
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = OPT_FSTEP,
    cycles: int = typer.Option(30, "--cycles", help="Cycles per step (fixed schedule, as the lab)."),
    workers: Optional[int] = OPT_WORKERS,
    scheduler: str = OPT_SCHEDULER,
    loss: str = typer.Option(
        "squared", "--loss", help="squared (least squares) or misses (a smooth count of the targets missed)."
    ),
) -> None:
    """Model updating: fit a family's free numbers so that the simulated sweeps match measured targets."""
    from ..identification import Targets, paper_targets
    from ..identification import identify as run_identify
    from ..identification.system_family import read_family

    paths = files(out=(out, (".toml",)), residuals=(residuals, (".csv",)))
    if (targets is None) == (not paper):
        raise typer.BadParameter("give either TARGETS.toml or --paper (one of them)")
    goal = paper_targets() if paper else Targets.from_toml(targets)
    fam, bounds = read_family(family)
    complete = True
    try:
        fit = run_identify(
            goal,
            fam,
            bounds,
            seed=seed,
            maxiter=maxiter,
            popsize=popsize,
            workers=workers,
            scheduler=scheduler,
            freqs_hz=frequencies(fmin, fmax, fstep),
            cycles=cycles,
            progress=True,
            loss=loss,
        )
    except Interrupted as stop:
        if stop.partial is None:
            interrupted("no candidate was evaluated; nothing was written")
        fit, complete = stop.partial, False
    params = data_table("fitted numbers", ("name", "value", "low", "high", "at bound"))
    for row in fit.parameter_table().itertuples(index=False):
        params.add_row(row.name, cell(row.value, ".6g"), cell(row.low, "g"), cell(row.high, "g"),
                       "yes" if row.at_bound else "")
    console.print(params)
    table = data_table("residuals (model - target) / tolerance",
                       ("cfg", "a_G", "dir", "quantity", "target", "model", "normalized", "met"))
    for row in fit.residuals.itertuples(index=False):
        table.add_row(row.configuration, cell(row.a_g, "g"), row.direction, row.quantity, cell(row.target),
                      cell(row.model), cell(row.normalized, "+.2f"), "yes" if row.within else "[red]no[/]")
    console.print(table)
    with interrupts_deferred() as held:
        fit.to_toml(paths["out"])
        if paths["residuals"] is not None:
            write_csv(fit.to_dataframe(), paths["residuals"])
    console.print(f"{escape(fit.message)}\nfitted system -> {paths['out']}")
    if not complete or held:
        err_console.print(
            f"[yellow]{paths['out']} holds the best candidate so far and says partial = true[/]"
        )
        interrupted(f"the best of {fit.n_evaluations} evaluations is in {paths['out']}")


@command("warm-up", hidden=True)
def warm_up() -> None:
    """Nothing to do any more: the engine is compiled when the package is installed (kept so that scripts
    that call it still run)."""
    from .._core import __file__ as core_file

    console.print("nothing to compile: pounding's core was built when the package was installed "
                  f"({core_file})")
