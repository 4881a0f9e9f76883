"""The multi-linear bumper's backbone, compiled: its branches, energy and free recovery.

Parameters at ``p[o:o + N_LAW_PARAMS]`` as :meth:`MultilinearBumper.params` lays them out:
damping, the number of slopes, 4 slopes, 3 breakpoints.
"""

from __future__ import annotations

import math

from .._jit import jit

MIN_NORMAL = 2.2250738585072014e-308  # the smallest normal double
EXP_NORMAL_LIMIT = 708.39  # exp(-x) is below it for larger x
TIE = 1e-9  # relative: a compression this close above a breakpoint recovers on the branch below


@jit
def ml_branch(p, o, d):
    """The multi-linear backbone's branch holding compression ``d``:
    ``(R(d), slope, branch index, R = slope d + offset's offset)``."""
    n = int(p[o + 1])
    force = 0.0
    lower = 0.0
    for j in range(n):
        k = p[o + 2 + j]
        if j == n - 1 or d <= p[o + 6 + j]:
            return force + k * (d - lower), k, j, force - k * lower
        upper = p[o + 6 + j]
        force += k * (upper - lower)
        lower = upper
    return 0.0, 0.0, 0, 0.0  # (not reached)


@jit
def ml_branch_line(p, o, j):
    """Branch ``j``'s line: ``(slope, offset, lower end)`` with ``R(d) = slope d + offset`` on it."""
    lower = 0.0 if j == 0 else p[o + 5 + j]
    k = p[o + 2 + j]
    return k, ml_branch(p, o, lower)[0] - k * lower, lower


@jit
def ml_energy(p, d):
    """The area under the backbone up to ``d`` (J), branch by branch."""
    n = int(p[1])
    energy = 0.0
    force = 0.0
    lower = 0.0
    for j in range(n):
        k = p[2 + j]
        upper = d if j == n - 1 else min(d, p[6 + j])
        if upper <= lower:
            break
        energy += (force + 0.5 * k * (upper - lower)) * (upper - lower)
        force += k * (upper - lower)
        lower = upper
    return energy


@jit
def _down_branch(p, o, d):
    """The branch a recovering (shrinking) compression ``d`` is on: ``(slope, offset, lower end,
    time to reach it from d)``, with ``d`` within ``TIE`` above a breakpoint counted below it
    (the recovery that reached a breakpoint goes on, down)."""
    c = p[o]
    j = ml_branch(p, o, d)[2]
    if j > 0 and d <= p[o + 5 + j] * (1.0 + TIE):
        j -= 1
    k, offset, lower = ml_branch_line(p, o, j)
    if j == 0:
        return k, offset, lower, math.inf
    if k > 0.0:
        target = -offset / k  # where this branch's force would be zero (<= lower)
        return k, offset, lower, c / k * math.log((d - target) / (lower - target))
    return k, offset, lower, (d - lower) * c / offset  # (flat: the force is the offset)


@jit
def ml_relax(p, o, d0, tau):
    """``damping dd = -R(d)`` from ``d0``, ``tau`` s on: branch by branch in closed form
    (exponential on a sloped branch, linear on a flat one)."""
    c = p[o]
    if c <= 0.0 or d0 <= 0.0:
        return 0.0, 0.0
    d = d0
    left = tau
    for _ in range(8):  # (at most one pass per branch)
        k, offset, lower, t_edge = _down_branch(p, o, d)
        if t_edge < left:
            left -= t_edge
            d = lower
            continue
        if k > 0.0:
            x = k / c * left
            if x > EXP_NORMAL_LIMIT:
                return 0.0, 0.0
            target = -offset / k
            d_new = target + (d - target) * math.exp(-x)
            if d_new < MIN_NORMAL:
                return 0.0, 0.0
            return d_new, -(k * d_new + offset) / c
        return d - offset / c * left, -offset / c
    return 0.0, 0.0  # (not reached)


@jit
def ml_relax_horizon(p, o, d0):
    """Time (s) the free recovery from ``d0`` takes to reach the lower end of its branch (inf on
    the lowest branch, which it approaches for ever, or without a dashpot)."""
    if p[o] <= 0.0 or d0 <= 0.0:
        return math.inf
    return _down_branch(p, o, d0)[3]
