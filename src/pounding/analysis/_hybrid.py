"""Any system (a single mass, a structure, a pair) as a hybrid system of linear modes, for the exact
monodromy of a periodic orbit.

For the systems whose every phase is linear (multi-linear isolators and storeys, elastic or kinematic,
without a Bouc-Wen spring; friction isolators of a constant friction, a triple friction pendulum's surfaces
in series; Kelvin-Voigt, multi-linear, elastic-plastic or rigid contacts: a law's memory, its springs'
slips or its plastic offset, joins the coordinates the core propagates) the motion between two events obeys
``x' = A_m x + b(t)`` with ``A_m`` constant in the mode ``m`` (which contacts touch, which springs slip
or which backbone branch holds).  With the forcing written as two more states, ``(sin theta, cos theta)``
with ``theta = Omega t + phase``, and a constant 1, the augmented system is homogeneous,
``X' = Ã_m X``, and ``X(t) = expm(Ã_m t) X(0)`` exactly: the top-left block of that exponential is the
phase's state-transition matrix.  At an event with guard ``g(x) = 0`` the mode changes from ``m`` to
``m'`` and the perturbations jump by the saltation matrix
``S = I + (f_m' - f_m) grad(g)^T / (grad(g) . f_m)``.  The core composes them (:func:`monodromy`).

The coordinates ``x``: every dof's displacement (m), then velocity (m/s), each contact's compression (m),
each hysteretic element's slips (m; a series's: its surfaces' displacements) (the shooter's ``coords``:
``_shooter``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from threadpoolctl import threadpool_limits

from ..engine.layout import (ACT_CONTACT, ACT_REGION, ACT_RELEASE, ACT_REVERSAL, E_ACTION, E_INDEX,  # noqa: F401  (the
                              ACT_YIELD)  # events' codes, here)
from ..engine.layout import ACT_LAW_BRANCH, EVENT_NAMES
from ..engine.kernels import System
from ..engine.kernels import monodromy as exact_monodromy
from ..engine.assembly import structures_of
from ..model.contact_laws import monodromy_caveat

if TYPE_CHECKING:
    from ..model import Adjacent, Oscillator, Structure


def unsupported(system: "Oscillator | Structure | Adjacent") -> str | None:
    """Why the monodromy of this system (a single mass, a structure or a pair) cannot be composed exactly
    here (None: it can)."""
    structures, links = structures_of(system)
    named = len(structures) > 1
    for b, s in enumerate(structures):
        who = ("the first's " if b == 0 else "the second's ") if named else "its "
        if s.isolator is not None and s.isolator.bouc_wen is not None:
            return f"{who}isolator has a Bouc-Wen spring (a nonlinear phase)"
        if s.isolator is not None and s.isolator.kernel_friction.get("friction_rate_s_m", 0.0) > 0.0:
            return f"{who}isolator's friction depends on the velocity (a nonlinear phase)"
        for w, wall in enumerate(s.walls):
            for side, law in (("left", wall.left), ("right", wall.right)):
                if (why := monodromy_caveat(law)) is not None:
                    return f"{who}wall {w}'s {side} law: {why}" + EXACT_LAWS
    for k, link in enumerate(links):
        if (why := monodromy_caveat(link.law)) is not None:
            return f"link {k}'s law: {why}" + EXACT_LAWS
    return None


EXACT_LAWS = " (exact: Kelvin-Voigt, multi-linear, elastic-plastic, rigid)"


class NoExactMonodromy(Exception):
    """The orbit's monodromy cannot be composed exactly here (an event met tangentially, or a
    propagation that does not end where the engine did): the solver falls back to finite
    differences and says so in its message.  Anything else raised here is a bug, not caught."""


def one_blas_thread() -> threadpool_limits:
    """A context in which BLAS and LAPACK run on one thread: the monodromy's products and
    exponentials are of matrices of a few rows, which a threaded BLAS slows down a hundredfold
    when the machine is busy (measured: ``expm`` of a 6-by-6 in 8 ms instead of 20 us)."""
    return threadpool_limits(limits=1, user_api="blas")


def monodromy(system: System, vec0: np.ndarray, events: np.ndarray, t_end: float, omega: float,
              amp: float, phase: float) -> tuple[np.ndarray, np.ndarray]:
    """The Jacobian of the map from ``x`` at the state vector ``vec0``'s time to ``x`` at
    ``t_end``, along the engine's ``events`` (rows of t, action, index), and ``x`` at ``t_end``
    as this propagation has it (to compare with the engine's).  ``system``: the core's system
    (one mass or several); ``x`` its displacements, velocities, compressions and slips (for one
    mass, :func:`coordinates`).

    Raises :class:`NoExactMonodromy` at an event met tangentially (no saltation matrix), or of a
    phase that is not linear.

    Returns
    -------
    jac : ndarray, shape (n, n)
    x_end : ndarray, shape (n,)
    """
    rows = np.ascontiguousarray(events, dtype=float).reshape(-1, 3)
    m = exact_monodromy(system, np.asarray(vec0, dtype=float), rows, float(t_end), float(omega), float(amp),
                        float(phase))
    jac, x_end, bad = m.jacobian, m.x_end, m.code
    if bad >= 0:
        row = rows[bad]
        raise NoExactMonodromy(f"the {_action(row[1])} event at t = {row[0]} is tangent (a grazing)")
    if bad <= -2:
        row = rows[-2 - bad]
        why = "ends a phase that is not linear"
        if int(row[1]) == ACT_LAW_BRANCH:
            why = ("is neither surely an edge of its branch (crossed moving) nor surely a turn (met still, "
                   "away from an edge, on a law that turns): a grazing of an edge, or a state the "
                   "propagation left")
        raise NoExactMonodromy(f"the {_action(row[1])} event at t = {row[0]} {why}")
    return jac, x_end


def _action(code: float) -> str:
    """An event table's action code by its name (``bumper_branch``)."""
    return EVENT_NAMES[int(code)] if 0 <= int(code) < len(EVENT_NAMES) else f"code {int(code)}"
