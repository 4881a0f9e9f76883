"""Command line: ``pounding simulate``, ``sweep``, ``campaign``, ``reproduce``, ``identify`` and
``warm-up``."""

from __future__ import annotations

from pathlib import Path
from collections.abc import Callable
from typing import Optional

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from ._errors import InputError

app = typer.Typer(add_completion=False, no_args_is_help=True,
                  help="pounding: base-isolated masses pounding against deformable bumpers.")
console = Console()
err_console = Console(stderr=True)


# options shared by several commands (one definition each)
OPT_FMIN = typer.Option(0.5, "--fmin", help="Lowest frequency, Hz.")
OPT_FMAX = typer.Option(5.0, "--fmax", help="Highest frequency, Hz.")
OPT_FSTEP = typer.Option(0.1, "--fstep", help="Frequency step, Hz.")
OPT_STEADY = typer.Option("adaptive", "--steady", help="adaptive (until periodic) or fixed.")
OPT_CYCLES = typer.Option(None, "--cycles", help="Cycles per step with --steady fixed (30).")
OPT_MEASURE_CYCLES = typer.Option(5, "--measure-cycles", help="Cycles measured at the end of a step.")
OPT_MAX_CYCLES = typer.Option(None, "--max-cycles", help="Most cycles per step, adaptive (500).")
OPT_WORKERS = typer.Option(None, "--workers", help="Parallel sweeps (default: all cores).")
OPT_NBS = typer.Option(None, "--nbs", help="NBs system TOML (instead of --preset).")
OPT_YBS = typer.Option(None, "--ybs", help="YBs system TOML (instead of --preset).")


def _fail(exc: Exception) -> None:
    err_console.print(f"[bold red]error:[/] {escape(str(exc))}")
    raise typer.Exit(code=2)


def _kv_table(title: str) -> tuple[Table, Callable[[str, str], None]]:
    """A two-column summary table and its ``add(label, value)`` (labels may hold [units])."""
    table = Table(title=escape(title), show_header=False)

    def add(label: str, value: str) -> None:
        table.add_row(escape(label), escape(value))

    return table, add


def _system(system: Optional[Path], preset: Optional[str], bumpers: bool = True):
    from . import presets
    from .model import Oscillator

    if (system is None) == (preset is None):
        raise typer.BadParameter("give either SYSTEM.toml or --preset NAME (one of them)")
    return Oscillator.from_toml(system) if system is not None else presets.by_name(preset, bumpers=bumpers)


@app.callback()
def _main() -> None:
    """Simulate, sweep and analyse impacting base-isolated oscillators."""


@app.command()
def simulate(
    system: Optional[Path] = typer.Argument(None, help="System TOML (see examples/). Omit to use --preset."),
    a_g: float = typer.Option(..., "--a-g", help="Peak table acceleration in g (the paper's a_G)."),
    freq: float = typer.Option(..., "--freq", help="Excitation frequency, Hz."),
    duration: float = typer.Option(20.0, "--duration", help="Simulated time, s."),
    preset: Optional[str] = typer.Option(None, "--preset", help="Use a built-in system: paper-printed, paper-damped or paper-calibrated."),
    no_bumpers: bool = typer.Option(False, "--no-bumpers", help="With --preset: the NBs configuration."),
    sample_rate: float = typer.Option(1000.0, "--sample-rate", help="History samples per second, Hz."),
    velocity: float = typer.Option(0.0, "--velocity", help="Initial velocity relative to the table, m/s."),
    contacts: Optional[Path] = typer.Option(None, "--contacts", help="Write the contact table (CSV)."),
    history: Optional[Path] = typer.Option(None, "--history", help="Write the sampled histories (CSV)."),
) -> None:
    """Simulate one harmonic excitation and summarise the run (exact extrema, contacts, energy)."""
    from .engine import State, simulate as run_simulation
    from .excitation import Harmonic

    try:
        osc = _system(system, preset, bumpers=not no_bumpers)
        exc = Harmonic(a_g, freq)
        with console.status(f"simulating {duration:g} s at {freq:g} Hz, a_G = {a_g:g} ..."):
            run = run_simulation(osc, exc, duration, State.at_rest(osc, velocity_m_s=velocity),
                                 sample_rate_hz=sample_rate)
    except InputError as exc_:
        _fail(exc_)
        return
    table, add_row = _kv_table(f"{system or preset}: a_G = {a_g:g}, f = {freq:g} Hz, {duration:g} s")
    add_row("status", run.message)
    add_row("D max / min [mm]", f"{run.displacement_max * 1e3:.4f} / {run.displacement_min * 1e3:.4f}")
    add_row("max |abs. acceleration| [g]", f"{run.abs_acceleration_max / exc.g:.4f}")
    add_row("alpha = max|a_abs| / A_t", f"{run.abs_acceleration_max / abs(exc.peak_m_s2):.4f}")
    n = len(run.contacts)
    add_row("contacts", f"{n} ({(run.contacts['side'] == 'left').sum()} left)" if n else "0")
    done = run.impacts.dropna(subset=["contact_time_s"])
    if len(done):
        add_row("mean restitution s", f"{done['restitution'].mean():.4f}")
        add_row("mean contact time [ms]", f"{done['contact_time_s'].mean() * 1e3:.3f}")
        add_row("max peak force [kN]", f"{done['peak_force_n'].max() / 1e3:.3f}")
    e = run.energy
    add_row("energy in / residual [J]", f"{e.input_work:.6g} / {e.residual:.2e}")
    console.print(table)
    if contacts is not None:
        run.contacts.to_csv(contacts, index=False)
        console.print(f"contacts -> {contacts}")
    if history is not None:
        run.to_dataframe().to_csv(history, index=False)
        console.print(f"history -> {history}")
    if not run.success:
        raise typer.Exit(code=1)


