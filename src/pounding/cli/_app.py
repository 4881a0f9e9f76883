"""The Typer app and what every command shares: errors, Ctrl-C, outputs, systems, frequencies."""

from __future__ import annotations

import contextlib
import functools
import signal
import sys
import threading
import warnings
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any, Optional

import numpy as np
import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table
from typer.core import TyperCommand, TyperGroup

from .._errors import InputError, MissingExtra, OutputError, PoundingWarning, Problem, StoreError
from .._io import FIGURE_SUFFIXES, atomic_write, interrupts_deferred, output_dir, output_file

NO_METAVAR = ""  # flags show no "<bool>" in the help



def _plain_help(option: Any) -> Any:
    """The help option shows no type (Typer shows ``--help <bool>`` otherwise)."""
    if option is not None:
        option.metavar = NO_METAVAR
    return option


class _Command(TyperCommand):
    """A command whose ``--help`` line shows no type, listed in ``pounding --help`` by its whole
    first sentence (Click cuts it to the terminal's width with "...")."""

    def get_help_option(self, ctx: Any) -> Any:
        return _plain_help(super().get_help_option(ctx))

    def get_short_help_str(self, limit: int = 45) -> str:
        first = " ".join((self.help or "").split("\n\n")[0].split())
        return first.split(". ")[0].rstrip(".") if first else super().get_short_help_str(limit)


class _Group(TyperGroup):
    """The ``pounding`` group, likewise; and every usage error (an option missing, unknown or given with
    one it excludes, a value Click or a command refuses) one line, exit 2, as bad input is: Click's own
    four lines (usage, a hint, a blank line, the error) read as a crash's."""

    def get_help_option(self, ctx: Any) -> Any:
        return _plain_help(super().get_help_option(ctx))

    def main(self, args: Any = None, prog_name: Any = None, complete_var: Any = None,
             standalone_mode: bool = True, **extra: Any) -> Any:
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode, **extra)
        # (Click's exceptions, from wherever this Typer takes Click: its own copy since 0.25, Click before)
        errors = sys.modules[typer.BadParameter.__module__]
        try:
            code = super().main(args, prog_name, complete_var, False, **extra)
        except getattr(errors, "NoArgsIsHelpError", ()) as exc:  # (no arguments: the help, as asked)
            exc.show()
            sys.exit(exc.exit_code)
        except errors.UsageError as exc:
            name = exc.ctx.command_path if exc.ctx is not None else "pounding"
            line = f"{exc.format_message()} (see {name} --help)"
            err_console.print(f"[bold red]error:[/] {escape(line)}", soft_wrap=True)
            sys.exit(2)
        except errors.ClickException as exc:
            exc.show()
            sys.exit(exc.exit_code)
        except typer.Abort:  # (Ctrl-C or end of input while Click prompts)
            err_console.print("[yellow]interrupted[/]")
            sys.exit(INTERRUPTED_EXIT)
        sys.exit(code if isinstance(code, int) else 0)


# Help texts are plain text (rich_markup_mode=None): in Rich's markup "[system]" is a style and vanished
# from the help, and a docstring's line breaks stayed as breaks in the middle of a sentence.
app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    rich_markup_mode=None,
    cls=_Group,
    help="pounding: base-isolated masses pounding against deformable bumpers.",
)


def _width(stream: Any) -> Optional[int]:
    """The consoles' width: the terminal's, or 160 columns when the output goes to a pipe or a file
    (Rich's 80 cut the tables' headers short: "configu…")."""
    try:
        return None if stream.isatty() else PIPED_WIDTH
    except (AttributeError, ValueError):  # (a closed or replaced stream)
        return PIPED_WIDTH


PIPED_WIDTH = 160
console = Console(width=_width(sys.stdout))
err_console = Console(stderr=True, width=_width(sys.stderr))
MISSING = "–"  # what a table shows for a number that is not there (NaN, None), rather than "nan"
INTERRUPTED_EXIT = 130  # the shell's code for a command ended by Ctrl-C (128 + SIGINT)


def _version(value: bool) -> None:
    if value:
        from .. import __version__

        console.print(f"pounding {__version__}")
        raise typer.Exit()


@app.callback()
def _main(
    version: bool = typer.Option(
        False,
        "--version",
        callback=_version,
        is_eager=True,
        metavar=NO_METAVAR,
        help="Print the version and exit.",
    ),
) -> None:
    """Simulate, sweep and analyse impacting base-isolated oscillators."""


