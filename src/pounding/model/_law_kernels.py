"""The contact laws' compiled side: every ``law_*`` function the engine calls, by law id.

The laws themselves (their parameters, validation and closed forms) are the dataclasses of
:mod:`pounding.model.contact_laws`, which re-exports all of this; a law's ``LAW_ID`` is its
constant here, and its ``params()`` lays out what these functions read.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit, jit_entry
from ._elastic_plastic import (EP_UNLOAD, EP_YIELD, EP_YIELD_BRANCH, ep_after_event, ep_edges, ep_energy,
                               ep_force, ep_force_path, ep_line, ep_turn_sign)
from ._kinematic_bumper import (kb_after_event, kb_branch_loss, kb_contact_state, kb_edges, kb_energy,
                                kb_force_path, kb_moved, kb_relax, kb_relax_horizon, kb_release_state,
                                kb_spring, kb_turn_sign)
from ._multilinear import (EXP_NORMAL_LIMIT, MIN_NORMAL, ml_branch, ml_branch_line, ml_energy, ml_relax,
                           ml_relax_horizon)

KELVIN_VOIGT = 0
HUNT_CROSSLEY = 1
JANKOWSKI = 2
MULTILINEAR = 3
ELASTIC_PLASTIC = 4
HERTZDAMP = 5
MULTILINEAR_KINEMATIC = 6  # MultilinearBumper(hysteresis="kinematic")
N_LAW_PARAMS = 10  # (MultilinearBumper: damping, branch count, 4 slopes, 3 breakpoints)
MAX_BRANCHES = 4
BRANCH_TIE = 1e-9  # relative: a compression this close to a breakpoint is at it (law_linear_branch)
# The compiled ``law_*`` functions read a law's parameters at ``p[o:o + N_LAW_PARAMS]``
# (``o`` an offset, so that the engine passes its phase record without slicing it: a
# slice costs a reference-count increment and decrement on every call).
AT_START = np.int64(0)  # the offset of a bare parameter array (typed: see engine/_layout.py)
# A bumper's law state is a block of N_LAW_STATE values at ``zs[zo:]`` (``zs`` the engine's state
# vector or phase record, ``zo`` the block's offset): ``zs[zo]`` an elastic-plastic law's
# offset or line, Hertzdamp's damping; ``zs[zo + 1:zo + 7]`` a kinematic multi-linear law's
# slips and slip directions (_kinematic_bumper.py).  Zero for a stateless law.
N_LAW_STATE = 7


@jit
def law_is_linear(law):
    """True when the force is linear in (d, dd) on each branch: every phase stays a linear ODE."""
    return law == KELVIN_VOIGT or law == MULTILINEAR or law == ELASTIC_PLASTIC or law == MULTILINEAR_KINEMATIC


@jit
def law_has_memory(law):
    """True when the law's state is memory of the path (as the isolator's slips are), not a
    function of the motion: what a test for a steady response must compare."""
    return law == ELASTIC_PLASTIC or law == MULTILINEAR_KINEMATIC


@jit
def law_contact_state(law, p, o, rate, zs, zo, d):
    """Set the law's state as a contact starts at compression ``d`` with compression rate
    ``rate`` (m/s, 0 at rest): Hertzdamp's damping ``xi_norm k / rate`` (0 at rest), an
    elastic-plastic law unloaded (0), a kinematic law's springs slipping back held."""
    if law == HERTZDAMP:
        zs[zo] = p[o + 1] * p[o] / rate if rate > 0.0 else 0.0
    elif law == MULTILINEAR_KINEMATIC:
        kb_contact_state(p, o, zs, zo, d)
    else:
        zs[zo] = 0.0


@jit
def law_release_state(law, p, o, zs, zo, d):
    """Set the law's state as the contact ends at compression ``d``: Hertzdamp keeps its damping
    (the bumper recovers with it), an elastic-plastic law is unloaded, a kinematic law's springs
    slipping in compression hold."""
    if law == ELASTIC_PLASTIC:
        zs[zo] = 0.0
    elif law == MULTILINEAR_KINEMATIC:
        kb_release_state(p, o, zs, zo, d)


