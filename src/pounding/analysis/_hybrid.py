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
same system in its state vector (``engine._layout``), :func:`coordinates` and :func:`mode_of`
read it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np
from scipy.linalg import expm
from threadpoolctl import threadpool_limits

from ..engine._layout import (ACT_CONTACT, ACT_REGION, ACT_RELEASE, ACT_REVERSAL, ACT_YIELD, DEF_L, DEF_R,
                              IN_L, IN_R, REGION, SIDE_L, STATE_BASE)
from ..engine._layout import D as I_D
from ..engine._layout import V as I_V
from ..model import Oscillator
from ..model.contact_laws import linear_form

I_DL, I_DR = 2, 3  # the compressions' places in x
FIRST_SLIP = 4


def unsupported(oscillator: Oscillator) -> str | None:
    """Why the monodromy of this system cannot be composed exactly here (None: it can)."""
    iso = oscillator.isolator
    if iso.bouc_wen is not None:
        return "its isolator has a Bouc-Wen spring (a nonlinear phase)"
    b = oscillator.bumpers
    if b is not None:
        for side, law in (("left", b.left), ("right", b.right)):
            if linear_form(law) is None:
                return f"its {side} bumper's law is {type(law).__name__} (exact: Kelvin-Voigt)"
    return None


class NoExactMonodromy(Exception):
    """The orbit's monodromy cannot be composed exactly here (an event met tangentially, or a
    propagation that does not end where the engine did): the solver falls back to finite
    differences and says so in its message.  Anything else raised here is a bug, not caught."""


@dataclass(frozen=True)
class Hybrid:
    """The numbers of the modes' matrices (SI units)."""

    mass: float
    c_d: float
    slopes: np.ndarray   # (n,)
    breaks: np.ndarray   # (n - 1,)
    kinematic: bool
    gaps: tuple[float, float]         # left, right (inf without bumpers)
    stiffness: tuple[float, float]    # of the bumpers, N/m
    damping: tuple[float, float]      # N s/m

    @classmethod
    def of(cls, oscillator: Oscillator) -> "Hybrid":
        iso = oscillator.isolator
        b = oscillator.bumpers
        if b is None:
            gaps, k, c = (np.inf, np.inf), (0.0, 0.0), (0.0, 0.0)
        else:
            gaps = (b.gap_left, b.gap_right)
            # (a law other than Kelvin-Voigt: no linear modes; its numbers are not used but for the
            # coordinates, where its compressions are no shooting coordinates)
            forms = [linear_form(law) for law in (b.left, b.right)]
            k = tuple(float(f[0]) if f else float(getattr(law, "stiffness", np.nan))
                      for f, law in zip(forms, (b.left, b.right)))
            c = tuple(float(f[1]) if f else 0.0 for f in forms)
        return cls(oscillator.mass, iso.damping, np.asarray(iso.slopes, float),
                   np.asarray(iso.breakpoints, float), iso.hysteresis == "kinematic", gaps, k, c)

    @property
    def n_slips(self) -> int:
        return self.slopes.size - 1 if self.kinematic else 0

    @property
    def size(self) -> int:
        """Length of ``x``."""
        return FIRST_SLIP + self.n_slips


def coordinates(h: Hybrid, vec: np.ndarray) -> np.ndarray:
    """``x`` from an engine state vector."""
    return np.concatenate(([vec[I_D], vec[I_V], vec[DEF_L], vec[DEF_R]],
                           vec[STATE_BASE:STATE_BASE + h.n_slips]))


def mode_of(h: Hybrid, vec: np.ndarray) -> tuple:
    """``(in contact left, in contact right, slip directions or the backbone branch)``."""
    n = h.slopes.size - 1
    iso = tuple(vec[STATE_BASE + n:STATE_BASE + 2 * n]) if h.kinematic else int(vec[REGION])
    return bool(vec[IN_L]), bool(vec[IN_R]), iso