# options shared by several commands (one definition each)
OPT_FMIN = typer.Option(0.5, "--fmin", help="Lowest frequency, Hz.")
OPT_FMAX = typer.Option(5.0, "--fmax", help="Highest frequency, Hz.")
OPT_FSTEP = typer.Option(0.1, "--fstep", help="Frequency step, Hz.")
OPT_STEADY = typer.Option("adaptive", "--steady", help="adaptive (until periodic) or fixed.")
OPT_CYCLES = typer.Option(None, "--cycles", help="Cycles per step with --steady fixed (30).")
OPT_MEASURE_CYCLES = typer.Option(5, "--measure-cycles", help="Cycles measured at the end of a step.")
OPT_MAX_CYCLES = typer.Option(None, "--max-cycles", help="Most cycles per step, adaptive (500).")
OPT_WORKERS = typer.Option(None, "--workers", help="Parallel sweeps (default: all cores).")
OPT_SCHEDULER = typer.Option("threads", "--scheduler",
                             help="threads, serial, processes, local (a Dask LocalCluster) or a Dask "
                                  "scheduler's address (tcp://host:8786).")
OPT_NBS = typer.Option(None, "--nbs", help="NBs system TOML (instead of --preset).")
OPT_YBS = typer.Option(None, "--ybs", help="YBs system TOML (instead of --preset).")
ARG_SYSTEM = typer.Argument(None, metavar="SYSTEM.toml",
                            help="System TOML (see examples/). Omit to use --preset.")
OPT_A_G = typer.Option(..., "--a-g", help="Peak table acceleration in g (the paper's a_G).")
OPT_FREQ = typer.Option(..., "--freq", help="Forcing frequency, Hz.")
# the built-in systems' names, as presets.PRESETS has them (written here so that the help needs no import of
# the model; tests/test_cli_hardening.py holds the two equal)
PRESET_NAMES = ("paper-printed", "paper-damped", "paper-calibrated", "paper-calibrated-v1",
                "paper-calibrated-v2", "paper-calibrated-measured", "paper-calibrated-laser")
PRESET_LIST = ", ".join(PRESET_NAMES[:-1]) + " or " + PRESET_NAMES[-1]
OPT_PRESET = typer.Option(None, "--preset", help=f"Use a built-in system: {PRESET_LIST}.")
OPT_NO_BUMPERS = typer.Option(
    False, "--no-bumpers", metavar=NO_METAVAR, help="The NBs configuration: the preset's or the file's "
    "system without its bumpers (a structure without its walls; a pair keeps its links)."
)
MAX_FREQUENCIES = 100_000


def command(name: Optional[str] = None, hidden: bool = False) -> Callable:
    """Register a command whose bad input exits 2 with the InputError's line, and whose Ctrl-C
    (outside the places that save partial results) exits 130 saying nothing was written (``hidden``:
    left out of ``--help``, kept for scripts)."""

    def register(fn: Callable) -> Callable:
        @functools.wraps(fn)
        def run(*args: Any, **kwargs: Any) -> Any:
            # (where output goes now)
            console.width, err_console.width = _width(sys.stdout), _width(sys.stderr)
            with _first_interrupt_only(), _warnings_as_lines():
                try:
                    return fn(*args, **kwargs)
                except (InputError, MissingExtra) as exc:  # (bad input, or an optional extra not installed)
                    fail(exc)
                except (StoreError, OutputError) as exc:  # (not the caller's input: exit 1)
                    err_console.print(f"[red]error:[/] {escape(str(exc))}")
                    raise typer.Exit(1) from None
                except KeyboardInterrupt:
                    interrupted("nothing was written")

        return app.command(name, cls=_Command, hidden=hidden)(run)

    return register


@contextlib.contextmanager
def _warnings_as_lines() -> Iterator[None]:
    """PoundingWarnings (implausible values) as one yellow line each, without Python's file and line."""

    def show(
        message: Any, category: type, filename: str, lineno: int, file: Any = None, line: Any = None
    ) -> None:
        if issubclass(category, PoundingWarning):
            err_console.print(f"[yellow]warning:[/] {escape(str(message))}")
        else:
            previous(message, category, filename, lineno, file, line)

    previous = warnings.showwarning
    warnings.showwarning = show
    try:
        yield
    finally:
        warnings.showwarning = previous


