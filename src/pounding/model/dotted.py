"""Dotted names of a system's numbers (``bumpers.law.stiffness``, ``isolator.slopes[0]``) in
its nested tables (``Oscillator.to_dict``): what parameter studies and continuation vary."""

from __future__ import annotations

import re
from typing import Any

_INDEX = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$")

# names that stand for several numbers set together: ``bumpers.gap``, the same gap both sides
ALIASES = {"bumpers.gap": ("bumpers.gap_left", "bumpers.gap_right")}


def set_value(table: dict, name: str, value: Any) -> None:
    """Set the dotted ``name`` (``bumpers.law.stiffness``, ``isolator.slopes[0]``, or an alias:
    ``bumpers.gap`` sets both gaps) in nested tables."""
    if name in ALIASES:
        for each in ALIASES[name]:
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
    if name in ALIASES:
        for each in ALIASES[name]:
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
    if name in ALIASES:
        return get_value(table, ALIASES[name][0])
    node: Any = table
    for part in name.split("."):
        key, idx = _INDEX.match(part).groups()
        node = node[key]
        if idx is not None:
            node = node[int(idx)]
    return node
