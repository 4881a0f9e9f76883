"""The engine's kernels as the protocols and the analyses call them: no module outside the engine calls the
compiled core (``pounding._core``, the one door).

* :func:`run_step` - one frequency step of a stepped-sine sweep, held cycle by cycle until steady (a sweep's,
  a basin's state's); what it returns is named (:class:`StepOutput`), its window's and cycles' columns are
  the core's (``W_*``, ``CY_*``).
* :func:`run_window` - a run of whole forcing cycles from a state, events only or sampled (a settled window
  measured once more); a :class:`RunOutput`.
* :func:`monodromy` - the exact Jacobian of a run's map (:class:`Monodromy`).
* :func:`law_forces` - a contact law's forces along a path of compressions (a fit's model).

The step holds its cycles one forcing period at a time (the state carried over is exact, so cutting at cycle
ends changes nothing).  After each cycle the state at the cycle end (the stroboscopic sample, table phase 0)
is kept; the response is steady with period multiple ``k`` when the last ``m`` strobes repeat those ``k``
cycles earlier to within ``steady_rtol`` of the response amplitude, after allowing for how slowly the
strobes still converge.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import _core
from .._core import (CONTACT_COLUMNS, Forcing, DOF_EXTREMA, EXCITATION, LAYOUT, PAIR_EXTREMA,  # noqa: F401
                     Monodromy, RunOutput, StepOutput, System, periodicity)  # (the door's names and types)

# a step's per-cycle record: exact extrema, then the impact sums of both sides (metrics: S_*)
CY_DMAX, CY_DMIN, CY_AMAX, CY_SUMS = (LAYOUT[k] for k in ("CY_DMAX", "CY_DMIN", "CY_AMAX", "CY_SUMS"))
CYCLE_COLS = LAYOUT["CYCLE_COLS"]
# its measurement window: extrema, number of cycles, impact sums (left then right), the events located
# (all, and the friction isolators' sticks)
W_DMAX, W_DMIN, W_AMAX, W_CYCLES, W_SUMS, W_EVENTS, W_STICKS = (
    LAYOUT[k] for k in ("W_DMAX", "W_DMIN", "W_AMAX", "W_CYCLES", "W_SUMS", "W_EVENTS", "W_STICKS"))
WINDOW_COLS = LAYOUT["WINDOW_COLS"]


def run_step(system: Any, amp_m_s2: float, omega_rad_s: float, state: np.ndarray, steady: tuple, rtol: float,
             max_events: int, control: np.ndarray) -> StepOutput:
    """Hold ``amp_m_s2 sin(omega_rad_s (t - t0))`` on the core's ``system`` from the state vector ``state``
    (time ``t0``) until steady: ``steady`` is ``(adaptive, n_cycles, measure_cycles, steady_rtol,
    max_period)``; ``control`` the run control (``pounding._control``)."""
    return _core.step(system, amp_m_s2, omega_rad_s, state, steady, rtol, max_events, control)


def run_window(system: Any, amp_m_s2: float, omega_rad_s: float, phase_rad: float, state: np.ndarray,
               t_end_s: float, sample_dt_s: float, rtol: float, max_events: int,
               control: np.ndarray) -> RunOutput:
    """The core's ``system`` under ``amp_m_s2 sin(omega_rad_s t + phase_rad)`` from the state vector
    ``state`` to ``t_end_s``, without the energy integrals: ``sample_dt_s`` the history's step (0: at
    events only; -1: no history)."""
    forcing = Forcing(kind=EXCITATION["harmonic"], p=np.array([amp_m_s2, omega_rad_s, phase_rad]),
                      rec_t=np.zeros(1), rec_a=np.zeros(1))
    return _core.run(system, forcing, np.array(state, dtype=float), t_end_s, sample_dt_s, rtol, max_events,
                     False, control)


def monodromy(system: Any, state: np.ndarray, events: np.ndarray, t_end_s: float, omega_rad_s: float,
              amp_m_s2: float, phase_rad: float) -> Monodromy:
    """The exact Jacobian of the core's ``system``'s map of its coordinates (displacements, velocities,
    compressions, slips) from the state vector ``state`` to ``t_end_s`` along the run's ``events`` (rows of
    t, action, index) under ``amp_m_s2 sin(omega_rad_s t + phase_rad)``."""
    return _core.monodromy(system, state, events, t_end_s, omega_rad_s, amp_m_s2, phase_rad)


def law_forces(law_id: int, params: np.ndarray, d_m: np.ndarray, dd_m_s: np.ndarray) -> np.ndarray:
    """A contact law's force (N) along a path from the unloaded bumper, shape (p,): its core id
    ``law_id`` and parameters ``params`` (a law's ``LAW_ID`` and ``params()``), the compressions ``d_m``
    (m) and their rates ``dd_m_s`` (m/s), shape (p,) each, in the path's order (a hysteretic law's
    state follows it)."""
    d = np.ascontiguousarray(d_m, dtype=float)
    dd = np.ascontiguousarray(dd_m_s, dtype=float)
    if d.ndim != 1 or dd.shape != d.shape:
        raise ValueError(f"law_forces: compressions of shape {d.shape} and rates of shape {dd.shape}; give "
                         "two 1-D arrays of one length")
    out = np.empty(d.size)
    _core.law_force_many(law_id, params, d, dd, out)
    return out