# the columns of `pounding sweep --out`, as issue 3 names them
SWEEP_CSV_COLUMNS = ["freq_hz", "alpha", "excursion_m", "eta", "e", "contact", "contacts_per_cycle",
                     "restitution", "contact_time_s", "mean_force_n", "peak_force_n",
                     "dissipated_energy_j", "steady", "period_multiple"]


def _frequencies(fmin: float, fmax: float, fstep: float):
    import numpy as np

    from ._checks import positive

    fmin = positive("--fmin", fmin, "Hz")
    fmax = positive("--fmax", fmax, "Hz")
    fstep = positive("--fstep", fstep, "Hz")
    if fmax < fmin:
        raise typer.BadParameter(f"--fmax {fmax:g} is below --fmin {fmin:g}; give fmin <= fmax")
    n = int(round((fmax - fmin) / fstep))
    return np.round(fmin + fstep * np.arange(n + 1), 10)


def _steady_options(steady: str, cycles: Optional[int], max_cycles: Optional[int]) -> dict:
    if steady == "fixed":
        return {"steady": "fixed", "cycles": cycles}
    if cycles is not None:
        raise typer.BadParameter("--cycles is for --steady fixed; use --max-cycles with adaptive")
    return {"steady": steady, "max_cycles": max_cycles}


