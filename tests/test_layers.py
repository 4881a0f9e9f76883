"""The package's import graph follows its documented layers (CONTRIBUTING.md): a module imports
only from its own layer or the ones below, at module level or inside a function alike, so that no
cycle hides behind an import in a function.  Two kinds of import are exempt: ``plots`` (results draw
themselves, importing it lazily) and imports under ``if TYPE_CHECKING:`` (annotations only)."""

from __future__ import annotations

import ast
from pathlib import Path

import pounding

ROOT = Path(pounding.__file__).resolve().parent

# lowest first: each line may import from itself and the lines above it
LAYERS = [
    ("_errors", "_checks", "_io", "_core_checks", "_core", "_control", "_delimited", "_units", "_tables",
     "_docs", "data"),
    ("model",),
    ("presets",),
    ("excitation", "records"),
    ("metrics",),
    ("engine",),
    ("_runner",),
    ("protocols",),
    ("studies",),
    ("analysis",),
    ("lab",),
    ("identification",),
    ("design",),
    ("reports",),
    ("plots",),
    ("_worker_boot", "cli", "__init__"),
]
RANK = {unit: i for i, units in enumerate(LAYERS) for unit in units}
EXEMPT = {"plots"}


def _unit(path: Path) -> str:
    return path.relative_to(ROOT).with_suffix("").parts[0]


def _type_checking_nodes(tree: ast.AST) -> set[int]:
    out: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            out.update(id(n) for stmt in node.body for n in ast.walk(stmt))
    return out


def imports_across_layers() -> list[str]:
    """Every import of a unit of a higher layer, as ``file:line unit -> module``."""
    bad = []
    for path in sorted(ROOT.rglob("*.py")):
        unit = _unit(path)
        tree = ast.parse(path.read_text())
        skip = _type_checking_nodes(tree)
        package = path.relative_to(ROOT.parent).with_suffix("").parts
        package = package if path.name == "__init__.py" else package[:-1]
        if path.name == "__init__.py":
            package = package[:-1]
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or id(node) in skip:
                continue
            if node.level:
                target = [*package[:len(package) - node.level + 1], *(node.module or "").split(".")]
            elif (node.module or "").startswith("pounding."):
                target = node.module.split(".")
            else:
                continue
            target = [t for t in target if t]
            if len(target) < 2:  # (from . import x, in the package's __init__)
                continue
            other = target[1]
            if other in (unit, *EXEMPT):
                continue
            if RANK.get(other, -1) > RANK[unit]:
                bad.append(f"{path.relative_to(ROOT)}:{node.lineno} {unit} -> {'.'.join(target[1:])}")
    return bad


def test_every_unit_has_a_layer():
    units = {_unit(p) for p in ROOT.rglob("*.py")}
    assert units <= set(RANK), f"units without a layer in LAYERS: {sorted(units - set(RANK))}"


def test_imports_point_down_the_layers():
    assert imports_across_layers() == []


def test_the_check_sees_an_import_up_the_layers(tmp_path, monkeypatch):
    # (a test that cannot fail is a defect: a planted upward import, inside a function, is found)
    fake = tmp_path / "pounding"
    for path in ROOT.rglob("*.py"):
        dest = fake / path.relative_to(ROOT)
        dest.parent.mkdir(parents=True, exist_ok=True)
        dest.write_text(path.read_text())
    (fake / "model" / "planted.py").write_text("def f():\n    from ..protocols import sweep\n")
    monkeypatch.setattr(__import__(__name__), "ROOT", fake)
    assert imports_across_layers() == ["model/planted.py:2 model -> protocols"]


def module_graph() -> dict[str, set[str]]:
    """Module -> the package's modules it imports (in functions too; not plots, not for annotations)."""
    graph: dict[str, set[str]] = {}
    modules = {".".join(p.relative_to(ROOT.parent).with_suffix("").parts).removesuffix(".__init__")
               for p in ROOT.rglob("*.py")}
    for path in sorted(ROOT.rglob("*.py")):
        name = ".".join(path.relative_to(ROOT.parent).with_suffix("").parts).removesuffix(".__init__")
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        tree = ast.parse(path.read_text())
        skip = _type_checking_nodes(tree)
        out = graph.setdefault(name, set())
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or id(node) in skip:
                continue
            if node.level:
                base = package.split(".")[:len(package.split(".")) - node.level + 1]
                target = ".".join([*base, *([node.module] if node.module else [])])
            elif (node.module or "").startswith("pounding"):
                target = node.module
            else:
                continue
            candidates = [f"{target}.{a.name}" for a in node.names] + [target]
            for cand in candidates:
                if cand in modules and cand != name and ".plots" not in cand and cand != "pounding":
                    out.add(cand)
                    break
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The graph's strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_no_module_imports_one_that_imports_it_back():
    assert cycles(module_graph()) == []
    # (and the check sees one: two modules importing each other, one of them in a function)
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def import_nodes(root: Path):
    """Every import statement under ``root``: (the module's path relative to it, the node)."""
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                yield path.relative_to(root), node


