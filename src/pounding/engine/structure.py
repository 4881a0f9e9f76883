"""A structure of several masses through the core: its system (:func:`kernel_structure`), its state
(:class:`StructureState`) and its run (:func:`simulate_structure`, which :func:`pounding.simulate`
calls for a :class:`~pounding.Structure`).

The core's contact slots are the walls' sides in order: wall ``w``'s left side is slot ``2 w``
(sign -1: it stops negative displacements), its right side slot ``2 w + 1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .. import _core
from .._checks import at_most, integer, positive, real
from .._errors import InputError, Problem
from ..excitation import Harmonic, Record
from ..model.contact_laws import linear_form
from ..model.structure import Structure
from ._control import DEFAULT_MAX_STEPS, check_budget, new_control, run_interruptibly, steps_per_second
from .result import MAX_TIME_S
from ._run_args import DIRECT_CALL_STEPS, check_rtol, history_rate, kernel_forcing
from .structure_result import StructureEnergy, StructureRun

_NO_WALLS: list = []


def kernel_structure(structure: Structure) -> _core.System:
    """The structure as the core's system: its levels, the storeys' matrices, the isolator between the
    base and the ground, and two contact slots per wall (left, sign -1; right, +1) against the ground.
    A structure of one level with one wall is, number for number, the oscillator's system."""
    slopes, breaks, rule, bw = structure.isolator.kernel_arrays()
    contacts = []
    for w in structure.walls:
        contacts.append((w.level, -1, -1.0, float(w.gap_left_m), int(w.left.LAW_ID), w.left.params()))
        contacts.append((w.level, -1, 1.0, float(w.gap_right_m), int(w.right.LAW_ID), w.right.params()))
    elements = [(0, -1, float(structure.isolator.damping), slopes, breaks, int(rule))]
    linear = [s.stiffness_n_m if s.is_linear else 0.0 for s in structure.storeys]  # (the others: elements)
    elements += [s.kernel_element(i) for i, s in enumerate(structure.storeys) if not s.is_linear]
    return _core.system(structure.masses_kg, structure.shear_matrix(linear), structure.damping_matrix,
                        elements, bw, bool(contacts), contacts or _NO_WALLS)


@dataclass(frozen=True)
class StructureState:
    """Where a structure is: the core's state vector (its layout is the structure's).  Start from
    :meth:`at_rest` or a run's ``final_state``; pass it as ``state`` to continue the run.

    Attributes
    ----------
    vector : ndarray
        The core's state vector (read-only): time, each level's displacement and velocity, the walls'
        contact states, the isolator's.
    n_levels : int
        The structure's levels.

    Examples
    --------
    >>> import pounding
    >>> iso = pounding.Isolator(slopes=[1.0e5], breakpoints=[])
    >>> b = pounding.Structure(1.0e3, iso, [pounding.Storey(1.0e3, 1.0e6)])
    >>> first = pounding.simulate(b, pounding.Harmonic(0.1, 1.0), 2.0)
    >>> state = first.final_state
    >>> state.time_s, state.displacements_m.shape
    (2.0, (2,))
    >>> later = pounding.simulate(b, pounding.Harmonic(0.1, 1.0), 2.0, state)
    >>> float(later.t[0]), float(later.t[-1])
    (2.0, 4.0)
    """

    vector: np.ndarray = field(repr=False)
    n_levels: int

    @classmethod
    def at_rest(cls, structure: Structure, time_s: float = 0.0) -> "StructureState":
        """At rest at ``time_s``: every level at 0, the walls' laws relaxed, the isolator on its
        backbone at 0."""
        if not isinstance(structure, Structure):
            raise InputError(Problem.WRONG_TYPE, "structure", structure, got=type(structure).__name__,
                             expected="pounding.Structure")
        time_s = at_most("time_s", real("time_s", time_s), MAX_TIME_S, " s", "give the time in s")
        vec = np.zeros(kernel_structure(structure).layout["size"])
        vec[0] = time_s
        return cls._of(vec, structure.n_levels)

    @classmethod
    def _of(cls, vector: np.ndarray, n_levels: int) -> "StructureState":
        vec = np.array(vector, dtype=float)
        vec.setflags(write=False)
        return cls(vec, n_levels)

    @property
    def time_s(self) -> float:
        """Time, s."""
        return float(self.vector[0])

    @property
    def displacements_m(self) -> np.ndarray:
        """Each level's displacement relative to the ground, m, shape (n_levels,)."""
        return self.vector[1:1 + self.n_levels].copy()

    @property
    def velocities_m_s(self) -> np.ndarray:
        """Each level's velocity relative to the ground, m/s, shape (n_levels,)."""
        return self.vector[1 + self.n_levels:1 + 2 * self.n_levels].copy()


_FIX = "start from StructureState.at_rest(structure) or a final_state of this structure"


