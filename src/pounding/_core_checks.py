"""The checks of what :func:`pounding._core.system` hands the compiled core: its pairs, levers, elements and
contact slots (a ``ValueError`` is a caller's bug: the public functions check what users give before)."""

from __future__ import annotations

import math
from typing import Any

def check_pair(i: int, j: int, n: int, what: str) -> None:
    """A ValueError unless dofs ``i`` and ``j`` are two of the ``n`` dofs (``j`` -1: the ground)."""
    if not (0 <= i < n and (j == -1 or (0 <= j < n and j != i))):
        raise ValueError(f"{what}: the pair ({i}, {j}) is not two of the {n} dofs (or one and the "
                         "ground, -1)")


def check_levers(p: Any, n: int, what: str) -> bool:
    """A ValueError unless pair ``p``'s levers are other dofs of the ``n`` with finite arms that leave it a
    motion; whether it has any."""
    weights: dict[int, float] = {}
    for end, lever, arm in (("i", p.lever_i, p.arm_i_m), ("j", p.lever_j, p.arm_j_m)):
        own = p.i if end == "i" else p.j
        side = 1.0 if end == "i" else -1.0
        if own >= 0:
            weights[own] = weights.get(own, 0.0) + side
        if lever == -1:
            continue
        if not (0 <= lever < n and lever != own and own != -1 and math.isfinite(arm)):
            raise ValueError(f"{what}: the lever of end {end} ({lever}, arm {arm}) is not another of the "
                             f"{n} dofs than {own} with a finite arm (the ground's end has none)")
        weights[lever] = weights.get(lever, 0.0) + side * arm
    if not any(weights.values()):
        raise ValueError(f"{what}: its levers cancel its ends (lever_i {p.lever_i}, arm_i_m {p.arm_i_m}; "
                         f"lever_j {p.lever_j}, arm_j_m {p.arm_j_m}): its relative displacement is 0 "
                         "whatever the motion; give levers and arms that leave it a motion")
    return p.lever_i != -1 or p.lever_j != -1


