"""``pounding lab``: a shaking-table recording in, the paper's measurements out (issue 17)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional

import typer

from .._io import interrupts_deferred, write_text
from ._app import cell, command, console, data_table, float_list, folder, save_figure, write_csv

ROLE_NAMES = ("time", "table_acc", "mass_acc", "displacement")


def _column(text: str) -> Any:
    """A column by name, or by 0-based index when it is a whole number."""
    text = text.strip()
    return int(text) if text.isdigit() else text


def _units(text: Optional[str]) -> Optional[dict[str, str]]:
    """``time=ms,table_acc=g,...`` as a dict."""
    if text is None:
        return None
    out = {}
    for part in text.split(","):
        if "=" not in part:
            raise typer.BadParameter(f"{part!r} is not role=unit; e.g. "
                                     "time=ms,table_acc=g,mass_acc=g,displacement=mm",
                                     param_hint="--units")
        role, unit = (p.strip() for p in part.split("=", 1))
        out[role] = unit
    return out


@command()
def lab(
    test: Path = typer.Argument(..., metavar="TEST.csv",
                                help="The recording: delimited text (CSV, TSV, whitespace)."),
    time: str = typer.Option(..., "--time", help="The time column (name, or 0-based index)."),
    table_acc: str = typer.Option(..., "--table-acc", help="The table's acceleration column."),
    mass_acc: str = typer.Option(..., "--mass-acc",
                                 help="The mass's accelerometer columns, comma-separated."),
    displacement: str = typer.Option(..., "--displacement", help="The mass's displacement (laser) column."),
    units: Optional[str] = typer.Option(
        None, "--units",
        help="Per role: time=s|ms, table_acc and mass_acc=g|m/s2|cm/s2, displacement=m|mm (SI if left out)."
    ),
    mass: float = typer.Option(..., "--mass", help="The mass on the table, kg."),
    gap: Optional[float] = typer.Option(None, "--gap", help="The total gap Delta (m) of a YBs test."),
    freqs: Optional[str] = typer.Option(None, "--freqs",
                                        help="The schedule's frequencies, Hz, comma-separated (else found)."),
    measure_cycles: int = typer.Option(5, "--measure-cycles",
                                       help="Whole cycles measured at the end of each step."),
    configuration: Optional[str] = typer.Option(
        None, "--configuration", help="NBs or YBs for the targets (default: YBs with --gap, else NBs)."
    ),
    a_g: Optional[float] = typer.Option(None, "--a-g",
                                        help="a_G (g) the targets are for (default: the measured one)."),
    out: Path = typer.Option(..., "--out",
                             help="Directory for steps.csv, impacts.csv, lab_sweep.png, targets.toml."),
) -> None:
    """Measure a stepped-sine shaking-table test: Table 2 per step, the contacts, a figure and targets for
    identify."""
    from ..identification import Targets
    from ..lab import analyse_stepped_sine, read_test

    out = folder("--out", out)
    schedule = None if freqs is None else float_list("--freqs", freqs)
    record = read_test(test, time=_column(time), table_acc=_column(table_acc),
                       mass_acc=[_column(c) for c in mass_acc.split(",")], displacement=_column(displacement),
                       units=_units(units))
    result = analyse_stepped_sine(record, mass_kg=mass, gap_total_m=gap, freqs_hz=schedule,
                                  measure_cycles=measure_cycles)
    targets = Targets.from_lab(result, configuration or ("YBs" if gap is not None else "NBs"), a_g=a_g)
    with interrupts_deferred():  # every file whole
        out.mkdir(parents=True, exist_ok=True)
        write_csv(result.to_dataframe(), out / "steps.csv")
        if gap is not None:
            write_csv(result.impacts, out / "impacts.csv")
        write_text(out / "targets.toml", targets.to_toml_text())
        save_figure(result.plot, out / "lab_sweep.png")
    cols = ["freq_hz", "alpha", "eta" if gap is not None else "e", "steady"]
    cols += ["contacts_per_cycle", "contact_time_s", "restitution"] if gap is not None else []
    summary = data_table(f"{test.name}: {len(result.steps)} steps, a_G {result.a_g:.4g}, "
                         f"{record.sample_rate_hz:g} Hz",
                         cols)
    for _, row in result.steps.iterrows():
        summary.add_row(*(cell(row[c]) for c in cols))
    console.print(summary)
    console.print(f"nu_R {result.nu_r:g}, alpha max {result.alpha_max:.4g}; steps.csv, "
                  f"{'impacts.csv, ' if gap is not None else ''}lab_sweep.png, targets.toml -> {out}")