@app.command()
def sweep(
    system: Optional[Path] = typer.Argument(None, help="System TOML (see examples/). Omit to use --preset."),
    a_g: float = typer.Option(..., "--a-g", help="Peak table acceleration in g (the paper's a_G)."),
    direction: str = typer.Option("up", "--direction", help="up or down."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the per-step table (CSV)."),
    preset: Optional[str] = typer.Option(None, "--preset", help="Use a built-in system: paper-printed, paper-damped or paper-calibrated."),
    no_bumpers: bool = typer.Option(False, "--no-bumpers", help="With --preset: the NBs configuration."),
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = OPT_FSTEP,
    steady: str = OPT_STEADY,
    cycles: Optional[int] = OPT_CYCLES,
    measure_cycles: int = OPT_MEASURE_CYCLES,
    max_cycles: Optional[int] = OPT_MAX_CYCLES,
    netcdf: Optional[Path] = typer.Option(None, "--netcdf", help="Also write the result as netCDF."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Also draw alpha and eta against nu (PNG, PDF...)."),
) -> None:
    """Stepped-sine sweep: each frequency held until steady (or for fixed cycles), state carried over."""
    from ._errors import Interrupted
    from .protocols import sweep as run_sweep

    try:
        osc = _system(system, preset, bumpers=not no_bumpers)
        freqs = _frequencies(fmin, fmax, fstep)
        result = run_sweep(osc, a_g, freqs, direction, measure_cycles=measure_cycles, progress=True,
                           **_steady_options(steady, cycles, max_cycles))
    except InputError as exc_:
        _fail(exc_)
        return
    except Interrupted as stop:
        err_console.print(f"[yellow]{escape(str(stop))}[/]")
        result = stop.partial
    table, add = _kv_table(f"{system or preset}: sweep {result.direction}, a_G = {a_g:g}")
    add("status", result.message)
    if result.steps_done:
        add("nu_R (alpha peak)", f"{result.nu_r:g}")
        add("alpha max", f"{result.alpha_max:.4f}")
        rng = result.contact_range_hz
        add("contact range [Hz]", "none" if rng is None else f"{rng[0]:g} - {rng[1]:g}")
        jumps = result.jumps()
        add("jumps [Hz]", ", ".join(f"{a:g}->{b:g} ({k})" for a, b, k in
                                    zip(jumps["freq_from_hz"], jumps["freq_to_hz"], jumps["kind"])) or "none")
    console.print(table)
    if out is not None:
        result.to_dataframe()[SWEEP_CSV_COLUMNS].to_csv(out, index=False)
        console.print(f"per-step table -> {out}")
    if netcdf is not None:
        result.to_xarray().to_netcdf(netcdf)
        console.print(f"dataset -> {netcdf}")
    if plot is not None:
        _save_figure(result.plot, plot)
    if result.steps_done < result.freqs_hz.size:
        raise typer.Exit(code=130)
    if not result.success:
        raise typer.Exit(code=1)


def _save_figure(draw: Callable, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    artists = draw()
    artists[0].figure.savefig(path, dpi=150)
    plt.close(artists[0].figure)
    console.print(f"figure -> {path}")


@app.command()
def campaign(
    out: Path = typer.Option(..., "--out", help="Directory for campaign.nc, steps.csv, table2-4.csv, campaign.png."),
    preset: Optional[str] = typer.Option(None, "--preset", help="Built-in system for both configurations: paper-printed, paper-damped or paper-calibrated."),
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
) -> None:
    """The paper's matrix: NBs at a_G 0.03, 0.05, 0.1 and YBs at 0.03, 0.05, 0.075, 0.1, up and down."""
    from . import presets
    from ._errors import Interrupted
    from .model import Oscillator
    from .protocols import campaign as run_campaign

    complete = True
    try:
        if preset is not None and (nbs or ybs):
            raise typer.BadParameter("give --preset or --nbs/--ybs, not both")
        if preset is not None:
            nbs_osc, ybs_osc = presets.by_name(preset, bumpers=False), presets.by_name(preset)
        elif nbs or ybs:
            nbs_osc = Oscillator.from_toml(nbs) if nbs else None
            ybs_osc = Oscillator.from_toml(ybs) if ybs else None
        else:
            raise typer.BadParameter("give --preset NAME, or --nbs and/or --ybs TOML files")
        result = run_campaign(nbs_osc, ybs_osc, freqs_hz=_frequencies(fmin, fmax, fstep),
                              measure_cycles=measure_cycles, workers=workers,
                              progress=True, **_steady_options(steady, cycles, max_cycles))
    except InputError as exc_:
        _fail(exc_)
        return
    except Interrupted as stop:
        err_console.print(f"[yellow]{escape(str(stop))}; saving them[/]")
        result, complete = stop.partial, False
    out.mkdir(parents=True, exist_ok=True)
    result.to_netcdf(out / "campaign.nc")
    steps = result.dataset.to_dataframe().reset_index()
    steps[steps["ran"]].drop(columns=["ran"]).to_csv(out / "steps.csv", index=False)
    table2 = result.table2()
    for name, df in (("table2", table2), ("table3", result.table3()), ("table4", result.table4())):
        df.to_csv(out / f"{name}.csv", index=False)
    _save_figure(result.plot, out / "campaign.png")
    summary = Table(title="Table 2 analogue (model)")
    for col in ("configuration", "a_g", "direction", "nu_r", "alpha", "eta", "e", "contact_nu_min",
                "contact_nu_max"):
        summary.add_column(col)
    for _, row in table2.iterrows():
        summary.add_row(*(f"{v:.4g}" if isinstance(v, float) else str(v) for v in row.to_numpy()))
    console.print(summary)
    console.print(f"campaign.nc, steps.csv, table2-4.csv, campaign.png -> {out}")
    if not complete:
        raise typer.Exit(code=130)


@app.command()
def reproduce(
    preset: Optional[str] = typer.Option(None, "--preset",
                                         help="Built-in system (default: the best the package has, paper-calibrated)."),
    nbs: Optional[Path] = OPT_NBS,
    ybs: Optional[Path] = OPT_YBS,
    out: Path = typer.Option(Path("report"), "--out", help="Directory for index.html, tables and figures."),
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = OPT_FSTEP,
    workers: Optional[int] = OPT_WORKERS,
) -> None:
    """The paper's tables and figures from the model, beside the measurements, in one HTML report."""
    from . import presets
    from ._errors import Interrupted
    from .model import Oscillator
    from .reports import reproduce as write_report

    try:
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
        beside = {"paper-printed": presets.paper_printed()}
        beside[label if (nbs or ybs) else (preset or presets.BEST_PRESET)] = ybs_osc
        report = write_report(nbs_osc, ybs_osc, out, system_label=label, beside=beside,
                              freqs_hz=_frequencies(fmin, fmax, fstep), workers=workers, progress=True)
    except InputError as exc_:
        _fail(exc_)
        return
    except Interrupted as stop:
        err_console.print(f"[yellow]{escape(str(stop))}; no report written[/]")
        raise typer.Exit(code=130) from None
    t2 = report.comparisons["2"]
    summary = Table(title=f"Table 2, model ({escape(label)}) beside measured (paper)")
    for col in ("cfg", "a_G", "dir", "nu_R model", "nu_R meas.", "alpha model", "alpha meas.",
                "eta|e model", "eta|e meas."):
        summary.add_column(col)
    for _, row in t2.iterrows():
        q = "eta" if row["configuration"] == "YBs" else "e"
        summary.add_row(row["configuration"], f"{row['a_g']:g}", row["direction"],
                        *(f"{row[c]:.3g}" for c in ("nu_r_model", "nu_r_measured", "alpha_model",
                                                    "alpha_measured", f"{q}_model", f"{q}_measured")))
    console.print(summary)
    console.print(f"report -> {report.index_html} (tables CSV, {len(report.figures)} figures PNG)")


@app.command()
def identify(
    targets: Optional[Path] = typer.Argument(None, help="Targets TOML (see examples/). Omit for --paper."),
    family: Path = typer.Option(..., "--family", help="Model family TOML: structure, fixed numbers, bounds."),
    out: Path = typer.Option(Path("calibrated.toml"), "--out", help="Write the fitted YBs system (TOML)."),
    paper: bool = typer.Option(False, "--paper", help="Fit the paper's Tables 2-4 (instead of TARGETS.toml)."),
    residuals: Optional[Path] = typer.Option(None, "--residuals", help="Also write the residual table (CSV)."),
    seed: int = typer.Option(0, "--seed", help="Seed of the global search (same seed, same result)."),
    maxiter: int = typer.Option(30, "--maxiter", help="Generations of differential evolution."),
    popsize: int = typer.Option(10, "--popsize", help="Population per free number."),
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = OPT_FSTEP,
    cycles: int = typer.Option(30, "--cycles", help="Cycles per step (fixed schedule, as the lab)."),
    workers: Optional[int] = OPT_WORKERS,
) -> None:
    """Model updating: fit a family's free numbers so that the simulated sweeps match measured targets."""
    from ._errors import Interrupted
    from .identification import ModelFamily, Targets, identify as run_identify, paper_targets

    try:
        if (targets is None) == (not paper):
            raise typer.BadParameter("give either TARGETS.toml or --paper (one of them)")
        goal = paper_targets() if paper else Targets.from_toml(targets)
        fam, bounds = ModelFamily.from_toml(family)
        fit = run_identify(goal, fam, bounds, seed=seed, maxiter=maxiter, popsize=popsize, workers=workers,
                           freqs_hz=_frequencies(fmin, fmax, fstep), cycles=cycles, progress=True)
    except InputError as exc_:
        _fail(exc_)
        return
    except Interrupted as stop:
        if stop.partial is None:
            raise typer.Exit(code=130) from None
        fit = stop.partial
        err_console.print("[yellow]interrupted: writing the best candidate so far[/]")
    params = Table(title="fitted numbers")
    for col in ("name", "value", "low", "high", "at bound"):
        params.add_column(col)
    for row in fit.parameter_table().itertuples(index=False):
        params.add_row(row.name, f"{row.value:.6g}", f"{row.low:g}", f"{row.high:g}", "yes" if row.at_bound else "")
    console.print(params)
    table = Table(title="residuals (model - target) / tolerance")
    for col in ("cfg", "a_G", "dir", "quantity", "target", "model", "normalized", "met"):
        table.add_column(col)
    for row in fit.residuals.itertuples(index=False):
        table.add_row(row.configuration, f"{row.a_g:g}", row.direction, row.quantity, f"{row.target:.4g}",
                      f"{row.model:.4g}", f"{row.normalized:+.2f}", "yes" if row.within else "[red]no[/]")
    console.print(table)
    fit.to_toml(out)
    if residuals is not None:
        fit.to_dataframe().to_csv(residuals, index=False)
    console.print(f"{escape(fit.message)}\nfitted system -> {out}")


@app.command("warm-up")
def warm_up() -> None:
    """Compile the engine now (10-20 s once after installing; later sessions load it in ~1 s)."""
    from ._warm_up import warm_up as run_warm_up

    with console.status("compiling pounding's kernels (once after installing: 10-20 s) ..."):
        report = run_warm_up()
    console.print(escape(report.message))
    for folder in report.cache_dirs:
        console.print(f"  cache: {escape(folder)}")


if __name__ == "__main__":  # pragma: no cover
    app()
