"""A design's bumper types: each ``[design.bumper_types.NAME]`` table's law (and capacity) on the base
system's bumpers, with its own design grid; one stripe analysis each, into its own store."""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._errors import InputError, Problem
from ..model import Oscillator
from ..model.oscillator import check_keys
from ..studies.spec import check_table

TYPE_KEYS = ("law", "capacity_m", "grid")


@dataclass(frozen=True, eq=False)
class BumperType:
    """One bumper type of a design: its name, the system with its bumpers, and its design grid
    (``bumpers.gap_m`` and the type's own dotted names)."""

    name: str
    system: Any  # Oscillator, or a Structure (a building: its moat's wall)
    grid: dict


def bumper_types(system: Oscillator, des: Mapping[str, Any], grid: dict, gaps: np.ndarray) -> tuple:
    """The design's bumper types: each ``[design.bumper_types.NAME]`` table's law (and capacity) on
    the base system's bumpers, with its own grid or the design's; or the base bumpers alone."""
    tables = dict(check_table("design.bumper_types", des.get("bumper_types", {})))
    if not tables:
        return ()  # (the base system's bumpers alone: DesignPlan.kinds)
    out = []
    for name, value in tables.items():
        where = f"design.bumper_types.{name}"
        if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_-]{0,39}", name) or name == "free":
            raise InputError(
                Problem.NOT_ONE_OF,
                where,
                name,
                choices="a name of letters, digits, - and _ that starts with a letter (up to 40; not "
                "'free', the store of the runs without bumpers)",
            )
        kind = check_table(where, value)
        check_keys(kind, where + ".", TYPE_KEYS, ("law",))
        tables_ = system.to_dict()
        bumpers = dict(tables_["bumpers"])
        bumpers.pop("law_right", None)  # (a type's law is both sides')
        bumpers["law"] = kind["law"]
        if "capacity_m" in kind:
            bumpers["capacity_m"] = kind["capacity_m"]
        tables_["bumpers"] = bumpers
        try:
            typed = Oscillator.from_dict(tables_)
        except InputError as exc:
            raise exc.relabel("bumpers.", where + ".") from None
        out.append(
            BumperType(name, typed, grid_of(where + ".grid", kind["grid"], gaps) if "grid" in kind else grid)
        )
    return tuple(out)


def grid_of(field: str, value: Any, gaps: np.ndarray, gap_dim: str = "bumpers.gap_m") -> dict:
    """A design grid: ``gap_dim`` (``bumpers.gap_m``, or a building's ``walls[w].gap_m``) from
    ``design.gaps_m``, then the table's dotted names."""
    grid = {gap_dim: gaps.tolist()}
    stem = gap_dim[: -len("_m")] if gap_dim.endswith("_m") else gap_dim
    same = (gap_dim, f"{stem}_left", f"{stem}_right", f"{stem}_left_m", f"{stem}_right_m")
    for name, values in check_table(field, value).items():
        if name in same:
            raise InputError(Problem.DUPLICATE, f"{field}.{name}", values, repeated="design.gaps_m")
        grid[name] = values
    return grid


def typed_store(store: str | Path, name: str) -> str:
    """The store of one bumper type's runs beside the design's (``x.zarr`` -> ``x_NAME.zarr``)."""
    text = str(store).rstrip("/")
    return text[: -len(".zarr")] + f"_{name}.zarr" if text.endswith(".zarr") else f"{text}_{name}"
