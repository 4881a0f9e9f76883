"""Command line: ``pounding simulate SYSTEM.toml --a-g 0.05 --freq 2.2 --duration 20``."""

from __future__ import annotations

from pathlib import Path
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


def _fail(exc: Exception) -> None:
    err_console.print(f"[bold red]error:[/] {exc}")
    raise typer.Exit(code=2)


@app.callback()
def _main() -> None:
    """Simulate, sweep and analyse impacting base-isolated oscillators."""


@app.command()
def simulate(
    system: Optional[Path] = typer.Argument(None, help="System TOML (see examples/). Omit to use --preset."),
    a_g: float = typer.Option(..., "--a-g", help="Peak table acceleration in g (the paper's a_G)."),
    freq: float = typer.Option(..., "--freq", help="Excitation frequency, Hz."),
    duration: float = typer.Option(20.0, "--duration", help="Simulated time, s."),
    preset: Optional[str] = typer.Option(None, "--preset", help="Use a built-in system: paper-printed."),
    no_bumpers: bool = typer.Option(False, "--no-bumpers", help="With --preset: the NBs configuration."),
    sample_rate: float = typer.Option(1000.0, "--sample-rate", help="History samples per second, Hz."),
    velocity: float = typer.Option(0.0, "--velocity", help="Initial velocity relative to the table, m/s."),
    contacts: Optional[Path] = typer.Option(None, "--contacts", help="Write the contact table (CSV)."),
    history: Optional[Path] = typer.Option(None, "--history", help="Write the sampled histories (CSV)."),
) -> None:
    """Simulate one harmonic excitation and summarise the run (exact extrema, contacts, energy)."""
    from . import presets
    from .engine import State, simulate as run_simulation
    from .excitation import Harmonic
    from .model import Oscillator

    try:
        if (system is None) == (preset is None):
            raise typer.BadParameter("give either SYSTEM.toml or --preset NAME (one of them)")
        osc = (Oscillator.from_toml(system) if system is not None
               else presets.by_name(preset, bumpers=not no_bumpers))
        exc = Harmonic(a_g, freq)
        with console.status(f"simulating {duration:g} s at {freq:g} Hz, a_G = {a_g:g} ..."):
            run = run_simulation(osc, exc, duration, State.at_rest(osc, velocity_m_s=velocity),
                                 sample_rate_hz=sample_rate)
    except InputError as exc_:
        _fail(exc_)
        return
    table = Table(title=f"{system or preset}: a_G = {a_g:g}, f = {freq:g} Hz, {duration:g} s",
                  show_header=False)
    add_row = lambda label, value: table.add_row(escape(label), escape(value))  # noqa: E731 (units in [])
    add_row("status", run.message)
    add_row("D max / min [mm]", f"{run.displacement_max * 1e3:.4f} / {run.displacement_min * 1e3:.4f}")
    add_row("max |abs. acceleration| [g]", f"{run.abs_acceleration_max / exc.g:.4f}")
    add_row("alpha = max|a_abs| / A_t", f"{run.abs_acceleration_max / abs(exc.peak_m_s2):.4f}")
    n = len(run.contacts)
    add_row("contacts", f"{n} ({(run.contacts['side'] == 'left').sum()} left)" if n else "0")
    if n:
        done = run.contacts.dropna()
        if len(done):
            s = (-done["v_out"] / done["v_in"]).mean()
            add_row("mean restitution s", f"{s:.4f}")
            add_row("mean contact time [ms]", f"{(done['t_end'] - done['t_start']).mean() * 1e3:.3f}")
            add_row("max peak force [kN]", f"{done['peak_force'].max() / 1e3:.3f}")
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


if __name__ == "__main__":  # pragma: no cover
    app()
