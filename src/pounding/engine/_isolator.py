"""Compiled isolator: the linear law of the current phase, its energy and its events.

Two hysteresis rules share the backbone ``slopes`` / ``breaks``:

* ``RULE_KINEMATIC``: a spring of slope ``K_n`` in parallel with ``n - 1`` elastic-perfectly-
  plastic springs; spring ``i`` has stiffness ``K_i - K_{i+1}`` and slips when its strain
  ``D - u_i`` reaches ``+-D_i``.  State: slips ``u_i`` and slip directions ``s_i``.
* ``RULE_ELASTIC``: the force follows the backbone; state: the branch ``REGION``.
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from ._layout import D as I_D
from ._layout import (ACT_REGION, ACT_REVERSAL, ACT_YIELD, E_ACTION, E_ALPHA, E_BETA, E_DIR,
                      E_GAMMA, E_INDEX, E_KIND, E_SIDE, KIND_LINEAR, REGION, SIDE_NONE,
                      STATE_BASE)

NO_SPRING = np.int64(0)  # the index of events that concern no spring (typed: see _layout.py)
RULE_KINEMATIC = 0
RULE_ELASTIC = 1


@jit
def backbone_force_at_break(slopes, breaks, j):
    """Backbone force (N) at breakpoint ``j`` (0-based)."""
    f = slopes[0] * breaks[0]
    for i in range(1, j + 1):
        f += slopes[i] * (breaks[i] - breaks[i - 1])
    return f


@jit
def iso_linear(slopes, breaks, rule, st):
    """``(k, r0)``: the rate-independent force is ``k D + r0`` until the next isolator event."""
    n_sp = slopes.size - 1
    if rule == RULE_ELASTIC:
        r = int(st[REGION])
        a = abs(r)
        k = slopes[a]
        if a == 0:
            return k, 0.0
        off = backbone_force_at_break(slopes, breaks, a - 1) - k * breaks[a - 1]
        return k, off if r > 0 else -off
    k = slopes[n_sp]
    r0 = 0.0
    kmax = 0.0
    for i in range(n_sp + 1):
        kmax = max(kmax, abs(slopes[i]))
    for i in range(n_sp):
        ki = slopes[i] - slopes[i + 1]
        s = st[STATE_BASE + n_sp + i]
        if s == 0.0:
            k += ki
            r0 -= ki * st[STATE_BASE + i]
        else:
            r0 += s * ki * breaks[i]
    if abs(k) < 1e-12 * kmax:
        k = 0.0  # exactly plastic: keep the closed form's k = 0 branch exact
    return k, r0


@jit
def iso_energy(slopes, breaks, rule, st, d):
    """Elastic energy stored in the isolator (J) at displacement ``d`` (m)."""
    n_sp = slopes.size - 1
    if rule == RULE_ELASTIC:
        a = abs(d)
        u = 0.0
        lo = 0.0
        f_lo = 0.0
        for j in range(n_sp + 1):
            hi = breaks[j] if j < n_sp else a
            top = min(a, hi)
            if top > lo:
                u += f_lo * (top - lo) + 0.5 * slopes[j] * (top - lo) ** 2
            if a <= hi:
                break
            f_lo += slopes[j] * (hi - lo)
            lo = hi
        return u
    u = 0.5 * slopes[n_sp] * d * d
    for i in range(n_sp):
        e = d - st[STATE_BASE + i]
        u += 0.5 * (slopes[i] - slopes[i + 1]) * e * e
    return u


@jit
def _add(evs, n, alpha, beta, gamma, action, index, direction):
    evs[n, E_KIND] = KIND_LINEAR
    evs[n, E_ALPHA] = alpha
    evs[n, E_BETA] = beta
    evs[n, E_GAMMA] = gamma
    evs[n, E_SIDE] = SIDE_NONE
    evs[n, E_ACTION] = action
    evs[n, E_INDEX] = index
    evs[n, E_DIR] = direction
    return n + 1


@jit
def iso_events(slopes, breaks, rule, st, evs, n):
    """Append the isolator's events for the current state to ``evs``; return the new count."""
    n_sp = slopes.size - 1
    if n_sp == 0:
        return n
    if rule == RULE_ELASTIC:
        r = int(st[REGION])
        a = abs(r)
        if r >= 0:
            if a < n_sp:
                n = _add(evs, n, breaks[a], -1.0, 0.0, ACT_REGION, NO_SPRING, 1.0)
            lower = breaks[a - 1] if r > 0 else -breaks[0]
            n = _add(evs, n, -lower, 1.0, 0.0, ACT_REGION, NO_SPRING, -1.0)
        else:
            n = _add(evs, n, -breaks[a - 1], -1.0, 0.0, ACT_REGION, NO_SPRING, 1.0)
            if a < n_sp:
                n = _add(evs, n, breaks[a], 1.0, 0.0, ACT_REGION, NO_SPRING, -1.0)
        return n
    slip_dir = 0.0
    for i in range(n_sp):
        s = st[STATE_BASE + n_sp + i]
        if s == 0.0:
            u = st[STATE_BASE + i]
            n = _add(evs, n, breaks[i] + u, -1.0, 0.0, ACT_YIELD, i, 1.0)
            n = _add(evs, n, breaks[i] - u, 1.0, 0.0, ACT_YIELD, i, -1.0)
        else:
            slip_dir = s
    if slip_dir != 0.0:
        n = _add(evs, n, 0.0, 0.0, slip_dir, ACT_REVERSAL, NO_SPRING, 0.0)
    return n


@jit
def iso_advance(slopes, breaks, rule, st, d_start, d_end):
    """Move slipping springs with the mass from ``d_start`` to ``d_end``; return their work (J)."""
    n_sp = slopes.size - 1
    work = 0.0
    if rule == RULE_ELASTIC:
        return work
    for i in range(n_sp):
        s = st[STATE_BASE + n_sp + i]
        if s != 0.0:
            work += (slopes[i] - slopes[i + 1]) * breaks[i] * abs(d_end - d_start)
            st[STATE_BASE + i] = d_end - s * breaks[i]
    return work


@jit
def iso_transition(slopes, breaks, rule, st, action, index, direction):
    """Apply an isolator event (yield, load reversal or change of branch) to the state."""
    n_sp = slopes.size - 1
    if action == ACT_REGION:
        st[REGION] += direction
    elif action == ACT_YIELD:
        st[STATE_BASE + n_sp + index] = direction
        st[STATE_BASE + index] = st[I_D] - direction * breaks[index]
    elif action == ACT_REVERSAL:
        for i in range(n_sp):
            st[STATE_BASE + n_sp + i] = 0.0
