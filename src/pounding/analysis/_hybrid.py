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

import math
from typing import NamedTuple

import numpy as np
from threadpoolctl import threadpool_limits

from .._jit import jit_alloc, jit_entry
from ..engine._layout import (ACT_CONTACT, ACT_REGION, ACT_RELEASE, ACT_REVERSAL, ACT_YIELD, DEF_L, DEF_R,
                              IN_L, IN_R, REGION, SIDE_L, STATE_BASE)
from ..engine._layout import D as I_D
from ..engine._layout import V as I_V
from ..model import Oscillator
from ..model.contact_laws import linear_form
from ._expm import expm_small, matmul, matvec

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


class Hybrid(NamedTuple):
    """The numbers of the modes' matrices (SI units), as the compiled propagation takes them."""

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
            gaps = (float(b.gap_left), float(b.gap_right))
            # (a law other than Kelvin-Voigt: no linear modes; its numbers are not used but for the
            # coordinates, where its compressions are no shooting coordinates)
            forms = [linear_form(law) for law in (b.left, b.right)]
            k = tuple(float(f[0]) if f else float(getattr(law, "stiffness", np.nan))
                      for f, law in zip(forms, (b.left, b.right)))
            c = tuple(float(f[1]) if f else 0.0 for f in forms)
        return cls(float(oscillator.mass), float(iso.damping), np.array(iso.slopes, dtype=float),
                   np.array(iso.breakpoints, dtype=float), iso.hysteresis == "kinematic", gaps, k, c)

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


def one_blas_thread() -> threadpool_limits:
    """A context in which BLAS and LAPACK run on one thread: the monodromy's products and
    exponentials are of matrices of a few rows, which a threaded BLAS slows down a hundredfold
    when the machine is busy (measured: ``expm`` of a 6-by-6 in 8 ms instead of 20 us)."""
    return threadpool_limits(limits=1, user_api="blas")


def monodromy(h: Hybrid, vec0: np.ndarray, events: np.ndarray, t_end: float, omega: float, amp: float,
              phase: float) -> tuple[np.ndarray, np.ndarray]:
    """The Jacobian of the map from ``x`` at the state vector ``vec0``'s time to ``x`` at
    ``t_end``, along the engine's ``events`` (rows of t, action, index), and ``x`` at ``t_end``
    as this propagation has it (to compare with the engine's).

    Raises :class:`NoExactMonodromy` at an event met tangentially (no saltation matrix).

    Returns
    -------
    jac : ndarray, shape (n, n)
    x_end : ndarray, shape (n,)
    """
    in_l, in_r, iso = mode_of(h, vec0)
    iso_arr = np.array(iso if h.kinematic else (iso,), dtype=float).reshape(-1)
    if iso_arr.size == 0:
        iso_arr = np.zeros(1)
    rows = np.ascontiguousarray(events, dtype=float).reshape(-1, 3)
    jac, x_end, bad = monodromy_kernel(h, coordinates(h, vec0), in_l, in_r, iso_arr, rows, float(vec0[0]),
                                       float(t_end), (float(omega), float(amp), float(phase)))
    if bad >= 0:
        row = events[bad]
        raise NoExactMonodromy(f"event {int(row[1])} at t = {row[0]} is tangent (a grazing)")
    return jac, x_end


# The compiled propagation (``monodromy_kernel`` and its parts).  A mode is ``(in_l, in_r, iso)``:
# ``iso`` the slip directions of a kinematic isolator's springs, or ``iso[0]`` the elastic rule's
# backbone branch.


