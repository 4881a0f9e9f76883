"""A structure as a model family for model updating: a base structure whose numbers, named as in its file,
are fitted or kept.

A rig that is more than one mass (the paper's bumpers on steel stands, a specimen on a flexible table) is
a :class:`~pounding.Structure`; :func:`pounding.identify` fits any of its numbers, named by their dotted
paths in its TOML tables (``isolator.damping``, ``walls[0].law.stiffness``, ``walls[0].stand.mass_kg``,
``storeys[0].stiffness_n_m``), every other number kept at the base's value.  The targets are of the base
(level 0: the mass a shaking table's rig carries): its NBs sweeps run the structure without its walls,
its YBs sweeps with them (``StructureSweepResult.paper_quantities``).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Any

from .._errors import InputError, Problem
from ..model.dotted import get_value, set_value, why_unresolved
from ..model.structure import Structure


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
    >>> rig = pounding.Structure.from_oscillator(pounding.presets.paper_calibrated())
    >>> family = pounding.StructureFamily(rig)
    >>> family.free_names({"walls[0].law.stiffness": (1e5, 1e7)})
    ('walls[0].law.stiffness',)
    >>> family.oscillator({"walls[0].law.stiffness": 2e6}).walls[0].law.stiffness
    2000000.0
    """

    base: Structure

    def __post_init__(self) -> None:
        if not isinstance(self.base, Structure):
            raise InputError(Problem.WRONG_TYPE, "base", self.base, got=type(self.base).__name__,
                             expected="pounding.Structure (one structure; its base is the measured mass)")
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
                                     "'walls[0].law.stiffness' or 'isolator.damping'")
        return tuple(bounds)

    def oscillator(self, values: dict[str, float]) -> Structure:
        """The YBs structure for ``values`` (the free numbers; the others the base's).  Raises
        :class:`~pounding.InputError` when they make no valid structure."""
        table = copy.deepcopy(self.base.to_dict())
        for name, value in values.items():
            set_value(table, name, float(value))
        return Structure.from_dict(table)

    def value(self, name: str) -> float:
        """The base's value of a number, by its dotted name."""
        return float(get_value(self.base.to_dict(), name))
