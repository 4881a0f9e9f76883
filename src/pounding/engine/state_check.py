"""Whether a state is one its system can be in: one check for every system (a single mass, a structure, a
pair), against the system's assembly (:func:`check_fits`), the check of its layout (:func:`check_layout`),
and both for a state given to a protocol (:func:`check_state`).

A state fits when each contact's flag, compression and law state agree with the displacements, each
hysteretic element's branch is the one of its deformation, each kinematic spring's slip leaves it within its
yield (at its yield while it slips) and a Bouc-Wen z is within its bound.  Lengths are compared to 1e-9 of the
system's own (a run's final state holds the rounding of its last event).
"""

from __future__ import annotations

import math
import warnings
from bisect import bisect_right
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from .._checks import instance_of
from .._errors import InputError, Problem, outside_stacklevel
from ..model.contact_laws import N_LAW_STATE, state_problem, stateless
from ..model.oscillator import Oscillator
from .assembly import Assembly, assemble, is_single_mass
from .state import LAYOUT_KEYS, State, shifted

if TYPE_CHECKING:
    from ..model import Adjacent, Structure

ROUNDED_RATE_M_S = 1e-12  # (a friction circle's slip rate this small, inwards, is a bearing at rest)


def contact_name(slot: tuple, pair: bool) -> str:
    """A contact slot's name in a structure's (or a pair's) tables: ``wall 0 left``, ``first wall 1 right``,
    ``link 0``."""
    owner, k, side = slot
    if owner < 0:
        return f"link {k}"
    who = ("first " if owner == 0 else "second ") if pair else ""
    return f"{who}wall {k} {('left', 'right')[side]}"


def one_mass(asm: Assembly) -> bool:
    """Whether the assembly is a single mass's (one structure, one moving level, no stand)."""
    return asm.dofs == ((0,),) and int(asm.system.n) == 1


def check_layout(state: State, asm: Assembly, fix: str) -> None:
    """An InputError unless ``state`` is laid out as the assembly's states are (its size, levels and
    blocks), its numbers finite."""
    lay = asm.layout
    if state.vector.size != lay["size"] or state.dofs != asm.dofs or any(
            state._lay[k] != lay[k] for k in LAYOUT_KEYS):
        n_contacts = lay["in"] - lay["def"]
        if state.dofs == asm.dofs and state.n_contacts == n_contacts:
            what = "isolator branches" if one_mass(asm) else "isolator branches or hysteretic storeys"
            why = (f"has {state.vector.size} numbers where this system's states have {lay['size']} (it is "
                   f"from a system with another number of {what})")
        elif one_mass(asm) and state.dofs == asm.dofs:
            why = (f"has {state.n_contacts} contact slots where this system has {n_contacts} (it is from a "
                   f"system {'with' if state.n_contacts else 'without'} bumpers)")
        else:
            whose = "this single mass's states" if one_mass(asm) else "this system's"
            why = (f"is a state of {state.vector.size} numbers, levels {state.dofs} and {state.n_contacts} "
                   f"contact slots, where {whose} have {lay['size']}, {asm.dofs} and {n_contacts}")
        raise InputError(Problem.BAD_STATE, "state", state, why=why, fix=fix)
    if not np.all(np.isfinite(state.vector)):
        raise InputError(Problem.BAD_STATE, "state", state, why="holds a number that is not finite", fix=fix)


