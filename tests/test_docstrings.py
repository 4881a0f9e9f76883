"""The public API's docstrings: each documents its parameters and returns, each has an example, every
example runs and prints what it says, and the docs' API reference lists every public name."""

from __future__ import annotations

import dataclasses
import doctest
import importlib
import inspect
import re
import types
from pathlib import Path

import matplotlib
import pytest

import pounding

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
SUBMODULES = ("plots", "records", "lab", "reports", "presets", "data", "design")
# numpydoc's checks that every public function and class must pass: parameters all documented and
# no unknown ones (PR01, PR02), each with a type and a description (PR04, PR07), returns documented
# (RT01), an example (EX01)
CHECKS = ("PR01", "PR02", "PR04", "PR07", "RT01", "EX01")


def public_names() -> dict[str, object]:
    """Every public function and class, by its documented name (``pounding.X``, ``pounding.plots.X``)."""
    names: dict[str, object] = {}
    for name in pounding.__all__:
        obj = getattr(pounding, name)
        if not isinstance(obj, types.ModuleType):
            names[f"pounding.{name}"] = obj
    for mod_name in SUBMODULES:
        mod = importlib.import_module(f"pounding.{mod_name}")
        for name in mod.__all__:
            names[f"pounding.{mod_name}.{name}"] = getattr(mod, name)
    return names


PUBLIC = public_names()


def test_the_public_surface_is_what_the_docs_say() -> None:
    assert len(PUBLIC) > 90
    listed = set(re.findall(r"^\s+(pounding\.[\w.]+)\s*$", (ROOT / "docs" / "api.rst").read_text(), re.M))
    assert set(PUBLIC) - listed == set(), "public names missing from docs/api.rst"
    assert listed - set(PUBLIC) == set(), "docs/api.rst lists names that are not public"


def _documented_fields(obj: type) -> set[str]:
    """The names a class's docstring documents under Parameters or Attributes (``a, b : float``
    counts both)."""
    from numpydoc.docscrape import NumpyDocString

    doc = NumpyDocString(inspect.getdoc(obj) or "")
    names: set[str] = set()
    for section in ("Parameters", "Attributes"):
        for param in doc[section]:
            names.update(n.strip().strip("*`") for n in param.name.split(","))
    return names


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_numpydoc_sections(name: str) -> None:
    from numpydoc.validate import validate

    obj = PUBLIC[name]
    result = validate(name)
    if isinstance(obj, type):
        # a class: an example, and every field documented under Parameters (what users pass) or
        # Attributes (what results carry); enumerations and exceptions are not built by users
        checks: tuple[str, ...] = ("EX01",)
        if dataclasses.is_dataclass(obj):
            missing = {f.name for f in dataclasses.fields(obj)} - _documented_fields(obj)
            assert missing == set(), f"{name}: fields not documented: {sorted(missing)}"
    else:
        checks = CHECKS
    errors = [f"{code}: {msg}" for code, msg in result["errors"] if code in checks]
    assert errors == [], f"{name}:\n" + "\n".join(errors)


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_examples_run(name: str, tmp_path, monkeypatch) -> None:
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)  # an example that writes files writes them here
    obj = PUBLIC[name]
    # a class's own methods' and properties' examples too (recurse: the members its __dict__ holds; a
    # method's example nothing ran had gone stale: Run.summary's alpha)
    finder = doctest.DocTestFinder(recurse=inspect.isclass(obj))
    tests = finder.find(obj, name, globs={"pounding": pounding})
    own = [t for t in tests if t.name == name]
    assert own and own[0].examples, f"{name} has no example"
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for t in tests:
        runner.run(t)
    plt.close("all")
    assert runner.failures == 0, f"{name}: {runner.failures} example(s) failed (the report is above)"


def test_a_broken_example_fails() -> None:
    """The runner above is not blind: a docstring whose output is wrong counts as a failure."""

    def f() -> None:
        """
        Examples
        --------
        >>> 1 + 1
        3
        """

    tests = doctest.DocTestFinder(recurse=False).find(f, "f")
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    for t in tests:
        runner.run(t, out=lambda s: None)
    assert runner.failures == 1
    assert inspect.getdoc(f).count(">>>") == 1


EXAMPLE_WIDTH = 80  # characters of an example's line as rendered: wider ones scroll sideways on the site


def _long_example_lines(doc: str) -> list[str]:
    """The lines of ``doc``'s examples (prompts, code and printed output) wider than ``EXAMPLE_WIDTH``."""
    lines, out, in_example = inspect.cleandoc(doc or "").splitlines(), [], False
    for line in lines:
        stripped = line.strip()
        in_example = stripped.startswith((">>>", "...")) or (in_example and stripped != "")
        if in_example and len(line.rstrip()) > EXAMPLE_WIDTH:
            out.append(line)
    return out


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_examples_fit_the_page(name: str) -> None:
    obj = PUBLIC[name]
    members = inspect.getmembers(obj) if inspect.isclass(obj) else []
    docs = [inspect.getdoc(obj)] + [inspect.getdoc(m) for _, m in members if inspect.isfunction(m)
                                    and getattr(m, "__qualname__", "").startswith(obj.__name__ + ".")]
    wide = [line for doc in docs for line in _long_example_lines(doc or "")]
    assert wide == [], f"{name}: example lines over {EXAMPLE_WIDTH} characters:\n" + "\n".join(wide)


def test_a_wide_example_is_seen() -> None:
    assert _long_example_lines(">>> x = 1\n>>> y = '" + "z" * 80 + "'\n") != []
    assert _long_example_lines("Text " * 40 + "\n\n>>> 1 + 1\n2\n") == []


def test_a_docstring_fragment_takes_its_lines_place_and_a_typo_is_an_error() -> None:
    from pounding._docs import FRAGMENTS, fill_doc

    def drawn(ax=None):
        """Draw.

        Parameters
        ----------
        {ax}

        Examples
        --------
        >>> {1}
        {1}
        """

    doc = fill_doc(drawn).__doc__
    first, second = FRAGMENTS["ax"].splitlines()
    assert f"\n        {first}\n        {second}\n" in doc and "{ax}" not in doc
    assert ">>> {1}\n        {1}\n" in doc  # (a doctest's output is not a fragment)

    def typo():
        """Draw.

        {axe}
        """

    with pytest.raises(KeyError):
        fill_doc(typo)
