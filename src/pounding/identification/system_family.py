"""A system as a model family for model updating: a base system (one mass, or a structure of several)
whose numbers, named as in its file, are fitted or kept.

:func:`pounding.identify` fits any number of the base, named by its dotted path in its TOML tables: a
single mass's (``isolator.damping_n_s_m``, ``bumpers.law.stiffness``, ``bumpers.gap_m`` for both gaps) or a
structure's (``walls[0].law.stiffness``, ``walls[0].stand.mass_kg``, ``storeys[0].stiffness_n_m``); every
other number keeps the base's value.  A rig that is more than one mass (the paper's bumpers on steel stands,
a specimen on a flexible table) is a :class:`~pounding.Structure`.  The targets are of the base's level 0
(the mass a shaking table's rig carries): its NBs sweeps run the system without its bumpers or walls, its
YBs sweeps with them (``SweepResult.paper_quantities``).  :class:`~pounding.ModelFamily` is the paper's
single mass built from its shape (the isolator's branches, the bumpers' law), its numbers short names for
the same paths (``ModelFamily.paths``), set in the file's tables in the same way.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .._checks import instance_of, parse_toml, read_text, read_toml
from .._errors import InputError, Problem, warn_renamed
from ..engine.assembly import MASS, STRUCTURE, kind_of
from ..model.dotted import get_value, set_value, why_unresolved
from ..model.oscillator import Oscillator
from ..model.structure import Structure
from ..model.systems import system_type

FAMILY_KEYS = ("system", "structure", "bounds")  # (structure: its name before, for one release)


@dataclass(frozen=True, eq=False)
class SystemFamily:
    """A system whose numbers are fitted by their dotted names (see the module's docstring).

    Parameters
    ----------
    base : Oscillator or Structure
        The system, with its bumpers or walls (YBs; NBs is it without them); every number not bounded keeps
        its value here.  A structure's base is isolated: level 0 is the measured mass.

    Examples
    --------
    >>> import pounding
    >>> family = pounding.SystemFamily(pounding.presets.paper_damped())
    >>> family.free_names({"bumpers.law.stiffness": (1e5, 1e7)})
    ('bumpers.law.stiffness',)
    >>> family.oscillator({"bumpers.law.stiffness": 2e6}).bumpers.law.stiffness
    2000000.0
    >>> rig = pounding.Structure.from_oscillator(pounding.presets.paper_damped())
    >>> family = pounding.SystemFamily(rig)
    >>> fitted = family.oscillator({"walls[0].law.stiffness": 2e6})
    >>> fitted.walls[0].law.stiffness
    2000000.0
    """

    base: Oscillator | Structure

    def __post_init__(self) -> None:
        kind = kind_of(self.base)
        if kind not in (MASS, STRUCTURE):
            instance_of("base", self.base, (Oscillator, Structure),
                        "pounding.Oscillator or pounding.Structure (one system; level 0 the measured mass)")
        if kind == STRUCTURE and self.base.fixed:
            raise InputError(Problem.WRONG_MODE, "base", "a fixed base", mode="an isolated structure",
                             fix="give the rig's isolated base (level 0, the mass its targets are of)")

    def free_names(self, bounds: dict[str, Any]) -> tuple[str, ...]:
        """The names ``bounds`` frees, checked: each a number of the base system."""
        table = self.base.to_dict()
        for name in bounds:
            why = why_unresolved(table, name) if isinstance(name, str) else "it is not a text"
            if why is not None:
                raise InputError(Problem.BAD_STATE, f"bounds.{name}", bounds[name],
                                 why=f"names no number of the system: {why}",
                                 fix="name a number by its path in the system's file, e.g. "
                                     "'walls[0].law.stiffness', 'bumpers.law.stiffness' or "
                                     "'isolator.damping_n_s_m'")
        return tuple(bounds)

    def oscillator(self, values: dict[str, float]) -> Oscillator | Structure:
        """The YBs system for ``values`` (the free numbers; the others the base's).  Raises
        :class:`~pounding.InputError` when they make no valid system."""
        table = copy.deepcopy(self.base.to_dict())
        for name, value in values.items():
            set_value(table, name, float(value))
        return type(self.base).from_dict(table)

    @classmethod
    def from_toml(cls, path: str | Path) -> tuple["SystemFamily", dict[str, tuple[float, float]]]:
        """A family and its bounds from a file: ``system = "rig.toml"`` (the base's file, one mass's or a
        structure's, relative to this one; ``structure``, its name before, still works for one release) and
        a ``[bounds]`` table of dotted names (quoted: ``"walls[0].stand.mass_kg" = [1, 100]``)."""
        from .family import check_bounds

        table = read_toml("family", path, FAMILY_KEYS)
        if "structure" in table and "system" not in table:
            warn_renamed("structure", "system", why="a family's base is any system's file")
            table["system"] = table.pop("structure")
        if "system" not in table:
            raise InputError(Problem.MISSING_KEY, "system", None, choices="system = \"rig.toml\" (the base "
                             "system's file)")
        instance_of("system", table["system"], str, "the path of a system's file")
        where = Path(path).parent / table["system"]
        try:
            kind = system_type(parse_toml(str(where), read_text("system", where)))
            base = kind.from_toml(where)
        except InputError as exc:
            raise exc.relabel("path", "system") from None
        family = cls(base)
        return family, check_bounds(family, table.get("bounds", {}))

    def value(self, name: str) -> float:
        """The base's value of a number, by its dotted name."""
        return float(get_value(self.base.to_dict(), name))


def read_family(path: str | Path) -> tuple[Any, dict[str, tuple[float, float]]]:
    """A family file's family and bounds: a :class:`SystemFamily`'s (it names a ``system``, or a
    ``structure`` as before) or a :class:`~pounding.ModelFamily`'s."""
    from .family import ModelFamily

    table = parse_toml(str(path), read_text("family", path))
    if "system" in table or "structure" in table:
        return SystemFamily.from_toml(path)
    return ModelFamily.from_toml(path)
