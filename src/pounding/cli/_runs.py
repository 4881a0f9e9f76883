"""``pounding simulate``, ``sweep`` and ``campaign``."""

from __future__ import annotations

import math

from pathlib import Path
from typing import Any, Optional

import typer
from rich.markup import escape

from .._errors import Interrupted
from .._io import atomic_write, interrupts_deferred
from ._app import (
    working,
    ARG_SYSTEM,
    OPT_A_G,
    OPT_CYCLES,
    OPT_FMAX,
    OPT_FMIN,
    OPT_FSTEP,
    OPT_MAX_CYCLES,
    OPT_MEASURE_CYCLES,
    OPT_NO_BUMPERS,
    OPT_PRESET,
    OPT_STEADY,
    command,
    console,
    figure_path,
    files,
    frequencies,
    interrupted,
    kv_table,
    run_files,
    save_figure,
    steady_options,
    system,
    write_csv,
)

CSV = (".csv",)
NETCDF = (".nc", ".nc4", ".netcdf")


@command()
def simulate(
    system_file: Optional[Path] = ARG_SYSTEM,
    a_g: Optional[float] = typer.Option(None, "--a-g",
                                        help="Peak table acceleration in g (the paper's a_G)."),
    freq: Optional[float] = typer.Option(None, "--freq", help="Excitation frequency, Hz."),
    record: Optional[Path] = typer.Option(
        None, "--record", help="Shake with a record instead: a PEER .AT2 file, or text with a time and an "
        "acceleration column (g; one column with --record-dt)."),
    record_dt: Optional[float] = typer.Option(None, "--record-dt",
                                              help="The time step (s) of a one-column record."),
    record_units: str = typer.Option("g", "--record-units", help="A text record's unit: g, m/s2 or cm/s2."),
    scale_pga: Optional[float] = typer.Option(None, "--scale-pga", help="Scale the record to this PGA, g (a "
                                              "pair: both components by the factor that scales --record's)."),
    record_y: Optional[Path] = typer.Option(
        None, "--record-y", help="A building in plan: the record's second component, along y (read as "
        "--record is); --record is then the component along x."),
    direction: Optional[float] = typer.Option(
        None, "--direction", help="A building in plan: --record alone moves it along this angle, degrees "
        "from x towards y; with --record-y, the pair's axes are turned by it against the building's (as "
        "pounding moat and orientations turn them: --record's component then acts along -DEG)."),
    duration: Optional[float] = typer.Option(
        None, "--duration", help="Simulated time, s (default 20 s; with --record, the record's length)."),
    preset: Optional[str] = OPT_PRESET,
    no_bumpers: bool = OPT_NO_BUMPERS,
    sample_rate: Optional[float] = typer.Option(
        None,
        "--sample-rate",
        help="History samples per second, Hz (default 1000, fewer for runs over 1000 s; 0: the events only).",
    ),
    velocity: float = typer.Option(0.0, "--velocity", help="Initial velocity relative to the table, m/s (a "
                                   "structure: every moving level's, as one body)."),
    contacts: Optional[Path] = typer.Option(None, "--contacts", help="Write the contact table (CSV)."),
    history: Optional[Path] = typer.Option(None, "--history", help="Write the sampled histories (CSV)."),
    plot: Optional[Path] = typer.Option(
        None, "--plot", help="Draw displacement and acceleration (PNG, PDF...); a building in plan: its "
        "orbit in plan."
    ),
) -> None:
    """Simulate a harmonic excitation or a record and summarise the run (exact extrema, contacts, energy).

    SYSTEM.toml may be a structure of several masses (examples/building_moat.toml), or two adjacent ones
    (examples/adjacent_buildings.toml): a row per level; --contacts then writes every contact, at the walls
    and the links. A building in plan (examples/plan_building.toml: [[floors]], [[bearings]], a [moat]) takes
    --record along --direction, or with its second component --record-y."""
    from ..engine import State, structure_runs
    from ..engine import simulate as run_simulation
    from ..engine.assembly import is_plan, structures_of

    out = files(contacts=(contacts, CSV), history=(history, CSV))
    plot = figure_path("--plot", plot)
    osc = system(system_file, preset, bumpers=not no_bumpers)
    exc, what = excitation(a_g, freq, record, record_dt, record_units, scale_pga)
    if duration is None:
        duration = exc.t[-1] if record is not None else 20.0
    if is_plan(osc):
        from ._plan import simulate_plan

        exc, what = plan_excitation(exc, what, record_y, direction, record_dt, record_units)
        simulate_plan(osc, exc, what, duration, velocity, sample_rate, out, plot, system_file)
        return
    for name, value in (("--record-y", record_y), ("--direction", direction)):
        if value is not None:
            raise typer.BadParameter(f"{name} is for a building in plan (a SYSTEM.toml with [[floors]]): a "
                                     "structure on a line moves along one direction")
    start = State.at_rest(osc, velocity_m_s=velocity)  # (a structure's moving levels all at it, as one body)
    wants_history = history is not None or plot is not None
    rate = sample_rate if wants_history else 0.0  # nothing to sample for: the events only (extrema are exact)
    levels = sum(s.n_levels for s in structures_of(osc)[0])
    complete = True
    try:
        with working(f"simulating {duration:g} s of {what}" + (f" on {levels} levels" if levels > 1 else "")
                     + " ..."):
            run = run_simulation(osc, exc, duration, start, sample_rate_hz=rate)
    except Interrupted as stop:
        run, complete = stop.partial, False
    s = run.summary()
    table, add_row = kv_table(f"{what}, {s['t_end_s']:g} s", system_file or preset)
    add_row("status", run.message)
    if hasattr(run, "links"):  # (a pair: each structure's contacts, and the links')
        _pair_rows(add_row, s)
    else:
        fixed = structure_runs(run)[0].structure.fixed
        _run_rows(add_row, s, exc, record is None, levels > 1, fixed)
    add_row("energy in / residual [J]", f"{s['input_work_j']:.6g} / {s['energy_residual_j']:.2e}")
    console.print(table)
    _level_tables(run, exc)
    run_files(run, out, plot, duration, complete)