def check_fits(vec: np.ndarray, asm: Assembly, fix: str, levered: Optional[tuple] = None) -> None:
    """An InputError (its field a :class:`State` property's, or ``vector[i]``) unless the state vector
    ``vec`` (laid out as the assembly's, its numbers finite) is a state the system can be in.

    ``levered``: for pairs on levers (a building in plan's), ``(contact_weights, element_weights,
    contact_names[, depths])``: each contact's and each element's displacement as weights on the dofs (shape
    (pairs, n)), and each contact's name; without, a pair's displacement is ``x_i - x_j``; ``depths``: the
    contacts (by index) whose depth past their gap is given (a ring's, not a line's).

    Read as Python floats: a solver checks one a run, and numpy's scalars cost several times more."""
    x_all = vec.tolist()
    lay = asm.layout
    n = int(asm.system.n)
    x = x_all[lay["x"]:lay["x"] + n]
    single = one_mass(asm)
    lengths = [max(map(abs, x), default=0.0), 1e-3] + [pair.gap_m for pair in asm.pairs]
    lengths += [b for element in asm.elements for b in element.breaks]
    tol = 1e-9 * max(lengths)

    def bad(field: str, value: float, why: str) -> InputError:
        return InputError(Problem.BAD_STATE, f"state.{field}", value, why=why, fix=fix)

    def rel(i: int, j: int) -> float:
        return x[i] - (x[j] if j >= 0 else 0.0)

    if levered is not None:  # (each pair's displacement from its weights)
        along = [list(np.asarray(w) @ np.asarray(x)) for w in levered[:2]]
    pair = len(asm.dofs) > 1
    for c, (i, j, sign, gap, law) in enumerate(asm.pairs):
        comp, flag = x_all[lay["def"] + c], x_all[lay["in"] + c]
        side = (levered[2][c] if levered is not None else ("left", "right")[c] if single
                else contact_name(asm.slots[c], pair))
        # (how far the pair is past its gap: beyond the bumper's free surface)
        depth = sign * (along[0][c] if levered is not None else rel(i, j)) - gap
        if levered is not None and len(levered) > 3 and c in levered[3]:  # (a ring's: from its centre)
            depth = levered[3][c]
        if flag not in (0.0, 1.0):
            raise bad(f"in_contact[{c}]", flag, f"is the {side} bumper's contact flag: 0 or 1")
        if comp < 0.0:
            raise bad(f"bumper_compression_m[{c}]", comp, f"is the {side} bumper's compression: it is >= 0")
        if flag == 1.0 and abs(depth - comp) > tol:
            raise bad(f"bumper_compression_m[{c}]", comp,
                      f"differs from the {side} bumper's depth {depth:g} m at the state's displacement while "
                      "in contact")
        if flag == 0.0 and depth - comp > tol:
            field = "displacement_m" if single else f"vector[{lay['x'] + i}]"
            raise bad(field, x[i], f"puts the {side} bumper's pair {depth:g} m past its gap, inside its "
                                   f"surface ({comp:g} m of compression) while not in contact")
        at = lay["z"] + c * N_LAW_STATE
        if law.STATE_CHECK is stateless and not any(x_all[at:at + N_LAW_STATE]):
            continue  # (a stateless law's block of zeros: what its check accepts, without numpy)
        found = state_problem(law, vec[at:at + N_LAW_STATE], flag == 1.0, comp, tol, side)
        if found is not None:
            q, value, why = found
            raise bad(f"vector[{at + q}]", value, why)
    first = 0
    for e, (i, j, slopes, breaks, rule, rings, _) in enumerate(asm.elements):
        n_sp = len(breaks)
        u = along[1][e] if levered is not None else rel(i, j)
        who = "the isolator's" if single else f"element {e}'s"
        if rule == 1:  # (elastic: the branch of its deformation; no slips, their places unused)
            region = x_all[lay["region"] + e]
            a = int(abs(region))
            edges = (0.0, *breaks, math.inf)
            if (region != round(region) or a > n_sp or not edges[a] - tol <= abs(u) <= edges[a + 1] + tol
                    or (region != 0.0 and math.copysign(1.0, region) != math.copysign(1.0, u))):
                field = "isolator_branch" if e == 0 else f"vector[{lay['region'] + e}]"
                raise bad(field, region, f"is not {who} backbone branch at its deformation {u:g} m (that is "
                                         f"{math.copysign(bisect_right(breaks, abs(u)), u):g})")
            first += n_sp
            continue
        if rule == 2:  # (friction: its slip's direction, -1, 0 or 1; 0 while its pair moves: it slips)
            slip = x_all[lay["region"] + e]
            field = "isolator_branch" if e == 0 else f"vector[{lay['region'] + e}]"
            if slip not in (-1.0, 0.0, 1.0):
                raise bad(field, slip, f"is {who} slip direction: -1, 0 (sticking) or 1")
            v = x_all[lay["v"]:lay["v"] + n]
            u_rate = v[i] - (v[j] if j >= 0 else 0.0)
            if slip * u_rate < 0.0:
                raise bad(field, slip, f"is {who} slip direction, against its pair's velocity {u_rate:g} m/s "
                                       "(a slip goes the way its pair moves)")
            if n_sp:  # (surfaces in series: each one's displacement and state, summing to the element's)
                _check_surfaces(x_all, lay, first, breaks, rings, u, slip, tol, who, bad)
            first += n_sp
            continue
        circle = e in asm.bouc_wen.elements and asm.bouc_wen.plastic[asm.bouc_wen.elements.index(e)]
        if x_all[lay["region"] + e] not in ((0.0, 1.0) if circle else (0.0,)):
            field = "isolator_branch" if e == 0 else f"vector[{lay['region'] + e}]"
            raise bad(field, x_all[lay["region"] + e],
                      f"is {who} slip on its friction circle: 0 (inside) or 1 (slipping)" if circle else
                      f"is {who} backbone branch, but a kinematic element has no branch state")
        for k in range(n_sp):
            slip = x_all[lay["base"] + first + k]
            direction = x_all[lay["base"] + lay["n_springs"] + first + k]
            if direction not in (-1.0, 0.0, 1.0):
                raise bad(f"vector[{lay['base'] + lay['n_springs'] + first + k}]", direction,
                          f"is {who} spring {k}'s slip direction: -1, 0 or 1")
            strain = u - slip
            brk = breaks[k]
            if abs(strain) > brk + tol if direction == 0.0 else abs(strain - direction * brk) > tol:
                raise bad(f"plastic_slips_m[{first + k}]", slip,
                          f"leaves {who} spring {k}'s strain {strain:g} m beyond its yield displacement "
                          f"{brk:g} m" + ("" if direction == 0.0 else " (or off it while it slips)"))
        first += n_sp
    springs, mates = asm.bouc_wen.numbers, asm.bouc_wen.mates
    for q in range(max(1, len(springs))):  # (each Bouc-Wen spring's z; one slot, 0, without any)
        at = lay["zeta"] + q
        z = x_all[at]
        if q >= len(springs):
            if z != 0.0:
                raise bad(f"vector[{at}]", z, "is a Bouc-Wen z, but no isolator here has a Bouc-Wen spring")
            continue
        bw = springs[q]
        z_max = (bw[2] / (bw[3] + bw[4])) ** (1.0 / bw[5])
        mate = mates[q]  # (a bidirectional spring's: its resultant)
        size = abs(z) if mate < 0 else float(np.hypot(z, x_all[lay["zeta"] + mate]))
        if size > z_max * (1.0 + 1e-9):
            what = "" if mate < 0 else f" (with vector[{lay['zeta'] + mate}], its other component: {size:g})"
            raise bad(f"vector[{at}]", z, f"is beyond the Bouc-Wen spring's largest |z|, {z_max:g}{what}")
        if asm.bouc_wen.plastic and asm.bouc_wen.plastic[q] and mate > q:
            _check_circle(x_all, lay, asm, levered, q, mate, size, bad)


