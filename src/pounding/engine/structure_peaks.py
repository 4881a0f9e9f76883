"""A structure's run in a few peaks (what a study's point, a pounding spectrum's run and a design's stripe
keep of it)."""

from __future__ import annotations

import math

import numpy as np

from ._layout import CONTACT_COLUMNS, impulses
from .adjacent_result import AdjacentRun
from .structure_result import StructureRun

# (the core's contact rows)
_SLOT, _PEAK_FORCE, _V_IN = (CONTACT_COLUMNS[k] for k in ("contact", "peak_force_n", "v_in_m_s"))


def force_max(table: np.ndarray) -> float:
    """A contact table's largest force, N: 0 without contact, inf where a rigid stop was struck (an impulse's
    force is unbounded; its impulse is in the table)."""
    if not len(table):
        return 0.0
    return math.inf if impulses(table).any() else float(table[:, _PEAK_FORCE].max())


def peaks_of(run: "StructureRun | AdjacentRun", g: float) -> dict[str, float]:
    """A structure's run (or two adjacent ones') in a few peaks: the (first) structure's base and top floor's
    largest displacement (``base_disp_max_m``, ``top_disp_max_m``) and the top floor's acceleration
    (``top_acc_max_g``, g); the largest absolute acceleration (``acc_max_g``, g) and storey drift ratio
    (``drift_ratio_max``) over every level and storey; the contacts at every wall and link (``impacts``),
    their largest force (``impact_force_max_n``, N) and approach speed (``impact_speed_max_m_s``), 0 without
    contact; ``status``.  A rigid stop's impact is an impulse: its force, and the acceleration of the level
    it strikes, are unbounded (inf), the rest exact."""
    parts = [run.first, run.second] if isinstance(run, AdjacentRun) else [run]
    first = parts[0]

    def peak(part: StructureRun, level: int) -> float:
        return max(abs(float(part.displacement_max[level])), abs(float(part.displacement_min[level])))

    ratios = [part.peak_drift / np.array([s.height_m for s in part.structure.storeys])
              for part in parts if len(part.structure.storeys)]
    tables = [part.contact_table for part in parts] + ([run.link_table] if len(parts) > 1 else [])
    rows = np.concatenate(tables)  # (never empty: the first part's table at least)
    struck = [{part.structure.walls[int(slot) // 2].level for slot in part.contact_table[
        impulses(part.contact_table), _SLOT]} for part in parts]  # (each part's levels a rigid impact struck)
    if len(parts) > 1:
        for slot in run.link_table[impulses(run.link_table), _SLOT]:
            link = run.adjacent.links[int(slot)]
            struck[0].add(link.level_first)
            struck[1].add(link.level_second)
    top = len(first.structure.storeys)
    return {"base_disp_max_m": peak(first, 0), "top_disp_max_m": peak(first, -1),
            "acc_max_g": math.inf if any(struck) else max(float(np.max(p.abs_acceleration_max))
                                                          for p in parts) / g,
            "top_acc_max_g": math.inf if top in struck[0] else float(first.abs_acceleration_max[-1]) / g,
            "drift_ratio_max": float(max(np.max(r) for r in ratios)) if ratios else float("nan"),
            "impacts": float(len(rows)),
            "impact_force_max_n": force_max(rows),
            "impact_speed_max_m_s": float(np.abs(rows[:, _V_IN]).max()) if len(rows) else 0.0,
            "status": float(run.status)}
