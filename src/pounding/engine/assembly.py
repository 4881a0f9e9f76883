"""One structure, or two side by side, assembled into the core's system (:func:`assemble`): their levels'
dofs (a fixed base's level 0 is the ground), the storeys' springs and dashpots, the hysteretic elements, and
the contact slots, each named (:class:`Pair`, :class:`HystereticElement`); where each part went
(:class:`Assembly`).

The core's contact slots are the walls' sides in order: wall ``w``'s left side is slot ``2 w``
(sign -1: it stops negative displacements), its right side slot ``2 w + 1``; then the links.
"""

from __future__ import annotations

import functools
from typing import Any, NamedTuple

import numpy as np

from .. import _core
from .._checks import instance_of
from ..model.adjacent import Adjacent
from ..model.oscillator import Oscillator
from ..model.plan import PlanBuilding
from ..model.structure import Structure
from .layout import P_MAX, P_MIN, X_D_MAX, X_D_MIN


class Pair(NamedTuple):
    """A contact slot of an assembly: dof ``i`` against dof ``j`` (-1: the ground), open while
    ``sign (x_i - x_j) <= gap_m``, and its law."""

    i: int
    j: int
    sign: float
    gap_m: float
    law: Any


class HystereticElement(NamedTuple):
    """A hysteretic element of an assembly (an isolator, a multi-linear storey): between dofs ``i`` and
    ``j`` (-1: the ground), its backbone's ``slopes`` (N/m) and ``breaks`` (m), its ``rule`` (the core's
    code: elastic, kinematic, friction) and, for friction surfaces in series, each one's ring stiffness
    (N/m; empty or 0: rigid) and friction (N)."""

    i: int
    j: int
    slopes: list
    breaks: list
    rule: int
    rings: tuple = ()
    frictions: tuple = ()


class Assembly(NamedTuple):
    """One structure, or two side by side, as the core's system, and where each part went.

    ``dofs[b][level]``: the core's dof of structure ``b``'s level (-1: the ground, a fixed base's level
    0); ``isolator[b]``: the element of its isolator (-1: a fixed base); ``slots[c]``: what contact slot
    ``c`` is, ``(b, wall, side)`` for a structure's wall (side 0 left, 1 right) or ``(-1, link, 0)``;
    ``layout``: ``system.layout`` as read once, shared by every run of a kept assembly (never written to)."""

    system: _core.System
    dofs: tuple
    isolator: tuple
    slots: tuple
    stands: tuple          # per structure: its stands' dofs, (wall, side, dof) each
    masses: np.ndarray     # (n,) kg
    k_fast: np.ndarray     # (n, n) N/m: the linear springs and every element at its stiffest slope
    c_all: np.ndarray      # (n, n) N s/m: the dashpots
    pairs: tuple           # each contact slot's Pair
    elements: tuple        # each hysteretic element's HystereticElement, in the core's order
    bouc_wen: "BoucWenSprings"  # each Bouc-Wen spring's numbers and mate, by its z's slot
    layout: dict           # the system's ``layout``, read once (the core makes a new dict each time)
    contact_tracks: tuple = ()  # each contact slot's tracked pair (its extrema), -1: against the ground


def clearances(asm: Assembly, run: _core.RunOutput) -> np.ndarray:
    """Each contact slot's smallest clearance over a run, m: its gap less the largest of ``sign (x_i - x_j)``
    (negative: it touched), from the run's exact extrema."""
    per_dof, tracked = run.per_dof(asm.system.n), run.per_pair(asm.system.n)
    out = np.empty(len(asm.pairs))
    for c, (i, _, sign, gap, _) in enumerate(asm.pairs):
        q = asm.contact_tracks[c]
        top, bottom = ((tracked[q, P_MAX], tracked[q, P_MIN]) if q >= 0
                       else (per_dof[i, X_D_MAX], per_dof[i, X_D_MIN]))
        out[c] = gap - (top if sign > 0 else -bottom)
    return out