def _run_rows(add_row: Any, s: Any, exc: Any, harmonic: bool, several: bool, fixed: bool) -> None:
    """A run's rows of the table ``pounding simulate`` prints, whatever the system (its summary's): the base's
    exact extrema (a single mass's own; a fixed base's none: it is the ground), the largest acceleration and
    alpha, the contacts (per level, where there are several)."""
    base = "base " if several else ""
    add_row(f"{base}D max / min [mm]",
            "- (a fixed base: the ground)" if fixed else
            f"{s['displacement_max_m'] * 1e3:.4f} / {s['displacement_min_m'] * 1e3:.4f}")
    if not fixed:
        add_row(f"{base}D at the end [mm]", f"{s['displacement_end_m'] * 1e3:.4f}")
    if s["sticks"] or s["slips"]:
        add_row("isolator sticks / slips", f"{s['sticks']} / {s['slips']}")
    if s["surface_slips"] or s["rings"]:  # (a triple friction pendulum's)
        add_row("surface slips / rings reached", f"{s['surface_slips']} / {s['rings']}")
    rigid = s["rigid_impacts"]  # (a rigid stop's impacts: impulses, no force)
    between = "inf at the rigid impacts (impulses); {} between them" if rigid else "{}"
    add_row("max |abs. acceleration| [g]", between.format(f"{s['abs_acceleration_max_m_s2'] / exc.g:.4f}"))
    alpha = s["alpha"]
    add_row("alpha = max|a_abs| / " + ("A_t" if harmonic else "PGA"), between.format(f"{alpha:.4f}")
            if not math.isnan(alpha) else "- (no shaking)")
    n, left = s["contacts"], f"{s['contacts_left']} left"
    add_row("contacts", f"{n} ({rigid} rigid impacts, {left})" if rigid else f"{n} ({left})" if n else "0")
    if n and several:
        add_row("contacts per level", _per_level(s, ""))
    _contact_rows(add_row, s)


def _per_level(s: Any, prefix: str) -> str:
    """A summary's contacts at each level with a wall that was struck: ``3 at level 0, 2 at level 2``."""
    at = [(int(k.rsplit("_", 1)[1]), v) for k, v in s.items()
          if k.startswith(f"{prefix}contacts_level_") and v]
    return ", ".join(f"{v} at level {lv}" for lv, v in at)


def _pair_rows(add_row: Any, s: Any) -> None:
    """A pair's rows of the table ``pounding simulate`` prints: each structure's contacts per level, and at
    the links."""
    for name in ("first", "second"):
        add_row(f"{name}: walls' contacts", _per_level(s, f"{name}_") if s[f"{name}_contacts"] else "0")
        if s[f"{name}_sticks"] or s[f"{name}_slips"]:
            add_row(f"{name}: isolator sticks / slips", f"{s[f'{name}_sticks']} / {s[f'{name}_slips']}")
        if s[f"{name}_surface_slips"] or s[f"{name}_rings"]:
            add_row(f"{name}: surface slips / rings reached",
                    f"{s[f'{name}_surface_slips']} / {s[f'{name}_rings']}")
    add_row("contacts at the links", str(s["link_contacts"]))


