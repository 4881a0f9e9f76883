"""Bumper contact laws: the one place where a law is defined.

A law relates the bumper's compression ``d`` (m, >= 0) and compression rate ``dd`` (m/s)
to the force it pushes with (N).  Bumpers are massless, so out of contact a bumper relaxes
by ``force(d, dd) = 0``; in contact ``d`` follows the mass, and contact ends when the force
would become a pull.  Adding a law means: a module here holding its frozen dataclass,
with a ``LAW_ID``, ``params()``, its ``STATE_CHECK`` (what its block of the state may hold,
:mod:`.law_states`) and ``LINEAR`` (whether its force is ``stiffness d + damping dd`` everywhere); a
line in :data:`LAWS`; and its C++ side in ``src/core/laws.cpp`` (its id in ``laws.hpp``'s ``LawId``
and a branch in each ``law_*`` function there, the one place the core tests a law's kind).  Nothing else
needs to change.

Laws whose force is linear in ``(d, dd)`` on each branch (:class:`KelvinVoigt`,
:class:`MultilinearBumper`, :class:`ElasticPlastic`) keep every phase of motion a linear ODE,
which the engine solves in closed form; the others are integrated numerically during contact.
"""

from __future__ import annotations

from dataclasses import fields
from typing import Any, Optional, Union

from ..._checks import instance_of
from ..._errors import InputError, Problem
from ._base import (ELASTIC_PLASTIC, HERTZDAMP, HUNT_CROSSLEY, JANKOWSKI, KELVIN_VOIGT,  # noqa: F401
                    MAX_BRANCHES, MAX_DAMPING_RATIO, MAX_EXPONENT, MAX_LAW_COEFFICIENT, MULTILINEAR,
                    MULTILINEAR_KINEMATIC, N_LAW_PARAMS, N_LAW_STATE)
from .elastic_plastic import ElasticPlastic
from .hertzdamp import Hertzdamp
from .hunt_crossley import HuntCrossley
from .jankowski import Jankowski
from .kelvin_voigt import KelvinVoigt
from .law_states import state_problem, stateless  # noqa: F401  (what the engine checks a state with)
from .multilinear import MultilinearBumper
from .rigid_stop import RigidStop, is_rigid, refuse_clamp  # noqa: F401  (what the engine and models ask)


def linear_form(law: Any) -> Optional[tuple[float, float]]:
    """``(stiffness N/m, damping N s/m)`` of a law whose force is ``stiffness d + damping dd`` at
    every compression (its ``LINEAR``), else None."""
    return (law.stiffness, law.damping) if law.LINEAR else None


def monodromy_caveat(law: Any) -> Optional[str]:
    """Why the exact monodromy cannot follow ``law`` (None: it can: a rigid stop, or a law whose force is
    linear in the compression, its rate and its memory on each branch, its ``PIECEWISE``)."""
    if is_rigid(law):
        return None
    if not law.PIECEWISE:
        return f"{type(law).__name__} is nonlinear in the compression"
    caveat = getattr(law, "monodromy_caveat", None)
    return caveat() if caveat is not None else None


ContactLaw = Union[KelvinVoigt, HuntCrossley, Jankowski, MultilinearBumper, ElasticPlastic, Hertzdamp,
                   RigidStop]
LAWS: dict[str, type] = {KelvinVoigt.TYPE: KelvinVoigt, HuntCrossley.TYPE: HuntCrossley,
                         Jankowski.TYPE: Jankowski, MultilinearBumper.TYPE: MultilinearBumper,
                         ElasticPlastic.TYPE: ElasticPlastic, Hertzdamp.TYPE: Hertzdamp,
                         RigidStop.TYPE: RigidStop}


def law_to_dict(law: ContactLaw) -> dict[str, Any]:
    """The law as a TOML-ready table: ``type`` plus its fields."""
    out: dict[str, Any] = {"type": law.TYPE}
    for f in fields(law):
        value = getattr(law, f.name)
        out[f.name] = list(value) if isinstance(value, tuple) else value
    return out


def law_from_dict(table: dict[str, Any], field: str) -> ContactLaw:
    """Build a law from a TOML table with a ``type`` key; unknown and missing keys are errors.

    Every field of the law must be given, defaults included: a table whose ``type`` was
    changed would otherwise be read with the new law's defaults filling what it lacks.  (But a
    multi-linear law's ``hysteresis``, added later, which files written before it lack.)
    """
    instance_of(field, table, dict, "table")
    kind = table.get("type")
    if kind not in LAWS:
        raise InputError(Problem.NOT_ONE_OF, f"{field}.type", kind, choices=", ".join(map(repr, LAWS)))
    cls = LAWS[kind]
    allowed = {f.name for f in fields(cls)}
    required = [f.name for f in fields(cls) if f.name not in getattr(cls, "OPTIONAL_KEYS", ())]
    for key in table:
        if key != "type" and key not in allowed:
            raise InputError(Problem.UNKNOWN_KEY, f"{field}.{key}", table[key],
                             choices=", ".join(sorted(allowed | {"type"})))
    for key in required:
        if key not in table:
            raise InputError(Problem.MISSING_KEY, f"{field}.{key}", None,
                             choices=", ".join(sorted(allowed)) + f" (a {kind} law needs every one of them)")
    try:
        return cls(**{k: v for k, v in table.items() if k != "type"})
    except InputError as exc:  # name the field by its place in the file
        raise exc.relabel("law", field) from None


def check_law(field: str, value: Any) -> None:
    """Refuse anything but a contact law for ``field`` (``bumpers.law``, ``wall.law_right``)."""
    instance_of(field, value, tuple(LAWS.values()),
                "contact law (" + ", ".join(cls.__name__ for cls in LAWS.values()) + ")")