MASS, STRUCTURE, PAIR = "single mass", "structure", "pair"  # the kinds of system (:func:`kind_of`)


def kind_of(system: Any) -> str | None:
    """Which kind of system ``system`` is: ``MASS``, ``STRUCTURE`` or ``PAIR`` (None: none). The one place
    the kinds are told apart; everything else reads a system through what every kind has
    (:func:`structures_of`: a single mass is the one-level structure it is) and asks this where a kind has
    something of its own (a single mass's paper metrics, a pair's two structures)."""
    for cls, kind in ((Oscillator, MASS), (Structure, STRUCTURE), (Adjacent, PAIR)):
        if isinstance(system, cls):
            return kind
    return None


def is_plan(system: Any) -> bool:
    """Whether ``system`` is a building in plan (a :class:`~pounding.model.plan.PlanBuilding`): ``simulate``
    runs it on its own path (``engine.plan_run``); the protocols do not take it yet."""
    return isinstance(system, PlanBuilding)


def is_single_mass(system: Any) -> bool:
    """Whether ``system`` is a single mass (an :class:`Oscillator`): the one-level structure whose sweeps,
    basins and files keep the paper's metrics and names of their own."""
    return kind_of(system) == MASS


def check_system(system: Any, field: str = "system") -> None:
    """An InputError naming ``field`` unless ``system`` is one the core runs: a single mass, a structure or
    two adjacent ones."""
    if kind_of(system) is None:
        instance_of(field, system, (Oscillator, Structure, Adjacent),
                    "pounding.Oscillator, pounding.Structure or pounding.Adjacent")


def structures_of(model: Oscillator | Structure | Adjacent) -> tuple[tuple[Structure, ...], tuple]:
    """(the structures, the links) of a model (a single mass: the one-level structure it is)."""
    kind = kind_of(model)
    if kind == PAIR:
        return model.structures, model.links
    if kind == MASS:
        return (_one_level(model),), ()
    return (model,), ()


# assemblies kept (:func:`assemble`): a pounding spectrum's systems at every period and gap (100 periods of 4
# systems), each met again by every record a worker runs; a few kB each
ASSEMBLIES_KEPT = 1024


@functools.lru_cache(maxsize=ASSEMBLIES_KEPT)  # (as many as the assemblies: a spectrum's masses)
def _one_level(oscillator: Oscillator) -> Structure:
    """The one-level structure a single mass is (:meth:`Structure.from_oscillator`), built once for the many
    runs of one system (a sweep's, a study's, a continuation's)."""
    return Structure.from_oscillator(oscillator)


def assemble(model: Oscillator | Structure | Adjacent) -> Assembly:
    """The core's system of a model and where each part went (:func:`_assemble`), built once for the many
    runs of one system (a sweep's, a study's, a spectrum's, a continuation's): an equal model (the models
    are frozen dataclasses, equal when their numbers are) gets the assembly kept for it, whose arrays are
    read-only.  A model that cannot be hashed is assembled anew."""
    return _kept(model) if can_keep(model) else _assemble(model)


def can_keep(model: Any) -> bool:
    """Whether what is built from ``model`` can be kept for it (:func:`assemble`): it hashes."""
    try:
        hash(model)
    except TypeError:
        return False
    return True


@functools.lru_cache(maxsize=ASSEMBLIES_KEPT)
def _kept(model: Oscillator | Structure | Adjacent) -> Assembly:
    asm = _assemble(model)
    for a in (asm.masses, asm.k_fast, asm.c_all, asm.bouc_wen.numbers):
        a.flags.writeable = False
    return asm