@jit
def law_moved(law, p, o, zs, zo, d, in_contact):
    """Set the law's state once the compression has moved to ``d`` over a step: in contact
    (``in_contact`` 1.0; between the law's events), or out of it (0.0), recovering (:func:`law_relax`, never
    past the end
    of a piece of its recovery: law_relax_horizon)."""
    if law == MULTILINEAR_KINEMATIC:
        kb_moved(p, o, zs, zo, d, in_contact)


@jit
def law_linear_branch(law, p, o, d, dd, zs, zo):
    """``(stiffness N/m, damping N s/m, offset N, branch)`` of a linear law at compression
    ``d`` (rate ``dd``, state ``z``): ``F = stiffness d + offset + damping dd`` on that branch.
    An elastic-plastic law's branch is its state's.  At a multi-linear law's breakpoint the branch
    the compression is heading into (the sign of its rate ``dd``): "at" to ``BRANCH_TIE`` of the
    breakpoint, since an event instant is located to 1e-15 s (at 0.5 m/s, 1.5e-12 of a 0.3 mm
    breakpoint: with a tighter tie the branch's end fired again and again, ZENO)."""
    if law == KELVIN_VOIGT:
        return p[o], p[o + 1], 0.0, 0
    if law == ELASTIC_PLASTIC:
        k, r, j = ep_line(p, o, zs[zo])
        return k, 0.0, r, j
    if law == MULTILINEAR_KINEMATIC:  # (its branch: the hardening knots passed)
        _, k, r, m = kb_spring(p, o, zs, zo, d, dd)
        return k, p[o], r, m
    n = int(p[o + 1])
    j = ml_branch(p, o, d)[2]
    if j < n - 1 and dd > 0.0 and abs(d - p[o + 6 + j]) <= BRANCH_TIE * p[o + 6 + j]:
        j += 1
    elif j > 0 and dd < 0.0 and abs(d - p[o + 5 + j]) <= BRANCH_TIE * p[o + 5 + j]:
        j -= 1
    return law_branch_coefficients(law, p, o, j)


@jit
def law_branch_coefficients(law, p, o, j):
    """:func:`law_linear_branch`'s numbers for branch ``j`` of a stateless linear law."""
    if law == KELVIN_VOIGT:
        return p[o], p[o + 1], 0.0, 0
    k, offset, _ = ml_branch_line(p, o, j)
    return k, p[o], offset, j


@jit
def law_branch_edges(law, p, o, j, zs, zo):
    """Compressions (m) where branch ``j`` (state ``z``) of a linear law ends, below and above:
    -1.0 for none (the lowest branch starts at 0, where the contact ends anyway).  Crossing the
    lower one leads to state ``EP_UNLOAD``, the upper one to ``EP_YIELD`` (an elastic-plastic
    law's lines; :func:`law_after_event`)."""
    if law == ELASTIC_PLASTIC:
        return ep_edges(p, o, zs[zo])
    if law == MULTILINEAR_KINEMATIC:
        return kb_edges(p, o, j, zs, zo)
    if law != MULTILINEAR:
        return -1.0, -1.0
    n = int(p[o + 1])
    return (p[o + 5 + j] if j > 0 else -1.0), (p[o + 6 + j] if j < n - 1 else -1.0)


EDGE_DOWN_STATE = EP_UNLOAD  # the state code an event row of the lower and upper edge carries
EDGE_UP_STATE = EP_YIELD


@jit
def law_branch_loss(law, p, o, j, d0, d1, zs, zo):
    """Energy (J) the spring of branch ``j`` dissipates as the compression goes from ``d0`` to
    ``d1`` on it (a dashpot's is apart): an elastic-plastic law's yield line dissipates
    ``(k1 - k2) dy`` per metre (its force minus the rate ``k2 d`` of the energy it stores);
    a kinematic law's slipping springs ``b_i delta_i`` each; every other branch is elastic."""
    if law == ELASTIC_PLASTIC and j == EP_YIELD_BRANCH:
        return (p[o] - p[o + 1]) * p[o + 2] * (d1 - d0)
    if law == MULTILINEAR_KINEMATIC:
        return kb_branch_loss(p, o, zs, zo, d0, d1)
    return 0.0


