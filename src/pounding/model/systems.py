"""The one place that tells the kinds of system apart: a single mass, a structure, two adjacent structures.

Everything else reads a system through what every kind has (:func:`structures_of`: its structures and
links, a single mass the one-level structure it is) or asks :func:`is_single_mass` where a single mass
has something of its own (its paper metrics); :func:`system_type` says which a file's tables are (their
``to_dict`` tables, as a TOML file or a study's ``[system]`` holds them)."""

from __future__ import annotations

from typing import Any

from .._checks import instance_of
from .adjacent import Adjacent
from .oscillator import Oscillator
from .structure import Structure


def system_type(table: dict[str, Any]) -> type:
    """The class a system's tables are of: two adjacent structures (``links``), a structure (``storeys`` or
    ``base_mass_kg``) or one mass (an ``Oscillator``'s)."""
    if "links" in table:
        return Adjacent
    if "storeys" in table or "base_mass_kg" in table:
        return Structure
    return Oscillator


def system_from_dict(table: dict[str, Any]) -> Any:
    """A system from its tables (``to_dict``'s): an ``Oscillator``, a ``Structure`` or an ``Adjacent``."""
    return system_type(table).from_dict(table)


def check_system(system: Any, field: str = "system") -> None:
    """An InputError naming ``field`` unless ``system`` is one the core runs: a single mass, a structure or
    two adjacent ones."""
    instance_of(field, system, (Oscillator, Structure, Adjacent),
                "pounding.Oscillator, pounding.Structure or pounding.Adjacent")


def is_single_mass(system: Any) -> bool:
    """Whether ``system`` is a single mass (an :class:`Oscillator`): the one-level structure whose sweeps,
    basins and files keep the paper's metrics and names of their own."""
    return isinstance(system, Oscillator)


def structures_of(model: Oscillator | Structure | Adjacent) -> tuple[tuple[Structure, ...], tuple]:
    """(the structures, the links) of a model (a single mass: the one-level structure it is)."""
    if isinstance(model, Adjacent):
        return model.structures, model.links
    if isinstance(model, Oscillator):
        return (Structure.from_oscillator(model),), ()
    return (model,), ()
