"""A building in plan's moat (:class:`pounding.model.plan.PlanBuilding`'s ``moat``): four walls around a
floor's rectangle (:class:`RectangularMoat`) or a ring around it (:class:`CircularMoat`), and the names of
their walls as contacts give them."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from .._checks import at_most, instance_of, integer, non_negative, plausible, real, real_tuple
from .._errors import InputError, Problem
from .contact_laws import check_law, law_to_dict
from .plan_parts import Floor
from .structure_parts import MAX_GAP_M, MAX_STOREYS

MOAT_SIDES = ("-x", "+x", "-y", "+y")  # (a rectangular moat's walls, in its gaps' order)
OUT_OF_REACH_M = 100.0  # a ring's gap in a free run (out_of_reach): no building's corner moves this far


def _moat_gap(name: str, gap: float) -> float:
    """A moat's gap (m, a real number) checked: >= 0, at most the largest, warned of if implausible."""
    non_negative(name, gap, "m")
    at_most(name, gap, MAX_GAP_M, " m", "give the gap in m (30 cm is 0.30)")
    plausible(name, gap, 0.0, 2.0, "gaps are in m (a 30 cm moat is 0.30)")
    return gap


@dataclass(frozen=True)
class RectangularMoat:
    """A rectangular moat around a floor: four walls, each struck by the floor's two corners on its side.

    Parameters
    ----------
    gap_m : float or (float, float, float, float)
        The clearance at rest between the floor's rectangle and each wall, m, >= 0: one for all four, or
        the walls at -x, +x, -y and +y.
    law : contact law
        The walls' contact law: any law, a :class:`pounding.RigidStop` included (a corner's impact turns
        the floor: its impulse acts on the floor's x or y and its rotation, and a corner held on a wall is
        a constraint on both).
    level : int
        The floor it surrounds (default 0: the base).

    Examples
    --------
    A moat 30 cm wide on three sides and 20 cm on the fourth, its walls of concrete behind a pad:

    >>> import pounding
    >>> pad = pounding.KelvinVoigt(stiffness=5.0e8, damping=1.0e6)
    >>> moat = pounding.RectangularMoat((0.3, 0.3, 0.3, 0.2), pad)
    >>> moat.gap_m  # m: the walls at -x, +x, -y, +y
    (0.3, 0.3, 0.3, 0.2)
    """

    gap_m: Any
    law: Any
    level: int = 0

    FIELDS: ClassVar[tuple[str, ...]] = ("gap_m", "law", "level")

    def __post_init__(self) -> None:
        gaps = real_tuple("moat.gap_m", self.gap_m)
        if len(gaps) not in (1, 4):
            raise InputError(Problem.LENGTH_MISMATCH, "moat.gap_m", list(gaps), got=len(gaps), expected=4,
                             hint=" (one for every wall, or the walls at -x, +x, -y, +y)")
        for j, g in enumerate(gaps):  # (one gap for all: checked, and warned of, once)
            _moat_gap("moat.gap_m" if len(gaps) == 1 else f"moat.gap_m[{j}]", g)
        object.__setattr__(self, "gap_m", gaps * 4 if len(gaps) == 1 else gaps)
        check_law("moat.law", self.law)
        object.__setattr__(self, "level", integer("moat.level", self.level, 0, MAX_STOREYS))

    @property
    def smallest_gap_m(self) -> float:
        """The smallest of its four gaps, m."""
        return float(min(self.gap_m))

    def to_dict(self) -> dict[str, Any]:
        return {"gap_m": list(self.gap_m), "law": law_to_dict(self.law), "level": self.level}


RING_WALL = "ring"  # (a circular moat's wall, as its contacts name it)
MOAT_WALLS = (*MOAT_SIDES, RING_WALL)  # (every wall a contact may strike: a side's index, then the ring)


