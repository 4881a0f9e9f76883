"""Which system a file's tables are: one mass, a structure or two adjacent structures (their ``to_dict``
tables, as a TOML file or a study's ``[system]`` holds them). A system built is told apart where systems are
assembled (:mod:`pounding.engine.assembly`)."""

from __future__ import annotations

from typing import Any

from .adjacent import Adjacent
from .oscillator import Oscillator
from .plan import PlanBuilding
from .structure import Structure


def system_type(table: dict[str, Any]) -> type:
    """The class a system's tables are of: two adjacent structures (``links``), a building in plan
    (``floors``), a structure (``storeys`` or ``base_mass_kg``) or one mass (an ``Oscillator``'s)."""
    if "links" in table:
        return Adjacent
    if "floors" in table:
        return PlanBuilding
    if "storeys" in table or "base_mass_kg" in table:
        return Structure
    return Oscillator


def system_from_dict(table: dict[str, Any]) -> Any:
    """A system from its tables (``to_dict``'s): an ``Oscillator``, a ``Structure``, an ``Adjacent`` or a
    ``PlanBuilding``."""
    return system_type(table).from_dict(table)