@jit
def law_turn_sign(law, p, o, zs, zo):
    """+1 (or -1) when the branch of the state ends where the compression rate, positive (or
    negative) on it, crosses zero: an elastic-plastic law's lines, a kinematic law's slipping
    springs.  0 for the other branches."""
    if law == ELASTIC_PLASTIC:
        return ep_turn_sign(zs[zo])
    if law == MULTILINEAR_KINEMATIC:
        return kb_turn_sign(p, o, zs, zo)
    return 0.0


@jit
def law_after_event(law, p, o, zs, zo, d, code):
    """Set the law's state after one of its branch events at compression ``d``: ``code`` is the
    event row's (:data:`EDGE_DOWN_STATE`, :data:`EDGE_UP_STATE`, or 0 for a turn).  A stateless
    law has none to set."""
    if law == ELASTIC_PLASTIC:
        zs[zo] = ep_after_event(p, o, zs[zo], d, code)
    elif law == MULTILINEAR_KINEMATIC:
        kb_after_event(p, o, zs, zo, d, code)


@jit
def law_switches_at_rest(law):
    """True when the force changes form where the compression rate changes sign (Jankowski's
    dashpot works on the approach only): the engine ends a numerical step there."""
    return law == JANKOWSKI


@jit
def law_force(law, p, o, d, dd, zs, zo):
    """Force of the bumper at compression ``d`` (m), rate ``dd`` (m/s) and law state ``zs[zo:]``.

    Returns ``(force, elastic_part, dforce/dd, dforce/d(dd))``.
    """
    k, c = p[o], p[o + 1]
    if law == KELVIN_VOIGT:
        return k * d + c * dd, k * d, k, c
    if law == ELASTIC_PLASTIC:
        f = ep_force(p, o, d, zs[zo])
        return f, f, ep_line(p, o, zs[zo])[0], 0.0
    if law == MULTILINEAR_KINEMATIC:
        f, slope, _, _ = kb_spring(p, o, zs, zo, d, dd)
        return f + k * dd, f, slope, k
    if law == MULTILINEAR:
        force, slope, _, _ = ml_branch(p, o, d)
        return force + k * dd, force, slope, k
    dpos = d if d > 0.0 else 0.0
    n = p[o + 2]
    if law == HERTZDAMP:  # Hunt-Crossley with the damping of this contact
        c = zs[zo]
    dn = dpos**n
    if dpos > 0.0:
        slope = n * dpos ** (n - 1.0)
    else:
        slope = 1.0 if n == 1.0 else 0.0
    if law == HUNT_CROSSLEY or law == HERTZDAMP:
        return dn * (k + c * dd), k * dn, slope * (k + c * dd), c * dn
    # JANKOWSKI: the dashpot c d^((n-1)/2) on the approach only
    if dd <= 0.0 or dpos <= 0.0:
        return k * dn, k * dn, k * slope, 0.0
    root = dpos ** (0.5 * (n - 1.0))
    return (k * dn + c * root * dd, k * dn, k * slope + 0.5 * (n - 1.0) * c * root / dpos * dd, c * root)


@jit
def law_energy(law, p, d, zs, zo):
    """Elastic energy stored at compression ``d`` (J), law state ``zs[zo:]``."""
    if law == KELVIN_VOIGT:
        return 0.5 * p[0] * d * d
    if law == MULTILINEAR:
        return ml_energy(p, d)
    if law == ELASTIC_PLASTIC:
        return ep_energy(p, AT_START, d, zs[zo])
    if law == MULTILINEAR_KINEMATIC:
        return kb_energy(p, AT_START, d, zs, zo)
    dpos = d if d > 0.0 else 0.0  # (Hunt-Crossley, Jankowski and Hertzdamp: the spring k d^n)
    return p[0] * dpos ** (p[2] + 1.0) / (p[2] + 1.0)


