"""A building in plan's run (``simulate`` of a :class:`~pounding.model.plan.PlanBuilding`): its arguments
checked, the core's run, its :class:`~pounding.engine.plan_result.PlanRun`.

The ground's motion: a :class:`~pounding.RecordPair` (its x component along the plan's x, its y along y), or
one component along x (a :class:`~pounding.Record` or :class:`~pounding.Harmonic`; along another direction:
:meth:`RecordPair.of_direction`)."""

from __future__ import annotations

import functools
import math
from typing import Any, Optional

import numpy as np

from .. import _core
from .._checks import instance_of, integer, positive
from .._errors import InputError, Interrupted, Problem, Status
from ..excitation import Harmonic, HarmonicPair, Record, RecordPair
from ..model.contact_laws import linear_form
from ..model.plan import PlanBuilding
from ..model.moats import wall_name
from .control import check_budget, fastest_of, new_control, run_interruptibly, steps_per_second
from .layout import P_MAX, P_MIN, X_A_MAX, X_D_MAX, X_D_MAX_T, X_D_MIN, X_D_MIN_T
from .plan_assembly import PlanAssembly, assemble_plan
from .plan_result import PlanRun
from .run_args import DIRECT_CALL_STEPS, check_rtol, history_rate, kernel_forcing
from .run_parts import EnergyLedger
from .state import MAX_TIME_S, State
from .state_check import check_fits

_FIX = "start from rest (state=None) or from a run of this building (run.final_state)"


@functools.lru_cache(maxsize=64)
def _kept(building: PlanBuilding) -> tuple[PlanAssembly, float, float]:
    """The building's assembly and its fastest rates (out of contact, in every contact at once), rad/s,
    built once for its many runs."""
    asm = assemble_plan(building)
    m, k, c = asm.masses, asm.k_fast.copy(), asm.c_all.copy()
    free, touching = fastest_of(m, k, c), math.inf
    form = linear_form(building.moat.law) if building.moat is not None else (0.0, 0.0)
    if form is not None:  # (a ring's contact pushes along x and y: both counted)
        for w in [*asm.contact_weights, *(ring[0] for ring in asm.rings)]:
            k += form[0] * np.outer(w, w)
            c += form[1] * np.outer(w, w)
        touching = fastest_of(m, k, c)
    return asm, free, touching


def _start(state: Optional[State], asm: PlanAssembly) -> State:
    """``state``, or rest at t = 0 when None: one of this building's states (its layout, its numbers finite,
    a time >= 0, and each contact's and element's state fitting the displacements: ``check_fits``)."""
    lay = asm.layout
    if state is None:
        return State._of(np.zeros(lay["size"]), asm.dofs, lay)
    instance_of("state", state, State, "pounding.State (a run's final_state)")
    vec = state.vector
    if state.layout is None or vec.size != lay["size"] or state.dofs != asm.dofs or any(
            state.layout.get(k) != v for k, v in lay.items()):
        raise InputError(Problem.BAD_STATE, "state", state,
                         why=f"is a state of {vec.size} numbers and levels {state.dofs}, not one of this "
                             f"building's ({lay['size']} numbers, {asm.system.n} dofs)", fix=_FIX)
    if not np.all(np.isfinite(vec)):
        raise InputError(Problem.BAD_STATE, "state", state, why="holds a number that is not finite", fix=_FIX)
    if not 0.0 <= vec[0] <= MAX_TIME_S:
        raise InputError(Problem.BAD_STATE, "state.time_s", float(vec[0]),
                         why=f"is outside [0, {MAX_TIME_S:g}] s", fix=_FIX)
    names = [f"moat {wall_name(side)} at corner {k}" for side, k in asm.contacts]
    check_fits(vec, asm, _FIX, (asm.contact_weights, asm.element_weights, names, _ring_depths(asm, vec)))
    return state


def _ring_depths(asm: PlanAssembly, vec: np.ndarray) -> dict:
    """A circular moat's contacts' depths past the ring in the state ``vec`` (m, by contact: a corner's
    distance from the ring's centre less its radius), none for a rectangle's walls."""
    lay = asm.layout
    x = vec[lay["x"]:lay["x"] + asm.system.n]
    return {c: math.hypot(px + float(asm.contact_weights[c] @ x), py + float(w_y @ x)) - radius
            for c, (w_y, px, py, radius) in enumerate(asm.rings)}


def simulate_plan(building: PlanBuilding, excitation: Any, duration: Any, state: Optional[State], rtol: Any,
                  sample_rate_hz: Any, max_events: Any, max_steps: Any) -> PlanRun:
    """``simulate`` of a building in plan: the arguments checked in their order, the run, its result."""
    instance_of("excitation", excitation, (RecordPair, HarmonicPair, Record, Harmonic),
                "pounding.RecordPair or pounding.HarmonicPair (two components), pounding.Record or "
                "pounding.Harmonic (along x)")
    duration = positive("duration", duration, "s")
    rtol = check_rtol(rtol)
    max_events = integer("max_events", max_events, 1)
    max_steps = integer("max_steps", max_steps, 1)
    asm, free, touching = _kept(building)
    state = _start(state, asm)
    rate = history_rate(sample_rate_hz, duration)
    t0 = state.time_s
    harmonic = isinstance(excitation, (Harmonic, HarmonicPair))
    omega = excitation.omega_rad_s if harmonic else 0.0
    knots = 0
    if not harmonic:
        knots = int(np.count_nonzero((excitation.t >= t0) & (excitation.t <= t0 + duration)))
    why = (f"the forcing, {omega:.3g} rad/s" if omega > free else
           f"the building's fastest motion {free:.3g} rad/s")
    why += f", and {knots} record samples" if knots else ""
    least = float(steps_per_second(free, omega)) * duration + knots
    check_budget("duration", duration, least, max_steps, why,
                 "shorten the duration, or check the building's numbers (SI units: kg, N/m, N s/m)")
    most = float(steps_per_second(touching, omega)) * duration + knots
    forcing = kernel_forcing(excitation)
    ctl = new_control(max_steps)
    out = run_interruptibly(lambda: _core.run(
        asm.system, forcing, state.vector.copy(), t0 + duration, 1.0 / rate if rate > 0 else 0.0, rtol,
        int(max_events), True, ctl), [ctl], direct=most < DIRECT_CALL_STEPS)
    run = plan_run_of(building, asm, excitation, rate, out)
    if run.status == Status.INTERRUPTED:
        raise Interrupted(run, round(run.final_state.time_s - t0, 6), duration, "simulated seconds")
    return run


