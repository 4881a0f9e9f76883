"""The parts of a structure (pounding.Structure): a storey of a shear building, a wall that stops a level,
the stand a wall's bumper may sit on; and a single mass's bumpers, the wall at its level 0 (one pair of sides,
checked and written as a wall's)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Optional

from .._checks import (at_least, at_most, backbone, integer, non_negative, plausible, positive,
                       real_tuple)
from .._errors import InputError, Problem, warn_renamed
from .contact_laws import ContactLaw, check_law, law_to_dict, refuse_clamp
from .isolator import HYSTERESIS_RULES

MAX_STOREYS = 50          # refused beyond (the history's columns grow with it)
MAX_STOREY_STIFFNESS = 1e13  # N/m, refused beyond (a unit error)
MAX_MASS_KG = 1e12  # refused beyond (a unit error)
MIN_MASS_KG = 1e-6  # refused below (1 mg: the phases' rates k/m overflowed at 1e-300 kg)
MAX_GAP_M = 1e3  # refused beyond (a unit error)


def check_mass(field_name: str, value: Any, hint: str = "masses are in kg (500 kg is 500.0)") -> float:
    """A mass (kg) as a float: positive, within [MIN_MASS_KG, MAX_MASS_KG], warned of outside 1 g - 1e9 kg."""
    mass = positive(field_name, value, "kg")
    at_most(field_name, mass, MAX_MASS_KG, " kg", "give the mass in kg")
    at_least(field_name, mass, MIN_MASS_KG, " kg", "give the mass in kg: 500 kg is 500.0")
    plausible(field_name, mass, 1e-3, 1e9, hint)
    return mass


def _check_mass_spring(part: Any, prefix: str) -> float:
    """Validate (and store as floats) a part's ``mass_kg``, ``stiffness_n_m`` and ``damping_n_s_m``, named
    ``prefix.<field>`` in errors; return the stiffness."""
    object.__setattr__(part, "mass_kg", check_mass(f"{prefix}.mass_kg", part.mass_kg))
    k = positive(f"{prefix}.stiffness_n_m", part.stiffness_n_m, "N/m")
    at_most(f"{prefix}.stiffness_n_m", k, MAX_STOREY_STIFFNESS, " N/m", "give the stiffness in N/m")
    object.__setattr__(part, "stiffness_n_m", k)
    c = non_negative(f"{prefix}.damping_n_s_m", part.damping_n_s_m, "N s/m")
    at_most(f"{prefix}.damping_n_s_m", c, MAX_STOREY_STIFFNESS, " N s/m", "give the damping in N s/m")
    object.__setattr__(part, "damping_n_s_m", c)
    return k


def check_backbone_after(part: Any, prefix: str, k: float) -> None:
    """Validate (and store as tuples) a multi-linear part's ``slopes_after_n_m``, ``breakpoints_m`` (drifts,
    m) and ``hysteresis`` after its first slope ``k`` (N/m), named ``prefix.<field>`` in errors: a storey's,
    a frame's."""
    after = real_tuple(f"{prefix}.slopes_after_n_m", part.slopes_after_n_m)
    try:
        slopes, breaks = backbone(prefix, (k, *after), part.breakpoints_m, MAX_STOREY_STIFFNESS, " N/m",
                                  "give the slopes in N/m", 10.0, "give the drifts in m (2 cm is 0.02)")
    except InputError as exc:  # (the helper's names: <prefix>.slopes[j], j >= 1, and <prefix>.breakpoints)
        if exc.field.startswith(f"{prefix}.slopes["):
            j = int(exc.field[len(f"{prefix}.slopes["):-1])
            raise exc.relabel(exc.field, f"{prefix}.slopes_after_n_m[{j - 1}]") from None
        raise exc.relabel(f"{prefix}.breakpoints", f"{prefix}.breakpoints_m") from None
    object.__setattr__(part, "slopes_after_n_m", slopes[1:])
    object.__setattr__(part, "breakpoints_m", breaks)
    if part.hysteresis not in HYSTERESIS_RULES:
        raise InputError(Problem.NOT_ONE_OF, f"{prefix}.hysteresis", part.hysteresis,
                         choices=", ".join(map(repr, HYSTERESIS_RULES)))


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
        check_backbone_after(self, "storey", k)

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


