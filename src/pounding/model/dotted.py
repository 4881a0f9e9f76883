"""Dotted names of a system's numbers (``bumpers.law.stiffness``, ``isolator.slopes_n_m[0]``) in
its nested tables (``Oscillator.to_dict``): what parameter studies and continuation vary."""

from __future__ import annotations

import re
from typing import Any

from .isolator import BoucWen, Isolator

_INDEX = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$")

# names that stand for several numbers set together: ``bumpers.gap_m``, the same gap both sides, a building
# in plan's ``moat.gap_m``, its four walls' (and a structure's wall's ``walls[i].gap_m``: :func:`alias_of`)
ALIASES = {"bumpers.gap_m": ("bumpers.gap_left_m", "bumpers.gap_right_m"),
           "moat.gap_m": tuple(f"moat.gap_m[{side}]" for side in range(4))}
_WALL_GAP = re.compile(r"^((?:first\.|second\.)?walls\[\d+\])\.gap_m$")
# the names before (0.1's), read for one release with a FutureWarning naming the new one
RENAMED = {"mass": "mass_kg", "bumpers.gap": "bumpers.gap_m", "bumpers.gap_left": "bumpers.gap_left_m",
           "bumpers.gap_right": "bumpers.gap_right_m"}


# an isolator's numbers and its Bouc-Wen spring's by their names before, wherever the isolator is
# (``isolator.slopes[0]``, ``first.isolator.damping``, ``isolator.bouc_wen.stiffness``): what comes before
# the name, the name, its index
_FIELDS_BEFORE = (
    (re.compile(r"^((?:first\.|second\.)?isolator\.)(slopes|breakpoints|damping)((?:\[\d+\])?)$"),
     Isolator.RENAMED),
    (re.compile(r"^((?:first\.|second\.)?isolator\.bouc_wen\.)(stiffness|yield_displacement)()$"),
     BoucWen.RENAMED),
)


def current_name(name: str) -> str:
    """``name``, or its new spelling when it is one of the names before (``bumpers.gap`` ->
    ``bumpers.gap_m``, ``isolator.slopes[0]`` -> ``isolator.slopes_n_m[0]``), with a ``FutureWarning``."""
    new = RENAMED.get(name)
    for pattern, renamed in _FIELDS_BEFORE if new is None else ():
        m = pattern.match(name)
        if m:
            new = m.group(1) + renamed[m.group(2)] + m.group(3)
    if new is None:
        return name
    from .._errors import warn_renamed

    warn_renamed(name, new, stacklevel=4)
    return new


def alias_of(name: str, table: dict | None = None) -> tuple[str, ...] | None:
    """The names an alias sets together (``bumpers.gap_m``: both gaps; ``walls[2].gap_m``: that wall's two
    gaps, ``second.walls[0].gap_m`` a pair's; ``moat.gap_m``: a building in plan's four), or None for a name
    that is not one (in the system ``table`` when given: a circular moat's ``moat.gap_m`` is one number)."""
    name = current_name(name)
    moat = table.get("moat", {}) if table is not None else {}
    if name == "moat.gap_m" and table is not None and not isinstance(moat.get("gap_m"), list):
        return None
    if name in ALIASES:
        return ALIASES[name]
    m = _WALL_GAP.match(name)
    return (f"{m.group(1)}.gap_left_m", f"{m.group(1)}.gap_right_m") if m else None


def set_value(table: dict, name: str, value: Any) -> None:
    """Set the dotted ``name`` (``bumpers.law.stiffness``, ``isolator.slopes_n_m[0]``, or an alias:
    ``bumpers.gap_m`` sets both gaps) in nested tables."""
    name = current_name(name)
    if alias_of(name, table):
        for each in alias_of(name, table):
            set_value(table, each, value)
        return
    parts = name.split(".")
    node: Any = table
    for depth, part in enumerate(parts):
        m = _INDEX.match(part)
        key, idx = m.group(1), m.group(2)
        last = depth == len(parts) - 1
        if last and idx is None:
            node[key] = value
            return
        node = node[key]
        if idx is not None:
            node[int(idx)] = value if last else node[int(idx)]
            if last:
                return
            node = node[int(idx)]