def _check_state(state: Optional[StructureState], structure: Structure, size: int) -> StructureState:
    if state is None:
        return StructureState.at_rest(structure)
    if not isinstance(state, StructureState):
        raise InputError(Problem.WRONG_TYPE, "state", state, got=type(state).__name__,
                         expected="pounding.StructureState (StructureState.at_rest(structure) or a run's "
                                  "final_state)")
    if state.vector.size != size or state.n_levels != structure.n_levels:
        raise InputError(Problem.BAD_STATE, "state", state,
                         why=f"is a state of {state.n_levels} levels and {state.vector.size} numbers, where "
                             f"this structure's have {structure.n_levels} and {size}",
                         fix=_FIX)
    if not np.all(np.isfinite(state.vector)):
        raise InputError(Problem.BAD_STATE, "state", state, why="holds a number that is not finite",
                         fix=_FIX)
    return state


def structure_rates(structure: Structure) -> tuple[float, float]:
    """(out of contact, in every contact at once) the structure's fastest rate, rad/s: the largest
    undamped frequency with the isolator at its stiffest slope (and the walls' linear springs), or a
    level's damping rate if larger (inf in contact for a nonlinear or multi-branch law)."""
    from scipy.linalg import eigvalsh

    iso = structure.isolator
    k_iso = max(abs(s) for s in iso.slopes)
    if iso.bouc_wen is not None:
        k_iso += iso.bouc_wen.a * iso.bouc_wen.stiffness
    m = structure.masses_kg
    k = structure.shear_matrix([max((s.stiffness_n_m, *s.slopes_after_n_m)) for s in structure.storeys])
    c = structure.damping_matrix.copy()
    k[0, 0] += k_iso
    c[0, 0] += iso.damping

    def rate(k: np.ndarray, c: np.ndarray) -> float:
        lam = float(eigvalsh(k, np.diag(m))[-1])
        return max(math.sqrt(max(lam, 0.0)), float(np.max(np.diag(c) / m)))

    free = rate(k, c)
    for w in structure.walls:
        for law in (w.left, w.right):
            form = linear_form(law)
            if form is None:
                return free, math.inf
            k[w.level, w.level] += form[0]
            c[w.level, w.level] += form[1]
    return free, rate(k, c)


def simulate_structure(structure: Structure, excitation: Harmonic | Record, duration: float,
                       state: Optional[StructureState] = None, *, rtol: float = 1e-10,
                       sample_rate_hz: Optional[float] = None, max_events: int = 10_000_000,
                       max_steps: int = DEFAULT_MAX_STEPS) -> StructureRun:
    """Simulate a structure under a base excitation, exactly at every contact (``pounding.simulate``
    with a :class:`~pounding.Structure`; the same arguments, a :class:`StructureRun` back)."""
    if not isinstance(structure, Structure):
        raise InputError(Problem.WRONG_TYPE, "structure", structure, got=type(structure).__name__,
                         expected="pounding.Structure")
    if not isinstance(excitation, (Harmonic, Record)):
        raise InputError(Problem.WRONG_TYPE, "excitation", excitation,
                         got=type(excitation).__name__, expected="pounding.Harmonic or pounding.Record")
    duration = positive("duration", duration, "s")
    rtol = check_rtol(rtol)
    max_events = integer("max_events", max_events, 1)
    max_steps = integer("max_steps", max_steps, 1)
    system = kernel_structure(structure)
    state = _check_state(state, structure, system.layout["size"])
    rate = history_rate(sample_rate_hz, duration)
    t0 = state.time_s
    omega = excitation.omega_rad_s if isinstance(excitation, Harmonic) else 0.0
    free, touching = structure_rates(structure)
    knots = 0
    why = f"the structure's fastest motion {max(free, omega):.3g} rad/s"
    if isinstance(excitation, Record):
        knots = int(np.count_nonzero((excitation.t >= t0) & (excitation.t <= t0 + duration)))
        why += f", and {knots} record samples"
    estimate = float(steps_per_second(free, omega)) * duration + knots
    check_budget("duration", duration, estimate, max_steps, why,
                 "shorten the duration, or check the structure's numbers (SI units: kg, N/m, N s/m)")
    most = float(steps_per_second(touching, omega)) * duration + knots
    ctl = new_control(max_steps)
    out = run_interruptibly(lambda: _core.run(
        system, kernel_forcing(excitation), state.vector.copy(), t0 + duration,
        1.0 / rate if rate > 0 else 0.0, rtol, max_events, True, ctl), [ctl], direct=most < DIRECT_CALL_STEPS)
    st, samples, contacts, events, ledger, extrema, status = out
    return StructureRun._of(structure, excitation, rate, StructureState._of(st, structure.n_levels), samples,
                            contacts, events, StructureEnergy.of(ledger), extrema, int(status), t0, duration)
