"""The multi-linear bumper with kinematic (Masing) hysteresis, compiled.

Parameters at ``p[o:o + N_LAW_PARAMS]`` as for the elastic multi-linear law: damping, the number
of slopes, 4 slopes, 3 breakpoints.  The backbone ``R(d)`` is split at each breakpoint ``b_i``
by the change of slope ``delta_i = k_i - k_(i+1)``:

* a softening step (``delta_i > 0``) is an elastic-perfectly-plastic spring of stiffness
  ``delta_i`` that slips when its strain ``d - u_i`` reaches ``+-b_i`` (Iwan's parallel
  springs: unloading and reloading follow the backbone turned over at twice the scale from
  each turning point, Masing's rule, with its memory);
* a hardening step (``delta_i < 0``) is an elastic spring ``-delta_i max(0, d - b_i)`` (the
  hole of the D-shaped bumper closed: elastic, it adds no loop);
* in parallel, the spring ``k_lin d`` with ``k_lin = k_1 - sum of the softening steps`` (>= 0,
  checked by :class:`MultilinearBumper`), and the dashpot.

Loaded from the unloaded state the force follows the backbone exactly.  The law's state, in a
bumper's block of ``N_LAW_STATE`` values at ``zs[zo:]``: ``zs[zo + 1 + i]`` the slip ``u_i``
(m) and ``zs[zo + 4 + i]`` its direction (-1, 0, +1) of the spring at breakpoint ``i``.

The springs keep their slips between contacts: a bumper unloaded from deep in its soft branch
keeps a set where its springs' forces cancel, and the next contact reloads it from there.  Out of
contact the massless bumper recovers by ``damping dd = -F(d)`` as the elastic law does, piece by
piece in closed form (a spring may slip back on the way), to its set; with no dashpot at once.
"""

from __future__ import annotations

import math

from .._jit import jit
from ._multilinear import EXP_NORMAL_LIMIT, MIN_NORMAL

TIE = 1e-9  # relative to a breakpoint: a compression this close to an edge is at it
EDGE_UP = -1.0  # the event codes of a branch's upper and lower edge (contact_laws.EDGE_UP_STATE, ...)
EDGE_DOWN = -2.0


@jit
def kb_linear_slope(p, o):
    """``k_lin`` (N/m): the first slope less every softening step (0 when they cancel it)."""
    n = int(p[o + 1])
    k = p[o + 2]
    for i in range(n - 1):
        step = p[o + 2 + i] - p[o + 3 + i]
        if step > 0.0:
            k -= step
    return max(k, 0.0)


@jit
def kb_spring(p, o, zs, zo, x, dx):
    """The springs at compression ``x`` (m), heading ``dx`` (its sign settles a hardening
    knot within ``TIE``): ``(force N, slope N/m, offset N, hardening knots passed)`` with
    ``force = slope x + offset`` until the next edge."""
    n = int(p[o + 1])
    k = kb_linear_slope(p, o)
    r = 0.0
    m = 0
    for i in range(n - 1):
        b = p[o + 6 + i]
        step = p[o + 2 + i] - p[o + 3 + i]
        if step > 0.0:
            s = zs[zo + 4 + i]
            if s == 0.0:
                k += step
                r -= step * zs[zo + 1 + i]
            else:
                r += s * step * b
        elif step < 0.0:
            if x - b > TIE * b or (abs(x - b) <= TIE * b and dx > 0.0):
                k -= step
                r += step * b
                m += 1
    return k * x + r, k, r, m


@jit
def kb_edges(p, o, j, zs, zo):
    """Compressions (m) where the branch with ``j`` hardening knots passed ends, below and above
    (-1.0 for none): the next slip of an elastic spring either way, the hardening knots around."""
    n = int(p[o + 1])
    lower = -1.0
    upper = math.inf
    count = 0
    for i in range(n - 1):
        b = p[o + 6 + i]
        step = p[o + 2 + i] - p[o + 3 + i]
        if step > 0.0:
            if zs[zo + 4 + i] == 0.0:
                u = zs[zo + 1 + i]
                upper = min(upper, u + b)
                if u - b > 0.0:
                    lower = max(lower, u - b)
        elif step < 0.0:
            if count < j:
                lower = max(lower, b)
            elif count == j:
                upper = min(upper, b)
            count += 1
    return lower, (upper if upper < math.inf else -1.0)


