"""What one point of a study keeps for a structure (or two adjacent ones): its peaks over the levels,
storeys, walls and links (``points.STRUCTURE_QUANTITIES``)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

_PEAK_FORCE = 6  # (the core's contact rows: slot, t_start, t_end, v_in, v_out, impulse, peak force, ...)


def run_parts(run: Any) -> list:
    """A structure's run, or each of two adjacent ones' (``AdjacentRun.first``, ``.second``)."""
    return [run.first, run.second] if hasattr(run, "first") else [run]


def structure_run_quantities(run: Any, g: float) -> dict[str, float]:
    """A structure's run's peaks (``STRUCTURE_RUN_QUANTITIES``): the (first) structure's base and top
    floor's largest displacement (m) and the top floor's acceleration (g); the largest absolute
    acceleration (g) and storey drift ratio over every level and storey; the contacts at every wall and
    link and their largest force (N, 0 without contact)."""
    parts = run_parts(run)
    first = parts[0]

    def peak(part: Any, level: int) -> float:
        return max(abs(float(part.displacement_max[level])), abs(float(part.displacement_min[level])))

    drift_ratio = [part.peak_drift / np.array([s.height_m for s in part.structure.storeys])
                   for part in parts if len(part.structure.storeys)]
    tables = [part.contact_table for part in parts] + ([run.link_table] if len(parts) > 1 else [])
    forces = np.concatenate([t[:, _PEAK_FORCE] for t in tables])
    return {"base_disp_max_m": peak(first, 0), "top_disp_max_m": peak(first, -1),
            "acc_max_g": max(float(np.max(p.abs_acceleration_max)) for p in parts) / g,
            "top_acc_max_g": float(first.abs_acceleration_max[-1]) / g,
            "drift_ratio_max": float(max(np.max(r) for r in drift_ratio)) if drift_ratio else math.nan,
            "impacts": float(forces.size), "impact_force_max_n": float(forces.max()) if forces.size else 0.0,
            "status": float(run.status)}


def structure_point(system: Any, options: dict[str, Any], max_steps: int, names: tuple, excitation: Any,
                    sweep_args: dict[str, Any]) -> np.ndarray:
    """One study point of a structure: its quantities ``names`` in order (``excitation``: the run's, None
    for a sweep; ``sweep_args``: a sweep's options)."""
    from ..engine.simulate import simulate
    from ..protocols.sweep import sweep

    if options["kind"] == "sweep":
        freqs = options.get("freqs_hz")
        res = sweep(system, options["a_g"], None if freqs is None else np.asarray(freqs, dtype=float),
                    options.get("direction", "up"), max_steps=max_steps, **sweep_args)
        q = res.quantities()
        q["steps_done"] = float(res.steps_done)
        q["status"] = float(res.status)
    else:
        duration = options.get("duration_s")
        if duration is None:  # (a record's own length)
            duration = float(excitation.t[-1])
        run = simulate(system, excitation, duration, sample_rate_hz=0, max_steps=max_steps)
        q = structure_run_quantities(run, excitation.g)
    return np.array([q[k] for k in names], dtype=float)
