"""Hide from imports every module that only an optional extra (or the test tools) installs, as a
Quick-start install (``pip install -e .``) would leave the environment.

``hide_extras.py`` (imported in a subprocess: ``python -c "import hide_extras; ..."`` with this folder on
the path) installs a finder that answers ``ModuleNotFoundError`` for the top-level
modules of every installed distribution that the core dependencies (``[project] dependencies`` in
``pyproject.toml``, and theirs) do not bring.
"""

from __future__ import annotations

import re
import sys
import tomllib
from importlib import metadata
from pathlib import Path

PYPROJECT = Path(__file__).resolve().parents[1] / "pyproject.toml"


def _name(req: str) -> str:
    return re.split(r"[<>=!~\[; ]", req.strip(), maxsplit=1)[0].lower().replace("_", "-")


def core_distributions() -> set[str]:
    """The core dependencies and everything they need (their extras that the requirement names too)."""
    deps = tomllib.loads(PYPROJECT.read_text(encoding="utf-8"))["project"]["dependencies"]
    todo = list(deps)
    seen: set[str] = set()
    while todo:
        req = todo.pop()
        name = _name(req)
        extras = re.search(r"\[([^\]]+)\]", req.split(";")[0])
        key = name + (f"[{extras.group(1)}]" if extras else "")
        if key in seen:
            continue
        seen.add(key)
        seen.add(name)
        try:
            reqs = metadata.requires(name) or []
        except metadata.PackageNotFoundError:
            continue
        wanted = {e.strip() for e in extras.group(1).split(",")} if extras else set()
        for r in reqs:
            marker = r.split(";", 1)[1] if ";" in r else ""
            extra = re.search(r"extra\s*==\s*['\"]([^'\"]+)", marker)
            if extra is None or extra.group(1) in wanted:
                todo.append(r.split(";")[0])
    return {s for s in seen if "[" not in s}


def hidden_modules() -> set[str]:
    """Top-level modules of the distributions beyond the core (pounding's own and the stdlib's kept)."""
    core = core_distributions() | {"pounding", "pip", "setuptools", "wheel"}
    hidden = set()
    for module, dists in metadata.packages_distributions().items():
        names = {d.lower().replace("_", "-") for d in dists}
        if module in sys.stdlib_module_names or module.startswith("_") or names & core:
            continue
        hidden.add(module)
    return hidden


class _Hide:
    """A meta-path finder that refuses the hidden modules (and everything below them)."""

    def __init__(self, hidden: set[str]):
        self.hidden = hidden

    def find_spec(self, fullname: str, path=None, target=None):
        if fullname.split(".")[0] not in self.hidden:
            return None
        raise ModuleNotFoundError(
            f"No module named {fullname!r} (hidden: only an optional extra installs it)", name=fullname)


def install() -> None:
    sys.meta_path.insert(0, _Hide(hidden_modules()))