def _level_tables(run: Any, exc: Any) -> None:
    """Each structure's table of levels (exact extrema and drift ratios), where it has more than one."""
    from rich.table import Table

    from ..engine import structure_runs

    parts = structure_runs(run)
    for name, part in zip(("first", "second") if len(parts) == 2 else ("",), parts):
        if part.structure.n_levels == 1:  # (one level: its extrema are the summary's)
            continue
        levels = Table(title=f"{name + ': ' if name else ''}each level (extrema exact)")
        for head in ("level", "max / min [mm]", "max |a_abs| [g]", "drift ratio [%]"):
            levels.add_column(escape(head), justify="right")
        for level, row in part.peaks().iterrows():
            ratio = row["drift_ratio_peak"]
            base = "ground" if part.structure.fixed else "base"
            levels.add_row(base if level == 0 else str(level),
                           f"{row['displacement_max_m'] * 1e3:.2f} / {row['displacement_min_m'] * 1e3:.2f}",
                           f"{row['abs_acceleration_max_m_s2'] / exc.g:.3f}",
                           "-" if ratio != ratio else f"{ratio * 100:.3f}")
        console.print(levels)


def _contact_rows(add_row: Any, s: Any) -> None:
    """A run's summary's contacts in the table ``pounding simulate`` prints, whatever the system: the mean
    restitution and contact time, the largest force (inf with rigid impacts)."""
    rigid = s["rigid_impacts"]
    if not math.isnan(s["restitution_mean"]):
        add_row("mean restitution s", f"{s['restitution_mean']:.4f}")
    if not math.isnan(s["contact_time_mean_s"]):
        add_row("mean contact time [ms]" + (" (holds and deformable contacts)" if rigid else ""),
                f"{s['contact_time_mean_s'] * 1e3:.3f}")
    if rigid:
        add_row("max peak force [kN]", "inf (the rigid impacts' impulses: see the contacts' impulse_n_s)")
    elif not math.isnan(s["peak_force_max_n"]):
        add_row("max peak force [kN]", f"{s['peak_force_max_n'] / 1e3:.3f}")


def excitation(a_g: float | None, freq: float | None, record: Path | None, record_dt: float | None,
               record_units: str, scale_pga: float | None) -> tuple[Any, str]:
    """The command line's excitation, and how to say it: --a-g and --freq, or --record."""
    from ..excitation import Harmonic, Record

    if record is None:
        if a_g is None or freq is None:
            raise typer.BadParameter("give --a-g and --freq (a harmonic excitation), or --record FILE")
        for name, value in (("--record-dt", record_dt), ("--scale-pga", scale_pga),
                            ("--record-units", None if record_units == "g" else record_units)):
            if value is not None:
                raise typer.BadParameter(f"{name} is for --record")
        return Harmonic(a_g, freq), f"a_G = {a_g:g}, f = {freq:g} Hz"
    if a_g is not None or freq is not None:
        raise typer.BadParameter("give --record, or --a-g and --freq, not both")
    if record.suffix.lower() == ".at2":
        for name, value in (("--record-dt", record_dt), ("--record-units", None if record_units == "g" else
                                                         record_units)):
            if value is not None:
                raise typer.BadParameter(f"{name} is for text records: an .AT2 file gives its DT and "
                                         "unit (g)")
        rec = Record.from_at2(record)
    else:
        columns = _text_columns(record)
        if columns == 0:
            raise typer.BadParameter(f"{record.name} holds no samples (an empty file, or comments only): "
                                     "give a record of time and acceleration, or of acceleration with "
                                     "--record-dt")
        if record_dt is not None and columns != 1:
            raise typer.BadParameter(f"{record.name} has {columns} columns: --record-dt is for a file of one "
                                     "column (accelerations); leave it out to read time and acceleration")
        if record_dt is None and columns != 2:
            raise typer.BadParameter(f"{record.name} has {columns} column(s): give a time and an "
                                     "acceleration column, or one acceleration column with --record-dt")
        if record_dt is not None:
            rec = Record.from_csv(record, accel=0, dt=record_dt, units=record_units)
        else:
            rec = Record.from_csv(record, time=0, accel=1, units=record_units)
    if scale_pga is not None:
        rec = rec.scaled(pga_g=scale_pga)
    return rec, f"record {rec.name} (PGA {rec.pga_g:.3g} g, {rec.duration_s:g} s)"


