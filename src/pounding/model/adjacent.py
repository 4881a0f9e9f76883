"""Two structures side by side that may pound each other: each on its own isolation or fixed at its base,
shaken by the same ground, joined by links (a gap and a contact law between two of their levels)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar, Union


from .._checks import at_most, instance_of, integer, non_negative, plausible
from .._errors import InputError, Problem
from ._toml import TomlFile
from .structure_parts import MAX_GAP_M
from .contact_laws import check_law, law_from_dict, law_to_dict
from .sliders import refuse_rigid_stops
from .oscillator import check_keys
from .structure import Structure
from .structure_parts import MAX_STOREYS

PathLike = Union[str, Path]


@dataclass(frozen=True)
class Link:
    """Where two adjacent structures may hit: a level of the first against a level of the second, which
    stands to its right, behind a gap, with a contact law (a bumper between them, or their slabs).

    The link is compressed by ``x_first - x_second - gap_m`` (displacements relative to the ground) and
    pushes the two apart.

    Parameters
    ----------
    level_first, level_second : int
        The levels that meet (0: a base).
    gap_m : float
        The separation at rest, m, >= 0.
    law : contact law
        Any of the package's contact laws.

    Examples
    --------
    >>> import pounding
    >>> slab_law = pounding.KelvinVoigt(stiffness=5.0e8, damping=2.0e5)
    >>> slab = pounding.Link(level_first=3, level_second=3, gap_m=0.05,
    ...                      law=slab_law)
    >>> slab.gap_m
    0.05
    """

    level_first: int
    level_second: int
    gap_m: float
    law: Any

    FIELDS: ClassVar[tuple[str, ...]] = ("level_first", "level_second", "gap_m", "law")

    def __post_init__(self) -> None:
        for name in ("level_first", "level_second"):
            object.__setattr__(self, name, integer(f"link.{name}", getattr(self, name), 0, MAX_STOREYS))
        gap = non_negative("link.gap_m", self.gap_m, "m")
        at_most("link.gap_m", gap, MAX_GAP_M, " m", "give the gap in m (5 cm is 0.05)")
        plausible("link.gap_m", gap, 0.0, 2.0, "gaps are in m (5 cm is 0.05)")
        object.__setattr__(self, "gap_m", gap)
        check_law("link.law", self.law)

    def to_dict(self) -> dict[str, Any]:
        return {"level_first": self.level_first, "level_second": self.level_second, "gap_m": self.gap_m,
                "law": law_to_dict(self.law)}


@dataclass(frozen=True)
class Adjacent(TomlFile):
    """Two structures side by side, the second to the right of the first, shaken by the same ground, that
    may pound each other at their links (and their own walls, if they have any).

    Parameters
    ----------
    first, second : Structure
        Each isolated or fixed at its base (:meth:`Structure.fixed_base`).  At most one of their isolators
        may have a Bouc-Wen spring.
    links : sequence of Link
        Where they may hit (at least one; at most one per pair of levels).

    Examples
    --------
    A three-storey isolated building 15 cm from a fixed-base neighbour, their roofs level:

    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02],
    ...                         damping_n_s_m=2.0e4)
    >>> isolated = pounding.Structure(3.0e4, iso,
    ...                               [pounding.Storey(2.0e4, 4.0e7)] * 3)
    >>> old = pounding.Structure.fixed_base(
    ...     [pounding.Storey(2.5e4, 3.0e7, 5.0e4)] * 3)
    >>> roof = pounding.Link(3, 3, 0.15, pounding.KelvinVoigt(5.0e8, 2.0e5))
    >>> pair = pounding.Adjacent(isolated, old, [roof])
    >>> quake = pounding.Harmonic(a_g=0.4, freq_hz=1.0)
    >>> run = pounding.simulate(pair, quake, 10.0)
    >>> len(run.links) > 0, run.first.structure is isolated
    (True, True)
    """

    first: Structure
    second: Structure
    links: tuple = ()

    FIELDS: ClassVar[tuple[str, ...]] = ("first", "second", "links")

    def __post_init__(self) -> None:
        for name in ("first", "second"):
            instance_of(name, getattr(self, name), Structure, "pounding.Structure")
        links = self.links
        if isinstance(links, (str, bytes, dict)) or not hasattr(links, "__iter__"):
            raise InputError(Problem.WRONG_TYPE, "links", links, got=type(links).__name__,
                             expected="sequence of Link")
        links = tuple(links)
        if not links:
            raise InputError(Problem.EMPTY, "links", [], hint=" (a Link: where the two structures may hit)")
        pairs = []
        for i, link in enumerate(links):
            instance_of(f"links[{i}]", link, Link, "Link")
            for name, s in (("level_first", self.first), ("level_second", self.second)):
                level = getattr(link, name)
                lowest = 1 if s.fixed else 0
                if not lowest <= level <= len(s.storeys):
                    raise InputError(Problem.OUT_OF_RANGE, f"links[{i}].{name}", level,
                                     range=f"{lowest} to {len(s.storeys)} (the levels of that structure"
                                           + (": its base is fixed" if s.fixed else "") + ")", hint="")
            pair = (link.level_first, link.level_second)
            if pair in pairs:
                levels = [(lk.level_first, lk.level_second) for lk in links]
                raise InputError(Problem.DUPLICATE, "links", levels, repeated=f"the levels {pair}")
            pairs.append(pair)
        object.__setattr__(self, "links", links)
        for s in (self.first, self.second):  # (a friction isolator's system: no rigid stop yet)
            refuse_rigid_stops(s.isolator, [(f"links[{i}].law", link.law) for i, link in enumerate(links)])

    @property
    def structures(self) -> tuple[Structure, Structure]:
        return self.first, self.second

    def without_bumpers(self) -> "Adjacent":
        """The pair with each structure without its walls (their bumpers, its moat), as
        :meth:`Structure.without_bumpers`; the links stay: they are where the two structures meet."""
        return replace(self, first=self.first.without_bumpers(), second=self.second.without_bumpers())

    # ------------------------------------------------------------------ TOML
    def to_dict(self) -> dict[str, Any]:
        """The pair as nested tables: ``[first]``, ``[second]``, ``[[links]]``."""
        return {"first": self.first.to_dict(), "second": self.second.to_dict(),
                "links": [lk.to_dict() for lk in self.links]}

    @classmethod
    def from_dict(cls, table: dict[str, Any]) -> "Adjacent":
        """Build from nested tables; every key is checked and unknown keys are errors."""
        table = {k: v for k, v in table.items() if k != "meta"} if isinstance(table, dict) else table
        check_keys(table, "", cls.FIELDS, required=cls.FIELDS)
        structures = []
        for name in ("first", "second"):
            instance_of(name, table[name], dict, f"table ([{name}]: a structure)")
            try:
                structures.append(Structure.from_dict(table[name]))
            except InputError as exc:
                raise exc.relabel("", f"{name}.") from None
        rows = table["links"]
        instance_of("links", rows, list, "array of tables ([[links]])")
        links = []
        for i, row in enumerate(rows):
            check_keys(row, f"links[{i}].", Link.FIELDS, required=Link.FIELDS)
            try:
                links.append(Link(row["level_first"], row["level_second"], row["gap_m"],
                                  law_from_dict(row["law"], f"links[{i}].law")))
            except InputError as exc:
                raise exc.relabel("link.", f"links[{i}].") from None
        return cls(structures[0], structures[1], tuple(links))


__all__ = ["Adjacent", "Link"]