def _check_circle(x_all: list, lay: dict, asm: Assembly, levered: Optional[tuple], q: int, mate: int,
                  size: float, bad: Any) -> None:
    """A plastic friction circle's state (Bouc-Wen springs ``q`` and ``mate``, ``size`` its ``|z|``): its
    two elements' slip flags alike, 0 or 1, slipping only on the circle and moving outwards."""
    e, f = asm.bouc_wen.elements[q], asm.bouc_wen.elements[mate]
    flag, other = x_all[lay["region"] + e], x_all[lay["region"] + f]
    field = f"vector[{lay['region'] + e}]"
    if flag != other:
        raise bad(field, flag, f"is a friction circle's slip, but its other axis's "
                               f"(vector[{lay['region'] + f}]) is {other:g}: one circle, one flag")
    if flag != 1.0:
        return
    if size < 1.0 - 1e-9:
        raise bad(field, flag, f"is a friction circle's slip (1: slipping), but its |z| is {size:g}, inside "
                               "the circle (a slip is on it, |z| = 1)")
    v = np.asarray(x_all[lay["v"]:lay["v"] + int(asm.system.n)])
    rates, levers = [], []
    for el in (e, f):
        if levered is not None:
            w = np.asarray(levered[1][el])
            rates.append(float(w @ v))
            levers.append(float(np.sum(np.abs(w))))
        else:
            i, j = asm.elements[el].i, asm.elements[el].j
            rates.append(float(v[i] - (v[j] if j >= 0 else 0.0)))
            levers.append(2.0)
    outwards = x_all[lay["zeta"] + q] * rates[0] + x_all[lay["zeta"] + mate] * rates[1]
    # (a run's final state's slip may end inwards by rounding: of the rate itself, of the velocities it is
    # made of, or, where walls hold the bearing's floor still, of the impulses that stopped it: a rate below
    # ROUNDED_RATE_M_S is a floor at rest)
    scale = max(math.hypot(*rates), max(levers) * float(np.max(np.abs(v))))
    if outwards < -1e-9 * scale - ROUNDED_RATE_M_S:
        raise bad(field, flag, f"is a friction circle's slip, against its bearing's velocity (z . u' = "
                               f"{outwards:g} m/s: a slip goes outwards, else it sticks)")


_FIX = "start from State.at_rest(system) or a final_state of this system"


def check_state(state: Optional[State], system: "Oscillator | Structure | Adjacent",
                asm: Optional[Assembly] = None) -> State:
    """``state``, or rest at t = 0 when None; it must belong to a system like ``system`` (a single mass, a
    structure or a pair; ``asm``: its assembly, when the caller has it).  Returns the state to run from (a
    single mass without bumpers given 0.1's state: laid out as its own, see :func:`_without_bumpers`)."""
    asm = assemble(system) if asm is None else asm
    if state is None:
        return shifted(asm, 0.0, 0.0, 0.0)
    instance_of("state", state, State, "pounding.State (e.g. run.final_state)")
    if is_single_mass(system):  # (0.1's layout was a single mass's alone)
        state = _without_bumpers(state, asm)
    check_layout(state, asm, _FIX)
    check_fits(state.vector, asm, _FIX)
    return state


