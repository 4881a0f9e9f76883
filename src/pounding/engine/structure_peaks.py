"""A structure's run in a few peaks (what a study's point, a pounding spectrum's run and a design's stripe
keep of it)."""

from __future__ import annotations

import numpy as np

from .structure_result import AdjacentRun, StructureRun


# (the core's contact rows: slot, t_start, t_end, v_in, v_out, impulse, peak force, ...)
_PEAK_FORCE, _V_IN = 6, 3


def peaks_of(run: "StructureRun | AdjacentRun", g: float) -> dict[str, float]:
    """A structure's run (or two adjacent ones') in a few peaks: the (first) structure's base and top floor's
    largest displacement (``base_disp_max_m``, ``top_disp_max_m``) and the top floor's acceleration
    (``top_acc_max_g``, g); the largest absolute acceleration (``acc_max_g``, g) and storey drift ratio
    (``drift_ratio_max``) over every level and storey; the contacts at every wall and link (``impacts``),
    their largest force (``impact_force_max_n``, N) and approach speed (``impact_speed_max_m_s``), 0 without
    contact; ``status``."""
    parts = [run.first, run.second] if isinstance(run, AdjacentRun) else [run]
    first = parts[0]

    def peak(part: StructureRun, level: int) -> float:
        return max(abs(float(part.displacement_max[level])), abs(float(part.displacement_min[level])))

    ratios = [part.peak_drift / np.array([s.height_m for s in part.structure.storeys])
              for part in parts if len(part.structure.storeys)]
    tables = [part.contact_table for part in parts] + ([run.link_table] if len(parts) > 1 else [])
    rows = np.concatenate(tables) if tables else np.zeros((0, 9))
    return {"base_disp_max_m": peak(first, 0), "top_disp_max_m": peak(first, -1),
            "acc_max_g": max(float(np.max(p.abs_acceleration_max)) for p in parts) / g,
            "top_acc_max_g": float(first.abs_acceleration_max[-1]) / g,
            "drift_ratio_max": float(max(np.max(r) for r in ratios)) if ratios else float("nan"),
            "impacts": float(len(rows)),
            "impact_force_max_n": float(rows[:, _PEAK_FORCE].max()) if len(rows) else 0.0,
            "impact_speed_max_m_s": float(np.abs(rows[:, _V_IN]).max()) if len(rows) else 0.0,
            "status": float(run.status)}
