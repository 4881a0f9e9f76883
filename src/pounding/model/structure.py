"""A structure of several masses: an isolated base, storeys above it (a shear building) and walls it
may pound against (a moat wall at the base or at any level); TOML in and out.

Degrees of freedom are levels: 0 is the base (on its isolator), ``i`` the floor carried by storey
``i`` (``storeys[i - 1]``).  Each displacement is relative to the ground (the shaking table).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, NamedTuple, Optional, Union

import numpy as np

from .._checks import (instance_of, plausible, real_tuple, sequence_of)
from .._errors import InputError, Problem
from ._toml import TomlFile
from .contact_laws import law_from_dict
from .friction import FrictionIsolator
from .sliders import is_friction, refuse_rigid_stops
from .triple_friction import TripleFrictionPendulum
from .isolator import Isolator
from .oscillator import ISOLATORS, Oscillator, check_keys, isolator_from_dict
from .structure_parts import MAX_STOREYS, Stand, Storey, Wall, check_mass

PathLike = Union[str, Path]


class Modes(NamedTuple):
    """Undamped modes: ``periods_s`` (m,) longest first, ``shapes`` (n, m), each column scaled to a largest
    component of +1, rows by level."""

    periods_s: np.ndarray
    shapes: np.ndarray


@dataclass(frozen=True)
class Structure(TomlFile):
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
    >>> iso = pounding.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02],
    ...                         damping_n_s_m=2.0e4)
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
    isolator: Optional[Union[Isolator, FrictionIsolator, TripleFrictionPendulum]]
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
            object.__setattr__(self, "base_mass_kg", check_mass("base_mass_kg", self.base_mass_kg))
            instance_of("isolator", self.isolator, ISOLATORS,
                        "Isolator, FrictionIsolator, TripleFrictionPendulum or None")
        for name, kind in (("storeys", Storey), ("walls", Wall)):
            object.__setattr__(self, name, sequence_of(name, getattr(self, name), kind, kind.__name__))
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
        if is_friction(self.isolator):  # (it carries the whole structure's weight)
            total = self.base_mass_kg + sum(st.mass_kg for st in self.storeys)
            object.__setattr__(self, "isolator", self.isolator.carrying(total))
            refuse_rigid_stops(self.isolator, [(f"walls[{i}].{side}", getattr(w, side))
                                               for i, w in enumerate(self.walls)
                                               for side in ("left", "right")])
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
            k[0, 0] += self.isolator.slopes_n_m[0]
        if m.size == 0:
            return Modes(np.zeros(0), np.zeros((0, 0)))
        w2, shapes = eigh(k, np.diag(m))
        periods = 2.0 * np.pi / np.sqrt(w2)
        big = np.argmax(np.abs(shapes), axis=0)
        shapes = shapes / shapes[big, np.arange(shapes.shape[1])]
        return Modes(periods, shapes)

    def without_bumpers(self) -> "Structure":
        """The structure without its walls (their bumpers, its moat): its NBs configuration, as
        :meth:`Oscillator.without_bumpers` is a single mass's."""
        return dataclasses.replace(self, walls=())

    @classmethod
    def from_oscillator(cls, oscillator: Oscillator) -> "Structure":
        """The single oscillator as a structure of one level (its bumpers a wall at the base)."""
        instance_of("oscillator", oscillator, Oscillator, "Oscillator")
        b = oscillator.bumpers
        walls = () if b is None else (Wall._of_bumpers(b),)  # (its numbers checked, and warned of, once)
        return cls(oscillator.mass_kg, oscillator.isolator, (), walls)

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
        check_keys(table, "", cls.FIELDS, required=())
        isolator = None
        if "isolator" in table:  # (neither it nor base_mass_kg: a fixed base)
            isolator = isolator_from_dict(table["isolator"])
        storeys, walls = [], []
        for name, out in (("storeys", storeys), ("walls", walls)):
            rows = table.get(name, [])
            instance_of(name, rows, list, f"array of tables ([[{name}]])")
            for i, row in enumerate(rows):
                prefix = f"{name}[{i}]."
                if name == "storeys":
                    check_keys(row, prefix, Storey.FIELDS, required=("mass_kg", "stiffness_n_m"))
                    try:
                        out.append(Storey(**row))
                    except InputError as exc:
                        raise exc.relabel("storey.", prefix) from None
                else:
                    check_keys(row, prefix, Wall.FIELDS,
                                required=("level", "gap_left_m", "gap_right_m", "law"))
                    right, stand = row.get("law_right"), row.get("stand")
                    if stand is not None:
                        check_keys(stand, prefix + "stand.", Stand.FIELDS,
                                    required=("mass_kg", "stiffness_n_m"))
                    try:
                        out.append(Wall(row["level"], row["gap_left_m"], row["gap_right_m"],
                                        law_from_dict(row["law"], prefix + "law"),
                                        None if right is None else law_from_dict(right, prefix + "law_right"),
                                        None if stand is None else Stand(**stand)))
                    except InputError as exc:
                        raise exc.relabel("stand.", prefix + "stand.").relabel("wall.", prefix) from None
        return cls(table.get("base_mass_kg"), isolator, tuple(storeys), tuple(walls), table.get("rayleigh"))


__all__ = ["Modes", "Stand", "Storey", "Structure", "Wall"]