def augmented_matrix(h: Hybrid, mode: tuple, omega: float, amp: float) -> np.ndarray:
    """``Ã_m``, shape (n + 3, n + 3): ``x`` then ``sin(theta)``, ``cos(theta)``, 1.

    ``amp`` is the table's peak acceleration (m/s^2), ``omega`` its circular frequency (rad/s).
    """
    n = h.size
    a = np.zeros((n + 3, n + 3))
    s_, c_, one = n, n + 1, n + 2
    m = h.mass
    a[0, 1] = 1.0
    # the mass: -(c_d V + isolator + right bumper - left bumper) / M - A(t)
    a[1, 1] -= h.c_d / m
    in_l, in_r, iso = mode
    if h.kinematic:
        k_n = h.slopes[-1]
        a[1, 0] -= k_n / m
        for i, s in enumerate(iso):
            dk = h.slopes[i] - h.slopes[i + 1]
            if s == 0.0:
                a[1, 0] -= dk / m
                a[1, FIRST_SLIP + i] += dk / m
            else:
                a[1, one] -= s * dk * h.breaks[i] / m
                a[FIRST_SLIP + i, 1] = 1.0  # a slipping spring moves with the mass
    else:
        j = abs(iso)
        k = h.slopes[j]
        a[1, 0] -= k / m
        if j > 0:
            f_break = h.slopes[0] * h.breaks[0] + float(np.dot(h.slopes[1:j], np.diff(h.breaks[:j])))
            a[1, one] -= np.sign(iso) * (f_break - k * h.breaks[j - 1]) / m
    for side, touching, row, sign in ((0, in_l, I_DL, -1.0), (1, in_r, I_DR, 1.0)):
        kb, cb, gap = h.stiffness[side], h.damping[side], h.gaps[side]
        if touching:
            # depth sign D - gap, force kb depth + cb depth', pushing the mass by -sign
            a[1, 0] -= kb / m
            a[1, 1] -= cb / m
            a[1, one] += sign * kb * gap / m
            a[row, 1] = sign  # the compression follows the mass
        elif cb > 0.0:
            a[row, row] = -kb / cb  # relaxing
    a[1, s_] = -amp
    a[s_, c_] = omega
    a[c_, s_] = -omega
    return a


def guard_gradient(h: Hybrid, action: int, index: int, mode: tuple, x: np.ndarray) -> np.ndarray:
    """``grad g`` in ``x`` of the event (the guard as the engine's event function)."""
    g = np.zeros(h.size)
    if action == ACT_CONTACT:
        sign = -1.0 if index == SIDE_L else 1.0
        g[0] = sign
        row = I_DL if index == SIDE_L else I_DR
        if h.damping[index] > 0.0:
            g[row] = -1.0  # the surface is where the relaxing bumper is
    elif action == ACT_RELEASE:  # the force reaches zero
        sign = -1.0 if index == SIDE_L else 1.0
        g[0] = sign * h.stiffness[index]
        g[1] = sign * h.damping[index]
    elif action == ACT_YIELD:
        g[0] = 1.0
        g[FIRST_SLIP + index] = -1.0
    elif action == ACT_REVERSAL:
        g[1] = 1.0
    elif action == ACT_REGION:
        g[0] = 1.0
    else:  # pragma: no cover (unsupported systems never get here)
        raise ValueError(f"no guard for event action {action}")
    return g


def next_mode(h: Hybrid, action: int, index: int, mode: tuple, x: np.ndarray, acc: float = 0.0) -> tuple:
    """The mode after the event (as the engine's transitions: ``_kernel``, ``_isolator``); ``acc``
    the acceleration before it, which says where a branch change at rest goes."""
    in_l, in_r, iso = mode
    if action in (ACT_CONTACT, ACT_RELEASE):
        now = action == ACT_CONTACT
        return (now, in_r, iso) if index == SIDE_L else (in_l, now, iso)
    if action == ACT_YIELD:
        s = list(iso)
        s[index] = 1.0 if x[0] - x[FIRST_SLIP + index] > 0.0 else -1.0
        return in_l, in_r, tuple(s)
    if action == ACT_REVERSAL:
        return in_l, in_r, tuple(0.0 for _ in iso)
    if action == ACT_REGION:
        heading = x[1] if x[1] != 0.0 else acc
        return in_l, in_r, iso + (1 if heading > 0.0 else -1)
    raise ValueError(f"no transition for event action {action}")  # pragma: no cover


def after_event(h: Hybrid, action: int, index: int, x: np.ndarray) -> np.ndarray:
    """The state's jump at the event: at a contact's start the compression is the depth (equal
    but for rounding); a yielding spring's slip is where its strain is the breakpoint."""
    y = x.copy()
    if action == ACT_CONTACT:
        row = I_DL if index == SIDE_L else I_DR
        y[row] = max(0.0, (-x[0] if index == SIDE_L else x[0]) - h.gaps[index])
    elif action == ACT_YIELD:
        strain = x[0] - x[FIRST_SLIP + index]
        y[FIRST_SLIP + index] = x[0] - np.sign(strain) * h.breaks[index]
    return y


def one_blas_thread() -> threadpool_limits:
    """A context in which BLAS and LAPACK run on one thread: the monodromy's products and
    exponentials are of matrices of a few rows, which a threaded BLAS slows down a hundredfold
    when the machine is busy (measured: ``expm`` of a 6-by-6 in 8 ms instead of 20 us)."""
    return threadpool_limits(limits=1, user_api="blas")


