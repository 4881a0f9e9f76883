"""Hypothesis profiles: random examples on developers' machines (they keep exploring, and
.hypothesis/ remembers what failed), the same examples every time in CI (``CI=true``), so that
a landing does not depend on the draw: a new failure found locally becomes a regression test."""

import os
import signal
from pathlib import Path

import pytest
from hypothesis import settings

settings.register_profile("ci", derandomize=True, database=None)
if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
    settings.load_profile("ci")

# A run started with SIGINT ignored (a background job of a shell without job control) never turns
# Ctrl-C into KeyboardInterrupt, which the Ctrl-C tests send themselves: Python's own handler back
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

# The test files in the order they go to the workers: the slowest first (their summed seconds measured on
# 1e7dc1b with ``pytest --durations=0``), the rest after in their own order. pytest-xdist hands out whole
# files (``--dist loadfile``, kept in this order by ``--no-loadscope-reorder``): a slow file handed out
# last runs alone at the end while the other worker idles (the README's test, 310 s, did).
SLOWEST_FIRST = (
    "test_readme.py", "test_structure.py", "test_ndof.py", "test_structure_laws.py", "test_study.py",
    "test_docs_pages.py", "test_reference.py", "test_report.py", "test_docs_cli.py",
    "test_measured_report.py", "test_multilinear.py", "test_docstrings.py", "test_lab_analysis.py",
    "test_rigid_stops.py", "test_report_figures.py", "test_report_stands.py", "test_records.py",
    "test_cli_hardening.py", "test_elastic_plastic.py", "test_design_cli.py",
    "test_structure_continuation.py", "test_bouc_wen.py", "test_model_updating.py", "test_measured_fit.py",
    "test_runner.py", "test_design.py", "test_curves.py",
    "test_cli_without_extras.py", "test_jankowski.py",
)


def pytest_configure(config):
    # (here, not in the sort below: that runs in every worker, where an error ends the run as an internal
    # error without its message)
    stale = [name for name in SLOWEST_FIRST if not (Path(__file__).parent / name).is_file()]
    if stale:
        raise pytest.UsageError(f"tests/conftest.py's SLOWEST_FIRST names no such file: {stale}")


def pytest_collection_modifyitems(config, items):
    rank = {name: i for i, name in enumerate(SLOWEST_FIRST)}
    items.sort(key=lambda item: rank.get(item.path.name, len(rank)))  # (stable: a file's own order kept)