def _assemble(model: Oscillator | Structure | Adjacent) -> Assembly:
    """The core's system of a single mass (the one-level structure it is), one structure or two adjacent
    ones: their levels' dofs in order (a fixed
    base's level 0 is the ground), the storeys' linear springs and dashpots, the hysteretic elements (the
    isolator with a Bouc-Wen spring first, the other isolator, then the multi-linear storeys), and the
    contact slots (each structure's walls, left then right side, then the links).  One structure of one
    level with one wall is, number for number, the oscillator's system."""
    structures, links = structures_of(model)
    dofs, masses = [], []
    for s in structures:
        levels = []
        for level in range(s.n_levels):
            if s.fixed and level == 0:
                levels.append(-1)
            else:
                levels.append(len(masses))
                masses.append(float(s.masses_kg[level]))
        dofs.append(tuple(levels))
    stands, stand_numbers = [], []  # (a bumper on a stand: a mass of its own, after every level)
    for s in structures:
        mine = []
        for w, wall in enumerate(s.walls):
            if wall.stand is not None:
                for side in (0, 1):
                    mine.append((w, side, len(masses)))
                    masses.append(float(wall.stand.mass_kg))
                    stand_numbers.append(wall.stand)
        stands.append(tuple(mine))
    n = len(masses)
    k0, c0 = np.zeros((n, n)), np.zeros((n, n))
    first_stand = n - len(stand_numbers)
    for q, stand in enumerate(stand_numbers):
        k0[first_stand + q, first_stand + q] = stand.stiffness_n_m
        c0[first_stand + q, first_stand + q] = stand.damping_n_s_m
    for s, levels in zip(structures, dofs):
        ks = s.shear_matrix([st.stiffness_n_m if st.is_linear else 0.0 for st in s.storeys])
        cs = s.damping_matrix
        inside = [lv for lv in range(s.n_levels) if levels[lv] >= 0]  # (a fixed base's ground row dropped)
        at = [levels[lv] for lv in inside]
        k0[np.ix_(at, at)] += ks[np.ix_(inside, inside)]
        c0[np.ix_(at, at)] += cs[np.ix_(inside, inside)]
    order = sorted(range(len(structures)), key=lambda b: not (structures[b].isolator is not None
                                                             and structures[b].isolator.bouc_wen is not None))
    elements, isolator = [], [-1] * len(structures)
    friction: dict[int, dict] = {}  # (an isolator's friction, by its element: a friction isolator's)
    bws: dict[int, np.ndarray] = {}  # (an isolator's Bouc-Wen spring, by its element)
    for b in order:
        s = structures[b]
        if s.fixed:
            continue
        slopes, breaks, rule, b_w = s.isolator.kernel_arrays()
        if b_w[0] != 0.0:
            bws[len(elements)] = np.asarray(b_w, dtype=float)
        isolator[b] = len(elements)
        friction[len(elements)] = s.isolator.kernel_friction
        elements.append((dofs[b][0], -1, float(s.isolator.damping_n_s_m), slopes, breaks, int(rule)))
    for s, levels in zip(structures, dofs):
        for i, st in enumerate(s.storeys):
            if not st.is_linear:
                top, bottom = levels[i + 1], levels[i]
                elements.append((top, bottom, *st.kernel_element(i)[2:]))
    k_fast, c_all = k0.copy(), c0.copy()
    for e, (i, j, c_d, slopes, _, _) in enumerate(elements):
        bw = bws.get(e)
        k = max(abs(x) for x in slopes) + (bw[0] * bw[2] / bw[1] if bw is not None else 0.0)
        _add_pair(k_fast, i, j, k)
        _add_pair(c_all, i, j, c_d)
    contacts, slots, pairs = [], [], []
    for b, (s, levels) in enumerate(zip(structures, dofs)):
        on = {(w, side): dof for w, side, dof in stands[b]}
        for w, wall in enumerate(s.walls):
            for side, (sign, gap, law) in enumerate(((-1.0, wall.gap_left_m, wall.left),
                                                     (1.0, wall.gap_right_m, wall.right))):
                other = on.get((w, side), -1)  # (the ground, or the bumper's stand)
                contacts.append(_core.contact_slot(i=levels[wall.level], j=other, sign=sign, gap_m=gap,
                                                   law=law.LAW_ID, params=law.params()))
                slots.append((b, w, side))
                pairs.append(Pair(levels[wall.level], other, sign, float(gap), law))
    for k, link in enumerate(links):
        contacts.append(_core.contact_slot(i=dofs[0][link.level_first], j=dofs[1][link.level_second],
                                           sign=1.0, gap_m=link.gap_m, law=link.law.LAW_ID,
                                           params=link.law.params()))
        slots.append((-1, k, 0))
        pairs.append(Pair(dofs[0][link.level_first], dofs[1][link.level_second], 1.0, float(link.gap_m),
                          link.law))
    # each storey's drift: its top level against the one below (the ground below a fixed base's first); then
    # each contact between two masses (a link, a bumper on its stand): its pair's relative displacement
    tracked = tuple((levels[i + 1], levels[i]) for s, levels in zip(structures, dofs)
                    for i in range(len(s.storeys)))
    between = [c for c, pair in enumerate(pairs) if pair.j >= 0]
    contact_tracks = tuple(len(tracked) + between.index(c) if c in between else -1 for c in range(len(pairs)))
    tracked += tuple((pairs[c].i, pairs[c].j) for c in between)
    kernel_elements = [_core.element(i=i, j=j, c_d=c_d, slopes=slopes, breaks=breaks, rule=rule,
                                     bw=bws.get(e, ()), **friction.get(e, {}))
                       for e, (i, j, c_d, slopes, breaks, rule) in enumerate(elements)]
    system = _core.system(masses, k0, c0, kernel_elements, bool(contacts), contacts, tracked)
    return Assembly(system, tuple(dofs), tuple(isolator), tuple(slots), tuple(stands), np.array(masses),
                    k_fast, c_all, tuple(pairs),
                    tuple(HystereticElement(i, j, [float(x) for x in slopes], [float(x) for x in breaks],
                                            rule,
                                            tuple(friction.get(e, {}).get("surface_ring_n_m", ())),
                                            tuple(friction.get(e, {}).get("surface_friction_n", ())))
                          for e, (i, j, _, slopes, breaks, rule) in enumerate(elements)),
                    bouc_wen_springs(kernel_elements), system.layout, contact_tracks)