def plan_excitation(exc: Any, what: str, record_y: Path | None, direction: float | None,
                    record_dt: float | None, record_units: str) -> tuple[Any, str]:
    """A building in plan's excitation from the command line's: ``exc`` (--record's, scaled, or a harmonic)
    with --record-y's second component (read as --record was, scaled by the same factor), turned by
    --direction; a harmonic or one record without --direction along x."""
    from .._checks import real
    from ..excitation import Harmonic, Record, RecordPair

    angle = None if direction is None else real("--direction", direction)
    if record_y is None:
        if angle is None or isinstance(exc, Harmonic):
            if angle is not None:
                raise typer.BadParameter("--direction is for a record (--record): a harmonic shakes a "
                                         "building in plan along x")
            return exc, what + ", along x"
        return RecordPair.of_direction(exc, angle), what + f", along {angle:g} deg"
    if not isinstance(exc, Record):
        raise typer.BadParameter("--record-y is the second component of --record: give --record too")
    if record_y.suffix.lower() == ".at2":
        second = Record.from_at2(record_y)
    elif record_dt is not None:
        second = Record.from_csv(record_y, accel=0, dt=record_dt, units=record_units)
    else:
        second = Record.from_csv(record_y, time=0, accel=1, units=record_units)
    factor = exc.meta.get("scale_factor", 1.0)  # (--scale-pga's, on --record: the pair scaled as one)
    pair = RecordPair(exc, second if factor == 1.0 else second.scaled(factor=factor))
    what = f"records {pair.name} (PGA {pair.pga_g[0]:.3g} g, {pair.pga_g[1]:.3g} g)"
    if angle is not None:
        pair, what = pair.rotated(angle), what + f", turned by {angle:g} deg"
    return pair, what


def _text_columns(path: Path) -> int:
    """The number of fields on a text record's first line (0 for an empty or unreadable file: the
    reader then says what is wrong)."""
    from .._checks import read_text
    from .._delimited import COMMENT, delimiter_of, split_fields

    for line in read_text("--record", path).splitlines():
        if line.strip() and not line.lstrip().startswith(COMMENT):
            return len(split_fields(line, delimiter_of(line)))
    return 0


# the columns of `pounding sweep --out`, as issue 3 names them
SWEEP_CSV_COLUMNS = [
    "freq_hz",
    "alpha",
    "excursion_m",
    "eta",
    "e",
    "contact",
    "contacts_per_cycle",
    "restitution",
    "contact_time_s",
    "mean_force_n",
    "peak_force_n",
    "dissipated_energy_j",
    "steady",
    "period_multiple",
    "events_per_cycle",
    "sticks_per_cycle",
]