def wall_name(side: int) -> str:
    """A moat's wall by its index in :data:`MOAT_WALLS`, as messages name it: ``wall -x``, ``ring``."""
    return RING_WALL if side == len(MOAT_SIDES) else f"wall {MOAT_SIDES[side]}"


@dataclass(frozen=True)
class CircularMoat:
    """A circular moat around a floor: a ring centred on the floor's rectangle, struck by its corners along
    the ring's normal (the wall pushes back towards the centre).

    Parameters
    ----------
    gap_m : float
        The clearance at rest between the floor's corners and the ring, m, >= 0: the ring's radius is the
        rectangle's half-diagonal plus it (:meth:`radius_m`).
    law : contact law
        The wall's contact law: any law, a :class:`pounding.RigidStop` included (a corner it holds slides
        along the ring, let go where the hold would pull).
    level : int
        The floor it surrounds (default 0: the base).
    out_of_reach : bool
        A ring moved out of reach (default False): its radius ``OUT_OF_REACH_M`` beyond the corners, never
        struck, the corners' distances from its centre tracked: what a free run of a building in a ring
        takes (:meth:`PlanBuilding.moat_out_of_reach`), its ``moat_demand_m`` the gap a ring needs.

    Examples
    --------
    A ring 25 cm clear of the corners of a 30 m by 12 m base:

    >>> import pounding
    >>> pad = pounding.KelvinVoigt(stiffness=5.0e8, damping=1.0e6)
    >>> moat = pounding.CircularMoat(0.25, pad)
    >>> round(moat.radius_m(pounding.Floor(2.0e6, (30.0, 12.0))), 3)  # m
    16.405
    """

    gap_m: Any
    law: Any
    level: int = 0
    out_of_reach: bool = False

    FIELDS: ClassVar[tuple[str, ...]] = ("gap_m", "law", "level", "out_of_reach")

    def __post_init__(self) -> None:
        if isinstance(self.gap_m, (list, tuple, np.ndarray)):
            raise InputError(Problem.WRONG_TYPE, "moat.gap_m", self.gap_m, got=type(self.gap_m).__name__,
                             expected="number (a ring has one gap; four: a RectangularMoat, shape = "
                                      "\"rectangle\" in a file)")
        gap = _moat_gap("moat.gap_m", real("moat.gap_m", self.gap_m))
        object.__setattr__(self, "gap_m", gap + 0.0)  # (-0.0 as 0.0)
        instance_of("moat.out_of_reach", self.out_of_reach, bool, "true or false")
        check_law("moat.law", self.law)
        object.__setattr__(self, "level", integer("moat.level", self.level, 0, MAX_STOREYS))

    @property
    def smallest_gap_m(self) -> float:
        """Its gap, m (a rectangle's smallest: one name for both)."""
        return self.gap_m

    @property
    def reach_m(self) -> float:
        """How far its corners may move towards it, m: its gap, or :data:`OUT_OF_REACH_M` for a ring moved
        out of reach (``out_of_reach``: never struck, the demand on it tracked; a free run's,
        :meth:`PlanBuilding.moat_out_of_reach`)."""
        return OUT_OF_REACH_M if self.out_of_reach else self.gap_m

    def radius_m(self, floor: Floor) -> float:
        """The ring's radius around ``floor`` (the one it surrounds), m: its half-diagonal plus the gap
        (:attr:`reach_m`)."""
        instance_of("floor", floor, Floor, "pounding.Floor")
        a, b = floor.size_m
        return float(math.hypot(a / 2.0, b / 2.0) + self.reach_m)

    def to_dict(self) -> dict[str, Any]:
        return {"shape": "circle", "gap_m": self.gap_m, "law": law_to_dict(self.law), "level": self.level,
                **({"out_of_reach": True} if self.out_of_reach else {})}


__all__ = ["CircularMoat", "MOAT_SIDES", "MOAT_WALLS", "OUT_OF_REACH_M", "RING_WALL", "RectangularMoat",
           "wall_name"]