class BoucWenSprings(NamedTuple):
    """A system's Bouc-Wen springs, by their z's slot (the elements that have one, in order): ``numbers``,
    each spring's (the core's ``BW_PARAMS``: force per unit z N, yield displacement m, a, beta, gamma, n),
    shape (b, BW_PARAMS); ``mates``, each spring's mate's slot (the spring it makes one bidirectional spring
    with, a bearing's other axis), -1 none; ``elements``, each spring's element; ``plastic``, whether it is
    a plastic circle's (the core's ``bw_plastic``: elastic inside ``|z| = 1``, slipping on it)."""

    numbers: np.ndarray
    mates: tuple
    elements: tuple = ()
    plastic: tuple = ()


def bouc_wen_springs(elements: list) -> BoucWenSprings:
    """The Bouc-Wen springs of the core's ``elements`` (:class:`pounding._core.Element`)."""
    slots = [e for e, el in enumerate(elements) if el.bw[0] != 0.0]
    rows = [list(elements[e].bw) for e in slots]
    return BoucWenSprings(np.array(rows, dtype=float).reshape(len(rows), _core.LAYOUT["BW_PARAMS"]),
                          tuple(slots.index(elements[e].bw_mate) if elements[e].bw_mate >= 0 else -1
                                for e in slots), tuple(slots),
                          tuple(bool(elements[e].bw_plastic) for e in slots))


def _add_pair(a: np.ndarray, i: int, j: int, value: float) -> None:
    a[i, i] += value
    if j >= 0:
        a[j, j] += value
        a[i, j] -= value
        a[j, i] -= value


def kernel_structure(structure: Structure | Adjacent) -> _core.System:
    """The structure as the core's system (:func:`assemble`)."""
    return assemble(structure).system
