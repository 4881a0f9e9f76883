"""The engine's up-front work estimate (the run control itself, Ctrl-C and the budget, is
``pounding._control``'s, re-exported here for the engine's callers).

:func:`isolator_rate` and :func:`steps_per_second` give a lower bound of the kernels' work
rate: a request that cannot finish within its budget is refused before any work starts.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._control import (DEFAULT_MAX_STEPS, new_control, request_stop, run_interruptibly,  # noqa: F401
                        stop_requested)
from .._errors import InputError, Problem
from ..model import Oscillator
from ..model.contact_laws import is_rigid, linear_form
SUBINTERVALS_PER_PERIOD = 8.0  # the core's (src/core/run.cpp): sub-intervals per period of the fastest motion


def isolator_rate(oscillator: Oscillator) -> tuple[float, str]:
    """The fastest rate of the isolated mass out of contact, rad/s, and what sets it.

    Out of contact the kernel cuts time into ``SUBINTERVALS_PER_PERIOD`` sub-intervals per
    period of the fastest of this motion (the frequency on the isolator's stiffest branch,
    or its decay rate when overdamped) and the forcing; contacts and events only add, so
    ``SUBINTERVALS_PER_PERIOD * max(rate, omega) / (2 pi)`` bounds the work per second below.
    """
    iso = oscillator.isolator
    k = max(abs(s) for s in iso.slopes_n_m)
    if iso.bouc_wen is not None:  # (its initial stiffness, in parallel)
        k += iso.bouc_wen.a * iso.bouc_wen.stiffness_n_m
    c = iso.damping_n_s_m
    m = oscillator.mass_kg
    rate = max(math.sqrt(k / m + (0.5 * c / m) ** 2), c / m)
    return rate, (
        f"the isolator's fastest motion {rate:.3g} rad/s: stiffness {k:.3g} N/m, damping "
        f"{c:.3g} N s/m, mass {m:.3g} kg"
    )


def contact_rate(oscillator: Oscillator) -> float:
    """An upper bound of the fastest rate of any phase, rad/s: the isolator's stiffest tangent
    and both linear bumpers at once (inf for a nonlinear law, which is integrated numerically)."""
    iso = oscillator.isolator
    k = max(abs(s) for s in iso.slopes_n_m) if iso.hysteresis == "elastic" else (
        abs(iso.slopes_n_m[-1]) + sum(abs(a - b) for a, b in zip(iso.slopes_n_m, iso.slopes_n_m[1:])))
    if iso.bouc_wen is not None:
        k += iso.bouc_wen.a * iso.bouc_wen.stiffness_n_m
    c = iso.damping_n_s_m
    b = oscillator.bumpers
    if b is not None:
        for law in (b.left, b.right):
            if is_rigid(law):  # (no stiffness: its impacts are events, its phases the isolator's)
                continue
            form = linear_form(law)
            if form is None:  # (several linear branches, or a nonlinear law)
                return math.inf
            k += form[0]
            c += form[1]
    m = oscillator.mass_kg
    return max(math.sqrt(k / m + (0.5 * c / m) ** 2), c / m)


def steps_per_second(rate_rad_s: float, omega_rad_s: Any) -> Any:
    """Least sub-intervals per simulated second at isolator rate and forcing ``omega_rad_s``."""
    return SUBINTERVALS_PER_PERIOD * np.maximum(rate_rad_s, omega_rad_s) / (2.0 * math.pi)


def check_budget(field: str, value: Any, estimate: float, budget: int, why: str, fix: str) -> None:
    """Refuse, naming ``field``, a request whose estimated sub-intervals exceed ``budget``."""
    if estimate > budget:
        raise InputError(
            Problem.OVER_BUDGET,
            field,
            value,
            estimate=f"{estimate:.3g}",
            budget=f"{budget:.3g}",
            why=why,
            fix=fix,
        )