def _without_bumpers(state: State, asm: Assembly) -> State:
    """A single mass's state laid out with two bumpers' contact slots (the core's one-mass layout: 0.1's
    for every mass, or a run's with bumpers), given to a mass without bumpers: the same state in that
    system's layout (no contact slots; a finished contact's running totals and the laws' states are left
    behind), with a ``FutureWarning``; refused while a bumper touches or is compressed."""
    lay = asm.layout
    if state.layout is not None or state.dofs != asm.dofs or lay["in"] != lay["def"]:
        return state
    old, vec = state._lay, state.vector
    dropped = (old["region"] - old["def"]) + (old["zeta"] - old["acc"])  # (the contacts' blocks)
    if vec.size - dropped != lay["size"]:
        return state  # (not that state: the layout check says why)
    if vec[old["def"]:old["region"]].any():
        raise InputError(Problem.BAD_STATE, "state.in_contact", state.in_contact,
                         why=f"has a bumper in contact or compressed (compressions "
                             f"{state.bumper_compression_m} m), but the system has no bumpers", fix=_FIX)
    kept = np.concatenate((vec[:old["def"]], vec[old["region"]:old["acc"]], vec[old["zeta"]:]))
    warnings.warn(f"this state has two bumpers' contact slots ({vec.size} numbers: a state of a mass with "
                  "bumpers, or 0.1's layout for every mass), but the system has no bumpers: it is taken as "
                  f"the same state in this system's layout ({kept.size} numbers); give a state of this "
                  "system (State.at_rest(oscillator) or a run's final_state)", FutureWarning,
                  stacklevel=outside_stacklevel())
    return State._from_kernel(kept, lay)


def _check_surfaces(x_all: list, lay: dict, first: int, breaks: Any, rings: Any, u: float, slip: float,
                    tol: float, who: str, bad: Any) -> None:
    """A series of friction surfaces in the state (a triple friction pendulum's): each one's state (0 held,
    the element's slip direction while it slips, 3 times it while it slips on its stiff ring (``rings``:
    each one's stiffness, N/m; empty or 0: rigid), +-2 held at its rigid ring on that side), its displacement
    within its rigid ring (at it for +-2), and their sum the element's deformation ``u``."""
    total, slipping = 0.0, False
    for k, ring in enumerate(breaks):
        at_u, at_s = lay["base"] + first + k, lay["base"] + lay["n_springs"] + first + k
        ug, state = x_all[at_u], x_all[at_s]
        stiff = bool(rings) and rings[k] > 0.0
        allowed = (0.0, slip, 3.0 * slip) if stiff else (-2.0, 0.0, slip, 2.0)
        if state not in allowed:
            raise bad(f"vector[{at_s}]", state, f"is {who} surface {k}'s state: 0 held, the element's slip "
                                                f"direction ({slip:g}) while it slips"
                                                + (" (3 times it on its stiff ring)" if stiff
                                                   else ", +-2 at its ring"))
        if not stiff and (abs(ug) > ring + tol
                          or (abs(state) == 2.0 and abs(ug - math.copysign(ring, state)) > tol)):
            raise bad(f"vector[{at_u}]", ug, f"is {who} surface {k}'s displacement, beyond its ring at "
                                             f"{ring:g} m (or off it while held there)")
        inside = -ring + tol < slip * ug < ring - tol  # (clearly within its travel: off its rings)
        outside = not -ring - tol <= slip * ug <= ring + tol  # (clearly past a ring)
        if stiff and ((abs(state) == 3.0 and inside) or (abs(state) == 1.0 and outside)):
            why = (f"on its stiff ring (3 times the slip direction) while its displacement {ug:g} m is "
                   f"within its travel {ring:g} m" if abs(state) == 3.0 else
                   f"within its travel while its displacement {ug:g} m is past its ring at {ring:g} m "
                   "(3 times the slip direction)")
            raise bad(f"vector[{at_s}]", state, f"is {who} surface {k}'s state, {why}")
        total += ug
        slipping = slipping or state in (slip, 3.0 * slip) and slip != 0.0
    if slip != 0.0 and not slipping:
        at = lay["base"] + lay["n_springs"] + first
        raise bad(f"vector[{at}]", x_all[at],
                  f"and {who} other surfaces' states leave none slipping while it slips: every surface at "
                  "its ring, its travel used up (a run that stopped with Status.CAPACITY cannot go on)")
    if abs(total - u) > tol:
        raise bad(f"vector[{lay['base'] + first}]", x_all[lay["base"] + first],
                  f"and {who} other surfaces' displacements sum to {total:g} m, not its displacement {u:g} m "
                  "(a triple friction pendulum starts centred, or from a run's final_state)")
