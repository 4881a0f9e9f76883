"""A building in plan (:class:`pounding.model.plan.PlanBuilding`) assembled into the core's system
(:func:`assemble_plan`): each floor's x, y and rotation, every bearing's axes and every multi-linear frame a
hysteretic element on levers (a point of a floor in plan moves as a dof plus an arm times its rotation), the
linear frames in the springs, the moat's walls each struck at the floor's two corners on its side; the
ground's two components along x and y; where each part went (:class:`PlanAssembly`).

Tracked (their exact extrema): each bearing's displacement along x and along y (the two make a vector, whose
exact longest a run finds), each frame's drift at its place, each corner of the moat's floor (the base's
without a moat) along x and along y (its clearance to the walls, or the moat's demand), and each floor's
centre of mass along x and y (a vector too)."""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from .. import _core
from ..model.isolator import HYSTERESIS_RULES
from ..model.plan import PlanBuilding, point_weights
from ..model.moats import MOAT_SIDES, CircularMoat
from ..model.plan_parts import Bearing
from .assembly import BoucWenSprings, HystereticElement, Pair, bouc_wen_springs


RING_SIDE = len(MOAT_SIDES)  # (a circular moat's contacts' side: after the rectangle's four walls)


class PlanAssembly(NamedTuple):
    """A building in plan as the core's system, and where each part went.

    ``element_names[e]``: ``("bearing", b, axis)`` or ``("frame", f, axis)``; ``contacts[c]``: ``(side,
    corner)``, the moat's wall (index of :data:`~pounding.model.moats.MOAT_SIDES`, :data:`RING_SIDE` a
    circular moat's ring) and the floor's corner (:meth:`Floor.corners_m`'s order); ``tracked[q]``:
    ``("bearing", b, axis)``, ``("frame", f, axis)`` or ``("corner", k, axis)`` or ``("centre", level,
    axis)``; ``vectors[v]``: bearing ``v``'s x and y (indices into ``tracked``), then each floor's centre's,
    then a ring's corners' (offset by their places: their distances from its centre);
    ``contact_tracks[c]``: contact ``c``'s corner along its axis (an index into ``tracked``; a ring's: x);
    ``corner_tracks[k][axis]``: corner ``k``'s along each axis (two corners on one edge move alike across it:
    one tracked pair serves both, named by the first)."""

    system: _core.System
    element_names: tuple
    contacts: tuple
    tracked: tuple
    vectors: tuple
    contact_tracks: tuple
    masses: np.ndarray          # (3 n,): kg, kg, kg m^2 per floor
    k_fast: np.ndarray          # (3 n, 3 n): the linear springs and every element at its stiffest slope
    c_all: np.ndarray           # (3 n, 3 n): every dashpot
    contact_weights: np.ndarray  # (contacts, 3 n): each contact's corner along its axis, as weights
    tracked_weights: np.ndarray  # (tracked, 3 n): each tracked pair's displacement, as weights
    element_weights: np.ndarray  # (elements, 3 n): each element's displacement, as weights
    pairs: tuple                 # each contact slot's assembly.Pair (its dofs without their levers)
    elements: tuple              # each element's assembly.HystereticElement (the same)
    layout: dict                 # the system's ``layout``, read once (as an Assembly's); read-only
    dofs: tuple = ()             # ((0, 1, ..., 3 n - 1),): the floors' dofs, as a State holds them
    bouc_wen: BoucWenSprings = BoucWenSprings(np.zeros((0, _core.LAYOUT["BW_PARAMS"])), ())  # (its springs)
    corner_tracks: tuple = ()    # (4, 2): each corner's tracked pair along x and y
    # a circular moat's (empty with four walls: a building has one or the other): each contact's ring as (its
    # point's y weights (3 n,), its place from the ring's centre (m, m), the radius m), contact by contact;
    # each corner's vector from the centre (an index into vectors)
    rings: tuple = ()
    ring_vectors: tuple = ()