@jit_alloc
def _augmented(h, in_l, in_r, iso, omega, amp):
    """``Ã_m``, shape (n + 3, n + 3): ``x`` then ``sin(theta)``, ``cos(theta)``, 1.

    ``amp`` is the table's peak acceleration (m/s^2), ``omega`` its circular frequency (rad/s).
    """
    n_sp = h.slopes.size - 1 if h.kinematic else 0
    n = FIRST_SLIP + n_sp
    a = np.zeros((n + 3, n + 3))
    s_, c_, one = n, n + 1, n + 2
    m = h.mass
    a[0, 1] = 1.0
    # the mass: -(c_d V + isolator + right bumper - left bumper) / M - A(t)
    a[1, 1] -= h.c_d / m
    if h.kinematic:
        a[1, 0] -= h.slopes[n_sp] / m
        for i in range(n_sp):
            dk = h.slopes[i] - h.slopes[i + 1]
            s = iso[i]
            if s == 0.0:
                a[1, 0] -= dk / m
                a[1, FIRST_SLIP + i] += dk / m
            else:
                a[1, one] -= s * dk * h.breaks[i] / m
                a[FIRST_SLIP + i, 1] = 1.0  # a slipping spring moves with the mass
    else:
        r = int(iso[0])
        j = abs(r)
        k = h.slopes[j]
        a[1, 0] -= k / m
        if j > 0:
            f_break = h.slopes[0] * h.breaks[0]
            dot = 0.0
            for i in range(1, j):
                dot += h.slopes[i] * (h.breaks[i] - h.breaks[i - 1])
            f_break += dot
            a[1, one] -= (1.0 if r > 0 else -1.0) * (f_break - k * h.breaks[j - 1]) / m
    for side in range(2):
        touching = in_l if side == 0 else in_r
        row = I_DL if side == 0 else I_DR
        sign = -1.0 if side == 0 else 1.0
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


@jit_alloc
def _guard_gradient(h, action, index, n):
    """``grad g`` in ``x`` of the event (the guard as the engine's event function)."""
    g = np.zeros(n)
    sign = -1.0 if index == SIDE_L else 1.0
    if action == ACT_CONTACT:
        g[0] = sign
        if h.damping[index] > 0.0:
            g[I_DL if index == SIDE_L else I_DR] = -1.0  # the surface is where the relaxing bumper is
    elif action == ACT_RELEASE:  # the force reaches zero
        g[0] = sign * h.stiffness[index]
        g[1] = sign * h.damping[index]
    elif action == ACT_YIELD:
        g[0] = 1.0
        g[FIRST_SLIP + index] = -1.0
    elif action == ACT_REVERSAL:
        g[1] = 1.0
    elif action == ACT_REGION:
        g[0] = 1.0
    return g


@jit_alloc
def _next_mode(action, index, in_l, in_r, iso, x, acc):
    """The mode after the event (as the engine's transitions: ``_kernel``, ``_isolator``); ``acc``
    the acceleration before it, which says where a branch change at rest goes."""
    new = iso.copy()
    if action == ACT_CONTACT or action == ACT_RELEASE:
        now = action == ACT_CONTACT
        if index == SIDE_L:
            in_l = now
        else:
            in_r = now
    elif action == ACT_YIELD:
        new[index] = 1.0 if x[0] - x[FIRST_SLIP + index] > 0.0 else -1.0
    elif action == ACT_REVERSAL:
        for i in range(new.size):
            new[i] = 0.0
    elif action == ACT_REGION:
        heading = x[1] if x[1] != 0.0 else acc
        new[0] += 1.0 if heading > 0.0 else -1.0
    return in_l, in_r, new


@jit_alloc
def _after_event(h, action, index, x):
    """The state's jump at the event: at a contact's start the compression is the depth (equal
    but for rounding); a yielding spring's slip is where its strain is the breakpoint."""
    if action == ACT_CONTACT:
        depth = (-x[0] if index == SIDE_L else x[0]) - h.gaps[index]
        x[I_DL if index == SIDE_L else I_DR] = max(0.0, depth)
    elif action == ACT_YIELD:
        strain = x[0] - x[FIRST_SLIP + index]
        sign = 1.0 if strain > 0.0 else -1.0 if strain < 0.0 else 0.0
        x[FIRST_SLIP + index] = x[0] - sign * h.breaks[index]


