"""What a study is: a base system, what each point computes, and a grid over dotted names.

A :class:`StudySpec` is plain data.  Its canonical form (:meth:`StudySpec.to_json`) is what a
store records and what workers receive: every point is rebuilt from it, in any process.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import instance_of, parse_toml, read_text
from .._errors import InputError, Problem
from ..model import Adjacent, Oscillator, Structure
from ..model.plan import PlanBuilding
from ..model.systems import system_from_dict, system_type
from ..model.dotted import alias_of, set_value, why_unresolved

System = Oscillator | Structure | Adjacent | PlanBuilding
SYSTEM_TYPES = (Oscillator, Structure, Adjacent, PlanBuilding)
SYSTEM_NAMES = "pounding.Oscillator, pounding.Structure, pounding.Adjacent or pounding.PlanBuilding"

KINDS = ("sweep", "simulate", "record")
# what each kind of point takes (defaults; None: required), by the name a grid can vary
COMPUTE_KEYS: dict[str, dict[str, Any]] = {
    "sweep": {"a_g": None, "direction": "up", "freqs_hz": None, "steady": "fixed", "cycles": 30,
              "measure_cycles": 5, "max_cycles": None, "steady_rtol": None, "f_ref_hz": None, "rtol": None},
    "simulate": {"a_g": None, "freq_hz": None, "duration_s": None, "phase_rad": 0.0, "v0_m_s": 0.0},
    "record": {"record": None, "scale_pga_g": None, "duration_s": None, "sa_g": None, "sa_period_s": None,
               "sa_damping_ratio": None, "angle_deg": None},
}
STRING_KEYS = ("direction", "steady", "record")  # compute keys whose values are text
MAX_POINTS = 10_000_000


@dataclass(frozen=True)
class StudySpec:
    """A parameter study: the base system, what each point computes, and the grid.

    Parameters
    ----------
    system : Oscillator, Structure, Adjacent or PlanBuilding
        The base system; each grid point changes some of its numbers.
    compute : dict
        ``{"kind": "sweep" | "simulate" | "record", ...options}``: ``sweep`` runs one sweep
        (``a_g`` in g, ``direction``, ``steady``, ``cycles``, ``measure_cycles``, ``freqs_hz``, ...)
        and keeps the paper's per-sweep quantities (Tables 2-4); ``simulate`` one harmonic run
        from rest (``a_g`` in g, ``freq_hz``, ``duration_s``, ``phase_rad``, ``v0_m_s``) and keeps
        its peaks; ``record`` one run under a record (``record``: a file, ``"el-centro"`` or
        ``"fema-p695:<set>:<index>"``; ``scale_pga_g``, or ``sa_g`` with ``sa_period_s`` and
        ``sa_damping_ratio`` (default 0.05): the record scaled to that pseudo-spectral
        acceleration; ``duration_s``, default the record's) or under a pair of components
        (``"fema-p695-pair:<set>:<index>"``, an event's two), its motion along x turned by ``angle_deg``
        (default 0: ``RecordPair.along``), the pair scaled by one factor to its largest direction's
        (RotD100) ``scale_pga_g`` or ``sa_g``. A building in plan takes both of a pair's components, the
        motion's axes turned by ``angle_deg`` against the building's (``RecordPair.rotated``, as
        ``pounding.orientations`` turns them), one record the same way (its motion then along
        ``-angle_deg`` in the building's axes); its points are runs, never sweeps.
    grid : dict
        Dotted name -> values (one axis each, in order): a number of the system
        (``"mass_kg"``, ``"isolator.damping_n_s_m"``, ``"isolator.slopes_n_m[0]"``, ``"bumpers.gap_left_m"``,
        ``"bumpers.law.stiffness"``; ``"bumpers.gap_m"`` sets both gaps; a structure's
        ``"storeys[2].stiffness_n_m"``, ``"walls[0].law.stiffness"``, ``"walls[0].gap_m"`` for both of a
        wall's gaps; a building in plan's ``"moat.gap_m"``, ``"bearings[0].isolator.slopes_n_m[1]"``,
        ``"floors[0].centre_m[0]"``) or a compute key (``"a_g"``, ``"record"``, ...). A structure's points
        keep its own quantities (``studies.points.quantities_of``).

    Examples
    --------
    The left gap against a_G, each point a 5 s harmonic run at 1.5 Hz from rest, from the tables
    of a study file (:meth:`from_toml` reads them from one):

    >>> import pounding
    >>> spec = pounding.StudySpec.from_dict({
    ...     "system": {"preset": "paper-damped"},
    ...     "compute": {"kind": "simulate", "freq_hz": 1.5, "duration_s": 5.0},
    ...     "grid": {"bumpers.gap_left_m": [0.01, 0.02], "a_g": [0.03, 0.05]}})
    >>> spec.kind, spec.dims, spec.shape, spec.size
    ('simulate', ('bumpers.gap_left_m', 'a_g'), (2, 2), 4)
    >>> spec.compute  # the defaults written out
    {'kind': 'simulate', 'freq_hz': 1.5, 'duration_s': 5.0, 'phase_rad': 0.0,
     'v0_m_s': 0.0}
    >>> system, options = spec.point((1, 0))  # the second gap, the first a_G
    >>> system.bumpers.gap_left_m, options["a_g"]
    (0.02, 0.03)
    """

    system: System
    compute: Mapping[str, Any]
    grid: Mapping[str, tuple]

    def __post_init__(self) -> None:
        instance_of("system", self.system, SYSTEM_TYPES, SYSTEM_NAMES)
        compute = _check_compute(self.compute)
        if isinstance(self.system, PlanBuilding) and compute["kind"] == "sweep":
            raise InputError(Problem.WRONG_MODE, "compute.kind", "sweep", mode="a structure on a line",
                             fix="a building in plan's points are runs: kind = \"record\" or \"simulate\"")
        grid = _check_grid(self.grid, compute, self.system)
        compute = _with_defaults(compute, grid)
        object.__setattr__(self, "compute", compute)
        object.__setattr__(self, "grid", grid)
        _check_points(self)

    # ------------------------------------------------------------------ reading
    @classmethod
    def from_toml(cls, path: str | Path) -> "StudySpec":
        """Read a study from TOML: ``[system]`` (``preset = "paper-calibrated"``, ``file = "x.toml"``
        relative to the study file, or the system's own tables), ``[compute]`` and ``[grid]``."""
        text = read_text("path", path)
        return cls.from_dict(parse_toml(str(path), text), base_dir=Path(path).parent)

    @classmethod
    def from_dict(cls, table: Mapping[str, Any], base_dir: str | Path = ".") -> "StudySpec":
        """Build from the TOML form's tables (``system``, ``compute``, ``grid``); a system
        ``file`` is read relative to ``base_dir``."""
        instance_of("study", table, Mapping, "table")
        unknown = sorted(set(table) - {"system", "compute", "grid", "meta"})
        if unknown:
            raise InputError(Problem.UNKNOWN_KEY, unknown[0], table[unknown[0]],
                             choices="system, compute, grid")
        for key in ("system", "compute", "grid"):
            if key not in table:
                raise InputError(Problem.MISSING_KEY, key, None, choices="system, compute, grid")
        base = Path(base_dir)
        compute = dict(check_table("compute", table["compute"]))
        grid = dict(check_table("grid", table["grid"]))
        if "record" in compute:
            compute["record"] = _record_path(compute["record"], base)
        if isinstance(grid.get("record"), list):
            grid["record"] = [_record_path(v, base) for v in grid["record"]]
        return cls(system_from_table(table["system"], base), compute, grid)

    @classmethod
    def _from_store(cls, tables: Mapping[str, Any]) -> "StudySpec":
        """The spec a store records, as it was checked when the study ran (its records are not
        read again: they may have moved since)."""
        spec = object.__new__(cls)
        object.__setattr__(spec, "system", system_from_dict(tables["system"]))
        object.__setattr__(spec, "compute", dict(tables["compute"]))
        object.__setattr__(spec, "grid", {k: tuple(v) for k, v in tables["grid"].items()})
        return spec

    def to_dict(self) -> dict[str, Any]:
        """The canonical tables: the system in full (never a preset's name), compute, grid."""
        return {"system": self.system.to_dict(), "compute": dict(sorted(self.compute.items())),
                "grid": {k: list(v) for k, v in self.grid.items()}}

    def to_json(self) -> str:
        """Canonical JSON of :meth:`to_dict` (the grid's axes in their order): what a store records."""
        return json.dumps(self.to_dict(), separators=(",", ":"))

    @property
    def sha256(self) -> str:
        """A hash of the spec's JSON form: a store remembers it, so a rerun with another spec is refused."""
        return hashlib.sha256(self.to_json().encode()).hexdigest()

    def _record_files(self) -> dict[str, str]:
        """The record files the study reads (compute's and the grid's, not the built-in records),
        each with the SHA-256 of its contents ("missing" for a file that is not there): a store
        remembers them, so that a resumed study notices a file changed since it started."""
        values = [self.compute.get("record"), *self.grid.get("record", ())]
        out = {}
        for value in values:
            if not _is_record_file(value):
                continue
            try:
                out[value] = hashlib.sha256(Path(value).read_bytes()).hexdigest()
            except OSError:
                out[value] = "missing"
        return out

    # ------------------------------------------------------------------ points
    @property
    def kind(self) -> str:
        """What each point computes: ``"sweep"``, ``"simulate"`` or ``"record"``."""
        return str(self.compute["kind"])

    @property
    def dims(self) -> tuple[str, ...]:
        """The grid's axes, by dotted name, in order."""
        return tuple(self.grid)

    @property
    def shape(self) -> tuple[int, ...]:
        """The number of values on each axis."""
        return tuple(len(v) for v in self.grid.values())

    @property
    def size(self) -> int:
        """The number of points in the grid."""
        return int(np.prod(self.shape, dtype=np.int64))

    def point(self, index: Sequence[int]) -> tuple[System, dict[str, Any]]:
        """The system and compute options of the grid point at ``index`` (one per axis)."""
        values = {name: self.grid[name][i] for name, i in zip(self.grid, index)}
        return point_of(self.system.to_dict(), self.compute, values)

    def indices(self) -> Iterator[tuple[int, ...]]:
        """Every point's index tuple, in C order."""
        return itertools.product(*(range(n) for n in self.shape))


def point_of(system_table: dict, compute: Mapping[str, Any], values: Mapping[str, Any]
             ) -> tuple[System, dict[str, Any]]:
    """The system (``system_table`` with the grid's values set) and the compute options of one point."""
    table = copy.deepcopy(system_table)
    system_values, options = split_values(compute, values)
    for name, value in system_values.items():
        set_value(table, name, value)
    return system_from_dict(table), options


def split_values(compute: Mapping[str, Any], values: Mapping[str, Any]
                 ) -> tuple[dict[str, Any], dict[str, Any]]:
    """A point's grid values split into the system's numbers and its compute options (``compute``
    with the grid's compute keys set)."""
    options = dict(compute)
    system_values = {}
    for name, value in values.items():
        if name in options or name in COMPUTE_KEYS[options["kind"]]:
            options[name] = value
        else:
            system_values[name] = value
    return system_values, options


# ---------------------------------------------------------------------- checks
def check_table(field: str, value: Any) -> dict:
    """``value`` as a dict, or an InputError naming ``field`` when it is no TOML table."""
    instance_of(field, value, Mapping, "table")
    return dict(value)


def system_from_table(value: Any, base_dir: Path) -> System:
    """The system of a TOML ``[system]`` table: a preset, a file (relative to ``base_dir``; an oscillator's,
    a structure's or two adjacent ones') or its own tables; ``bumpers = false`` drops a preset's or a
    file's bumpers (a structure's walls; a pair's links stay)."""
    if isinstance(value, SYSTEM_TYPES):
        return value
    table = check_table("system", value)
    if "preset" in table or "file" in table:
        extra = sorted(set(table) - {"preset", "file", "bumpers"})
        if extra or ("preset" in table and "file" in table):
            field = "system." + (extra[0] if extra else "file")
            raise InputError(Problem.UNKNOWN_KEY, field, table.get(extra[0]) if extra else table["file"],
                             choices="preset = NAME or file = PATH (one of them), and bumpers = true/false; "
                                     "or the system's own tables, without preset or file")
        bumpers = table.get("bumpers", True)
        instance_of("system.bumpers", bumpers, bool,
                    "true or false (with preset or file: keep the bumpers or not)")
        if "preset" in table:
            from ..presets import by_name

            try:
                return by_name(table["preset"], bumpers=bumpers)
            except InputError as exc:
                raise exc.relabel("preset", "system.preset") from None
        path = table["file"]
        instance_of("system.file", path, str, "path")
        try:
            file_table = parse_toml(str(base_dir / path), read_text("path", base_dir / path))
            osc = system_type(file_table).from_toml(base_dir / path)
        except InputError as exc:
            raise exc.relabel("path", "system.file") from None
        return osc if bumpers else osc.without_bumpers()
    try:
        return system_from_dict(table)
    except InputError as exc:
        raise InputError(exc.problem, f"system.{exc.field}", exc.value, **exc._details) from None


def _is_record_file(value: Any) -> bool:
    """Whether a compute or grid value names a record file (not a built-in record, not absent)."""
    return isinstance(value, str) and value != "el-centro" and not value.startswith(("fema-p695:",
                                                                                        "fema-p695-pair:"))


def _record_path(value: Any, base_dir: Path) -> Any:
    """A record's file, made absolute (relative to ``base_dir``): workers elsewhere read the same."""
    if not _is_record_file(value):
        return value
    return str((base_dir / Path(value).expanduser()).resolve())


def _check_compute(value: Any) -> dict[str, Any]:
    compute = check_table("compute", value)
    if "kind" not in compute:
        raise InputError(Problem.MISSING_KEY, "compute.kind", None, choices=", ".join(KINDS))
    kind = compute["kind"]
    if kind not in KINDS:
        raise InputError(Problem.NOT_ONE_OF, "compute.kind", kind, choices=", ".join(KINDS))
    keys = COMPUTE_KEYS[kind]
    unknown = sorted(set(compute) - set(keys) - {"kind"})
    if unknown:
        raise InputError(Problem.UNKNOWN_KEY, f"compute.{unknown[0]}", compute[unknown[0]],
                         choices=", ".join(keys))
    for key, v in compute.items():
        if key == "kind":
            continue
        if key in STRING_KEYS:
            instance_of(f"compute.{key}", v, str, "str")
        elif key == "freqs_hz":
            if (not isinstance(v, (list, tuple)) or not v
                    or not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)):
                raise InputError(Problem.WRONG_TYPE, "compute.freqs_hz", v, got=type(v).__name__,
                                 expected="list of frequencies in Hz")
            compute[key] = [float(x) for x in v]
        elif isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InputError(Problem.NOT_A_NUMBER, f"compute.{key}", v)
        else:
            compute[key] = _number(key, v)
    if "record" in compute:
        compute["record"] = _record_path(compute["record"], Path.cwd())
    return compute


def _with_defaults(compute: dict[str, Any], grid: dict[str, tuple]) -> dict[str, Any]:
    """The defaults written out (the store says what ran), but for the grid's axes."""
    out = dict(compute)
    for key, default in COMPUTE_KEYS[compute["kind"]].items():
        if default is not None and key not in out and key not in grid:
            out[key] = default
    return out


INTEGER_KEYS = ("cycles", "measure_cycles", "max_cycles")


def _number(key: str, value: Any) -> Any:
    """A compute number in its canonical type (1 and 1.0 are the same study)."""
    if key in INTEGER_KEYS:
        if float(value) != int(value):
            raise InputError(Problem.NOT_INTEGER, f"compute.{key}", value, minimum=1)
        return int(value)
    return float(value)


def _check_grid(value: Any, compute: dict[str, Any], system: System) -> dict[str, tuple]:
    grid = check_table("grid", value)
    if not grid:
        raise InputError(Problem.EMPTY, "grid", grid)
    table = system.to_dict()
    out: dict[str, tuple] = {}
    keys = COMPUTE_KEYS[compute["kind"]]
    for name, values in grid.items():
        field = f"grid.{name!s}"
        instance_of(field, name, str, "str")
        if isinstance(values, (str, bytes)) or not isinstance(values, (list, tuple, np.ndarray)):
            raise InputError(Problem.WRONG_TYPE, field, values, got=type(values).__name__,
                             expected="list of values, e.g. [0.01, 0.02]")
        values = list(values.tolist() if isinstance(values, np.ndarray) else values)
        if not values:
            raise InputError(Problem.EMPTY, field, values)
        if name == "kind" or name == "freqs_hz":
            raise InputError(Problem.UNKNOWN_KEY, field, values,
                             choices="numbers of the system or " + ", ".join(k for k in keys
                                                                             if k != "freqs_hz"))
        if name in compute:
            raise InputError(Problem.DUPLICATE, field, values,
                             repeated=f"compute.{name} (a key is set in [compute] or varied in [grid], not "
                                      "both)")
        if name in keys:
            if name in STRING_KEYS:
                if not all(isinstance(v, str) for v in values):
                    raise InputError(Problem.WRONG_TYPE, field, values, got="values other than text",
                                     expected="list of text values")
                if name == "record":
                    values = [_record_path(v, Path.cwd()) for v in values]
            elif not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                         for v in values):
                raise InputError(Problem.NOT_A_NUMBER, field, values)
            else:
                values = [_number(name, v) for v in values]
        else:
            why = why_unresolved(table, name)
            if why is not None:
                raise InputError(Problem.UNKNOWN_KEY, field, values,
                                 choices=f"a number of the system or a compute key ({', '.join(keys)}): "
                                         f"{why}")
            if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
                raise InputError(Problem.NOT_A_NUMBER, field, values)
            values = [float(v) for v in values]
        if len(set(values)) != len(values):
            raise InputError(Problem.DUPLICATE, field, values, repeated="a value")
        out[name] = tuple(values)
    for alias in out:  # (an alias and what it sets on two axes: which one wins?)
        names = alias_of(alias, table) or ()
        both = [n for n in names if n in out]
        if both:
            raise InputError(Problem.DUPLICATE, f"grid.{both[0]}", list(out[both[0]]),
                             repeated=f"grid.{alias} (which sets {' and '.join(names)})")
    missing = [k for k, d in keys.items() if d is None and k not in compute and k not in out
               and k not in ("freqs_hz", "max_cycles", "steady_rtol", "f_ref_hz", "rtol", "scale_pga_g",
                             "sa_g", "sa_period_s", "sa_damping_ratio", "angle_deg",
                             "duration_s" if compute["kind"] == "record" else "")]
    if missing:
        raise InputError(Problem.MISSING_KEY, f"compute.{missing[0]}", None,
                         choices=f"{missing[0]} in [compute] or as a grid axis")
    return out


def _check_points(spec: StudySpec) -> None:
    """Every value of every axis builds a valid system (named by its grid entry), and every point
    does too (named by its values); records are read once each."""
    from .points import check_options

    size = spec.size
    if size > MAX_POINTS:
        raise InputError(Problem.TOO_MUCH_WORK, "grid", dict(spec.shape and zip(spec.dims, spec.shape)),
                         estimate=size, unit="points", budget=MAX_POINTS,
                         fix="split the study, or use fewer values")
    table = spec.system.to_dict()
    keys = COMPUTE_KEYS[spec.kind]
    # the compute axes at their first value (a point needs them); the system's axes one at a time
    first = {name: values[0] for name, values in spec.grid.items() if name in keys}
    try:  # the compute options themselves
        system, options = point_of(table, spec.compute, first)
        check_options(system, options)
    except InputError as exc:
        key = re.split(r"[\[.]", exc.field)[0]
        if key in spec.grid:
            raise _named(exc, key, first[key]) from None
        raise InputError(exc.problem, f"compute.{exc.field}", exc.value, **exc._details) from None
    for name, values in spec.grid.items():
        for v in values:
            try:
                system, options = point_of(table, spec.compute, {**first, name: v})
                check_options(system, options)
            except InputError as exc:
                raise _named(exc, name, v) from None
    # a combination the single values do not catch (e.g. breakpoints out of order): the system's axes
    # only (the compute axes, checked one at a time above, do not change the system)
    axes = {n: v for n, v in spec.grid.items() if n not in keys}
    if int(np.prod([len(v) for v in axes.values()], dtype=np.int64)) <= 200_000:
        for combination in itertools.product(*axes.values()):
            values = {**first, **dict(zip(axes, combination))}
            try:
                point_of(table, spec.compute, values)
            except InputError as exc:
                raise InputError(Problem.BAD_STATE, "grid", values,
                                 why=f"makes a system that is refused ({exc.field} "
                                     f"{exc.problem.why.format(**exc._details)})",
                                 fix="change the grid's values so that every combination is valid") from None


def _named(exc: InputError, name: str, value: Any) -> InputError:
    """``exc`` (raised building one point) named by the grid entry that caused it."""
    why = exc.problem.why.format(**exc._details)
    fix = exc.problem.fix.format(**exc._details)
    return InputError(Problem.BAD_STATE, f"grid.{name}", value,
                      why=f"is refused: it makes {exc.field} = {exc.value!r}, which {why}", fix=fix)
