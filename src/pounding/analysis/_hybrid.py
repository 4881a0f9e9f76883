"""The oscillator as a hybrid system of linear modes: vector fields, guards and saltation
matrices, for the exact monodromy of a periodic orbit.

For the systems whose every phase is linear (a multi-linear isolator, elastic or kinematic,
without Bouc-Wen spring; Kelvin-Voigt bumpers) the motion between two events obeys
``x' = A_m x + b(t)`` with ``A_m`` constant in the mode ``m`` (which bumpers touch, which
isolator springs slip or which backbone branch holds).  With the forcing written as two more
states, ``(sin theta, cos theta)`` with ``theta = Omega t + phase``, and a constant 1, the
augmented system is homogeneous, ``X' = Ã_m X``, and ``X(t) = expm(Ã_m t) X(0)`` exactly: the
top-left block of that exponential is the phase's state-transition matrix.  At an event with
guard ``g(x) = 0`` the mode changes from ``m`` to ``m'`` and the perturbations jump by the
saltation matrix ``S = I + (f_m' - f_m) grad(g)^T / (grad(g) . f_m)``.

The coordinates ``x``: ``D`` (m), ``V`` (m/s), the bumpers' compressions ``delta_L``,
``delta_R`` (m), then the kinematic isolator's slips ``u_i`` (m).  Where the engine has the
same system in its state vector (its core system's layout), :func:`coordinates` and :func:`mode_of`
read it; without bumpers there are no compressions.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from threadpoolctl import threadpool_limits

from ..engine.layout import (ACT_CONTACT, ACT_REGION, ACT_RELEASE, ACT_REVERSAL, E_ACTION, E_INDEX,  # noqa: F401  (the
                              ACT_YIELD)  # events' codes, here)
from ..engine.kernels import System
from ..engine.kernels import monodromy as exact_monodromy
from ..model import Oscillator
from ..model.adjacent import Adjacent
from ..model.structure import Structure
from ..model.contact_laws import is_rigid, linear_form

def unsupported(system: "Oscillator | Structure | Adjacent") -> str | None:
    """Why the monodromy of this system (one mass, a structure or a pair) cannot be composed exactly here
    (None: it can)."""
    if isinstance(system, (Structure, Adjacent)):
        structures, links = structures_and_links(system)
        named = len(structures) > 1
        for b, s in enumerate(structures):
            who = ("the first's " if b == 0 else "the second's ") if named else "its "
            if s.isolator is not None and s.isolator.bouc_wen is not None:
                return f"{who}isolator has a Bouc-Wen spring (a nonlinear phase)"
            for w, wall in enumerate(s.walls):
                for side, law in (("left", wall.left), ("right", wall.right)):
                    if linear_form(law) is None and not is_rigid(law):
                        return (f"{who}wall {w}'s {side} law is {type(law).__name__} "
                                "(exact: Kelvin-Voigt, rigid)")
        for k, link in enumerate(links):
            if linear_form(link.law) is None and not is_rigid(link.law):
                return f"link {k}'s law is {type(link.law).__name__} (exact: Kelvin-Voigt, rigid)"
        return None
    iso = system.isolator
    if iso.bouc_wen is not None:
        return "its isolator has a Bouc-Wen spring (a nonlinear phase)"
    b = system.bumpers
    if b is not None:
        for side, law in (("left", b.left), ("right", b.right)):
            if linear_form(law) is None and not is_rigid(law):
                return f"its {side} bumper's law is {type(law).__name__} (exact: Kelvin-Voigt, rigid)"
    return None


def structures_and_links(model: "Structure | Adjacent") -> tuple[tuple, tuple]:
    """(the structures, the links) of a structure or a pair."""
    if isinstance(model, Adjacent):
        return model.structures, model.links
    return (model,), ()


class NoExactMonodromy(Exception):
    """The orbit's monodromy cannot be composed exactly here (an event met tangentially, or a
    propagation that does not end where the engine did): the solver falls back to finite
    differences and says so in its message.  Anything else raised here is a bug, not caught."""


class Hybrid(NamedTuple):
    """One mass's numbers (SI units) its shooting coordinates and their constraints are read by, and where
    its core system's state vector holds them (``lay``: the system's layout; the propagation itself takes
    the core's system: :func:`monodromy`)."""

    mass: float
    c_d: float
    slopes: np.ndarray   # (n,)
    breaks: np.ndarray   # (n - 1,)
    kinematic: bool
    gaps: tuple[float, float]         # left, right (inf without bumpers)
    stiffness: tuple[float, float]    # of the bumpers, N/m
    damping: tuple[float, float]      # N s/m
    lay: dict                         # the core system's layout

    @classmethod
    def of(cls, oscillator: Oscillator, layout: dict) -> "Hybrid":
        iso = oscillator.isolator
        b = oscillator.bumpers
        if b is None:
            gaps, k, c = (np.inf, np.inf), (0.0, 0.0), (0.0, 0.0)
        else:
            gaps = (float(b.gap_left_m), float(b.gap_right_m))
            # (a law other than Kelvin-Voigt: no linear modes; its numbers are not used but for the
            # coordinates, where its compressions are no shooting coordinates)
            forms = [linear_form(law) for law in (b.left, b.right)]
            k = tuple(float(f[0]) if f else float(getattr(law, "stiffness", np.nan))
                      for f, law in zip(forms, (b.left, b.right)))
            c = tuple(float(f[1]) if f else 0.0 for f in forms)
        return cls(float(oscillator.mass_kg), float(iso.damping_n_s_m), np.array(iso.slopes_n_m, dtype=float),
                   np.array(iso.breakpoints_m, dtype=float), iso.hysteresis == "kinematic", gaps, k, c,
                   dict(layout))

    @property
    def n_contacts(self) -> int:
        """The bumpers' contact slots: 2 (left, right), or 0 without bumpers."""
        return self.lay["in"] - self.lay["def"]

    @property
    def compressions(self) -> tuple[int, ...]:
        """The bumpers' compressions' places in ``x`` (left, right; none without bumpers)."""
        return tuple(range(2, 2 + self.n_contacts))

    @property
    def first_slip(self) -> int:
        """The first slip's place in ``x``."""
        return 2 + self.n_contacts

    @property
    def n_slips(self) -> int:
        return self.slopes.size - 1 if self.kinematic else 0

    @property
    def size(self) -> int:
        """Length of ``x``."""
        return self.first_slip + self.n_slips


