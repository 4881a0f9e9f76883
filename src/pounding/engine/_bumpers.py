"""The bumpers' event rows of a phase, and what of their laws the kernel's steps must respect."""

from __future__ import annotations

import math

from .._jit import jit
from ..model.contact_laws import (AT_START, EDGE_DOWN_STATE, EDGE_UP_STATE, law_branch_edges, law_is_linear,
                                  law_relax_horizon, law_switches_at_rest, law_turn_sign)
from ._layout import (ACT_CONTACT, ACT_LAW_BRANCH, ACT_RELEASE, E_ACTION, E_ALPHA, E_BETA, E_DIR, E_GAMMA,
                      E_INDEX, E_KIND, E_SIDE, EV_COLS, DEF_L, DEF_R, IN_L, IN_R, KIND_LINEAR, KIND_RELEASE,
                      P_JBL, P_JBR, P_LAWL, P_LAWR, P_NLL, P_NLR, SIDE_L, SIDE_NONE, SIDE_R, ZL_AT, ZR_AT)


@jit
def bumper_events(st, ph, sy, evs, n):
    """Append the bumpers' event rows to ``evs`` from row ``n`` on; return the new count.

    Out of contact, the contact start against the relaxing surface; in contact, the compression
    back to zero and the law's force-based release, and a linear law's branch ends: where the
    compression leaves the branch (a multi-linear law's breakpoints, an elastic-plastic law's
    lines), or where the compression rate turns (an elastic-plastic law leaving a line).
    """
    if not sy.has_b:
        return n
    gap_l, gap_r, law_l, p_l, law_r, p_r = sy.gap_l, sy.gap_r, sy.law_l, sy.p_l, sy.law_r, sy.p_r
    for side in (SIDE_L, SIDE_R):
        sign = -1.0 if side == SIDE_L else 1.0
        gap = gap_l if side == SIDE_L else gap_r
        in_contact = st[IN_L] if side == SIDE_L else st[IN_R]
        law = law_l if side == SIDE_L else law_r
        if in_contact != 0.0 and law_is_linear(law):  # its branch's ends (compression x = sign D - gap)
            zo = ZL_AT if side == SIDE_L else ZR_AT
            p = p_l if side == SIDE_L else p_r
            lower, upper = law_branch_edges(law, p, AT_START, int(ph[P_JBL] if side == SIDE_L else ph[P_JBR]),
                                            st, zo)
            turn = law_turn_sign(law, p, AT_START, st, zo)
            if turn != 0.0:  # the compression rate sign V (of sign ``turn`` on the branch) crossing zero
                row = evs[n]
                row[E_KIND] = KIND_LINEAR
                row[E_ALPHA] = 0.0
                row[E_BETA] = 0.0
                row[E_GAMMA] = turn * sign
                row[E_SIDE] = SIDE_NONE  # (a velocity: rounded as the isolator's reversals are)
                row[E_ACTION] = ACT_LAW_BRANCH
                row[E_INDEX] = side
                row[E_DIR] = 0.0
                n += 1
            for edge, up in ((lower, False), (upper, True)):
                if edge < 0.0:
                    continue
                row = evs[n]
                row[E_KIND] = KIND_LINEAR
                row[E_ALPHA] = (gap + edge) if up else -(gap + edge)  # upper - x, or x - lower
                row[E_BETA] = -sign if up else sign
                row[E_GAMMA] = 0.0
                row[E_SIDE] = side
                row[E_ACTION] = ACT_LAW_BRANCH
                row[E_INDEX] = side
                row[E_DIR] = EDGE_UP_STATE if up else EDGE_DOWN_STATE
                n += 1
        row = evs[n]
        row[E_SIDE] = SIDE_NONE
        row[E_GAMMA] = 0.0
        row[E_INDEX] = side
        row[E_DIR] = 0.0
        row[E_KIND] = KIND_LINEAR
        if in_contact == 0.0:
            # surface at sign*(gap + relaxing compression): g = gap + d(t) - sign*D
            row[E_ALPHA] = gap
            row[E_BETA] = -sign
            row[E_SIDE] = side
            row[E_ACTION] = ACT_CONTACT
            n += 1
        else:
            # compression sign*D - gap back to zero, or the law's force-based release (the side
            # given so that both are rounded against the run's lengths, as the contact start)
            row[E_ALPHA] = -gap
            row[E_BETA] = sign
            row[E_ACTION] = ACT_RELEASE
            row[E_SIDE] = side
            n += 1
            row = evs[n]
            for j in range(EV_COLS):
                row[j] = evs[n - 1, j]
            row[E_KIND] = KIND_RELEASE
            n += 1
    return n


@jit
def law_switches(ph):
    """True when a bumper in contact has a law whose form changes with the sign of its rate."""
    return ((ph[P_NLL] != 0.0 and law_switches_at_rest(int(ph[P_LAWL])))
            or (ph[P_NLR] != 0.0 and law_switches_at_rest(int(ph[P_LAWR]))))


@jit
def relax_horizon(st, sy):
    """Time (s) until a bumper relaxing out of contact reaches the end of its law's branch
    (inf when none does): the contact function ``gap + d(t) - sign D`` is smooth only up to
    there, and a sub-interval ending there keeps one law of recovery in each (a multi-linear
    bumper leaving its steep branch for a flat one recovers at constant speed and caught a
    mass that had left it, inside one sub-interval, unseen)."""
    out = math.inf
    if st[IN_L] == 0.0 and st[DEF_L] > 0.0:
        out = min(out, law_relax_horizon(sy.law_l, sy.p_l, AT_START, st[DEF_L], st, ZL_AT))
    if st[IN_R] == 0.0 and st[DEF_R] > 0.0:
        out = min(out, law_relax_horizon(sy.law_r, sy.p_r, AT_START, st[DEF_R], st, ZR_AT))
    return out
