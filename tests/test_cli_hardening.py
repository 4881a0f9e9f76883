"""The command line at its edges: bad paths before any work, Ctrl-C bursts, flags, version."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import re
import threading
import tomllib
from pathlib import Path

import pandas as pd
import pytest
import xarray as xr
from typer.testing import CliRunner

import pounding as pd_
from pounding.cli import app

EXAMPLES = Path(__file__).parents[1] / "examples"
YBS = str(EXAMPLES / "paper_printed_ybs.toml")
NBS = str(EXAMPLES / "paper_printed_nbs.toml")
runner = CliRunner()


def _run(*args: str):
    return runner.invoke(app, list(args))


def test_version_and_flags_without_bool_placeholders():
    out = _run("--version")
    assert out.exit_code == 0 and pd_.__version__ in out.output
    for cmd, flag in (("simulate", "--no-bumpers"), ("identify", "--paper")):
        help_text = _run(cmd, "--help").output
        line = next(ln for ln in help_text.splitlines() if flag in ln)
        assert "<bool>" not in line, line


@pytest.mark.parametrize(
    "args, words",
    [
        (["campaign", "--preset", "paper-damped", "--out", "{file}"], "is a file"),
        (["reproduce", "--out", "{file}"], "is a file"),
        (
            [
                "identify",
                "--paper",
                "--family",
                str(EXAMPLES / "family.toml"),
                "--out",
                "{tmp}/missing/x.toml",
            ],
            "does not exist",
        ),
        (["sweep", YBS, "--a-g", "0.05", "--plot", "{tmp}/s.xyz"], "extension"),
        (["simulate", YBS, "--a-g", "0.05", "--freq", "2.2", "--history", "{tmp}"], "is a directory"),
        (["simulate", YBS, "--a-g", "0.05", "--freq", "2.2", "--contacts", "{tmp}/c.txt"], "extension"),
        (["simulate", "{tmp}", "--a-g", "0.05", "--freq", "2.2"], "is a directory"),
        (["simulate", YBS, "--a-g", "0.05", "--freq", "2.2", "--velocity", "inf"], "velocity_m_s"),
        (["simulate", YBS, "--a-g", "0.05", "--freq", "2.2", "--velocity", "nan"], "velocity_m_s"),
        (["sweep", YBS, "--a-g", "0.05", "--fstep", "1e-7"], "--fstep"),
        (["campaign", "--nbs", YBS, "--ybs", NBS, "--out", "{tmp}/c"], "swapped"),
    ],
)
def test_bad_inputs_and_outputs_fail_at_once_naming_them(tmp_path, args, words):
    existing = tmp_path / "existing.txt"
    existing.write_text("keep me")
    args = [a.format(file=existing, tmp=tmp_path) for a in args]
    t0 = time.perf_counter()
    out = _run(*args)
    text = " ".join(out.output.split())  # (the console wraps long lines)
    assert out.exit_code == 2, out.output
    assert words in text and "Fix" in text, text
    assert "Traceback" not in text and "Oscillator(mass_kg=500.0, isolator" not in text
    assert time.perf_counter() - t0 < 5.0  # before any computation
    assert existing.read_text() == "keep me"


def test_zero_table_acceleration_and_a_narrow_range():
    out = _run("simulate", YBS, "--a-g", "0", "--freq", "2.2", "--duration", "2")
    assert out.exit_code == 0, out.output
    assert "a_G = 0" in out.output
    out = _run("sweep", YBS, "--a-g", "0.05", "--fmin", "1", "--fmax", "1.05", "--steady", "fixed")
    assert out.exit_code == 0, out.output
    from pounding.cli._app import frequencies

    assert list(frequencies(1.0, 1.05, 0.1)) == [1.0]
    assert list(frequencies(0.5, 5.0, 0.1))[-1] == 5.0 and len(frequencies(0.5, 5.0, 0.1)) == 46


def test_simulate_plot_and_an_events_only_history(tmp_path):
    png, hist = tmp_path / "run.png", tmp_path / "h.csv"
    out = _run(
        "simulate",
        YBS,
        "--a-g",
        "0.05",
        "--freq",
        "2.2",
        "--duration",
        "3",
        "--velocity",
        "0.6",
        "--plot",
        str(png),
        "--history",
        str(hist),
        "--sample-rate",
        "0",
    )
    assert out.exit_code == 0, out.output
    assert png.stat().st_size > 10_000 and "events only" in out.output
    df = pd.read_csv(hist, keep_default_na=False)
    assert (df["event"].iloc[1:-1] != "").all()  # every row but the first and last is an event's


def _cpu_s(pid: int) -> float:
    """CPU time a process and its live descendants (worker processes) have used, s (Linux's /proc;
    elsewhere the wall clock stands in: inf)."""
    stats = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            stats[int(entry.name)] = (int(fields[1]), int(fields[11]) + int(fields[12]))
    if pid not in stats:
        return float("inf")
    tree, ticks = {pid}, 0
    for _ in range(8):  # (workers are children or grandchildren: a forkserver's)
        tree |= {p for p, (ppid, _) in stats.items() if ppid in tree}
    ticks = sum(stats[p][1] for p in tree)
    return ticks / os.sysconf("SC_CLK_TCK")


def _interrupt(args: list[str], tmp_path: Path, ready: str, after: int = 1,
               cpu_after_s: float = 0.0) -> subprocess.CompletedProcess:
    """Run the command, and once its stderr has shown ``after`` lines matching the regular expression
    ``ready`` (a progress line: work under way, whatever the machine's load), and then used
    ``cpu_after_s`` more seconds of CPU (work done, however slowly the machine gives it), send SIGINT
    twice 30 ms apart; return what it did.  Waits for what the command says and does, not for a time."""
    env = dict(os.environ, COLUMNS="200")
    proc = subprocess.Popen(
        [sys.executable, "-m", "pounding.cli", *args],
        cwd=tmp_path,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    err: list[str] = []
    out: list[str] = []
    seen = threading.Event()

    def read() -> None:
        count = 0
        for line in proc.stderr:
            err.append(line)
            if re.search(ready, line):
                count += 1
                if count >= after:
                    seen.set()
        seen.set()  # (it ended without: the assertions below say how)

    readers = [threading.Thread(target=read, daemon=True),
               threading.Thread(target=lambda: out.extend(proc.stdout), daemon=True)]
    for reader in readers:  # (each pipe read by one thread only, as the process writes it)
        reader.start()
    assert seen.wait(timeout=600), "".join(err)
    target = _cpu_s(proc.pid) + cpu_after_s
    deadline = time.monotonic() + 600
    while cpu_after_s and proc.poll() is None and _cpu_s(proc.pid) < target and time.monotonic() < deadline:
        time.sleep(0.02)  # (polling an observable state: the CPU time the process has used)
    proc.send_signal(signal.SIGINT)
    time.sleep(0.03)  # (the second Ctrl-C of a burst: its spacing is the test's subject, not a wait)
    proc.send_signal(signal.SIGINT)
    try:
        proc.wait(timeout=300)
    except subprocess.TimeoutExpired:
        proc.kill()
        raise
    for reader in readers:
        reader.join(timeout=60)
    return subprocess.CompletedProcess(args, proc.returncode, "".join(out), "".join(err))


def test_two_ctrl_c_in_a_campaign_keep_the_finished_steps_readable(tmp_path):
    # 20000 cycles a step: the first steps (0.5 Hz, 40000 s) take about half a second, the
    # whole campaign (6.4e6 simulated s) about a minute on two cores; at 3000 cycles a faster
    # machine finished all 644 steps within the 5 s before the interrupt
    done = _interrupt(
        ["campaign", "--preset", "paper-damped", "--out", "out", "--steady", "fixed", "--cycles", "20000"],
        tmp_path,
        r"^campaign: [1-9]",
    )
    assert done.returncode == 130, done.stderr
    assert "interrupted" in done.stderr and "Traceback" not in done.stderr
    out = tmp_path / "out"
    ds = xr.open_dataset(out / "campaign.nc")
    assert ds.attrs["complete"] == 0 and bool(ds["ran"].any())
    for name in ("steps", "table2", "table3", "table4"):
        pd.read_csv(out / f"{name}.csv")
    assert not pd.read_csv(out / "table2.csv")["complete"].all()
    assert not list(out.glob(".*tmp*"))  # no temporary file left


def test_two_ctrl_c_in_a_simulate_keep_the_run_so_far(tmp_path):
    done = _interrupt(
        [
            "simulate",
            "--preset",
            "paper-printed",
            "--a-g",
            "0.05",
            "--freq",
            "2.2",
            "--duration",
            "1e6",
            "--velocity",
            "0.6",
            "--contacts",
            "c.csv",
        ],
        tmp_path,
        r"^simulating ",
        cpu_after_s=2.0,
    )
    assert done.returncode == 130, done.stderr
    assert "interrupted: the run up to t = " in done.stderr
    contacts = pd.read_csv(tmp_path / "c.csv")
    assert len(contacts) > 100


def test_two_ctrl_c_in_identify_write_a_partial_toml(tmp_path):
    family = tmp_path / "family.toml"
    family.write_text((EXAMPLES / "family.toml").read_text())
    done = _interrupt(
        [
            "identify",
            "--paper",
            "--family",
            str(family),
            "--out",
            "fit.toml",
            "--maxiter",
            "50",
            "--popsize",
            "10",
        ],
        tmp_path,
        r"^identify: [1-9]",
    )
    assert done.returncode == 130, done.stderr
    text = (tmp_path / "fit.toml").read_text()
    assert tomllib.loads(text)["meta"]["partial"] is True
    pd_.Oscillator.from_toml(tmp_path / "fit.toml")  # still a system file


def _commands() -> list[str]:
    from typer.main import get_command

    return sorted(get_command(app).commands)


def test_help_texts_lose_no_words():
    """Help is plain text: "[system]" is no Rich markup to drop, no flag shows "<bool>", and the
    command list gives each command's whole first sentence (Click cut it short with "...")."""
    study_help = _run("study", "--help").output
    assert "[system], [compute] and [grid]" in study_help, study_help
    listing = _run("--help").output
    commands = listing.split("Commands:")[1]
    assert "..." not in commands, listing
    assert "branch points, period-doublings" in " ".join(listing.split())
    for cmd in _commands():
        text = _run(cmd, "--help").output
        assert "<bool>" not in text, (cmd, text)
        assert "Show this message and exit." in text


def test_piped_tables_keep_whole_headers_and_show_no_nan(tmp_path):
    """CliRunner's output is no terminal, as a pipe's: the campaign's table has every header whole,
    and its missing numbers (e for YBs, the contact range for NBs) show as "–", not "nan"."""
    out = _run("campaign", "--preset", "paper-damped", "--out", str(tmp_path / "c"), "--fmin", "1.5",
               "--fmax", "1.6", "--steady", "fixed", "--cycles", "5")
    assert out.exit_code == 0, out.output
    for header in ("configuration", "direction", "contact_nu_min", "contact_nu_max"):
        assert header in out.output, out.output
    assert "nan" not in out.output and "…" not in out.output, out.output
    assert "–" in out.output


def test_cell_formats_numbers_text_and_gaps():
    from pounding.cli._app import MISSING, cell

    assert cell(float("nan")) == MISSING and cell(None) == MISSING
    assert cell(1.23456) == "1.235" and cell(2.0, "g") == "2" and cell("YBs") == "YBs"
    assert cell(True) == "yes" and cell(float("inf")) == "inf"


def test_a_ctrl_c_while_the_campaign_is_written_says_it_is_complete(tmp_path, monkeypatch):
    """Ctrl-C after the last step, while the files are written: they are all written, and the line
    says the campaign is complete (it said "complete = 0")."""
    from pounding.cli import _campaign

    save = _campaign._save_campaign

    def save_and_interrupt(result, out):
        os.kill(os.getpid(), signal.SIGINT)  # (held off while the files are written)
        save(result, out)

    monkeypatch.setattr(_campaign, "_save_campaign", save_and_interrupt)
    out = _run("campaign", "--preset", "paper-damped", "--out", str(tmp_path / "c"), "--fmin", "1.5",
               "--fmax", "1.6", "--steady", "fixed", "--cycles", "5")
    assert out.exit_code == 130, out.output
    assert "after the campaign had finished" in out.output and "complete" in out.output, out.output
    assert "complete = 0" not in out.output
    assert xr.open_dataset(tmp_path / "c" / "campaign.nc").attrs["complete"] == 1


@pytest.mark.parametrize("args", [
    ["campaign", "--preset", "paper-printed", "--fmin", "1.0", "--fmax", "1.0", "--steady", "fixed",
     "--cycles", "3", "--measure-cycles", "1"],
    ["spectrum", "--record", "examples/el_centro_ns.AT2", "--periods", "1:1.5:0.5", "--gaps", "0.05"],
    ["identify", "examples/targets.toml", "--family", "examples/family.toml", "--maxiter", "0", "--popsize",
     "2", "--fmin", "1", "--fmax", "2", "--fstep", "1", "--cycles", "10"],
])
def test_a_full_disk_at_the_end_is_named_and_exits_1(args, tmp_path, monkeypatch):
    """Campaign, spectrum and identify write their outputs when they end: a write that fails (a full
    disk, mocked) is an error naming the file, exit 1 (not the user's input), no traceback, and no
    temporary file left.  (A study writes as it goes: tests/test_study.py.)"""
    import errno

    import pounding._io

    out = tmp_path / ("fit.toml" if args[0] == "identify" else "out")

    class FullDisk:  # (pounding._io's os only: Numba's cache goes on writing)
        def __getattr__(self, name):
            return getattr(os, name)

        def replace(self, src, dst):
            raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(pounding._io, "os", FullDisk())
    res = CliRunner().invoke(app, [*args, "--out", str(out)])
    assert res.exit_code == 1, res.output
    said = " ".join(res.output.split())  # (the console wraps long paths)
    assert "could not be written" in said and "No space left on device" in said
    assert "Traceback" not in res.output and not any(p.name.startswith(".") for p in tmp_path.rglob("*"))


def test_an_error_of_another_file_in_a_writer_is_not_called_the_outputs(tmp_path):
    """atomic_write names the output when its own write fails; an error of something else the
    writer touches (an input it reads) stays as it was."""
    from pounding._io import atomic_write

    def reads_a_missing_input(tmp):
        open(tmp_path / "missing.nc", "rb")

    with pytest.raises(FileNotFoundError) as info:
        atomic_write(tmp_path / "out.nc", reads_a_missing_input)
    assert not isinstance(info.value, pd_.OutputError) and not (tmp_path / "out.nc").exists()


def test_the_help_imports_no_engine_and_no_numerics():
    """``pounding --help`` starts at once: the command line imports Typer and Rich, not the engine,
    SciPy, pandas or xarray (what took 4-6 s); measured by what is imported, not by a clock."""
    code = ("import sys; from pounding.cli import app; from typer.main import get_command; "
            "get_command(app).get_help; print(sorted(m for m in ('numba', 'scipy', 'pandas', 'xarray', "
            "'matplotlib', 'pounding.engine', 'pounding.model') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == "[]", out.stdout + out.stderr
    help_run = subprocess.run([sys.executable, "-m", "pounding.cli", "--help"], capture_output=True,
                              text=True, timeout=120)
    assert help_run.returncode == 0 and "reproduce" in help_run.stdout


def test_every_preset_list_names_every_preset():
    from pounding import presets
    from pounding.cli._app import PRESET_NAMES

    assert tuple(PRESET_NAMES) == tuple(presets.PRESETS)
    for cmd in ("simulate", "sweep", "campaign", "reproduce", "basins", "lyapunov", "bifurcation",
                "continue", "coexistence"):
        text = runner.invoke(app, [cmd, "--help"], terminal_width=300).output
        for name in PRESET_NAMES:
            assert name in text, (cmd, name)


def test_tables_keep_every_label_at_80_columns():
    from rich.console import Console

    from pounding.cli._app import data_table

    table = data_table("Table 2, model (preset paper-calibrated) beside measured (paper)",
                       ("cfg", "a_G", "dir", "nu_R model", "nu_R meas.", "alpha model", "alpha meas.",
                        "eta|e model", "eta|e meas."))
    for row in (("NBs", "0.03", "down", "1.1", "1.2", "2.17", "1.8", "0.743", "1.03"),
                ("YBs", "0.075", "up", "2.5", "2.5", "16.2", "16.18", "1.25", "1.25")):
        table.add_row(*row)
    console = Console(width=80, record=True)
    console.print(table)
    text = console.export_text()
    assert "…" not in text and "0.075" in text and "down" in text and "16.18" in text, text
    assert max(len(line) for line in text.splitlines()) <= 80


def test_a_grazing_of_both_bumpers_is_one_line():
    from types import SimpleNamespace as B

    from pounding.cli._continue import _one_line_each

    left = B(kind="grazing", side="wall0_left", freq_hz=1.6053052485, a_g=0.05)
    right = B(kind="grazing", side="wall0_right", freq_hz=1.6053052498, a_g=0.05)
    fold = B(kind="fold", side="", freq_hz=1.6052636858, a_g=0.05)
    labels = [label for label, _ in _one_line_each([fold, left, right])]
    assert labels == ["fold", "grazing (wall0_left and wall0_right)"]
    far = B(kind="grazing", side="wall0_right", freq_hz=1.2350879755, a_g=0.05)
    labels = [label for label, _ in _one_line_each([left, far])]
    assert labels == ["grazing (wall0_left)", "grazing (wall0_right)"]


def test_wide_bounds_are_warned_about():
    fam = pd_.ModelFamily(500.0, branches=3, law="kelvin_voigt",
                          fixed={"slope_1": 38e3, "slope_2": 18e3, "slope_3": 2e3, "breakpoint_1": 0.015,
                                 "breakpoint_2": 0.04, "gap": 0.015})
    from pounding.identification.family import check_bounds

    with pytest.warns(pd_.PoundingWarning, match="bounds.bumper_stiffness .* spans 600 decades"):
        check_bounds(fam, {"isolator_damping": (100, 5000), "bumper_stiffness": (1e-300, 1e300),
                           "bumper_damping": (10, 5000)})