@command()
def sweep(
    system_file: Optional[Path] = ARG_SYSTEM,
    a_g: float = OPT_A_G,
    direction: str = typer.Option("up", "--direction", help="up or down."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the per-step table (CSV)."),
    preset: Optional[str] = OPT_PRESET,
    no_bumpers: bool = OPT_NO_BUMPERS,
    fmin: float = OPT_FMIN,
    fmax: float = OPT_FMAX,
    fstep: float = OPT_FSTEP,
    steady: str = OPT_STEADY,
    cycles: Optional[int] = OPT_CYCLES,
    measure_cycles: int = OPT_MEASURE_CYCLES,
    max_cycles: Optional[int] = OPT_MAX_CYCLES,
    netcdf: Optional[Path] = typer.Option(None, "--netcdf", help="Also write the result as netCDF (.nc)."),
    plot: Optional[Path] = typer.Option(
        None, "--plot", help="Also draw alpha and eta against nu (PNG, PDF...)."
    ),
) -> None:
    """Stepped-sine sweep: each frequency held until steady (or for fixed cycles), state carried over."""
    from ..protocols import sweep as run_sweep

    paths = files(out=(out, CSV), netcdf=(netcdf, NETCDF))
    plot = figure_path("--plot", plot)

    osc = system(system_file, preset, bumpers=not no_bumpers)
    freqs = frequencies(fmin, fmax, fstep)
    options = steady_options(steady, cycles, max_cycles)
    from ..protocols.sweep import make_plan

    make_plan(osc, a_g, freqs, direction, measure_cycles=measure_cycles, **options)  # all checks, no work
    try:
        result = run_sweep(
            osc, a_g, freqs, direction, measure_cycles=measure_cycles, progress=True, **options
        )
    except Interrupted as stop:
        result = stop.partial
    table, add = kv_table(f"sweep {result.direction}, a_G = {a_g:g}", system_file or preset)
    add("status", result.message)
    several = len(result.levels) > 1
    if result.steps_done:  # (the sweep's features: of the top level of the first structure, a mass's own)
        add("nu_R (alpha peak" + (" of the top level)" if several else ")"), f"{result.nu_r:g}")
        add("alpha max" + (" (top level)" if several else ""), f"{result.alpha_max:.4f}")
        rng = result.contact_range_hz
        add("contact range [Hz]", "none" if rng is None else f"{rng[0]:g} - {rng[1]:g}")
        jumps = result.jumps()
        add("jumps [Hz]", ", ".join(f"{a:g}->{b:g} ({k})" for a, b, k in
                                    zip(jumps["freq_from_hz"], jumps["freq_to_hz"], jumps["kind"])) or "none")
        add("events per cycle", _events_per_cycle(result))
    console.print(table)
    if several and result.steps_done:
        console.print(_structure_sweep_table(result))
    complete = result.steps_done == result.freqs_hz.size
    with interrupts_deferred() as held:
        if paths["out"] is not None:
            frame = result.to_dataframe()
            done = frame["freq_hz"].isin(result.freqs_hz[: result.steps_done])
            # (one level: the columns issue 3 names; several: every column, one row per step and level)
            write_csv(frame[done] if several else frame.loc[done, SWEEP_CSV_COLUMNS], paths["out"])
            console.print(f"per-step table -> {paths['out']}")
        if paths["netcdf"] is not None:
            atomic_write(paths["netcdf"], lambda tmp: result.to_xarray().to_netcdf(tmp))
            console.print(f"dataset -> {paths['netcdf']}")
        if plot is not None and result.steps_done:
            save_figure(result.plot, plot)
    if not complete and result.status == 0 or held:
        interrupted(
            f"{result.steps_done} of {result.freqs_hz.size} steps finished; they are in the "
            "summary" + (" and the files written" if any(paths.values()) or plot else "")
        )
    if not result.success:
        raise typer.Exit(code=1)


def _events_per_cycle(result) -> str:
    """The fewest and the most events the engine located per cycle over the finished steps, with the most
    sticks per cycle where a friction isolator stuck: ``"6 - 18 (sticks: up to 2)"``."""
    done = result.steps_done
    per_cycle = result.window_events[:done] / result.window_cycles[:done, None]
    text = f"{per_cycle[:, 0].min():g} - {per_cycle[:, 0].max():g}"
    return text + (f" (sticks: up to {per_cycle[:, 1].max():g})" if per_cycle[:, 1].max() > 0 else "")


def _structure_sweep_table(result):
    """A structure's sweep, one row per level: its alpha's peak and where, its largest excursion and the
    storey below's largest drift; and the contacts."""
    import numpy as np
    from rich.table import Table

    from ..protocols.sweep_window import level_name, slot_name

    done = slice(0, result.steps_done)
    table = Table(title="per level, over the steps")
    for name in ("level", "alpha max", "at f [Hz]", "excursion max [mm]", "drift max [mm]"):
        table.add_column(escape(name), justify="right", no_wrap=True)
    below = {lv: s for s, lv in enumerate(result.storeys)}
    def largest(values, fmt: str, scale: float = 1.0) -> str:  # ("-": no step measured it)
        return "-" if not np.any(np.isfinite(values)) else format(np.nanmax(values) * scale, fmt)

    for q, lv in enumerate(result.levels):
        alpha = result.alpha[done, q]
        excursion = result.level_metrics[done, q, 0] - result.level_metrics[done, q, 1]
        drift = largest(result.peak_drift[done, below[lv]], ".3f", 1e3) if lv in below else "-"
        at = f"{result.freqs_hz[int(np.nanargmax(alpha))]:g}" if np.any(np.isfinite(alpha)) else "-"
        table.add_row(level_name(result.levels, q), largest(alpha, ".4f"), at, largest(excursion, ".3f", 1e3),
                      drift)
    for c in range(len(result.contact_slots)):
        per_cycle = result.contacts_per_cycle[done, c]
        hit = result.freqs_hz[done][per_cycle > 0]
        table.add_section()
        table.add_row(slot_name(result.contact_slots, c), "contacts:",
                      "none" if hit.size == 0 else f"{hit.min():g} - {hit.max():g} Hz",
                      largest(per_cycle, "g") + "/cycle at most" if hit.size else "", "")
    return table