class _Sides:
    """What a pair of contact sides has (a wall's, a single mass's bumpers: fields ``gap_left_m``,
    ``gap_right_m``, ``law``, ``law_right``): each side's law, the checks of their gaps and laws, their
    table."""

    @property
    def left(self) -> ContactLaw:
        """The left side's contact law."""
        return self.law  # type: ignore[attr-defined]

    @property
    def right(self) -> ContactLaw:
        """The right side's contact law (``law`` unless ``law_right`` is given)."""
        return self.law if self.law_right is None else self.law_right  # type: ignore[attr-defined]

    def _check_gaps(self, prefix: str, plausible_max_m: float, example: str) -> None:
        for name in ("gap_left_m", "gap_right_m"):
            gap = non_negative(f"{prefix}.{name}", getattr(self, name), "m")
            at_most(f"{prefix}.{name}", gap, MAX_GAP_M, " m", "give the gap in m (15 mm is 0.015)")
            plausible(f"{prefix}.{name}", gap, 0.0, plausible_max_m, f"gaps are in m ({example})")
            object.__setattr__(self, name, gap)

    def _check_laws(self, prefix: str) -> None:
        for name in ("law", "law_right"):
            value = getattr(self, name)
            if value is None and name == "law_right":
                continue
            check_law(f"{prefix}.{name}", value)
        refuse_clamp(f"{prefix}.gap_left_m", self.gap_left_m, self.gap_right_m,  # type: ignore[attr-defined]
                     self.left, self.right)

    def _sides_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"gap_left_m": self.gap_left_m, "gap_right_m": self.gap_right_m,  # type: ignore
                               "law": law_to_dict(self.law)}  # type: ignore[attr-defined]
        if self.law_right is not None:  # type: ignore[attr-defined]
            out["law_right"] = law_to_dict(self.law_right)  # type: ignore[attr-defined]
        return out


@dataclass(frozen=True)
class Wall(_Sides):
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
        self._check_gaps("wall", 2.0, "a 15 cm moat is 0.15")
        self._check_laws("wall")
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

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"level": self.level, **self._sides_dict()}
        if self.stand is not None:
            out["stand"] = self.stand.to_dict()
        return out