def coordinates(h: Hybrid, vec: np.ndarray) -> np.ndarray:
    """``x`` from an engine state vector."""
    return vec[coordinate_places(h)]


def coordinate_places(h: Hybrid) -> list[int]:
    """Where :func:`coordinates` reads ``x`` in an engine state vector."""
    lay = h.lay
    return [lay["x"], lay["v"], *range(lay["def"], lay["in"]), *range(lay["base"], lay["base"] + h.n_slips)]


def mode_of(h: Hybrid, vec: np.ndarray) -> tuple:
    """``(in contact left, in contact right, slip directions or the backbone branch)`` (never in contact
    without bumpers)."""
    lay = h.lay
    n = h.slopes.size - 1
    base = lay["base"]
    iso = tuple(vec[base + n:base + 2 * n].tolist()) if h.kinematic else int(vec[lay["region"]])
    if not h.n_contacts:
        return False, False, iso
    return bool(vec[lay["in"]]), bool(vec[lay["in"] + 1]), iso


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
        raise NoExactMonodromy(f"event {int(row[1])} at t = {row[0]} is tangent (a grazing)")
    if bad <= -2:
        row = rows[-2 - bad]
        raise NoExactMonodromy(f"event {int(row[1])} at t = {row[0]} ends a phase that is not linear")
    return jac, x_end


def oscillator_monodromy(h: Hybrid, system: System, vec0: np.ndarray, events: np.ndarray, t_end: float,
                         omega: float, amp: float, phase: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`monodromy` of one mass in its coordinates ``x`` (:func:`coordinates`: the system's,
    without the unused slips of an isolator of the elastic rule, which come last)."""
    jac, x_end = monodromy(system, vec0, events, t_end, omega, amp, phase)
    return jac[:h.size, :h.size], x_end[:h.size]