def why_unresolved(table: dict, name: str) -> str | None:
    """None when the dotted ``name`` reaches a number of the system ``table``; else why not."""
    name = current_name(name)
    if alias_of(name, table):
        for each in alias_of(name, table):
            why = why_unresolved(table, each)
            if why is not None:
                return why
        return None
    node: Any = table
    for part in name.split("."):
        m = _INDEX.match(part)
        if m is None:
            return f"{part!r} is not a name (letters, digits, _ and an optional [index])"
        key, idx = m.group(1), m.group(2)
        if not isinstance(node, dict) or key not in node:
            keys = ", ".join(sorted(node)) if isinstance(node, dict) else "none"
            return f"{key!r} is not there (the keys there: {keys})"
        node = node[key]
        if idx is not None:
            if not isinstance(node, list):
                return f"{key!r} is not a list"
            if int(idx) >= len(node):
                return f"{key!r} has {len(node)} values (index 0 to {len(node) - 1})"
            node = node[int(idx)]
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        return f"it holds {type(node).__name__}, not a number"
    return None


def get_value(table: dict, name: str) -> Any:
    """The value at the dotted ``name`` (one :func:`why_unresolved` accepts; an alias's first)."""
    name = current_name(name)
    if alias_of(name, table):
        return get_value(table, alias_of(name, table)[0])
    node: Any = table
    for part in name.split("."):
        key, idx = _INDEX.match(part).groups()
        node = node[key]
        if idx is not None:
            node = node[int(idx)]
    return node


# the units of a system's numbers by their last key (SI); a Hertz-type law's by its exponent
_UNITS = {"mass": "kg", "mass_kg": "kg", "base_mass_kg": "kg", "stiffness_n_m": "N/m",
          "damping_n_s_m": "N s/m", "height_m": "m", "gap_left_m": "m", "gap_right_m": "m", "gap_m": "m",
          "slopes_after_n_m": "N/m", "breakpoints_m": "m", "slopes_n_m": "N/m", "slopes": "N/m",
          "breakpoints": "m",
          "gap_left": "m", "gap_right": "m", "gap": "m",
          "capacity_m": "m", "capacities_m": "m", "radii_m": "m", "mu": "-", "ring_stiffness_n_m": "N/m",
          "yield_displacement": "m", "yield_displacement_m": "m", "yield_compression": "m",
          "post_yield_stiffness": "N/m", "effective_mass": "kg", "exponent": "-", "damping_ratio": "-",
          "xi_norm": "-", "a": "-", "beta": "-",
          "gamma": "-", "n": "-", "a_g": "g", "freq_hz": "Hz", "duration_s": "s", "period_s": "s",
          "pga_g": "g", "sa_g": "g"}
_HERTZ_TYPES = ("hunt_crossley", "jankowski", "hertzdamp")


def unit_of(name: str, table: dict | None = None) -> str:
    """The unit of the dotted ``name`` (``bumpers.gap_m`` -> ``"m"``,
    ``isolator.damping_n_s_m`` -> ``"N s/m"``,
    ``a_g`` -> ``"g"``); ``table`` (``Oscillator.to_dict``) tells a Hertz-type law's stiffness
    (``N/m^1.5``) from a linear one's.  ``""`` for a name it does not know."""
    key = _INDEX.match(name.split(".")[-1] or "")
    leaf = key.group(1) if key else name
    if leaf in _UNITS:
        return _UNITS[leaf]
    if leaf in ("stiffness", "damping"):
        law = None
        parent = name.rsplit(".", 1)[0]
        if table is not None and parent.split(".")[-1] in ("law", "law_right") \
                and why_unresolved(table, parent + ".stiffness") is None:
            law = get_value(table, parent)  # (a bumper's, a wall's or a link's law)
        if law and law.get("type") in _HERTZ_TYPES:
            n = f"{float(law.get('exponent', 1.5)):g}"
            return f"N/m^{n}" if leaf == "stiffness" else f"N s/m^{float(n) + 1:g}"
        if name.startswith("isolator.bouc_wen") and leaf == "stiffness":
            return "N/m"
        return "N/m" if leaf == "stiffness" else "N s/m"
    return ""


def with_unit(name: str, value: Any, table: dict | None = None, sep: str = " = ") -> str:
    """``name`` and ``value`` with its unit: ``"bumpers.gap_m = 0.05 m"``, ``"a_g = 0.3 g"``."""
    unit = unit_of(name, table)
    shown = f"{value:g}" if isinstance(value, (int, float)) and not isinstance(value, bool) else str(value)
    return f"{name}{sep}{shown}" + (f" {unit}" if unit and unit != "-" else "")
