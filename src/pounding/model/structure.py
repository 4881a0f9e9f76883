"""A structure of several masses: an isolated base, storeys above it (a shear building) and walls it
may pound against (a moat wall at the base or at any level); TOML in and out.

Degrees of freedom are levels: 0 is the base (on its isolator), ``i`` the floor carried by storey
``i`` (``storeys[i - 1]``).  Each displacement is relative to the ground (the shaking table).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, NamedTuple, Optional, Union

import numpy as np
import tomli_w

from .._checks import (at_least, at_most, backbone, integer, non_negative, parse_toml, plausible, positive,
                       read_text, real_tuple)
from .._errors import InputError, Problem
from .bumpers import MAX_GAP_M
from .contact_laws import LAWS, law_from_dict, law_to_dict
from .isolator import HYSTERESIS_RULES, Isolator
from .oscillator import MAX_MASS_KG, MIN_MASS_KG, Oscillator, _check_keys

PathLike = Union[str, Path]
MAX_STOREYS = 50          # refused beyond (the history's columns grow with it)
MAX_STOREY_STIFFNESS = 1e13  # N/m, refused beyond (a unit error)


def _mass(field_name: str, value: Any) -> float:
    mass = positive(field_name, value, "kg")
    at_most(field_name, mass, MAX_MASS_KG, " kg", "give the mass in kg")
    at_least(field_name, mass, MIN_MASS_KG, " kg", "give the mass in kg: 500 kg is 500.0")
    plausible(field_name, mass, 1e-3, 1e9, "masses are in kg (500 kg is 500.0)")
    return mass


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
        object.__setattr__(self, "mass_kg", _mass("storey.mass_kg", self.mass_kg))
        k = positive("storey.stiffness_n_m", self.stiffness_n_m, "N/m")
        at_most("storey.stiffness_n_m", k, MAX_STOREY_STIFFNESS, " N/m", "give the stiffness in N/m")
        object.__setattr__(self, "stiffness_n_m", k)
        c = non_negative("storey.damping_n_s_m", self.damping_n_s_m, "N s/m")
        at_most("storey.damping_n_s_m", c, MAX_STOREY_STIFFNESS, " N s/m", "give the damping in N s/m")
        object.__setattr__(self, "damping_n_s_m", c)
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
        object.__setattr__(self, "mass_kg", _mass("stand.mass_kg", self.mass_kg))
        k = positive("stand.stiffness_n_m", self.stiffness_n_m, "N/m")
        at_most("stand.stiffness_n_m", k, MAX_STOREY_STIFFNESS, " N/m", "give the stiffness in N/m")
        object.__setattr__(self, "stiffness_n_m", k)
        c = non_negative("stand.damping_n_s_m", self.damping_n_s_m, "N s/m")
        at_most("stand.damping_n_s_m", c, MAX_STOREY_STIFFNESS, " N s/m", "give the damping in N s/m")
        object.__setattr__(self, "damping_n_s_m", c)

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
            if not isinstance(value, tuple(LAWS.values())):
                raise InputError(Problem.WRONG_TYPE, f"wall.{name}", value, got=type(value).__name__,
                                 expected="contact law (KelvinVoigt, HuntCrossley, Jankowski, "
                                          "MultilinearBumper, ElasticPlastic or Hertzdamp)")
        if self.stand is not None and not isinstance(self.stand, Stand):
            raise InputError(Problem.WRONG_TYPE, "wall.stand", self.stand, got=type(self.stand).__name__,
                             expected="Stand or None")

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


class Modes(NamedTuple):
    """Undamped modes: ``periods_s`` (m,) longest first, ``shapes`` (n, m), each column scaled to a largest
    component of +1, rows by level."""

    periods_s: np.ndarray
    shapes: np.ndarray


@dataclass(frozen=True)
class Structure:
    """A base-isolated shear building: the base on its isolator, storeys above it, walls it may pound.

    Equations of motion (``x``: each level's displacement relative to the ground, m)::

        M x'' + C x' + K x + e_0 (C_d x_0' + R_d(x_0)) + sum of wall forces = -M 1 A(t)

    with ``K``, ``C`` the storeys' springs and dashpots between adjacent levels and the isolator
    (``R_d`` its backbone and hysteresis, ``C_d`` its dashpot) between the base and the ground.
    A structure with no storeys and one wall at the base is the single :class:`Oscillator`.

    Parameters
    ----------
    base_mass_kg : float or None
        The isolated base's mass, kg, > 0; None with ``isolator`` None: a building fixed at its base
        (:meth:`fixed_base`), whose level 0 is the ground.
    isolator : Isolator or None
        The isolator under the base (any the package has); None: a fixed base.
    storeys : sequence of Storey
        From the first above the base up; at most 50.
    walls : sequence of Wall
        At most one per level.
    rayleigh : (float, float), optional
        Rayleigh damping of the superstructure as the damping ratios of its first two fixed-base modes
        (each in [0, 1); needs two storeys or more): ``C = a0 M + a1 K`` of the storeys above the base,
        acting on their motion relative to the base (so it damps no motion of the whole building on its
        isolator), in addition to the storeys' own dashpots.

    Examples
    --------
    A three-storey building on a bilinear isolator, in a moat 10 cm wide around its base:

    >>> import pounding
    >>> iso = pounding.Isolator(slopes=[4.0e6, 1.0e6], breakpoints=[0.02],
    ...                         damping=2.0e4)
    >>> storeys = [pounding.Storey(2.0e4, 4.0e7, 4.0e4)] * 3
    >>> moat = pounding.Wall(0, 0.10, 0.10, pounding.KelvinVoigt(2.0e8, 1.0e5))
    >>> b = pounding.Structure(3.0e4, iso, storeys, walls=[moat])
    >>> b.n_levels, b.modes().periods_s.round(3).tolist()  # s, isolated
    (4, [0.976, 0.195, 0.103, 0.077])
    >>> b.modes(fixed_base=True).periods_s.round(3).tolist()  # s
    [0.316, 0.113, 0.078]
    >>> quake = pounding.Harmonic(a_g=0.3, freq_hz=1.2)
    >>> run = pounding.simulate(b, quake, duration=10.0)
    >>> len(run.contacts), run.contacts["level"].unique().tolist()  # the base
    (43, [0])
    >>> (run.displacement_max * 1e3).round(1).tolist()  # mm, each level (exact)
    [114.6, 157.1, 192.3, 209.4]
    """

    base_mass_kg: Optional[float]
    isolator: Optional[Isolator]
    storeys: tuple = ()
    walls: tuple = field(default=())
    rayleigh: Optional[tuple] = None

    FIELDS: ClassVar[tuple[str, ...]] = ("base_mass_kg", "isolator", "storeys", "walls", "rayleigh")

    def __post_init__(self) -> None:
        if (self.base_mass_kg is None) != (self.isolator is None):
            field_name = "isolator" if self.isolator is None else "base_mass_kg"
            raise InputError(Problem.WRONG_CONFIGURATION, field_name, None,
                             got="with one of base_mass_kg and isolator None",
                             fix="give both (an isolated base) or neither (a fixed base: "
                                 "Structure.fixed_base)")
        if self.isolator is not None:
            object.__setattr__(self, "base_mass_kg", _mass("base_mass_kg", self.base_mass_kg))
            if not isinstance(self.isolator, Isolator):
                raise InputError(Problem.WRONG_TYPE, "isolator", self.isolator,
                                 got=type(self.isolator).__name__, expected="Isolator or None")
        for name, kind in (("storeys", Storey), ("walls", Wall)):
            items = getattr(self, name)
            if isinstance(items, (str, bytes, dict)) or not hasattr(items, "__iter__"):
                raise InputError(Problem.WRONG_TYPE, name, items, got=type(items).__name__,
                                 expected=f"sequence of {kind.__name__}")
            items = tuple(items)
            for i, item in enumerate(items):
                if not isinstance(item, kind):
                    raise InputError(Problem.WRONG_TYPE, f"{name}[{i}]", item, got=type(item).__name__,
                                     expected=kind.__name__)
            object.__setattr__(self, name, items)
        if len(self.storeys) > MAX_STOREYS:
            raise InputError(Problem.TOO_LARGE, "storeys", len(self.storeys), maximum=MAX_STOREYS,
                             what=" storeys", fix=f"give at most {MAX_STOREYS} storeys")
        if self.rayleigh is not None:
            ratios = real_tuple("rayleigh", self.rayleigh)
            if len(ratios) != 2:
                raise InputError(Problem.LENGTH_MISMATCH, "rayleigh", list(ratios), got=len(ratios),
                                 expected=2, hint=" (the damping ratios of the first two fixed-base modes)")
            for j, z in enumerate(ratios):
                if not 0.0 <= z < 1.0:
                    raise InputError(Problem.OUT_OF_RANGE, f"rayleigh[{j}]", z, range="[0, 1)",
                                     hint=" (a damping ratio: 5 % is 0.05)")
                plausible(f"rayleigh[{j}]", z, 0.0, 0.3, "damping ratios are fractions (5 % is 0.05)")
            if len(self.storeys) < 2:
                raise InputError(Problem.WRONG_CONFIGURATION, "rayleigh", list(ratios),
                                 got=f"of {len(self.storeys)} storey(s): one fixed-base mode at most",
                                 fix="give the storeys' dashpots (damping_n_s_m) instead, or two storeys or "
                                     "more")
            object.__setattr__(self, "rayleigh", ratios)
            a0, a1 = self.rayleigh_coefficients()
            w = 2.0 * np.pi / self.modes(fixed_base=True).periods_s
            zeta = a0 / (2.0 * w) + 0.5 * a1 * w  # (every fixed-base mode's ratio: none may be negative)
            if zeta.min() < -1e-12:
                k = int(np.argmin(zeta))
                raise InputError(Problem.OUT_OF_RANGE, "rayleigh", list(ratios),
                                 range="ratios that damp every mode (a0 M + a1 K gives the fixed-base "
                                       f"mode {k + 1}, of period {2 * np.pi / w[k]:.3g} s, the ratio "
                                       f"{zeta[k]:.3g})",
                                 hint=": bring the two ratios closer together")
        levels = [w.level for w in self.walls]
        if self.fixed and not self.storeys:
            raise InputError(Problem.WRONG_CONFIGURATION, "storeys", [],
                             got="fixed at its base without storeys",
                             fix="give at least one storey (or an isolator and a base mass)")
        for i, level in enumerate(levels):
            if self.fixed and level == 0:
                raise InputError(Problem.OUT_OF_RANGE, f"walls[{i}].level", level,
                                 range=f"1 to {len(self.storeys)} (the base is fixed: level 0 is the ground)",
                                 hint="")
            if level > len(self.storeys):
                raise InputError(Problem.OUT_OF_RANGE, f"walls[{i}].level", level,
                                 range=f"0 to {len(self.storeys)} (the levels of this structure)",
                                 hint=" (0 is the base)")
            if level in levels[:i]:
                raise InputError(Problem.DUPLICATE, "walls", levels, repeated=f"level {level}")

    # ------------------------------------------------------------------ matrices
    @classmethod
    def fixed_base(cls, storeys: Any, walls: Any = (), rayleigh: Any = None) -> "Structure":
        """A building fixed at its base: storey 1 stands on the ground (level 0, which does not move
        relative to it).  A neighbour without isolation (:class:`Adjacent`), or a building against a stop."""
        return cls(None, None, storeys, walls, rayleigh)

    @property
    def fixed(self) -> bool:
        """The base is fixed to the ground (no isolator)."""
        return self.isolator is None

    @property
    def n_levels(self) -> int:
        """The degrees of freedom: the base and one per storey."""
        return 1 + len(self.storeys)

    @property
    def masses_kg(self) -> np.ndarray:
        """Each level's mass, kg, shape (n_levels,) (NaN for the ground of a fixed base)."""
        base = np.nan if self.base_mass_kg is None else self.base_mass_kg
        return np.array([base] + [s.mass_kg for s in self.storeys])

    def shear_matrix(self, values: Any) -> np.ndarray:
        """Springs (or dashpots) ``values[i]`` (one per storey) between levels i and i + 1, as an
        (n_levels, n_levels) matrix."""
        n = self.n_levels
        out = np.zeros((n, n))
        for i, s in enumerate(values):  # storey i joins levels i and i + 1
            out[i, i] += s
            out[i + 1, i + 1] += s
            out[i, i + 1] -= s
            out[i + 1, i] -= s
        return out

    @property
    def stiffness_matrix(self) -> np.ndarray:
        """The storeys' springs at their initial stiffness, N/m, shape (n_levels, n_levels) (the isolator
        not included)."""
        return self.shear_matrix([s.stiffness_n_m for s in self.storeys])

    def rayleigh_coefficients(self) -> tuple[float, float]:
        """``(a0, a1)`` of the Rayleigh damping ``a0 M + a1 K`` (1/s, s): the two fixed-base modes' ratios
        met; (0, 0) without ``rayleigh``."""
        if self.rayleigh is None:
            return 0.0, 0.0
        periods = self.modes(fixed_base=True).periods_s
        w1, w2 = 2.0 * np.pi / periods[0], 2.0 * np.pi / periods[1]
        z1, z2 = self.rayleigh
        # z_i = a0 / (2 w_i) + a1 w_i / 2
        a1 = 2.0 * (z2 * w2 - z1 * w1) / (w2 * w2 - w1 * w1)
        a0 = 2.0 * z1 * w1 - a1 * w1 * w1
        return float(a0), float(a1)

    @property
    def damping_matrix(self) -> np.ndarray:
        """The storeys' dashpots and the Rayleigh damping, N s/m, shape (n_levels, n_levels) (the isolator's
        dashpot not included)."""
        c = self.shear_matrix([s.damping_n_s_m for s in self.storeys])
        if self.rayleigh is not None:  # a0 M + a1 K above the base, on the motion relative to the base
            a0, a1 = self.rayleigh_coefficients()
            c_s = a0 * np.diag(self.masses_kg[1:]) + a1 * self.stiffness_matrix[1:, 1:]
            t = np.hstack([-np.ones((self.n_levels - 1, 1)), np.eye(self.n_levels - 1)])  # x_s - x_base
            c = c + t.T @ c_s @ t
        return c

    def modes(self, fixed_base: bool = False) -> Modes:
        """Undamped modes about rest: isolated (the isolator at its initial stiffness) or with the base
        held fixed (the superstructure alone; no modes for a structure without storeys).  A fixed-base
        building has only the latter."""
        from scipy.linalg import eigh

        k = self.stiffness_matrix
        m = self.masses_kg
        if fixed_base or self.fixed:
            k, m = k[1:, 1:], m[1:]
        else:
            k = k.copy()
            k[0, 0] += self.isolator.slopes[0]
        if m.size == 0:
            return Modes(np.zeros(0), np.zeros((0, 0)))
        w2, shapes = eigh(k, np.diag(m))
        periods = 2.0 * np.pi / np.sqrt(w2)
        big = np.argmax(np.abs(shapes), axis=0)
        shapes = shapes / shapes[big, np.arange(shapes.shape[1])]
        return Modes(periods, shapes)

    @classmethod
    def from_oscillator(cls, oscillator: Oscillator) -> "Structure":
        """The single oscillator as a structure of one level (its bumpers a wall at the base)."""
        if not isinstance(oscillator, Oscillator):
            raise InputError(Problem.WRONG_TYPE, "oscillator", oscillator, got=type(oscillator).__name__,
                             expected="Oscillator")
        b = oscillator.bumpers
        walls = () if b is None else (Wall(0, b.gap_left, b.gap_right, b.left,
                                           None if b.right is b.left else b.right),)
        return cls(oscillator.mass, oscillator.isolator, (), walls)

    # ------------------------------------------------------------------ TOML
    def to_dict(self) -> dict[str, Any]:
        """The structure as nested tables with the constructor's field names."""
        out: dict[str, Any] = {} if self.fixed else {"base_mass_kg": self.base_mass_kg,
                                                     "isolator": self.isolator.to_dict()}
        if self.storeys:
            out["storeys"] = [{f: (list(v) if isinstance(v, tuple) else v) for f in Storey.FIELDS
                               if (v := getattr(s, f)) != ()} for s in self.storeys]
        if self.walls:
            out["walls"] = [w.to_dict() for w in self.walls]
        if self.rayleigh is not None:
            out["rayleigh"] = list(self.rayleigh)
        return out

    @classmethod
    def from_dict(cls, table: dict[str, Any]) -> "Structure":
        """Build from nested tables; every key is checked and unknown keys are errors."""
        table = {k: v for k, v in table.items() if k != "meta"} if isinstance(table, dict) else table
        _check_keys(table, "", cls.FIELDS, required=())
        isolator = None
        if "isolator" in table:  # (neither it nor base_mass_kg: a fixed base)
            iso_table = table["isolator"]
            _check_keys(iso_table, "isolator.", Isolator.FIELDS,
                        required=tuple(f for f in Isolator.FIELDS if f not in Isolator.OPTIONAL))
            isolator = Isolator(**iso_table)
        storeys, walls = [], []
        for name, out in (("storeys", storeys), ("walls", walls)):
            rows = table.get(name, [])
            if not isinstance(rows, list):
                raise InputError(Problem.WRONG_TYPE, name, rows, got=type(rows).__name__,
                                 expected=f"array of tables ([[{name}]])")
            for i, row in enumerate(rows):
                prefix = f"{name}[{i}]."
                if name == "storeys":
                    _check_keys(row, prefix, Storey.FIELDS, required=("mass_kg", "stiffness_n_m"))
                    try:
                        out.append(Storey(**row))
                    except InputError as exc:
                        raise exc.relabel("storey.", prefix) from None
                else:
                    _check_keys(row, prefix, Wall.FIELDS,
                                required=("level", "gap_left_m", "gap_right_m", "law"))
                    right, stand = row.get("law_right"), row.get("stand")
                    if stand is not None:
                        _check_keys(stand, prefix + "stand.", Stand.FIELDS,
                                    required=("mass_kg", "stiffness_n_m"))
                    try:
                        out.append(Wall(row["level"], row["gap_left_m"], row["gap_right_m"],
                                        law_from_dict(row["law"], prefix + "law"),
                                        None if right is None else law_from_dict(right, prefix + "law_right"),
                                        None if stand is None else Stand(**stand)))
                    except InputError as exc:
                        raise exc.relabel("stand.", prefix + "stand.").relabel("wall.", prefix) from None
        return cls(table.get("base_mass_kg"), isolator, tuple(storeys), tuple(walls), table.get("rayleigh"))

    @classmethod
    def from_toml(cls, path: PathLike) -> "Structure":
        """Read a structure from a TOML file (see ``examples/building_moat.toml``)."""
        text = read_text("path", path)
        try:
            return cls.from_toml_text(text)
        except InputError as exc:
            if exc.problem is Problem.BAD_TOML:
                raise exc.relabel("text", str(path)) from None
            raise

    @classmethod
    def from_toml_text(cls, text: str) -> "Structure":
        """Read a structure from TOML text."""
        if not isinstance(text, str):
            raise InputError(Problem.WRONG_TYPE, "text", text, got=type(text).__name__, expected="str")
        return cls.from_dict(parse_toml("text", text))

    def to_toml_text(self) -> str:
        """The TOML text of :meth:`to_toml`."""
        return tomli_w.dumps(self.to_dict())

    def to_toml(self, path: PathLike) -> Path:
        """Write the structure to a TOML file that :meth:`from_toml` reads back identically (atomically)."""
        from .._io import output_file, write_text

        return write_text(output_file("path", path, (".toml",)), self.to_toml_text())


__all__ = ["Modes", "Stand", "Storey", "Structure", "Wall"]
