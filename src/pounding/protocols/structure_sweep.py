"""A stepped-sine sweep of a structure of several masses (:func:`pounding.sweep` with a
:class:`~pounding.Structure` or :class:`~pounding.Adjacent`).

Each step runs as a single mass's does (the core's ``step``: cycles until the whole state, every level's,
repeats at the cycle ends, or a fixed number), and its measured window is then run once more from the
exact state at its start, for every level's exact extrema, every storey's drift and every contact.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from .._errors import Interrupted, Status
from ..engine.control import new_control
from ..engine.layout import T
from ..engine.kernels import (CONTACT_COLUMNS, DOF_EXTREMA, PAIR_EXTREMA, W_CYCLES, RunOutput, StepOutput,
                              run_window)
from ..engine.assembly import assemble
from ..engine.state import State
from ..excitation import GRAVITY_M_S2, Harmonic
from .sweep_result import sweep_message
from .structure_sweep_result import (C_COUNT, C_IMPULSE, C_PEAK, C_RESTITUTION, C_TIME, CONTACT_STATS,
                                     StructureSweepResult,
                                     labels_of)

# the core's columns: a level's extrema, a storey's drift, a contact's row
_LEVEL = [DOF_EXTREMA[k] for k in ("d_max", "d_min", "a_abs_max")]
_DRIFT = [PAIR_EXTREMA[k] for k in ("max", "min")]
_SLOT, _T_START, _T_END, _V_IN, _V_OUT, _IMPULSE, _PEAK = (
    CONTACT_COLUMNS[k] for k in ("contact", "t_start_s", "t_end_s", "v_in_m_s", "v_out_m_s", "impulse_n_s",
                                 "peak_force_n"))


def run_structure_plan(plan, advance: Callable[[int], None] | None = None,
                       control: np.ndarray | None = None) -> StructureSweepResult:
    """Run a validated plan (``sweep.make_plan`` of a structure) step by step; ``advance(1)`` after each
    step; on a stop from ``control`` (or a KeyboardInterrupt) :class:`~pounding.Interrupted` carries the
    finished steps."""
    ctl = new_control(plan.max_steps) if control is None else control
    model = plan.oscillator
    asm = assemble(model)
    system = asm.system
    n_steps = plan.freqs_hz.size
    levels, storeys, slots = labels_of(model, asm)
    level_dof = [d for dofs in asm.dofs for d in dofs]
    level = np.full((n_steps, len(levels), 3), np.nan)       # dmax, dmin, amax
    drift = np.full((n_steps, len(storeys), 2), np.nan)      # max, min
    contact = np.full((n_steps, len(slots), CONTACT_STATS), np.nan)
    cycles_run = np.zeros(n_steps, dtype=np.int64)
    period_multiple = np.zeros(n_steps, dtype=np.int64)
    window_cycles = np.zeros(n_steps, dtype=np.int64)
    window_states = np.full((n_steps, system.layout["size"]), np.nan)
    strobe_cap = plan.measure_cycles + (plan.max_period - 1 if plan.steady == "adaptive" else 0)
    strobes = np.full((n_steps, strobe_cap, 2, len(levels)), np.nan)
    step_start_s = np.full(n_steps, np.nan)
    state = plan.state.vector.copy()

    def take(i: int, f: float, start: np.ndarray, exc: Harmonic, stepped: StepOutput) -> int:
        code, win_state = stepped.status, stepped.window_state
        m = int(stepped.window[W_CYCLES])
        if code == Status.SUCCESS:  # the window once more, from its exact start, every level measured
            t0 = float(win_state[T])
            at = Harmonic(plan.a_g, f, phase=-(exc.omega_rad_s * t0))
            period = 1.0 / float(f)
            out = run_window(system, at.peak_m_s2, at.omega_rad_s, at.phase, win_state, t0 + m * period,
                             period, plan.rtol, plan.max_events_per_cycle * m, ctl)
            code = out.status
            if code == Status.INTERRUPTED:
                return code
            if code == Status.SUCCESS:
                _measure(out, level_dof, at.peak_m_s2, m, t0, level[i], drift[i], contact[i], system.n)
                strobes[i, :min(m, strobe_cap)] = _strobes(out.samples, level_dof, t0, period, m,
                                                           system.n)[:strobe_cap]
        step_start_s[i] = start[T]
        cycles_run[i] = stepped.cycles_run
        period_multiple[i] = stepped.period_multiple
        window_cycles[i] = m
        window_states[i] = win_state
        return code

    state, done, status, interrupted = plan.steps(system, state, ctl, advance, take)
    result = StructureSweepResult(
        structure=model, a_g=plan.a_g, freqs_hz=plan.freqs_hz, direction=plan.direction,
        steady_mode=plan.steady, cycles=plan.cycles, measure_cycles=plan.measure_cycles,
        f_ref_hz=plan.f_ref_hz,
        g=GRAVITY_M_S2, levels=levels, storeys=storeys, contact_slots=slots, level_metrics=level,
        drift_metrics=drift, contact_metrics=contact, cycles_run=cycles_run, period_multiple=period_multiple,
        window_cycles=window_cycles, window_states=window_states, step_start_s=step_start_s, steps_done=done,
        final_state=State._of(state, asm.dofs, system.layout), status=status, window_strobes=strobes,
        omega_min_rad_s=plan.omega_min_rad_s,
        message=sweep_message(status, done, n_steps, plan, cycles_run, period_multiple, interrupted))
    if interrupted:
        raise Interrupted(result, done, n_steps)
    return result


def _strobes(samples: np.ndarray, level_dof: list, t0: float, period: float, m: int,
             n_dof: int) -> np.ndarray:
    """Each level's (displacement, velocity) at the end of each of a window's ``m`` cycles, from its run's
    samples (uniform at the period, and one at each event), shape (m, 2, levels)."""
    out = np.full((m, 2, len(level_dof)), np.nan)
    j = np.rint((samples[:, 0] - t0) / period)
    on = (np.abs(samples[:, 0] - (t0 + j * period)) <= 1e-9 * period) & (j >= 1) & (j <= m)
    for row in samples[on]:
        k = int(round((row[0] - t0) / period)) - 1
        for q, d in enumerate(level_dof):
            out[k, :, q] = (row[1 + d], row[1 + n_dof + d]) if d >= 0 else (0.0, 0.0)
    return out


def _measure(out: RunOutput, level_dof: list, peak_m_s2: float, m: int, t0: float,
             level: np.ndarray, drift: np.ndarray, contact: np.ndarray, n_dof: int) -> None:
    """One window's run (the core's output) into a step's rows: each level's extrema, each storey's drift,
    each contact slot's statistics (the contacts that ended in the window, per cycle)."""
    contacts, per_dof, pairs = out.contacts, out.per_dof(n_dof), out.per_pair(n_dof)
    for q, d in enumerate(level_dof):
        level[q] = per_dof[d, _LEVEL] if d >= 0 else (0.0, 0.0, peak_m_s2)  # (a fixed base: the ground)
    drift[:] = pairs[:len(drift)][:, _DRIFT]
    ended = contacts[np.isfinite(contacts[:, _T_END])]
    for c in range(contact.shape[0]):
        rows = ended[ended[:, _SLOT] == c]
        contact[c, C_COUNT] = len(rows) / m
        # (a contact already on at the window's start has its true start: the state carries it)
        contact[c, C_TIME] = float(np.mean(rows[:, _T_END] - rows[:, _T_START])) if len(rows) else math.nan
        contact[c, C_IMPULSE] = float(np.mean(rows[:, _IMPULSE])) if len(rows) else math.nan
        contact[c, C_PEAK] = float(np.max(rows[:, _PEAK])) if len(rows) else math.nan
        moving = rows[rows[:, _V_IN] != 0.0]  # (a contact met at rest has no restitution)
        contact[c, C_RESTITUTION] = (float(np.mean(-moving[:, _V_OUT] / moving[:, _V_IN])) if len(moving)
                                     else math.nan)
