"""The engine's up-front work estimate (the run control itself, Ctrl-C and the budget, is
``pounding._control``'s, re-exported here for the engine's callers).

:func:`fastest_rates` and :func:`steps_per_second` give a lower bound of the kernels' work
rate: a request that cannot finish within its budget is refused before any work starts.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from .._control import (DEFAULT_MAX_STEPS, new_control, request_stop, run_interruptibly,  # noqa: F401
                        stop_requested)
from .._errors import InputError, Problem
from ..model.contact_laws import is_rigid, linear_form
from .assembly import ASSEMBLIES_KEPT, Assembly, _add_pair, assemble, can_keep

SUBINTERVALS_PER_PERIOD = 8.0  # the core's (src/core/run.cpp): sub-intervals per period of the fastest motion


def fastest_rates(asm: Assembly) -> tuple[float, float]:
    """(out of contact, in every contact at once) the fastest rate of an assembled system's motion, rad/s.

    Out of contact: the largest undamped frequency with every hysteretic element (the isolator, a yielding
    storey) at its stiffest slope and a Bouc-Wen spring at its initial stiffness, or a degree of freedom's
    damping rate when larger (overdamped: ``sqrt(w^2 + (c / 2m)^2)`` and ``c / m`` with the largest
    ``c / m``). In contact: the same with every contact's linear spring and dashpot added (inf for a
    nonlinear or multi-branch law, which is integrated numerically; a rigid stop adds none: its impacts are
    events). The kernel cuts time into ``SUBINTERVALS_PER_PERIOD`` sub-intervals per period of the fastest
    of this motion and the forcing; contacts and events only add, so the first bounds the work per second
    from below and the second from above.
    """
    m = asm.masses
    k, c = asm.k_fast.copy(), asm.c_all.copy()
    free = fastest_of(m, k, c)
    for i, j, _, _, law in asm.pairs:
        if is_rigid(law):
            continue
        form = linear_form(law)
        if form is None:
            return free, math.inf
        _add_pair(k, i, j, form[0])
        _add_pair(c, i, j, form[1])
    return free, fastest_of(m, k, c)


def fastest_of(m: np.ndarray, k: np.ndarray, c: np.ndarray) -> float:
    """The fastest rate of the motion ``M x'' + C x' + K x = 0`` (``m`` the diagonal of M), rad/s: the largest
    undamped frequency, or the fastest damping rate when larger (:func:`fastest_rates`)."""
    if m.size == 1:  # (one mass: k / m itself, no eigensolver)
        lam, decay = float(k[0, 0]) / float(m[0]), float(c[0, 0]) / float(m[0])
    else:  # (K v = lam M v: M^-1/2 K M^-1/2's eigenvalues)
        scale = 1.0 / np.sqrt(m)
        lam = float(np.linalg.eigvalsh(k * np.outer(scale, scale))[-1])
        decay = float(np.max(np.diag(c) / m))
    return max(math.sqrt(max(lam, 0.0) + (0.5 * decay) ** 2), decay)


def model_rates(model: Any, asm: Assembly) -> tuple[float, float]:
    """:func:`fastest_rates` of a model's assembly ``asm``, kept with the assembly (:func:`assemble`) for the
    many runs of one system."""
    return _kept_rates(model) if can_keep(model) else fastest_rates(asm)


@functools.lru_cache(maxsize=ASSEMBLIES_KEPT)
def _kept_rates(model: Any) -> tuple[float, float]:
    return fastest_rates(assemble(model))


def fastest_rate(system: Any) -> tuple[float, str]:
    """The fastest rate of any system's motion out of contact, rad/s (:func:`fastest_rates`), and what sets
    it, for a protocol's work estimate."""
    asm = assemble(system)
    free = fastest_rates(asm)[0]
    return free, why_rate(asm, free)


def why_rate(asm: Assembly, rate: float) -> str:
    """What sets the fastest rate ``rate`` (rad/s) of an assembled system, for an estimate's message."""
    if asm.masses.size > 1:
        return f"the system's fastest motion {rate:.3g} rad/s"
    return (f"the isolator's fastest motion {rate:.3g} rad/s: stiffness {asm.k_fast[0, 0]:.3g} N/m, damping "
            f"{asm.c_all[0, 0]:.3g} N s/m, mass {asm.masses[0]:.3g} kg")


def steps_per_second(rate_rad_s: float, omega_rad_s: Any) -> Any:
    """Least sub-intervals per simulated second at a system's fastest rate and forcing ``omega_rad_s``."""
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