def plan_run_of(building: PlanBuilding, asm: PlanAssembly, excitation: Any, rate: float,
                out: _core.RunOutput) -> PlanRun:
    """The :class:`PlanRun` of the core's run of a building in plan (its status ``NONFINITE`` where a
    successful run's extrema or ledger are not finite)."""
    n, levels = asm.system.n, building.n_levels
    nh = asm.system.n_elements
    samples = out.samples
    k = samples.shape[0]
    status = Status(out.status)
    if status == Status.SUCCESS and not (np.isfinite(out.ledger).all() and np.isfinite(out.extrema).all()):
        status = Status.NONFINITE
    per_dof, tracked, norms = out.per_dof(n), out.per_pair(n), out.norms
    nx = _core.NORM_EXTREMA
    nb = len(building.bearings)
    bearing_q = np.array([[asm.tracked.index(("bearing", b, axis)) for axis in (0, 1)] for b in range(nb)])
    frame_q = [asm.tracked.index(("frame", f, "xy".index(fr.axis))) for f, fr in enumerate(building.frames)]
    element_of = {name: e for e, name in enumerate(asm.element_names)}
    bearing_e = [[element_of[("bearing", b, axis)] for axis in (0, 1)] for b in range(nb)]
    x = samples[:, 1:1 + n]
    weights = asm.tracked_weights[bearing_q]  # (nb, 2, n)
    corners = np.array(asm.corner_tracks, dtype=int).reshape(4, 2)
    return PlanRun(
        building=building, excitation=excitation, sample_rate_hz=rate, t=samples[:, 0],
        displacement=x.reshape(k, levels, 3), velocity=samples[:, 1 + n:1 + 2 * n].reshape(k, levels, 3),
        displacement_max=per_dof[:, X_D_MAX].reshape(levels, 3),
        displacement_max_time_s=per_dof[:, X_D_MAX_T].reshape(levels, 3),
        displacement_min=per_dof[:, X_D_MIN].reshape(levels, 3),
        displacement_min_time_s=per_dof[:, X_D_MIN_T].reshape(levels, 3),
        abs_acceleration_max=per_dof[:, X_A_MAX].reshape(levels, 3),
        bearing_displacement=np.einsum("kn,ban->kba", x, weights),
        bearing_force=samples[:, [1 + 3 * n + e for row in bearing_e for e in row]].reshape(k, nb, 2),
        bearing_displacement_max_m=norms[:nb, nx["max"]].copy(),
        bearing_displacement_max_time_s=norms[:nb, nx["max_t"]].copy(),
        bearing_displacement_at_max_m=norms[:nb, [nx["at_p"], nx["at_q"]]].copy(),
        plan_displacement_max_m=norms[nb:nb + levels, nx["max"]].copy(),
        bearing_axis_max_m=tracked[bearing_q, P_MAX], bearing_axis_min_m=tracked[bearing_q, P_MIN],
        frame_drift_max_m=tracked[frame_q, P_MAX], frame_drift_min_m=tracked[frame_q, P_MIN],
        corner_displacement_max_m=tracked[corners, P_MAX], corner_displacement_min_m=tracked[corners, P_MIN],
        clearance_m=_clearances(building, asm, tracked, norms[:, nx["max"]]),
        contact_force=samples[:, [1 + 3 * n + nh + c for c in range(len(asm.contacts))]],
        contact_slots=asm.contacts, contact_table=out.contacts, event_table=out.events,
        chatter_table=out.chatters, energy=EnergyLedger.of(out.ledger),
        final_state=State._of(out.state, asm.dofs, asm.layout), status=status)


def _clearances(building: PlanBuilding, asm: PlanAssembly, tracked: np.ndarray,
                lengths: np.ndarray) -> np.ndarray:
    """Each moat wall's smallest clearance over the run, m: its gap less its corners' largest approach
    (exact, from the corners' tracked extrema); a ring's (one): its radius less its corners' largest distance
    from its centre (exact, the corners' vectors' ``lengths``); empty without a moat."""
    if building.moat is None:
        return np.zeros(0)
    if asm.rings:
        return np.array([asm.rings[0][3] - float(np.max(lengths[list(asm.ring_vectors)]))])
    out = np.full(4, np.inf)
    for (side, _), q in zip(asm.contacts, asm.contact_tracks):
        approach = tracked[q, P_MAX] if side % 2 == 1 else -tracked[q, P_MIN]
        out[side] = min(out[side], building.moat.gap_m[side] - approach)
    return out


__all__ = ["plan_run_of", "simulate_plan"]
