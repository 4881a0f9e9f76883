"""Every command-line example of the documentation runs as written and gives something: exit code 0,
something printed, no warning, and every file it names written and not empty; every shipped example file
reads without a warning.

The commands are read from the pages' ``bash`` blocks (a line ending in a backslash goes on), each run in
a folder of its own where ``examples/`` is the repository's.  A command the README also shows is left to
``test_readme.py``, which runs the README's blocks in order (nothing is run twice).
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from typer.testing import CliRunner

import pounding.model  # noqa: F401 - the core loaded before the runner swaps the streams (a rebuilding
from pounding.cli import app  # editable install's build writes to them)

ROOT = Path(__file__).parents[1]
DOCS = ROOT / "docs"
# the options whose value is a file or folder the command writes
OUTPUTS = ("--out", "--plot", "--netcdf", "--contacts", "--history", "--bifurcations", "--matrix", "--store")


def _commands(text: str) -> list[str]:
    out = []
    for block in re.findall(r"```(?:bash|shell|console)\n(.*?)```", text, flags=re.S):
        for line in re.sub(r"\\\n\s*", " ", block).splitlines():
            line = line.split("  #")[0].split(" # ")[0].strip()
            if line.startswith("pounding "):
                out.append(line)
    return out


README = set(_commands((ROOT / "README.md").read_text(encoding="utf-8")))
EXAMPLES = [(page.relative_to(DOCS).as_posix(), cmd)
            for page in sorted(DOCS.rglob("*.md")) if "_build" not in page.parts
            for cmd in _commands(page.read_text(encoding="utf-8")) if cmd not in README]


def test_the_pages_hold_command_line_examples():
    assert len(EXAMPLES) >= 10
    assert {page for page, _ in EXAMPLES} >= {"structures.md", "response.md", "design.md"}


@pytest.mark.parametrize("page, command", EXAMPLES, ids=[f"{p}:{c.split()[1]}:{i}" for i, (p, c) in
                                                         enumerate(EXAMPLES)])
def test_every_command_line_example_of_the_docs_runs_and_gives_something(page, command, tmp_path,
                                                                         monkeypatch):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    args = shlex.split(command)[1:]
    done = CliRunner().invoke(app, args, catch_exceptions=False)
    assert done.exit_code == 0, (page, command, done.output[-3000:])
    assert done.output.strip(), (page, command)
    assert "warning:" not in done.output, (page, command, done.output[-3000:])  # (an example never warns)
    written = [args[i + 1] for i, a in enumerate(args[:-1]) if a in OUTPUTS]
    for name in written:
        path = tmp_path / name
        assert path.exists(), (command, name)
        size = sum(f.stat().st_size for f in path.rglob("*") if f.is_file()) if path.is_dir() else \
            path.stat().st_size
        assert size > 0, (command, name)


SYSTEMS = ("adjacent_buildings", "building_moat", "elastic_plastic_ybs", "friction_pendulum_moat",
           "masing_ybs", "paper_printed_nbs", "paper_printed_ybs", "paper_slider_nbs", "paper_slider_ybs",
           "soft_stop_building", "triple_friction_moat", "plan_building", "plan_rubber_building",
           "plan_friction_building", "plan_ring_building")


def test_every_shipped_example_file_reads_without_a_warning():
    """A shipped example never warns about itself: each file read as its command reads it, pounding's
    warnings as errors (the design and study files with their systems and records)."""
    import warnings

    import tomllib

    import pounding
    from pounding.design.plan import DesignPlan
    from pounding.model.systems import system_type
    from pounding.studies.spec import StudySpec

    examples = ROOT / "examples"
    with warnings.catch_warnings():
        warnings.simplefilter("error", pounding.PoundingWarning)  # (not a dependency's deprecations)
        for name in SYSTEMS:
            path = examples / f"{name}.toml"
            system_type(tomllib.loads(path.read_text(encoding="utf-8"))).from_toml(path)
        pounding.Targets.from_toml(examples / "targets.toml")
        pounding.ModelFamily.from_toml(examples / "family.toml")
        for name in ("study_gaps", "study_moat"):
            StudySpec.from_toml(examples / f"{name}.toml")
        for name in ("design_ups", "design_building", "design_plan_building"):
            DesignPlan.from_toml(examples / f"{name}.toml")
        pounding.Record.from_at2(examples / "el_centro_ns.AT2")
    shipped = {p.stem for p in examples.glob("*.toml")}
    assert shipped == set(SYSTEMS) | {"targets", "family", "study_gaps", "study_moat", "design_ups",
                                      "design_building", "design_plan_building"}, \
        "a new example: read it here too"