def _levers(building: PlanBuilding, storey: int, axis: int, p: tuple[float, float],
            ground: bool = False) -> dict:
    """A line at point ``p`` of floor ``storey`` along ``axis`` against the same point of the floor below
    (the ground below the base; ``ground``: against the ground whatever the floor, a moat's wall) as the
    core's pair: its dofs, levers and arms (no lever for an arm of 0)."""
    floors = building.placed_floors
    out = {}
    for end, level in (("i", storey), ("j", -1 if ground else storey - 1)):
        if level < 0:
            out[end] = -1
            continue
        (dof, _), (lever, arm) = point_weights(floors[level], level, axis, p)
        out[end] = dof
        if arm != 0.0:
            out[f"lever_{end}"], out[f"arm_{end}_m"] = lever, arm
    return out


def _point(floor: Any, level: int, axis: int, p: tuple[float, float], n: int) -> np.ndarray:
    """Point ``p`` of floor ``level``'s displacement along ``axis`` as weights on the ``n`` dofs."""
    w = np.zeros(n)
    for dof, v in point_weights(floor, level, axis, p):
        w[dof] += v
    return w


def assemble_plan(building: PlanBuilding) -> PlanAssembly:
    """The core's system of a building in plan and where each part went (the module's docstring)."""
    n = building.n_dofs
    masses = np.diag(building.mass_matrix).copy()
    k0, c0 = np.zeros((n, n)), np.zeros((n, n))
    k_fast, c_all = np.zeros((n, n)), np.zeros((n, n))  # (the elements' stiffest slopes and dashpots)
    elements, element_names, tracked, tracked_names, tracked_weights = [], [], [], [], []
    element_weights, pairs = [], []
    for storey, axis, index, at, part in building.lines():
        p = (0.0, at) if axis == 0 else (at, 0.0)
        pair = _levers(building, storey, axis, p)
        kind = "bearing" if isinstance(part, Bearing) else "frame"
        w = building.line_weights(storey, axis, at)
        if kind == "frame" and part.is_linear:
            k0 += part.stiffness_n_m * np.outer(w, w)
            c0 += part.damping_n_s_m * np.outer(w, w)
        elif kind == "frame":
            c0 += part.damping_n_s_m * np.outer(w, w)
            k_fast += max(part.stiffness_n_m, *part.slopes_after_n_m) * np.outer(w, w)
            elements.append(_core.element(c_d=0.0, slopes=[part.stiffness_n_m, *part.slopes_after_n_m],
                                          breaks=list(part.breakpoints_m),
                                          rule=HYSTERESIS_RULES.index(part.hysteresis), **pair))
            element_names.append((kind, index, axis))
            element_weights.append(w)
        else:
            slopes, breaks, rule, bw = part.kernel_arrays(axis)
            k_bw = bw[0] * bw[2] / bw[1] if bw[0] != 0.0 else 0.0  # (a Bouc-Wen spring's initial stiffness)
            k_fast += (float(np.max(np.abs(slopes))) + k_bw) * np.outer(w, w)
            c_all += part.laws[axis].damping_n_s_m * np.outer(w, w)
            # (a bidirectional spring: the bearing's x and y elements, each the other's mate)
            mate = len(elements) + (1 if axis == 0 else -1) if part.coupled else -1
            elements.append(_core.element(c_d=part.laws[axis].damping_n_s_m, slopes=slopes, breaks=breaks,
                                          rule=int(rule), bw=bw if bw[0] != 0.0 else (), bw_mate=mate,
                                          bw_plastic=part.plastic_circle, **part.kernel_friction, **pair))
            element_names.append((kind, index, axis))
            element_weights.append(w)
        tracked.append(_core.tracked_pair(**pair))
        tracked_names.append((kind, index, axis))
        tracked_weights.append(w)
    vectors = tuple((tracked_names.index(("bearing", b, 0)), tracked_names.index(("bearing", b, 1)))
                    for b in range(len(building.bearings)))
    contacts, contact_names, contact_tracks, contact_weights = [], [], [], []
    moat = building.moat
    level = 0 if moat is None else moat.level  # (without a moat: the base's corners, its demand on one)
    floor, corners = building.placed_floors[level], building.floors[level].corners_m()
    edges: dict = {}  # (a corner's motion along x is x - (p_y - c_y) theta: its edge's across x, p_y)
    corner_tracks = []
    for k, corner in enumerate(corners):  # (each corner along x and y: its clearance to the walls)
        row = []
        for axis in (0, 1):
            edge = (axis, corner[1 - axis])
            if edge not in edges:
                tracked.append(_core.tracked_pair(**_levers(building, level, axis, corner, ground=True)))
                tracked_names.append(("corner", k, axis))
                tracked_weights.append(_point(floor, level, axis, corner, n))
                edges[edge] = len(tracked) - 1
            row.append(edges[edge])
        corner_tracks.append(tuple(row))
    rings, ring_vectors, offsets = [], [], [(0.0, 0.0)] * len(vectors)
    if isinstance(moat, CircularMoat):  # (each corner against the ring, along its normal)
        radius = moat.radius_m(building.floors[moat.level])
        for k, corner in enumerate(corners):
            pair = _levers(building, moat.level, 0, corner, ground=True)
            along_y = _levers(building, moat.level, 1, corner, ground=True)
            pairs.append(Pair(pair["i"], pair["j"], 1.0, moat.gap_m, moat.law))
            contacts.append(_core.contact_slot(
                sign=1.0, gap_m=moat.gap_m, law=moat.law.LAW_ID, params=moat.law.params(), **pair,
                ring_y=_core.tracked_pair(**along_y), ring_at_m=corner, ring_radius_m=radius))
            contact_names.append((RING_SIDE, k))
            contact_tracks.append(corner_tracks[k][0])
            contact_weights.append(_point(floor, moat.level, 0, corner, n))
            rings.append((_point(floor, moat.level, 1, corner, n), float(corner[0]), float(corner[1]),
                          radius))
            ring_vectors.append(len(vectors) + k)
        vectors += tuple(corner_tracks)
        offsets += [tuple(map(float, corner)) for corner in corners]
    elif moat is not None:
        for side, (axis, sign) in enumerate(((0, -1.0), (0, 1.0), (1, -1.0), (1, 1.0))):
            for k, corner in enumerate(corners):
                if corner[axis] * sign < 0.0:  # (the two corners on that wall's side)
                    continue
                pair = _levers(building, moat.level, axis, corner, ground=True)
                pairs.append(Pair(pair["i"], pair["j"], sign, float(moat.gap_m[side]), moat.law))
                contacts.append(_core.contact_slot(sign=sign, gap_m=moat.gap_m[side], law=moat.law.LAW_ID,
                                                   params=moat.law.params(), **pair))
                contact_names.append((side, k))
                contact_tracks.append(corner_tracks[k][axis])
                contact_weights.append(_point(floor, moat.level, axis, corner, n))
    for level in range(building.n_levels):  # (each floor's centre of mass in plan: its x and y, a vector)
        for axis in (0, 1):
            tracked.append(_core.tracked_pair(i=3 * level + axis, j=-1))
            tracked_names.append(("centre", level, axis))
            tracked_weights.append(np.eye(n)[3 * level + axis])
    centres = tuple((tracked_names.index(("centre", level, 0)), tracked_names.index(("centre", level, 1)))
                    for level in range(building.n_levels))
    # (the floors' centres after the bearings, then a ring's corners: each vector's place in a run's norms)
    ring_vectors = [v + len(centres) for v in ring_vectors]
    nb = len(building.bearings)
    vectors = vectors[:nb] + centres + vectors[nb:]
    offsets = offsets[:nb] + [(0.0, 0.0)] * len(centres) + offsets[nb:]
    influence = np.zeros((n, 2))
    influence[0::3, 0] = 1.0
    influence[1::3, 1] = 1.0
    system = _core.system(masses, k0, c0, elements, bool(contacts), contacts, tuple(tracked),
                          influence=influence, vectors=vectors,
                          vector_offsets_m=np.array(offsets).reshape(len(vectors), 2) if rings else None)
    return PlanAssembly(system, tuple(element_names), tuple(contact_names), tuple(tracked_names), vectors,
                        tuple(contact_tracks), masses, k0 + k_fast, c0 + c_all,
                        np.array(contact_weights).reshape(len(contacts), n), np.array(tracked_weights),
                        np.array(element_weights).reshape(len(elements), n), tuple(pairs),
                        tuple(HystereticElement(el.i, el.j, list(el.slopes), list(el.breaks), el.rule)
                              for el in elements), system.layout, (tuple(range(n)),),
                        bouc_wen_springs(elements),
                        tuple(corner_tracks), tuple(rings), tuple(ring_vectors))


__all__ = ["RING_SIDE", "PlanAssembly", "assemble_plan"]