def exponential(a: np.ndarray, tau: float) -> np.ndarray:
    """``expm(a tau)``, the states that evolve alone (a relaxing bumper: its row and column hold
    only the diagonal) by their scalar exponential: their rates (``stiffness / damping``, up to
    1e6 1/s) would make ``expm`` square its way down from a huge norm, slowly."""
    off = a - np.diag(np.diag(a))
    alone = ~(off.any(axis=0) | off.any(axis=1))
    out = np.zeros_like(a)
    rest = np.flatnonzero(~alone)
    out[np.ix_(rest, rest)] = expm(a[np.ix_(rest, rest)] * tau)
    idx = np.flatnonzero(alone)
    out[idx, idx] = np.exp(np.diag(a)[idx] * tau)
    return out


EIGEN_COND = 1e6  # a mode whose eigenvectors are worse conditioned takes expm


def mode_matrices(h: Hybrid, mode: tuple, omega: float, amp: float, modes: Optional[dict]) -> tuple:
    """``(Ã_m, its eigen-decomposition or None)``; with ``modes`` (a dict kept over many periods of
    one forcing) each mode's are computed once.  The decomposition is of the states that do not
    evolve alone (``exponential``'s split), given only when its eigenvectors are well conditioned
    (below ``EIGEN_COND``): LAPACK's eigenvectors of a repeated eigenvalue (a touched bumper's
    compression, a stuck slip and the constant state all have 0) are often not independent, and
    such a mode's exponentials come from ``expm``."""
    if modes is not None and mode in modes:
        return modes[mode]
    a = augmented_matrix(h, mode, omega, amp)
    eig = None
    if modes is not None:
        off = a - np.diag(np.diag(a))
        alone = ~(off.any(axis=0) | off.any(axis=1))
        rest, idx = np.flatnonzero(~alone), np.flatnonzero(alone)
        lam, vecs = np.linalg.eig(a[np.ix_(rest, rest)])
        if np.isfinite(vecs).all() and np.linalg.cond(vecs) < EIGEN_COND:
            eig = (lam, vecs, np.linalg.inv(vecs), np.ix_(rest, rest), idx, np.diag(a)[idx])
        modes[mode] = (a, eig)
    return a, eig


def _eigen_exponential(eig: tuple, size: int, tau: float) -> np.ndarray:
    """``expm(Ã tau)`` from :func:`mode_matrices`' decomposition."""
    lam, vecs, inv, block, idx, rates = eig
    out = np.zeros((size, size))
    out[block] = ((vecs * np.exp(lam * tau)) @ inv).real
    out[idx, idx] = np.exp(rates * tau)
    return out


def monodromy(h: Hybrid, vec0: np.ndarray, events: np.ndarray, t_end: float, omega: float, amp: float,
              phase: float, modes: Optional[dict] = None) -> tuple[np.ndarray, np.ndarray]:
    """The Jacobian of the map from ``x`` at the state vector ``vec0``'s time to ``x`` at
    ``t_end``, along the engine's ``events`` (rows of t, action, index), and ``x`` at ``t_end``
    as this propagation has it (to compare with the engine's).

    ``modes``: a dict kept over many calls with the same forcing (:func:`mode_matrices`): each
    phase's exponential then comes from its mode's eigen-decomposition, computed once (about ten
    times faster than ``expm``, to some 1e-12 instead of the last digit).  Without it (the
    periodic-orbit solvers), ``expm`` each phase.

    Returns
    -------
    jac : ndarray, shape (n, n)
    x_end : ndarray, shape (n,)
    """
    n = h.size
    t = float(vec0[0])
    mode = mode_of(h, vec0)
    xa = np.concatenate((coordinates(h, vec0), [np.sin(omega * t + phase), np.cos(omega * t + phase), 1.0]))
    jac = np.eye(n)
    a, eig = mode_matrices(h, mode, omega, amp, modes)
    for t_ev, action, index in np.vstack((events, [[t_end, -1.0, -1.0]])):
        step = exponential(a, t_ev - t) if eig is None else _eigen_exponential(eig, n + 3, t_ev - t)
        xa = step @ xa
        jac = step[:n, :n] @ jac
        t = t_ev
        if action < 0:
            break
        action, index = int(action), int(index)
        x = xa[:n]
        f_before = (a @ xa)[:n]
        new = next_mode(h, action, index, mode, x, f_before[1])
        a_after, eig_after = mode_matrices(h, new, omega, amp, modes)
        f_after = (a_after @ xa)[:n]
        grad = guard_gradient(h, action, index, mode, x)
        rate = float(grad @ f_before)
        if rate == 0.0 and np.any(f_after != f_before):  # (tangent: no saltation; the caller falls back)
            raise NoExactMonodromy(f"event {action} at t = {t_ev} is tangent (a grazing)")
        if rate != 0.0:
            jac = (np.eye(n) + np.outer(f_after - f_before, grad) / rate) @ jac
        xa[:n] = after_event(h, action, index, x)
        mode, a, eig = new, a_after, eig_after
    return jac, xa[:n]