@jit
def kb_turn_sign(p, o, zs, zo):
    """The direction the slipping springs slip in (they all slip with the motion), 0 for none:
    the branch ends where the compression rate of that sign crosses zero."""
    n = int(p[o + 1])
    for i in range(n - 1):
        s = zs[zo + 4 + i]
        if s != 0.0:
            return s
    return 0.0


@jit
def kb_after_event(p, o, zs, zo, x, code):
    """Update the springs after an event at compression ``x``: a turn (``code`` 0) holds every
    slipping spring where it is; an edge (``EDGE_UP`` or ``EDGE_DOWN``) starts the slip of the
    spring whose edge it is (the nearest edge of that side: a hardening knot changes no state)."""
    n = int(p[o + 1])
    if code == 0.0:
        for i in range(n - 1):
            s = zs[zo + 4 + i]
            if s != 0.0:
                zs[zo + 1 + i] = x - s * p[o + 6 + i]
                zs[zo + 4 + i] = 0.0
        return
    sgn = 1.0 if code == EDGE_UP else -1.0
    best = math.inf
    for i in range(n - 1):  # the nearest edge on that side, of a spring or a knot
        b = p[o + 6 + i]
        step = p[o + 2 + i] - p[o + 3 + i]
        if step > 0.0 and zs[zo + 4 + i] == 0.0:
            best = min(best, abs(x - (zs[zo + 1 + i] + sgn * b)) / b)
        elif step < 0.0:
            best = min(best, abs(x - b) / b)
    for i in range(n - 1):  # every spring at that edge slips (a knot: none)
        b = p[o + 6 + i]
        step = p[o + 2 + i] - p[o + 3 + i]
        if step > 0.0 and zs[zo + 4 + i] == 0.0:
            gap = abs(x - (zs[zo + 1 + i] + sgn * b)) / b
            if gap <= best + TIE:
                zs[zo + 4 + i] = sgn


@jit
def kb_branch_loss(p, o, zs, zo, x0, x1):
    """Energy (J) the slipping springs dissipate as the compression goes from ``x0`` to ``x1``."""
    n = int(p[o + 1])
    loss = 0.0
    for i in range(n - 1):
        s = zs[zo + 4 + i]
        if s != 0.0:
            loss += s * (p[o + 2 + i] - p[o + 3 + i]) * p[o + 6 + i] * (x1 - x0)
    return loss


@jit
def kb_energy(p, o, x, zs, zo):
    """Elastic energy (J) stored at compression ``x`` in the springs' state."""
    n = int(p[o + 1])
    k_lin = kb_linear_slope(p, o)
    e = 0.5 * k_lin * x * x
    for i in range(n - 1):
        b = p[o + 6 + i]
        step = p[o + 2 + i] - p[o + 3 + i]
        if step > 0.0:
            s = zs[zo + 4 + i]
            strain = x - zs[zo + 1 + i] if s == 0.0 else s * b
            e += 0.5 * step * strain * strain
        elif step < 0.0 and x > b:
            e -= 0.5 * step * (x - b) * (x - b)
    return e


@jit
def kb_contact_state(p, o, zs, zo, x):
    """A contact starts at compression ``x``: springs slipping back (recovering) hold there."""
    n = int(p[o + 1])
    for i in range(n - 1):
        if zs[zo + 4 + i] < 0.0:
            zs[zo + 1 + i] = x + p[o + 6 + i]
            zs[zo + 4 + i] = 0.0


@jit
def kb_release_state(p, o, zs, zo, x):
    """A contact ends at compression ``x``: springs slipping in compression hold there (the
    bumper recovers, its compression falling)."""
    n = int(p[o + 1])
    for i in range(n - 1):
        if zs[zo + 4 + i] > 0.0:
            zs[zo + 1 + i] = x - p[o + 6 + i]
            zs[zo + 4 + i] = 0.0


@jit
def kb_moved(p, o, zs, zo, x, in_contact):
    """The compression moved to ``x`` (m): the slipping springs' slips follow it; out of contact
    (``in_contact`` 0.0, a float as the state vector has it: a recovery, never past the end of
    one of its pieces) the springs whose strain reached ``-b_i`` on the way down slip back."""
    n = int(p[o + 1])
    for i in range(n - 1):
        b = p[o + 6 + i]
        if p[o + 2 + i] - p[o + 3 + i] <= 0.0:
            continue
        s = zs[zo + 4 + i]
        if s == 0.0 and in_contact == 0.0 and x - (zs[zo + 1 + i] - b) <= TIE * b:
            s = -1.0
            zs[zo + 4 + i] = s
        if s != 0.0:
            zs[zo + 1 + i] = x - s * b