def check_elements(elements: list, n: int, element_type: type) -> None:
    """A ValueError unless ``elements`` are hysteretic elements (``element_type``) the core can take on ``n``
    dofs: their pairs, levers, backbones, rules, friction and Bouc-Wen springs (a mate each other's)."""
    for e, el in enumerate(elements):
        if not isinstance(el, element_type):
            raise ValueError(f"element {e}: an Element, got {type(el).__name__}")
        check_pair(el.i, el.j, n, f"element {e}")
        if check_levers(el, n, f"element {e}") and el.rule == 2:
            raise ValueError(f"element {e}: a friction element on a lever is not supported yet (its tie "
                             "holds a dof, not a point): place it on a dof of its own")
        surfaces = len(el.surface_friction_n)
        if surfaces:  # (a series of friction surfaces: a slope, a travel and a friction each)
            if (el.rule != 2 or surfaces < 2 or len(el.slopes) != surfaces or len(el.breaks) != surfaces
                    or el.friction_n != 0.0 or el.friction_rate_s_m != 0.0 or el.j != -1
                    or any(el.bw) or min(el.slopes) <= 0.0 or min(el.breaks) <= 0.0
                    or min(el.surface_friction_n) <= 0.0
                    or len(el.surface_ring_n_m) not in (0, surfaces)
                    or not all(0.0 <= r < math.inf for r in el.surface_ring_n_m)):
                raise ValueError(f"element {e}: surfaces in series are the friction rule's (2), on the "
                                 "ground, at least two, each a slope > 0, a travel > 0 (inf: no ring), a "
                                 "friction > 0 and a finite ring stiffness >= 0 (0: rigid; none: all rigid); "
                                 "no friction_n, velocity dependence or Bouc-Wen spring beside them")
            continue
        if len(el.surface_ring_n_m):
            raise ValueError(f"element {e}: ring stiffnesses are a series of surfaces' (surface_friction_n)")
        if len(el.slopes) < 1 or len(el.breaks) != len(el.slopes) - 1 or el.rule not in (0, 1, 2):
            raise ValueError(f"element {e}: {len(el.slopes)} slopes need {len(el.slopes) - 1} breaks, "
                             "rule 0, 1 or 2")
        preslip = (el.rule == 0 and el.friction_rate_s_m > 0.0 and len(el.slopes) == 2
                   and not any(el.bw))  # (a sliding bearing's pre-slip with a velocity dependence)
        if (el.rule == 2 or preslip) != (el.friction_n > 0.0) or (
                el.rule == 2 and (len(el.slopes) != 1 or el.j != -1 or any(el.bw))):
            raise ValueError(f"element {e}: the friction rule (2) is an isolator's (on the ground), of one "
                             "slope, a friction force > 0 and no Bouc-Wen spring; a pre-slip's velocity "
                             "dependence (rule 0 of two slopes) has its friction at rest too; no other rule "
                             "has a friction force")
        if preslip and not (el.slopes[0] > el.slopes[1] and el.breaks[0] > 0.0 and math.isclose(
                el.friction_n, (el.slopes[0] - el.slopes[1]) * el.breaks[0], rel_tol=1e-9)):
            at = (el.slopes[0] - el.slopes[1]) * el.breaks[0]
            raise ValueError(f"element {e}: a pre-slip's friction at rest is the force at which it slips, "
                             f"(slopes[0] - slopes[1]) breaks[0] = {at!r} N, its first slope the stiffer; "
                             f"got friction_n {el.friction_n!r}")
        if el.friction_rate_s_m < 0.0 or (el.friction_rate_s_m > 0.0) != (el.friction_fast_n > 0.0) or (
                el.friction_rate_s_m > 0.0 and el.rule != 2 and el.bw_mate == -1 and not preslip):
            raise ValueError(f"element {e}: a velocity-dependent friction is the friction rule's, a "
                             "pre-slip's (rule 0 of two slopes) or a friction circle's (a bidirectional "
                             "Bouc-Wen spring, bw_mate), with a fast friction > 0 and a rate > 0 together")
    for e, el in enumerate(elements):
        if el.bw_plastic and el.bw[0] == 0.0:
            raise ValueError(f"element {e}: a plastic circle (bw_plastic) is a Bouc-Wen spring's: give its "
                             "numbers (bw)")
        if el.bw_plastic and el.bw_mate == -1:
            raise ValueError(f"element {e}: a plastic circle (bw_plastic) is a bidirectional spring's: give "
                             "its mate (bw_mate)")
    for e, el in enumerate(elements):  # (a bidirectional Bouc-Wen spring: two elements, each the other's)
        mate = el.bw_mate
        if mate == -1:
            continue
        if not (0 <= mate < len(elements) and mate != e and elements[mate].bw_mate == e and el.bw[0] != 0.0
                and list(elements[mate].bw) == list(el.bw)
                and (elements[mate].friction_fast_n, elements[mate].friction_rate_s_m)
                == (el.friction_fast_n, el.friction_rate_s_m)):
            raise ValueError(f"element {e}: its Bouc-Wen mate {mate} is another element whose mate it is, "
                             "both with the same Bouc-Wen numbers and velocity dependence")
        if el.bw_plastic != elements[mate].bw_plastic or (el.bw_plastic and not (
                el.rule == 0 and el.bw[2] == 1.0 and el.bw[3] + el.bw[4] == 1.0)):
            raise ValueError(f"element {e}: a plastic circle (bw_plastic) is both mates', on the kinematic "
                             "rule (0), with a = 1 and beta + gamma = 1")


def check_contacts(contacts: list, n: int, slot_type: type, law_ids: dict) -> None:
    """A ValueError unless ``contacts`` are contact slots (``slot_type``) the core can take on ``n`` dofs:
    their pairs, levers, signs and law ids (``law_ids``: the core's)."""
    for c, slot in enumerate(contacts):
        if not isinstance(slot, slot_type):
            raise ValueError(f"contact {c}: a ContactSlot, got {type(slot).__name__}")
        check_pair(slot.i, slot.j, n, f"contact {c}")
        if slot.sign not in (-1.0, 1.0) or slot.law not in law_ids.values():
            raise ValueError(f"contact {c}: sign +-1 and a law id of LAW_IDS")
        if slot.ring_y is not None:  # (a ring's wall: its point's pair along y, its place, the radius)
            check_pair(slot.ring_y.i, slot.ring_y.j, n, f"contact {c}'s ring_y")
            check_levers(slot.ring_y, n, f"contact {c}'s ring_y")
            place = (slot.ring_px_m, slot.ring_py_m, slot.ring_radius_m)
            if slot.sign != 1.0 or not all(math.isfinite(v) for v in place) or not slot.ring_radius_m > 0.0:
                raise ValueError(f"contact {c}: a ring's wall has sign +1, a finite place and a radius > 0")
        if check_levers(slot, n, f"contact {c}") and slot.law == law_ids["rigid"] and slot.j >= 0:
            raise ValueError(f"contact {c}: a rigid stop on levers between two dofs is not supported yet "
                             "(its impulse's weights would add where a lever is the other end): put its wall "
                             "on the ground, or use a compliant law")