@jit_alloc
def _exponential(a, tau):
    """``expm(a tau)``, the states that evolve alone (a relaxing bumper: its row and column hold
    only the diagonal) by their scalar exponential: their rates (``stiffness / damping``, up to
    1e6 1/s) would make the Padé approximant square its way down from a huge norm.  (Loops
    throughout: Numba's array expressions and index helpers cost seconds of a cold start.)"""
    size = a.shape[0]
    rest = np.zeros(size, dtype=np.int64)
    n_rest = 0
    for i in range(size):
        joined = False
        for j in range(size):
            if i != j and (a[i, j] != 0.0 or a[j, i] != 0.0):
                joined = True
        if joined:
            rest[n_rest] = i
            n_rest += 1
    sub = np.zeros((n_rest, n_rest))
    for i in range(n_rest):
        for j in range(n_rest):
            sub[i, j] = a[rest[i], rest[j]] * tau
    block = expm_small(sub)
    out = np.zeros((size, size))
    for i in range(size):
        out[i, i] = math.exp(a[i, i] * tau)  # (the states alone; the others' overwritten below)
    for i in range(n_rest):
        for j in range(n_rest):
            out[rest[i], rest[j]] = block[i, j]
    return out


@jit_alloc
def _identity(n):
    out = np.zeros((n, n))
    for i in range(n):
        out[i, i] = 1.0
    return out


@jit_alloc
def _head(x, n):
    """A copy of ``x[:n]``."""
    out = np.zeros(n)
    for i in range(n):
        out[i] = x[i]
    return out


@jit_alloc
def _top_left(m, n):
    """A copy of ``m[:n, :n]``."""
    out = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            out[i, j] = m[i, j]
    return out


@jit_entry
def monodromy_kernel(h, x0, in_l, in_r, iso, events, t0, t_end, forcing):
    """:func:`monodromy`'s propagation: ``(jac (n, n), x at t_end (n,), the row of a tangent event
    or -1)``.  ``forcing`` is ``(omega rad/s, peak m/s^2, phase rad)``."""
    omega, amp, phase = forcing
    n = x0.size
    t = t0
    xa = np.zeros(n + 3)
    for i in range(n):
        xa[i] = x0[i]
    xa[n] = math.sin(omega * t + phase)
    xa[n + 1] = math.cos(omega * t + phase)
    xa[n + 2] = 1.0
    jac = _identity(n)
    a = _augmented(h, in_l, in_r, iso, omega, amp)
    m_ev = events.shape[0]
    for e in range(m_ev + 1):
        t_ev = events[e, 0] if e < m_ev else t_end
        step = _exponential(a, t_ev - t)
        xa = matvec(step, xa)
        jac = matmul(_top_left(step, n), jac)
        t = t_ev
        if e == m_ev:
            break
        action, index = int(events[e, 1]), int(events[e, 2])
        x = _head(xa, n)
        f_before = matvec(a, xa)
        new_l, new_r, new_iso = _next_mode(action, index, in_l, in_r, iso, x, f_before[1])
        a_after = _augmented(h, new_l, new_r, new_iso, omega, amp)
        f_after = matvec(a_after, xa)
        grad = _guard_gradient(h, action, index, n)
        rate = 0.0
        for i in range(n):
            rate += grad[i] * f_before[i]
        if rate == 0.0:  # (tangent: no saltation, unless the field does not jump)
            for i in range(n):
                if f_after[i] != f_before[i]:
                    return jac, _head(xa, n), e
        else:
            jump = _identity(n)
            for i in range(n):
                for j in range(n):
                    jump[i, j] += (f_after[i] - f_before[i]) * grad[j] / rate
            jac = matmul(jump, jac)
        _after_event(h, action, index, x)
        for i in range(n):
            xa[i] = x[i]
        in_l, in_r, iso, a = new_l, new_r, new_iso, a_after
    return jac, _head(xa, n), -1
