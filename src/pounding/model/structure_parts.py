"""The parts of a structure (pounding.Structure): a storey of a shear building, a wall that stops a level,
the stand a wall's bumper may sit on."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Optional

from .._checks import (at_least, at_most, backbone, integer, non_negative, plausible, positive,
                       real_tuple)
from .._errors import InputError, Problem
from .bumpers import MAX_GAP_M
from .contact_laws import check_law, law_to_dict, refuse_clamp
from .isolator import HYSTERESIS_RULES
from .oscillator import MAX_MASS_KG, MIN_MASS_KG

MAX_STOREYS = 50          # refused beyond (the history's columns grow with it)
MAX_STOREY_STIFFNESS = 1e13  # N/m, refused beyond (a unit error)


def _mass(field_name: str, value: Any) -> float:
    mass = positive(field_name, value, "kg")
    at_most(field_name, mass, MAX_MASS_KG, " kg", "give the mass in kg")
    at_least(field_name, mass, MIN_MASS_KG, " kg", "give the mass in kg: 500 kg is 500.0")
    plausible(field_name, mass, 1e-3, 1e9, "masses are in kg (500 kg is 500.0)")
    return mass


def _check_mass_spring(part: Any, prefix: str) -> float:
    """Validate (and store as floats) a part's ``mass_kg``, ``stiffness_n_m`` and ``damping_n_s_m``, named
    ``prefix.<field>`` in errors; return the stiffness."""
    object.__setattr__(part, "mass_kg", _mass(f"{prefix}.mass_kg", part.mass_kg))
    k = positive(f"{prefix}.stiffness_n_m", part.stiffness_n_m, "N/m")
    at_most(f"{prefix}.stiffness_n_m", k, MAX_STOREY_STIFFNESS, " N/m", "give the stiffness in N/m")
    object.__setattr__(part, "stiffness_n_m", k)
    c = non_negative(f"{prefix}.damping_n_s_m", part.damping_n_s_m, "N s/m")
    at_most(f"{prefix}.damping_n_s_m", c, MAX_STOREY_STIFFNESS, " N s/m", "give the damping in N s/m")
    object.__setattr__(part, "damping_n_s_m", c)
    return k


@dataclass(frozen=True)
class Storey:
    """One storey of a shear building: the floor's mass and the storey's lateral spring and dashpot
    that carry it on the level below.

    Parameters
    ----------
    mass_kg : float
        The floor's mass, kg, > 0.
    stiffness_n_m : float
        The storey's lateral stiffness, N/m, > 0.
    damping_n_s_m : float
        The storey's dashpot, N s/m, >= 0.
    height_m : float
        The storey's height, m, > 0 (for drift ratios; default 3 m).
    slopes_after_n_m : sequence of float
        A multi-linear storey: its backbone's slopes after the first (``stiffness_n_m``), N/m, >= 0;
        empty (the default) for a linear storey.
    breakpoints_m : sequence of float
        The drifts where the slope changes, m, > 0 and increasing, one per slope after the first.
    hysteresis : {"kinematic", "elastic"}
        How a multi-linear storey unloads, as an :class:`Isolator` does: Masing's rule (springs that slip:
        a loop that dissipates) or along the backbone.

    Examples
    --------
    A storey of 20 t on columns of 40 MN/m, its fixed-base period:

    >>> import math, pounding
    >>> s = pounding.Storey(mass_kg=2.0e4, stiffness_n_m=4.0e7, damping_n_s_m=4.0e4)
    >>> round(2 * math.pi * math.sqrt(s.mass_kg / s.stiffness_n_m), 3)  # s
    0.14
    """

    mass_kg: float
    stiffness_n_m: float
    damping_n_s_m: float = 0.0
    height_m: float = 3.0
    slopes_after_n_m: tuple = ()
    breakpoints_m: tuple = ()
    hysteresis: str = "kinematic"

    FIELDS: ClassVar[tuple[str, ...]] = ("mass_kg", "stiffness_n_m", "damping_n_s_m", "height_m",
                                         "slopes_after_n_m", "breakpoints_m", "hysteresis")

    def __post_init__(self) -> None:
        k = _check_mass_spring(self, "storey")
        h = positive("storey.height_m", self.height_m, "m")
        at_most("storey.height_m", h, 1e3, " m", "give the height in m")
        plausible("storey.height_m", h, 0.1, 20.0, "heights are in m (a storey of 3 m is 3.0)")
        object.__setattr__(self, "height_m", h)
        after = real_tuple("storey.slopes_after_n_m", self.slopes_after_n_m)
        try:
            slopes, breaks = backbone("storey", (k, *after), self.breakpoints_m, MAX_STOREY_STIFFNESS, " N/m",
                                      "give the slopes in N/m", 10.0, "give the drifts in m (2 cm is 0.02)")
        except InputError as exc:  # (the helper's names: storey.slopes[j], j >= 1, and storey.breakpoints)
            if exc.field.startswith("storey.slopes["):
                j = int(exc.field[len("storey.slopes["):-1])
                raise exc.relabel(exc.field, f"storey.slopes_after_n_m[{j - 1}]") from None
            raise exc.relabel("storey.breakpoints", "storey.breakpoints_m") from None
        object.__setattr__(self, "slopes_after_n_m", slopes[1:])
        object.__setattr__(self, "breakpoints_m", breaks)
        if self.hysteresis not in HYSTERESIS_RULES:
            raise InputError(Problem.NOT_ONE_OF, "storey.hysteresis", self.hysteresis,
                             choices=", ".join(map(repr, HYSTERESIS_RULES)))

    @property
    def is_linear(self) -> bool:
        """A linear storey (no breakpoints)."""
        return not self.breakpoints_m

    def kernel_element(self, below: int) -> tuple:
        """The storey's spring as the core's hysteretic element between levels ``below + 1`` and ``below``
        (its dashpot is in the structure's damping matrix)."""
        return (below + 1, below, 0.0, [self.stiffness_n_m, *self.slopes_after_n_m], list(self.breakpoints_m),
                HYSTERESIS_RULES.index(self.hysteresis))


@dataclass(frozen=True)
class Stand:
    """What a bumper stands on when it is not the ground: a mass on a spring and a dashpot to the ground (a
    steel stand bolted to the shaking table, a flexible wall).

    Parameters
    ----------
    mass_kg : float
        The stand's moving mass with its bumper, kg, > 0.
    stiffness_n_m : float
        Its lateral stiffness to the ground, N/m, > 0.
    damping_n_s_m : float
        Its dashpot, N s/m, >= 0.

    Examples
    --------
    A steel stand of 20 kg, 2 MN/m (a natural frequency near 50 Hz):

    >>> import math, pounding
    >>> stand = pounding.Stand(mass_kg=20.0, stiffness_n_m=2.0e6,
    ...                        damping_n_s_m=50.0)
    >>> w = math.sqrt(stand.stiffness_n_m / stand.mass_kg)  # rad/s
    >>> round(w / (2 * math.pi), 1)  # Hz
    50.3
    """

    mass_kg: float
    stiffness_n_m: float
    damping_n_s_m: float = 0.0

    FIELDS: ClassVar[tuple[str, ...]] = ("mass_kg", "stiffness_n_m", "damping_n_s_m")

    def __post_init__(self) -> None:
        _check_mass_spring(self, "stand")

    def to_dict(self) -> dict[str, Any]:
        return {f: getattr(self, f) for f in self.FIELDS}


@dataclass(frozen=True)
class Wall:
    """A wall on both sides of one level (a moat wall around the base, or a stop at a floor), each side
    behind its gap, with a contact law (a bumper on the wall, or the wall itself).

    Parameters
    ----------
    level : int
        The level it stops: 0 the base, ``i`` the floor on storey ``i``.
    gap_left_m, gap_right_m : float
        Gaps to the left (negative displacements) and right sides, m, >= 0.
    law : contact law
        Any of the package's contact laws (``KelvinVoigt``, ``MultilinearBumper``, ...); the right side's
        too unless ``law_right`` is given.
    law_right : contact law, optional
        The right side's law.
    stand : Stand, optional
        Each side's bumper on a stand of its own (these numbers, both sides), not on the ground: the
        stands move, and the structure's level hits them.

    Examples
    --------
    A moat wall 10 cm from the base on each side, faced with a stiff elastic layer:

    >>> import pounding
    >>> face = pounding.KelvinVoigt(stiffness=2.0e8, damping=1.0e5)
    >>> moat = pounding.Wall(level=0, gap_left_m=0.10, gap_right_m=0.10, law=face)
    >>> moat.left is moat.right
    True
    """

    level: int
    gap_left_m: float
    gap_right_m: float
    law: Any
    law_right: Any = None
    stand: Optional[Stand] = None

    FIELDS: ClassVar[tuple[str, ...]] = ("level", "gap_left_m", "gap_right_m", "law", "law_right", "stand")

    def __post_init__(self) -> None:
        object.__setattr__(self, "level", integer("wall.level", self.level, 0, MAX_STOREYS))
        for name in ("gap_left_m", "gap_right_m"):
            gap = non_negative(f"wall.{name}", getattr(self, name), "m")
            at_most(f"wall.{name}", gap, MAX_GAP_M, " m", "give the gap in m (15 mm is 0.015)")
            plausible(f"wall.{name}", gap, 0.0, 2.0, "gaps are in m (a 15 cm moat is 0.15)")
            object.__setattr__(self, name, gap)
        for name in ("law", "law_right"):
            value = getattr(self, name)
            if value is None and name == "law_right":
                continue
            check_law(f"wall.{name}", value)
        refuse_clamp("wall.gap_left_m", self.gap_left_m, self.gap_right_m, self.left, self.right)
        if self.stand is not None and not isinstance(self.stand, Stand):
            raise InputError(Problem.WRONG_TYPE, "wall.stand", self.stand, got=type(self.stand).__name__,
                             expected="Stand or None")

    @classmethod
    def _of_bumpers(cls, bumpers: Any) -> "Wall":
        """A single mass's bumpers as the wall at its level 0, from numbers its ``Bumpers`` checked (and
        warned about) already: not checked, nor warned about, a second time."""
        values = {"level": 0, "gap_left_m": bumpers.gap_left_m, "gap_right_m": bumpers.gap_right_m,
                  "law": bumpers.left, "law_right": None if bumpers.right is bumpers.left else bumpers.right,
                  "stand": None}
        wall = object.__new__(cls)
        for name, value in values.items():
            object.__setattr__(wall, name, value)
        return wall

    @property
    def left(self) -> Any:
        return self.law

    @property
    def right(self) -> Any:
        return self.law if self.law_right is None else self.law_right

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"level": self.level, "gap_left_m": self.gap_left_m,
                               "gap_right_m": self.gap_right_m, "law": law_to_dict(self.law)}
        if self.law_right is not None:
            out["law_right"] = law_to_dict(self.law_right)
        if self.stand is not None:
            out["stand"] = self.stand.to_dict()
        return out


__all__ = ["Stand", "Storey", "Wall"]
