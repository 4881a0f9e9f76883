"""What every contact law shares: the core's law ids, the sizes of a law's parameters and state, the
bounds of its numbers and their checks."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..._checks import at_most, non_negative, positive, real
from ..._core import LAW_IDS, LAYOUT
from ..._errors import InputError, Problem

# each law's id, as the core's laws (src/core/laws.cpp, the law's C++ side) know it
KELVIN_VOIGT, HUNT_CROSSLEY, JANKOWSKI, MULTILINEAR, ELASTIC_PLASTIC, HERTZDAMP, MULTILINEAR_KINEMATIC = (
    LAW_IDS[k] for k in ("kelvin_voigt", "hunt_crossley", "jankowski", "multilinear", "elastic_plastic",
                         "hertzdamp", "multilinear_kinematic"))
N_LAW_PARAMS = LAYOUT["N_LAW_PARAMS"]  # a law's parameters as the core reads them
N_LAW_STATE = LAYOUT["N_LAW_STATE"]    # the numbers of its state in the engine's state vector
MAX_BRANCHES = 4  # slopes of a multi-linear law (its parameters hold 4 slopes and 3 breakpoints)

MAX_LAW_COEFFICIENT = 1e18  # stiffness or damping beyond any bumper (N/m^n, N s/m^(n+1)): refused
MAX_EXPONENT = 10.0
MAX_DAMPING_RATIO = 100.0  # Jankowski's xi: 10 already gives a restitution of about 0.03


def engine_needs(type_name: str, state_check: Callable, *, linear: bool, law_id: int | None = None,
                 rigid: bool = False, piecewise: bool = False) -> Callable[[type], type]:
    """A contact law's class decorator: what the engine asks of the law, declared in one line above it (its
    C++ side: src/core/laws.cpp).  It sets the class's ``TYPE`` (its ``type`` in a system's file),
    ``STATE_CHECK`` (what its block of the state may hold: :mod:`.law_states`), ``LINEAR`` (whether its force
    is stiffness d + damping dd at every compression: the rate bound needs it),
    ``RIGID`` (a rigid stop: an impact law, no force), ``PIECEWISE`` (its force linear in ``d``, ``dd`` and
    its state's memory on each of its branches, as ``LINEAR`` laws' everywhere: the exact monodromy composes
    its branches; a class may name a case it does not cover in ``monodromy_caveat()``) and ``LAW_ID`` (the
    core's id; None: the class gives its own, e.g. a property)."""

    def declare(cls: type) -> type:
        cls.TYPE, cls.LINEAR, cls.RIGID = type_name, linear, rigid  # type: ignore[attr-defined]
        cls.PIECEWISE = piecewise or linear  # type: ignore[attr-defined]
        cls.STATE_CHECK = staticmethod(state_check)  # type: ignore[attr-defined]
        if law_id is not None:
            cls.LAW_ID = law_id  # type: ignore[attr-defined]
        return cls

    return declare


def coefficient(field: str, value: Any, unit: str, strict: bool) -> float:
    """A law's stiffness or damping ``value`` in ``unit``: > 0 (``strict``) or >= 0, and below any
    bumper's."""
    out = positive(field, value, unit) if strict else non_negative(field, value, unit)
    return at_most(field, out, MAX_LAW_COEFFICIENT, f" {unit}", f"give it in {unit}")


def padded(values: list[float]) -> np.ndarray:
    """A law's parameters as the compiled kernels take them, shape (N_LAW_PARAMS,)."""
    out = np.zeros(N_LAW_PARAMS)
    out[: len(values)] = values
    return out


def exponent_value(value: Any) -> float:
    """A law's exponent, in [1, MAX_EXPONENT]."""
    exponent = real("law.exponent", value)
    if not 1.0 <= exponent <= MAX_EXPONENT:
        raise InputError(Problem.OUT_OF_RANGE, "law.exponent", value,
                         range=f"[1, {MAX_EXPONENT:g}]", hint=" (1.5 is Hertzian contact)")
    return exponent