@jit
def _down_piece(p, o, zs, zo, x):
    """The springs' force on the way down from ``x`` (a recovery: no spring slips in
    compression): ``(slope, offset, lower end)`` of the piece below ``x`` (an edge within
    ``TIE`` counts as passed)."""
    n = int(p[o + 1])
    k = kb_linear_slope(p, o)
    r = 0.0
    lower = 0.0
    for i in range(n - 1):
        b = p[o + 6 + i]
        step = p[o + 2 + i] - p[o + 3 + i]
        if step > 0.0:
            u = zs[zo + 1 + i]
            if zs[zo + 4 + i] == 0.0 and x - (u - b) > TIE * b:
                k += step
                r -= step * u
                lower = max(lower, u - b)
            else:  # slipping back
                r -= step * b
        elif step < 0.0 and x - b > TIE * b:
            k -= step
            r += step * b
            lower = max(lower, b)
    return k, r, lower


@jit
def kb_relax(p, o, d0, tau, zs, zo):
    """``damping dd = -F(d)`` from ``d0``, ``tau`` s on: ``(compression, rate)``, piece by piece
    (exponential on a sloped piece, linear on a flat one), to the set where the force is 0 (or
    to 0); at once without a dashpot."""
    c = p[o]
    if d0 <= 0.0:
        return 0.0, 0.0
    x = d0
    left = tau
    for _ in range(16):  # (one pass per piece: at most 3 springs and 3 knots)
        k, r, lower = _down_piece(p, o, zs, zo, x)
        f = k * x + r
        if f <= 0.0:
            return x, 0.0  # at its set
        if k > 0.0:
            target = -r / k
            if target >= lower:  # approaches the set for ever (at once without a dashpot)
                if c <= 0.0:
                    return target, 0.0
                arg = k / c * left
                if arg > EXP_NORMAL_LIMIT:
                    return target, 0.0
                gap = (x - target) * math.exp(-arg)
                if gap < MIN_NORMAL:
                    return target, 0.0
                return target + gap, -k * gap / c
            t_edge = c / k * math.log((x - target) / (lower - target)) if c > 0.0 else 0.0
        else:
            t_edge = (x - lower) * c / r if c > 0.0 else 0.0
        if t_edge < left or c <= 0.0:
            left -= t_edge
            x = lower
            if x <= 0.0:
                return 0.0, 0.0
            continue
        if k > 0.0:
            target = -r / k
            gap = (x - target) * math.exp(-k / c * left)
            return target + gap, -k * gap / c
        return x - r / c * left, -r / c
    return x, 0.0  # (not reached)


@jit
def kb_relax_horizon(p, o, d0, zs, zo):
    """Time (s) the recovery from ``d0`` takes to reach the lower end of its piece (inf when it
    approaches its set on it, or without a dashpot)."""
    c = p[o]
    if c <= 0.0 or d0 <= 0.0:
        return math.inf
    k, r, lower = _down_piece(p, o, zs, zo, d0)
    if k * d0 + r <= 0.0:
        return math.inf
    if k > 0.0:
        target = -r / k
        if target >= lower:
            return math.inf
        return c / k * math.log((d0 - target) / (lower - target))
    return (d0 - lower) * c / r


@jit
def kb_force_path(p, o, d, v, out):
    """The force (N) along the compressions ``d`` (m) at rates ``v`` (m/s), samples in order from
    the unloaded bumper: each spring's strain moves with the compression, held within ``+-b_i``
    (exact for a path that does not turn back between samples)."""
    n = int(p[o + 1])
    k_lin = kb_linear_slope(p, o)
    e0 = e1 = e2 = 0.0  # the springs' strains (no allocation: compiled code without reference counts)
    prev = 0.0
    for q in range(d.size):
        x = d[q]
        f = k_lin * x + p[o] * v[q]
        for i in range(n - 1):
            b = p[o + 6 + i]
            step = p[o + 2 + i] - p[o + 3 + i]
            if step > 0.0:
                e = e0 if i == 0 else (e1 if i == 1 else e2)
                e = min(max(e + x - prev, -b), b)
                if i == 0:
                    e0 = e
                elif i == 1:
                    e1 = e
                else:
                    e2 = e
                f += step * e
            elif step < 0.0 and x > b:
                f -= step * (x - b)
        prev = x
        out[q] = f