@jit
def law_relax(law, p, o, d0, tau, zs, zo):
    """Free recovery of a massless bumper: compression and its rate ``tau`` s after ``d0``
    (law state ``zs[zo:]``)."""
    if d0 <= 0.0:
        return 0.0, 0.0
    if law == KELVIN_VOIGT:
        if p[o + 1] <= 0.0:
            return 0.0, 0.0
        rate = p[o] / p[o + 1]
        x = rate * tau
        # relaxed below the smallest normal double: exactly 0 (else exp() takes its slow
        # underflow path, and subnormal arithmetic slows every event value after it)
        if x > EXP_NORMAL_LIMIT:
            return 0.0, 0.0
        d = d0 * math.exp(-x)
        if d < MIN_NORMAL:
            return 0.0, 0.0
        return d, -rate * d
    if law == MULTILINEAR:
        return ml_relax(p, o, d0, tau)
    if law == MULTILINEAR_KINEMATIC:
        return kb_relax(p, o, d0, tau, zs, zo)
    c = zs[zo] if law == HERTZDAMP else p[o + 1]
    if law == JANKOWSKI or law == ELASTIC_PLASTIC or c <= 0.0:  # (no dashpot: back at once)
        return 0.0, 0.0
    speed = p[o] / c
    d = d0 - speed * tau
    if d <= 0.0:
        return 0.0, 0.0
    return d, -speed


@jit
def law_relax_horizon(law, p, o, d0, zs, zo):
    """Time (s) until the free recovery from ``d0`` changes form (a multi-linear law's next
    branch); inf for the laws whose recovery is one formula."""
    if law == MULTILINEAR:
        return ml_relax_horizon(p, o, d0)
    if law == MULTILINEAR_KINEMATIC:
        return kb_relax_horizon(p, o, d0, zs, zo)
    return math.inf


@jit
def law_release(law, p, o, d, dd, ddd, zs, zo):
    """A smooth function that crosses zero downwards when the force would turn into a pull.

    Returns ``(value, rate)`` for compression ``d``, rate ``dd``, acceleration ``ddd`` and law
    state ``zs[zo:]``.
    """
    if law == KELVIN_VOIGT:
        return p[o] * d + p[o + 1] * dd, p[o] * dd + p[o + 1] * ddd
    if law == JANKOWSKI:  # never pulls: the contact ends with the compression
        return 1.0, 0.0
    if law == ELASTIC_PLASTIC:  # (never pulls either; the engine uses its phase's branch and this
        # for the size of its terms: the branch's, as on the unloading line K2 may be 1e-9 K1)
        k, r, _ = ep_line(p, o, zs[zo])
        return k * d + abs(r), k * dd
    if law == MULTILINEAR_KINEMATIC:
        force, slope, _, _ = kb_spring(p, o, zs, zo, d, dd)
        return force + p[o] * dd, slope * dd + p[o] * ddd
    if law == MULTILINEAR:
        force, slope, _, _ = ml_branch(p, o, d)
        return force + p[o] * dd, slope * dd + p[o] * ddd
    c = zs[zo] if law == HERTZDAMP else p[o + 1]
    return p[o] + c * dd, c * ddd


@jit_entry
def law_force_many(law, p, d, dd, out):
    """``law_force`` at each ``(d[i], dd[i])`` into ``out[i]`` (N): arrays of one shape (n,).
    A hysteretic law's state follows the path from the unloaded state, sample by sample."""
    if law == ELASTIC_PLASTIC:
        ep_force_path(p, AT_START, d, out)
        return
    if law == MULTILINEAR_KINEMATIC:
        kb_force_path(p, AT_START, d, dd, out)
        return
    zs = np.zeros(N_LAW_STATE)
    for i in range(d.size):
        out[i] = law_force(law, p, AT_START, d[i], dd[i], zs, AT_START)[0]
