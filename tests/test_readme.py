"""The README's Python blocks run as written, in order, in one namespace (as a reader pastes them)."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

ROOT = Path(__file__).parents[1]


def _python_blocks() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_the_readme_has_no_placeholders():
    blocks = _python_blocks()
    assert len(blocks) >= 5
    for block in blocks:
        assert "..." not in block, block


def test_every_python_block_of_the_readme_runs(tmp_path, monkeypatch):
    import matplotlib.pyplot as plt

    shutil.copytree(ROOT / "examples", tmp_path / "examples")  # the blocks use paths from the checkout
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    for i, block in enumerate(_python_blocks()):
        try:
            exec(compile(block, f"README.md python block {i}", "exec"), namespace)
        finally:
            plt.close("all")
    assert (tmp_path / "report" / "index.html").is_file()
    assert (tmp_path / "calibrated.toml").is_file()
