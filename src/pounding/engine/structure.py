"""A structure of several masses through the core: the checks of its state (a :class:`State`) and its run
(:func:`simulate_structure`, which :func:`pounding.simulate` calls for a :class:`~pounding.Structure`); its
system is assembled in :mod:`.assembly`."""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Optional

import numpy as np

from .. import _core
from .._checks import instance_of
from .._errors import Interrupted, Status
from ..excitation import Harmonic, Record
from ..model.contact_laws import is_rigid, linear_form
from ..model.adjacent import Adjacent
from ..model.structure import Structure
from .control import DEFAULT_MAX_STEPS, check_budget, new_control, run_interruptibly, steps_per_second
from ._chatter import chatter_frame
from .state import State
from .state_check import contact_name
from .layout import CONTACT_COLUMNS
from .run_args import DIRECT_CALL_STEPS, checked_run_args, kernel_forcing
from .adjacent_result import AdjacentRun
from .assembly import Assembly, _add_pair, assemble, clearances, structures_of
from .result import EnergyLedger
from .structure_result import StructureRun


def structure_rates(asm: Assembly) -> tuple[float, float]:
    """(out of contact, in every contact at once) the fastest rate of the assembled structures, rad/s: the
    largest undamped frequency with every hysteretic element at its stiffest slope (and the contacts'
    linear springs), or a dof's damping rate if larger (inf in contact for a nonlinear or multi-branch
    law)."""
    m = asm.masses
    k, c = asm.k_fast.copy(), asm.c_all.copy()
    scale = 1.0 / np.sqrt(m)

    def rate(k: np.ndarray, c: np.ndarray) -> float:  # (K v = lam M v: M^-1/2 K M^-1/2's eigenvalues)
        lam = float(np.linalg.eigvalsh(k * np.outer(scale, scale))[-1])
        return max(math.sqrt(max(lam, 0.0)), float(np.max(np.diag(c) / m)))

    free = rate(k, c)
    for i, j, _, _, law in asm.pairs:
        if is_rigid(law):  # (no stiffness: its impacts are events)
            continue
        form = linear_form(law)
        if form is None:
            return free, math.inf
        _add_pair(k, i, j, form[0])
        _add_pair(c, i, j, form[1])
    return free, rate(k, c)


def structure_rate(model: Structure | Adjacent) -> tuple[float, str]:
    """The fastest rate of the structure's motion out of contact, rad/s, and what sets it (what a
    protocol's work estimate counts from, as ``isolator_rate`` for one mass)."""
    free, _ = structure_rates(assemble(model))
    return free, f"the structure's fastest motion {free:.3g} rad/s"


def simulate_structure(structure: Structure | Adjacent, excitation: Harmonic | Record, duration: float,
                       state: Optional[State] = None, *, rtol: float = 1e-10,
                       sample_rate_hz: Optional[float] = None, max_events: int = 10_000_000,
                       max_steps: int = DEFAULT_MAX_STEPS) -> StructureRun | AdjacentRun:
    """Simulate a structure (or two adjacent ones) under a base excitation, exactly at every contact
    (``pounding.simulate`` with a :class:`~pounding.Structure` or :class:`~pounding.Adjacent`; the same
    arguments, a :class:`StructureRun` or :class:`AdjacentRun` back)."""
    instance_of("structure", structure, (Structure, Adjacent), "pounding.Structure or pounding.Adjacent")
    asm, state, duration, rtol, rate, max_events, max_steps, omega, knots = checked_run_args(
        structure, excitation, duration, state, rtol, sample_rate_hz, max_events, max_steps)
    t0 = state.time_s
    free, touching = structure_rates(asm)
    why = f"the structure's fastest motion {max(free, omega):.3g} rad/s"
    if isinstance(excitation, Record):
        why += f", and {knots} record samples"
    estimate = float(steps_per_second(free, omega)) * duration + knots
    check_budget("duration", duration, estimate, max_steps, why,
                 "shorten the duration, or check the structure's numbers (SI units: kg, N/m, N s/m)")
    most = float(steps_per_second(touching, omega)) * duration + knots
    ctl = new_control(max_steps)
    out = run_interruptibly(lambda: _core.run(
        asm.system, kernel_forcing(excitation), state.vector.copy(), t0 + duration,
        1.0 / rate if rate > 0 else 0.0, rtol, max_events, True, ctl), [ctl], direct=most < DIRECT_CALL_STEPS)
    return run_of(structure, asm, excitation, rate, out, t0, duration)


def run_of(model: Any, asm: Any, excitation: Any, rate: float, out: _core.RunOutput, t0: float,
           duration: float) -> "StructureRun | AdjacentRun":
    """The result of the core's run of one structure, or two adjacent ones (``Interrupted`` on Ctrl-C)."""
    samples, contacts, events = out.samples, out.contacts, out.events
    energy = EnergyLedger.of(out.ledger)
    status = Status(out.status)
    if status == Status.SUCCESS and not (np.all(np.isfinite(out.extrema)) and np.isfinite(energy.residual)):
        status = Status.NONFINITE
    final = State._of(out.state, asm.dofs, asm.system.layout)
    structures = structures_of(model)[0]
    parts = [StructureRun._part(s, b, asm, structures, excitation, rate, out, status, t0)
             for b, s in enumerate(structures)]
    clear = clearances(asm, out)
    names = tuple(contact_name(slot, len(parts) > 1) for slot in asm.slots)
    chatter = chatter_frame(out.chatters, names, "contact")
    if len(parts) == 1:
        run: Any = dataclasses.replace(parts[0], event_table=events, energy=energy, final_state=final,
                                       clearance_m=clear, chatters=chatter)
    else:
        links = [c for c, (owner, _, _) in enumerate(asm.slots) if owner == -1]
        slot = CONTACT_COLUMNS["contact"]
        link_rows = contacts[np.isin(contacts[:, slot], links)].copy()
        link_rows[:, slot] -= links[0]
        n, nh = asm.system.n, asm.system.n_elements
        run = AdjacentRun(model, excitation, rate, parts[0], parts[1], samples[:, 0],
                          samples[:, [1 + 3 * n + nh + c for c in links]], link_rows, events, energy, final,
                          status, clear, chatter)
    if status == Status.INTERRUPTED:
        raise Interrupted(run, round(final.time_s - t0, 6), duration, "simulated seconds")
    return run
