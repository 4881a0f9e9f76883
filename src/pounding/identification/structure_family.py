"""A structure as a model family for model updating: a base structure whose numbers, named as in its file,
are fitted or kept.

A rig that is more than one mass (the paper's bumpers on steel stands, a specimen on a flexible table) is
a :class:`~pounding.Structure`; :func:`pounding.identify` fits any of its numbers, named by their dotted
paths in its TOML tables (``isolator.damping_n_s_m``, ``walls[0].law.stiffness``, ``walls[0].stand.mass_kg``,
``storeys[0].stiffness_n_m``), every other number kept at the base's value.  The targets are of the base
(level 0: the mass a shaking table's rig carries): its NBs sweeps run the structure without its walls,
its YBs sweeps with them (``SweepResult.paper_quantities``).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .._checks import instance_of, parse_toml, read_text, read_toml
from .._errors import InputError, Problem
from ..model.dotted import get_value, set_value, why_unresolved
from ..model.structure import Structure

FAMILY_KEYS = ("structure", "bounds")


@dataclass(frozen=True, eq=False)
class StructureFamily:
    """A structure whose numbers are fitted by their dotted names (see the module's docstring).

    Parameters
    ----------
    base : Structure
        The structure, with its walls (YBs; NBs is it without them); every number not bounded keeps
        its value here.

    Examples
    --------
    >>> import pounding
    >>> rig = pounding.Structure.from_oscillator(pounding.presets.paper_damped())
    >>> family = pounding.StructureFamily(rig)
    >>> family.free_names({"walls[0].law.stiffness": (1e5, 1e7)})
    ('walls[0].law.stiffness',)
    >>> family.oscillator({"walls[0].law.stiffness": 2e6}).walls[0].law.stiffness
    2000000.0
    """

    base: Structure

    def __post_init__(self) -> None:
        instance_of("base", self.base, Structure,
                    "pounding.Structure (one structure; its base is the measured mass)")
        if self.base.fixed:
            raise InputError(Problem.WRONG_MODE, "base", "a fixed base", mode="an isolated structure",
                             fix="give the rig's isolated base (level 0, the mass its targets are of)")

    def free_names(self, bounds: dict[str, Any]) -> tuple[str, ...]:
        """The names ``bounds`` frees, checked: each a number of the base structure."""
        table = self.base.to_dict()
        for name in bounds:
            why = why_unresolved(table, name) if isinstance(name, str) else "it is not a text"
            if why is not None:
                raise InputError(Problem.BAD_STATE, f"bounds.{name}", bounds[name],
                                 why=f"names no number of the structure: {why}",
                                 fix="name a number by its path in the structure's file, e.g. "
                                     "'walls[0].law.stiffness' or 'isolator.damping_n_s_m'")
        return tuple(bounds)

    def oscillator(self, values: dict[str, float]) -> Structure:
        """The YBs structure for ``values`` (the free numbers; the others the base's).  Raises
        :class:`~pounding.InputError` when they make no valid structure."""
        table = copy.deepcopy(self.base.to_dict())
        for name, value in values.items():
            set_value(table, name, float(value))
        return Structure.from_dict(table)

    @classmethod
    def from_toml(cls, path: str | Path) -> tuple["StructureFamily", dict[str, tuple[float, float]]]:
        """A family and its bounds from a file: ``structure = "rig.toml"`` (the base's file, relative to
        this one) and a ``[bounds]`` table of dotted names (quoted: ``"walls[0].stand.mass_kg" = [1,
        100]``)."""
        from .family import check_bounds

        table = read_toml("family", path, FAMILY_KEYS)
        if "structure" not in table:
            raise InputError(Problem.MISSING_KEY, "structure", None, choices="structure = \"rig.toml\" (the "
                             "base structure's file)")
        instance_of("structure", table["structure"], str, "the path of a structure's file")
        try:
            base = Structure.from_toml(Path(path).parent / table["structure"])
        except InputError as exc:
            raise exc.relabel("path", "structure") from None
        family = cls(base)
        return family, check_bounds(family, table.get("bounds", {}))

    def value(self, name: str) -> float:
        """The base's value of a number, by its dotted name."""
        return float(get_value(self.base.to_dict(), name))


def read_family(path: str | Path) -> tuple[Any, dict[str, tuple[float, float]]]:
    """A family file's family and bounds: a :class:`StructureFamily`'s (it names a ``structure``) or a
    :class:`~pounding.ModelFamily`'s."""
    from .family import ModelFamily

    table = parse_toml(str(path), read_text("family", path))
    if "structure" in table:
        return StructureFamily.from_toml(path)
    return ModelFamily.from_toml(path)
