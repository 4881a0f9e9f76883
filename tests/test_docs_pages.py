"""The documentation site's pages: their Python blocks run as written, page by page, in one namespace
per page (as a reader pastes them); the site's index reaches every page and gallery script."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

ROOT = Path(__file__).parents[1]
DOCS = ROOT / "docs"
PAGES = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md") if "_build" not in p.parts)
# the one block that needs what no test machine has: a SLURM queue (docs/studies.md, "On a cluster")
NEEDS_A_CLUSTER = "SLURMCluster"


def _python_blocks(page: str) -> list[str]:
    text = (DOCS / page).read_text(encoding="utf-8")
    return [b for b in re.findall(r"```python\n(.*?)```", text, flags=re.S) if NEEDS_A_CLUSTER not in b]


def test_the_pages_have_examples():
    assert sum(len(_python_blocks(p)) for p in PAGES) >= 6
    assert {"getting_started.md", "guide/model.md", "guide/metrics.md", "paper.md"} <= set(PAGES)


@pytest.mark.parametrize("page", [p for p in PAGES if _python_blocks(p)])
def test_python_blocks_run(page, tmp_path, monkeypatch):
    import matplotlib.pyplot as plt

    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    for i, block in enumerate(_python_blocks(page)):
        try:
            exec(compile(block, f"docs/{page} python block {i}", "exec"), namespace)
        finally:
            plt.close("all")


def test_every_page_and_example_is_in_a_toctree():
    """Sphinx warns (an error with -W) about a page in no toctree; this says which, without a build."""
    toctrees = "\n".join(p.read_text(encoding="utf-8") for p in [DOCS / "index.rst",
                                                                 DOCS / "guide" / "index.md"])
    for page in PAGES:
        name = page.removesuffix(".md")
        if name in ("index", "guide/index"):
            continue
        assert re.search(rf"^\s*/?{re.escape(name.removeprefix('guide/'))}\s*$", toctrees, re.M), page
    scripts = sorted((ROOT / "examples" / "gallery").glob("plot_*.py"))
    assert len(scripts) >= 9
    for script in scripts:
        text = script.read_text(encoding="utf-8")
        assert text.startswith('"""\n'), f"{script.name}: sphinx-gallery needs a docstring title first"
