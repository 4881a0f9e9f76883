"""The whole system: a mass on an isolator, optionally between two bumpers; TOML in and out."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar, Optional, Union


from .._checks import instance_of
from .._errors import InputError, Problem, renamed_fields
from ._toml import TomlFile, renamed_keys
from .contact_laws import law_from_dict
from .friction import FrictionIsolator
from .sliders import is_friction, refuse_rigid_stops
from .triple_friction import TripleFrictionPendulum
from .isolator import Isolator
from .structure_parts import Bumpers, check_mass

PathLike = Union[str, Path]


@renamed_fields({"mass": "mass_kg"})  # (the names before, 0.1's: one more release, with a warning)
@dataclass(frozen=True)
class Oscillator(TomlFile):
    """Single-degree-of-freedom base-isolated mass, optionally bounded by bumpers.

    Equation of motion (``D``: displacement of the mass relative to the table, m)::

        M D'' + C_d D' + R_d(D) + F_bR - F_bL = -M A(t)

    Parameters
    ----------
    mass_kg : float
        ``M`` in kg, > 0.  (``mass``, its name before, still works for one release, with a warning.)
    isolator : Isolator
        Backbone, hysteresis rule and dashpot of the isolator.
    bumpers : Bumpers or None
        ``None`` is the paper's NBs configuration (no bumpers).

    Examples
    --------
    The paper's YBs system with ``C_d = 1 kN s/m`` (:func:`pounding.presets.paper_damped`), built
    by hand, saved to TOML and read back:

    >>> import pounding
    >>> isolator = pounding.Isolator(slopes_n_m=[38_000.0, 18_000.0, 2_000.0],
    ...                              breakpoints_m=[0.015, 0.040],
    ...                              hysteresis="kinematic", damping_n_s_m=1_000.0)
    >>> bumpers = pounding.Bumpers(0.015, 0.015,
    ...                            pounding.KelvinVoigt(stiffness=1.46e6,
    ...                                                 damping=5.0))
    >>> ybs = pounding.Oscillator(mass_kg=500.0, isolator=isolator, bumpers=bumpers)
    >>> ybs == pounding.presets.paper_damped()
    True
    >>> ybs.without_bumpers().bumpers is None
    True
    >>> path = ybs.to_toml("ybs.toml")
    >>> pounding.Oscillator.from_toml("ybs.toml") == ybs
    True
    """

    mass_kg: float
    isolator: Isolator
    bumpers: Optional[Bumpers] = None

    FIELDS: ClassVar[tuple[str, ...]] = ("mass_kg", "isolator", "bumpers")

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass_kg", check_mass("mass_kg", self.mass_kg,
                                                       "the mass is in kg (500 kg is 500.0)"))
        instance_of("isolator", self.isolator, ISOLATORS,
                    "Isolator, FrictionIsolator or TripleFrictionPendulum")
        if self.bumpers is not None and not isinstance(self.bumpers, Bumpers):
            raise InputError(Problem.WRONG_TYPE, "bumpers", self.bumpers,
                             got=type(self.bumpers).__name__, expected="Bumpers or None")
        if is_friction(self.isolator):  # (it carries the mass's weight)
            object.__setattr__(self, "isolator", self.isolator.carrying(self.mass_kg))
            if self.bumpers is not None:
                refuse_rigid_stops(self.isolator, (("bumpers.law", self.bumpers.law),
                                                   ("bumpers.law_right", self.bumpers.law_right)))

    def without_bumpers(self) -> "Oscillator":
        """The same mass and isolator in the NBs configuration."""
        return replace(self, bumpers=None)

    def mirrored(self) -> "Oscillator":
        """The system seen in a mirror: gaps and bumper laws swap sides."""
        return replace(self, bumpers=None if self.bumpers is None else self.bumpers.mirrored())

    # ------------------------------------------------------------------ TOML
    def to_dict(self) -> dict[str, Any]:
        """The system as nested tables with the constructor's field names."""
        out: dict[str, Any] = {"mass_kg": self.mass_kg, "isolator": self.isolator.to_dict()}
        if self.bumpers is not None:
            out["bumpers"] = self.bumpers.to_dict()
        return out

    @classmethod
    def from_dict(cls, table: dict[str, Any]) -> "Oscillator":
        """Build from nested tables; every key is checked and unknown keys are errors."""
        if "meta" in table:  # notes about the file (who wrote it, whether it is partial): not the system
            instance_of("meta", table["meta"], dict, "table of notes")
            table = {k: v for k, v in table.items() if k != "meta"}
        table = renamed_keys(table, "", cls.RENAMED)
        check_keys(table, "", cls.FIELDS, required=("mass_kg", "isolator"))
        isolator = isolator_from_dict(table["isolator"])
        bumpers = None
        if "bumpers" in table:
            b = renamed_keys(table["bumpers"], "bumpers.", Bumpers.RENAMED)
            check_keys(b, "bumpers.", Bumpers.FIELDS, required=("gap_left_m", "gap_right_m", "law"))
            law_right = b.get("law_right")
            bumpers = Bumpers(
                gap_left_m=b["gap_left_m"], gap_right_m=b["gap_right_m"],
                law=law_from_dict(b["law"], "bumpers.law"),
                law_right=None if law_right is None else law_from_dict(law_right, "bumpers.law_right"),
                capacity_m=b.get("capacity_m"),
            )
        return cls(mass_kg=table["mass_kg"], isolator=isolator, bumpers=bumpers)


def check_keys(table: Any, prefix: str, allowed: tuple[str, ...], required: tuple[str, ...]) -> None:
    """A TOML table's keys: every key one of ``allowed`` and every ``required`` one there, or an InputError
    naming the key (``prefix`` + key) and the choices."""
    instance_of(prefix.rstrip(".") or "system", table, dict, "table")
    for key in table:
        if key not in allowed:
            raise InputError(Problem.UNKNOWN_KEY, prefix + key, table[key], choices=", ".join(allowed))
    for key in required:
        if key not in table:
            raise InputError(Problem.MISSING_KEY, prefix + key, None, choices=", ".join(allowed))


ISOLATORS = (Isolator, FrictionIsolator, TripleFrictionPendulum)  # (every kind of isolator a system takes)


def isolator_from_dict(table: Any,
                       prefix: str = "isolator.") -> "Isolator | FrictionIsolator | TripleFrictionPendulum":
    """An isolator from its TOML table: a triple friction pendulum when it has ``radii_m``, a friction
    isolator when it has ``mu``, else a rubber one (its backbone); every key checked."""
    instance_of(prefix.rstrip("."), table, dict, "table ([isolator])")
    kind = (TripleFrictionPendulum if "radii_m" in table else FrictionIsolator if "mu" in table
            else Isolator)
    iso_table = renamed_keys(table, prefix, kind.RENAMED)
    check_keys(iso_table, prefix, kind.FIELDS,
               required=tuple(f for f in kind.FIELDS if f not in kind.OPTIONAL))
    return kind(**iso_table)