def importers_of_the_compiled_core(root: Path) -> list[str]:
    """Every module that imports the compiled module (``_pounding_core``) other than its door,
    ``pounding/_core.py``, as ``file:line``."""
    bad = []
    for rel, node in import_nodes(root):
        names = [getattr(node, "module", None) or "", *(a.name for a in node.names)]
        if str(rel) != "_core.py" and any("_pounding_core" in n for n in names):
            bad.append(f"{rel}:{node.lineno}")
    return bad


def test_only_the_door_imports_the_compiled_core(tmp_path):
    assert importers_of_the_compiled_core(ROOT) == []
    (tmp_path / "analysis").mkdir()
    (tmp_path / "analysis" / "planted.py").write_text("def f():\n    from .. import _pounding_core\n")
    assert importers_of_the_compiled_core(tmp_path) == ["analysis/planted.py:2"]


# the door's functions (its kernels and the system's constructors): the engine's to call
KERNELS = {node.name for node in ast.parse((ROOT / "_core.py").read_text()).body
           if isinstance(node, ast.FunctionDef) and not node.name.startswith("_")}
# the small kernels called below the engine in the flow of data, by the layers that own what they compute:
# a record's elastic spectrum and a pair's in each direction (the excitation's, for
# ``Record.scaled(sa_g=...)`` and RotD spectra) and an impact's measurements (the metrics', which every
# run's result reads)
BELOW_THE_ENGINE = {("excitation/_spectrum_run.py", "spectrum"),
                    ("excitation/_spectrum_run.py", "spectrum_pair"), ("metrics/impacts.py", "impact_row")}


def callers_of_the_core_runs(root: Path) -> list[str]:
    """Every module outside the engine that takes the core's runs (or the door module itself, which would
    let it call them), as ``file:line``: the protocols and the analyses go through ``engine.kernels``."""
    bad = []
    for rel, node in import_nodes(root):
        if rel.parts[0] == "engine" or str(rel) == "_core.py" or not isinstance(node, ast.ImportFrom):
            continue
        door = (node.module or "").split(".")[-1] == "_core"
        takes = {a.name for a in node.names} - {name for where, name in BELOW_THE_ENGINE if where == str(rel)}
        if (door and takes & KERNELS) or (not door and "_core" in takes):
            bad.append(f"{rel}:{node.lineno}")
    return bad


def test_only_the_engine_runs_the_core(tmp_path):
    assert callers_of_the_core_runs(ROOT) == []
    assert {"run", "step", "monodromy", "system", "impact_row", "law_force_many", "spectrum"} <= KERNELS
    (tmp_path / "protocols").mkdir()
    (tmp_path / "protocols" / "a.py").write_text("from .. import _core\n")
    (tmp_path / "protocols" / "b.py").write_text("from .._core import LAYOUT, step\n")
    (tmp_path / "protocols" / "c.py").write_text("from .._core import LAYOUT\n")  # (a name: allowed)
    (tmp_path / "metrics").mkdir()
    (tmp_path / "metrics" / "e.py").write_text("from .._core import CONTACT_COLUMNS, impact_row\n")
    (tmp_path / "engine").mkdir()
    (tmp_path / "engine" / "d.py").write_text("from .. import _core\n")
    assert callers_of_the_core_runs(tmp_path) == ["metrics/e.py:1", "protocols/a.py:1", "protocols/b.py:1"]


def private_names_across_packages(root: Path) -> list[str]:
    """Every private name (a leading underscore, not a module) a module imports from another package, as
    ``file:line name``: what is shared is public where it belongs."""
    bad = []
    for rel, node in import_nodes(root):
        if not isinstance(node, ast.ImportFrom) or node.level < 2 or len(rel.parts) < 2:
            continue  # (a package's own modules may share their private names)
        home = root.joinpath(*(node.module or "").split("."))
        for alias in node.names:
            is_module = (home / f"{alias.name}.py").exists() or (home / alias.name).is_dir()
            if alias.name.startswith("_") and not alias.name.startswith("__") and not is_module:
                bad.append(f"{rel}:{node.lineno} {alias.name}")
    return bad


def test_no_private_name_crosses_a_package(tmp_path):
    assert private_names_across_packages(ROOT) == []
    for folder, text in (("model", "def _helper(): ...\n"), ("design", "from ..model.m import _helper\n"),
                         ("studies", "from .. import _core\nfrom ..model import m\n")):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / ("m.py" if folder == "model" else "a.py")).write_text(text)
    (tmp_path / "_core.py").write_text("")
    assert private_names_across_packages(tmp_path) == ["design/a.py:1 _helper"]
