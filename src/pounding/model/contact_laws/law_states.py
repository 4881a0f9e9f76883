"""What a bumper law's own state may hold: each law's check of its block of the state vector.

A law keeps ``N_LAW_STATE`` numbers in the engine's state (``engine/layout.Z_L``, ``Z_R``):
0 for a stateless law; Hertzdamp's damping; an elastic-plastic law's line or offset; a
kinematic multi-linear law's slips and slip directions.  Each law class names its check as
``STATE_CHECK``; :func:`state_problem` calls it, and the engine names the field and raises
(``engine/simulate.py``).

Each check takes ``(block, law, touching, comp, tol, side)`` and returns None for a block the law
can be in, else ``(q, value, why)``: the place in the block, its value and why it cannot be.
"""

from __future__ import annotations

import functools
from typing import Any, Optional

import numpy as np

# an elastic-plastic law's codes of its lines in its block (the core's, src/core/laws.cpp)
EP_YIELD, EP_UNLOAD = -1.0, -2.0

Problem = Optional[tuple[int, float, str]]


def _slips_unused(block: np.ndarray) -> Problem:
    for q in range(1, block.size):
        if block[q] != 0.0:
            return q, float(block[q]), ("is a kinematic multi-linear bumper's slip, but that bumper has "
                                        "another law")
    return None


def state_problem(law: Any, block: np.ndarray, touching: bool, comp: float, tol: float, side: str) -> Problem:
    """Why ``law`` cannot be in state ``block`` (its ``N_LAW_STATE`` numbers of a state vector) at
    compression ``comp`` (m, to ``tol``), in contact or not, on the bumper of ``side``; or None."""
    return law.STATE_CHECK(block, law, touching, comp, tol, side)


def stateless(block: np.ndarray, *_: Any) -> Problem:
    """A law without state (Kelvin-Voigt, Hunt-Crossley, Jankowski, elastic multi-linear): zeros."""
    found = _slips_unused(block)
    if found is None and block[0] != 0.0:
        return 0, float(block[0]), ("is a bumper law's state, but that bumper has none (a stateless law, or "
                                    "out of contact)")
    return found


def hertzdamp(block: np.ndarray, *_: Any) -> Problem:
    """Hertzdamp's damping of the last contact, >= 0."""
    found = _slips_unused(block)
    if found is None and block[0] < 0.0:
        return 0, float(block[0]), "is a Hertzdamp bumper's damping, which is >= 0"
    return found


def elastic_plastic(block: np.ndarray, law: Any, touching: bool, comp: float, tol: float,
                    side: str) -> Problem:
    """0 out of contact; in contact a line's code or a plastic offset whose elastic branch holds
    the compression ``comp`` (m, to ``tol``)."""
    if not touching:
        return stateless(block)
    found = _slips_unused(block)
    if found:
        return found
    z = float(block[0])
    k1, k2, dy = law.stiffness, law.post_yield_stiffness, law.yield_compression
    if z == EP_UNLOAD:
        return None
    if z == EP_YIELD:  # (the yield line starts at the yield compression)
        if comp < dy - tol:
            return 0, z, (f"puts the {side} bumper on its yield line at compression {comp:g} m, below its "
                          f"yield compression {dy:g} m")
        return None
    low = k1 * z / (k1 - k2)
    if z < 0.0 or not low - tol <= comp <= low + dy + tol:
        return 0, z, (f"is no plastic offset of the {side} bumper at compression {comp:g} m (its elastic "
                      "branch would not hold it)")
    return None


def multilinear(block: np.ndarray, law: Any, touching: bool, comp: float, tol: float, side: str) -> Problem:
    """An elastic multi-linear bumper has no state; a kinematic one, its springs' (``kinematic``)."""
    if law.hysteresis == "kinematic":
        return kinematic(block, law, touching, comp, tol)
    return stateless(block)


def kinematic(block: np.ndarray, law: Any, touching: bool, comp: float, tol: float) -> Problem:
    """A kinematic multi-linear bumper's springs: each softening's slip direction -1, 0 or +1, its
    strain within its breakpoint (at it while slipping); the other places 0.  Out of contact (the
    bumper recovering) no spring slips in compression, and the springs do not pull."""
    slopes, breaks = law.slopes, law.breakpoints
    soft, unused = _softenings(slopes, breaks, block.size)
    z = block.tolist()  # (Python's floats: the same numbers, read faster than numpy's scalars)
    for q in unused:
        if z[q] != 0.0:
            return q, z[q], ("is no state of this kinematic multi-linear bumper (a place for a "
                             "softening it has not): 0")
    for i in soft:
        u, s = z[1 + i], z[4 + i]
        if s not in (-1.0, 0.0, 1.0):
            return 4 + i, s, "is a slip direction: -1, 0 or +1"
        strain = comp - u
        if (abs(strain) > breaks[i] + tol) if s == 0.0 else abs(strain - s * breaks[i]) > tol:
            return 1 + i, u, (f"leaves the bumper spring {i}'s strain {strain:g} m beyond its "
                              f"breakpoint {breaks[i]:g} m")
        if s > 0.0 and not touching:
            return 4 + i, s, ("slips the bumper spring in compression while out of contact (it holds "
                              "once the contact ends)")
    if not touching and comp > 0.0:
        k_lin = slopes[0] - sum(slopes[i] - slopes[i + 1] for i in soft)
        held = 0.0  # (added in order: numpy's scalars were, where Python 3.12's sum of floats compensates)
        for i in soft:
            held = held + ((slopes[i] - slopes[i + 1]) * (comp - z[1 + i]) if z[4 + i] == 0.0
                           else (slopes[i] - slopes[i + 1]) * z[4 + i] * breaks[i])
        force = max(k_lin, 0.0) * comp + held
        force += sum((slopes[i + 1] - slopes[i]) * max(comp - breaks[i], 0.0)
                     for i in range(len(breaks)) if slopes[i + 1] > slopes[i])
        if force < -tol * max(slopes) - 1e-9:
            return 1, z[1], (f"makes the recovering bumper pull ({force:g} N at its compression "
                             f"{comp:g} m)")
    return None


@functools.lru_cache(maxsize=64)
def _softenings(slopes: tuple, breaks: tuple, size: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """(the breakpoints where a kinematic multi-linear backbone softens (its slope falls), the places of
    a block of ``size`` numbers it has no use for, in order)."""
    soft = tuple(i for i in range(len(breaks)) if slopes[i] > slopes[i + 1])
    return soft, tuple(q for q in range(size) if q == 0 or (q - 1) % 3 not in soft)