@contextlib.contextmanager
def _first_interrupt_only() -> Iterator[None]:
    """Only the first Ctrl-C of a command interrupts; the ones after it (a burst of them) are
    ignored, so that saving what the first one left is not cut short."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    count = [0]

    def handler(signum: int, frame: Any) -> None:
        count[0] += 1
        if count[0] == 1:
            raise KeyboardInterrupt

    previous = signal.signal(signal.SIGINT, handler)
    try:
        yield
    finally:
        # once interrupted, the command is ending with 130: a Ctrl-C more while the process
        # exits (after the default handler is back) would otherwise kill it by the signal
        signal.signal(signal.SIGINT, signal.SIG_IGN if count[0] else previous)


def fail(exc: Exception) -> None:
    notes = "".join(f" {n}" for n in getattr(exc, "__notes__", ()))  # (which task of many, e.g.)
    err_console.print(f"[bold red]error:[/] {escape(str(exc) + notes)}", soft_wrap=True)  # (one line)
    raise typer.Exit(code=2)


def interrupted(kept: str) -> None:
    """One line saying what Ctrl-C left, then exit 130."""
    err_console.print(f"[yellow]interrupted: {escape(kept)}[/]")
    raise typer.Exit(code=INTERRUPTED_EXIT)


def cell(value: Any, fmt: str = ".4g") -> str:
    """A table cell: a number in ``fmt``, ``MISSING`` for NaN or None, text and booleans as they are."""
    if value is None or isinstance(value, str):
        return MISSING if value is None else value
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    try:
        number = float(value)
    except (TypeError, ValueError):
        return str(value)
    return MISSING if number != number else format(number, fmt)


class _FittedTable(Table):
    """A table whose cells are never cut: each column at least as wide as its widest cell, the headers
    wrapping at their spaces where the terminal is narrow (80 columns cut "a_G" to "a…")."""

    def __rich_console__(self, console: Any, options: Any) -> Any:
        from rich.text import Text

        for col in self.columns:
            widths = [Text.from_markup(c).cell_len if isinstance(c, str) else Text(str(c)).cell_len
                      for c in col.cells]
            header = str(col.header)
            col.min_width = max(widths + [max((len(w) for w in header.split()), default=0)])
            col.no_wrap = False
        yield from super().__rich_console__(console, options)


def data_table(title: str, columns: Iterable[str]) -> Table:
    """A table with a header row; no cell is ever cut (headers wrap at 80 columns; ``console`` is wide
    when piped)."""
    table = _FittedTable(title=escape(title))
    for col in columns:
        table.add_column(escape(col))
    return table


def kv_table(title: str, system: Any = None) -> tuple[Table, Callable[[str, str], None]]:
    """A two-column summary table and its ``add(label, value)`` (labels may hold [units]).

    The system (a file's path, or a preset's name) is the first row, not part of the title: a
    long path made the title wrap in the middle of a phrase ("a_G =" / "0, f = 2.2 Hz")."""
    table = Table(title=escape(title), show_header=False)

    def add(label: str, value: str) -> None:
        table.add_row(escape(label), escape(value))

    if system is not None:
        add("system", str(system))
    return table, add


def system(path: Optional[Path], preset: Optional[str], bumpers: bool = True):
    """The system of a command: SYSTEM.toml (an oscillator's, a structure's or a pair's) or a preset."""
    from .. import presets
    from .._checks import parse_toml, read_text
    from ..model.systems import system_type

    if (path is None) == (preset is None):
        raise typer.BadParameter("give either SYSTEM.toml or --preset NAME (one of them)")
    if path is None:
        return presets.by_name(preset, bumpers=bumpers)
    text = read_text("SYSTEM", path)
    table = parse_toml(str(path), text)
    kind = system_type(table)
    system = kind.from_dict(table)  # (the file read and parsed once; a structure's or a pair's, or one mass)
    if bumpers:
        return system
    plain = system.without_bumpers()  # (--no-bumpers: the file's system, NBs)
    if plain.to_dict() == system.to_dict():
        warnings.warn(f"--no-bumpers: {path} has no bumpers or walls to take away (links stay); it runs as "
                      "written", PoundingWarning, stacklevel=2)
    return plain


def several_masses(osc) -> bool:
    """Whether ``osc`` is a structure of several masses (or a pair), not one mass."""
    from ..engine.assembly import is_single_mass

    return not is_single_mass(osc)


def frequencies(fmin: float, fmax: float, fstep: float):
    """``fmin, fmin + fstep, ...`` up to ``fmax`` (inclusive within rounding), Hz."""
    import numpy as np

    from .._checks import positive

    fmin = positive("--fmin", fmin, "Hz")
    fmax = positive("--fmax", fmax, "Hz")
    fstep = positive("--fstep", fstep, "Hz")
    if fmax < fmin:
        raise InputError(
            Problem.BAD_OUTPUT, "--fmax", fmax, why=f"is below --fmin {fmin:g}", fix="give fmin <= fmax"
        )
    n = int(np.floor((fmax - fmin) / fstep * (1.0 + 1e-9) + 1e-9))  # steps that stay within fmax
    if n + 1 > MAX_FREQUENCIES:
        raise InputError(
            Problem.TOO_LARGE,
            "--fstep",
            fstep,
            maximum=MAX_FREQUENCIES,
            what=f" frequencies from {fmin:g} to {fmax:g} Hz at this step",
            fix=f"give a step of at least {(fmax - fmin) / (MAX_FREQUENCIES - 1):.3g} Hz",
        )
    return np.round(fmin + fstep * np.arange(n + 1), 10)


def steady_options(steady: str, cycles: Optional[int], max_cycles: Optional[int]) -> dict:
    if steady == "fixed":
        return {"steady": "fixed", "cycles": cycles}
    if cycles is not None:
        raise typer.BadParameter("--cycles is for --steady fixed; use --max-cycles with adaptive")
    return {"steady": steady, "max_cycles": max_cycles}


def files(**paths: tuple[Optional[Path], Optional[Iterable[str]]]) -> dict[str, Optional[Path]]:
    """Check output files before any work: ``name=(path or None, known suffixes or None)``."""
    return {
        name: None if path is None else output_file(f"--{name.replace('_', '-')}", path, suffixes)
        for name, (path, suffixes) in paths.items()
    }


def folder(name: str, path: Path) -> Path:
    """Check an output directory before any work (created later, when there is something to write)."""
    return output_dir(name, path)


def figure_path(name: str, path: Optional[Path]) -> Optional[Path]:
    return None if path is None else output_file(name, path, FIGURE_SUFFIXES)


def save_figure(draw: Callable, path: Path) -> None:
    """Draw with ``draw()`` (it returns its artists or Figure) and save the figure atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plots import figure_of

    fig = figure_of(draw())
    try:
        atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=150))
    finally:
        plt.close(fig)
    console.print(f"figure -> {path}")


def write_csv(df: Any, path: Path) -> None:
    atomic_write(path, lambda tmp: df.to_csv(tmp, index=False))


@contextlib.contextmanager
def working(text: str) -> Iterator[None]:
    """A spinner with ``text`` while the work goes on (on a terminal), or ``text`` as one line on stderr
    (a log or a pipe, where a spinner leaves nothing): what the command is doing, never silence."""
    if err_console.is_terminal:
        with err_console.status(escape(text)):
            yield
    else:
        err_console.print(escape(text), soft_wrap=True)
        yield


def float_list(option: str, text: str) -> list[float]:
    """A comma-separated list of numbers (``--freqs 1.4,1.6``); a bad one is named, with the fix."""
    out = []
    for part in text.split(","):
        try:
            out.append(float(part))
        except ValueError:
            raise typer.BadParameter(f"{part.strip()!r} is not a number; give numbers separated by commas, "
                                     f"e.g. {option} 1.4,1.6,1.8") from None
    return out


def run_files(run: Any, out: dict, plot: Optional[Path], duration: float, complete: bool) -> None:
    """What ``pounding simulate`` writes of any run (its contacts, its history, its plot), whole whatever
    Ctrl-C comes; then the word on an interrupted run, and exit code 1 for a run that did not finish."""
    with interrupts_deferred() as held:  # the files are written whole, whatever Ctrl-C comes
        if out["contacts"] is not None:
            write_csv(run.contacts, out["contacts"])
            console.print(f"contacts -> {out['contacts']}")
        if out["history"] is not None:
            write_csv(run.to_dataframe(), out["history"])
            note = " (events only: --sample-rate 0)" if run.sample_rate_hz == 0 else ""
            console.print(f"history -> {out['history']}{note}")
        if plot is not None:
            save_figure(run.plot, plot)
    if not complete or held:
        interrupted(
            f"the run up to t = {run.final_state.time_s:g} s of {duration:g} s is in the summary"
            + (" and the files written" if any(out.values()) or plot else "")
        )
    if not run.success:
        raise typer.Exit(code=1)