@dataclass(frozen=True, init=False)
class Bumpers(_Sides):
    """Left and right bumpers, each behind its gap (the paper's YBs configuration).

    A bumper only pushes.  Contact with the right bumper starts when the displacement ``D``
    reaches ``gap_right_m + d_R(t)``, where ``d_R >= 0`` is the bumper's current compression
    (it may not have recovered from the previous contact); contact ends when the force would
    become a pull; in between contacts the bumper relaxes by its own law.  Mirror for left.

    Parameters
    ----------
    gap_left_m, gap_right_m : float
        Distances in m from the mass at rest to each bumper's free surface, >= 0.  The
        paper's total gap is ``gap_left_m + gap_right_m = 0.03`` m.  (``gap_left`` and
        ``gap_right``, their names before, still work for one release, with a warning.)
    law : KelvinVoigt, HuntCrossley, Jankowski, MultilinearBumper, ElasticPlastic or Hertzdamp
        Contact law of the left bumper, and of the right one unless ``law_right`` is given.
    law_right : KelvinVoigt, HuntCrossley, Jankowski, MultilinearBumper, ElasticPlastic or Hertzdamp, optional
        Contact law of the right bumper when it differs from the left one.
    capacity_m : float, optional
        The deepest compression the bumpers take (m), > 0: what a design checks their runs'
        ``compression_max_m`` against (``StripeAnalysis.outcomes("compression")``).  It does not
        change the motion.

    Each side's law is ``left`` and ``right``; ``total_gap`` is their gaps' sum.

    Examples
    --------
    The paper's YBs bumpers, 15 mm from the mass on each side; a stiffer one on the right:

    >>> import pounding
    >>> epdm = pounding.KelvinVoigt(stiffness=1.46e6, damping=5.0)
    >>> bumpers = pounding.Bumpers(gap_left_m=0.015, gap_right_m=0.015, law=epdm)
    >>> bumpers.total_gap  # m
    0.03
    >>> stiff = pounding.Bumpers(0.015, 0.010, epdm,
    ...                          law_right=pounding.KelvinVoigt(5.0e6, 5.0))
    >>> stiff.right.stiffness, stiff.mirrored().gap_left_m
    (5000000.0, 0.01)
    """

    gap_left_m: float
    gap_right_m: float
    law: ContactLaw
    law_right: Optional[ContactLaw] = None
    capacity_m: Optional[float] = None

    FIELDS: ClassVar[tuple[str, ...]] = ("gap_left_m", "gap_right_m", "law", "law_right", "capacity_m")
    # the names before (0.1's), still read for one release with a warning: in Python, TOML and dotted names
    RENAMED: ClassVar[dict[str, str]] = {"gap_left": "gap_left_m", "gap_right": "gap_right_m"}

    def __init__(self, gap_left_m: Any = None, gap_right_m: Any = None, law: Any = None,
                 law_right: Optional[ContactLaw] = None, capacity_m: Optional[float] = None,
                 **renamed: Any) -> None:
        given = {"gap_left_m": gap_left_m, "gap_right_m": gap_right_m}
        for old, value in renamed.items():
            if old not in self.RENAMED:
                raise TypeError(f"Bumpers() got an unexpected keyword argument '{old}'")
            warn_renamed(old, self.RENAMED[old])
            given[self.RENAMED[old]] = value
        for name, value in (*given.items(), ("law", law)):
            if value is None:
                raise InputError(Problem.MISSING_INPUT, f"bumpers.{name}", None,
                                 what=f"Bumpers({name}=...)")
        object.__setattr__(self, "gap_left_m", given["gap_left_m"])
        object.__setattr__(self, "gap_right_m", given["gap_right_m"])
        object.__setattr__(self, "law", law)
        object.__setattr__(self, "law_right", law_right)
        object.__setattr__(self, "capacity_m", capacity_m)
        self.__post_init__()

    @property
    def gap_left(self) -> float:
        """``gap_left_m`` under its name before (a warning: it goes in the next release)."""
        warn_renamed("gap_left", "gap_left_m")
        return self.gap_left_m

    @property
    def gap_right(self) -> float:
        """``gap_right_m`` under its name before (a warning: it goes in the next release)."""
        warn_renamed("gap_right", "gap_right_m")
        return self.gap_right_m

    def __post_init__(self) -> None:
        self._check_gaps("bumpers", 0.5, "15 mm is 0.015")
        if self.capacity_m is not None:
            capacity = positive("bumpers.capacity_m", self.capacity_m, "m")
            plausible("bumpers.capacity_m", capacity, 0.0, 0.5, "a bumper's capacity is in m (20 mm is 0.02)")
            object.__setattr__(self, "capacity_m", capacity)
        self._check_laws("bumpers")

    @property
    def total_gap(self) -> float:
        """``Delta = gap_left_m + gap_right_m`` in m."""
        return self.gap_left_m + self.gap_right_m

    def mirrored(self) -> "Bumpers":
        """The same bumpers seen in a mirror (left and right swapped)."""
        if self.law_right is None:
            return Bumpers(self.gap_right_m, self.gap_left_m, self.law, capacity_m=self.capacity_m)
        return Bumpers(self.gap_right_m, self.gap_left_m, self.law_right, self.law, self.capacity_m)

    def to_dict(self) -> dict[str, Any]:
        """The constructor's fields as plain values (the TOML form: ``Oscillator.to_toml`` writes it)."""
        out = self._sides_dict()
        if self.capacity_m is not None:
            out["capacity_m"] = self.capacity_m
        return out


__all__ = ["Bumpers", "Stand", "Storey", "Wall"]
