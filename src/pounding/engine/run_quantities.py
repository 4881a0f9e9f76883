"""Every run in a few peaks (a study's point, a pounding spectrum's run, a design's stripe): one function
for every system's run, a single mass's, a structure's, a pair's (:func:`peaks_of`), read off its result or
off the core's outputs alone (:class:`PartPeaks`, what ``engine.simulate.peaks`` reads)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from .._errors import Status
from .._tables import RunQuantities
from ..excitation.peak import ground_peak
from .layout import CONTACT_COLUMNS as CORE_CONTACT_COLUMNS
from .layout import force_max, impulses
from .layout import (C_MAX_COMPRESSION, C_SLOT, C_V_IN, DOF_EXTREMA_LEN, P_MAX, P_MIN, X_A_MAX, X_A_MAX_T,
                     X_D_MAX, X_D_MAX_T, X_D_MIN, X_D_MIN_T)

if TYPE_CHECKING:
    from ..model.structure import Structure


# every run's point (a study's, a pounding spectrum's, a design stripe's), one meaning for every system: a
# single mass is a one-level structure, its base, its top and its only level the mass
RUN_QUANTITIES = ("acc_max_g", "disp_max_m", "impacts", "impact_force_max_n", "impact_speed_max_m_s",
                  "compression_max_m", "top_disp_max_m", "top_acc_max_g", "drift_ratio_max", "status")


def peaks_of(run: Any, g: float) -> dict[str, float]:
    """Every run in a few peaks, :data:`RUN_QUANTITIES` (a structure's, one of a single mass or two
    adjacent ones'): the largest absolute acceleration over every level (``acc_max_g``, g); the (first)
    structure's base's largest displacement (``disp_max_m``: a single mass's own, a building's base: the
    moat's demand); the contacts at every wall and link (``impacts``), their largest force
    (``impact_force_max_n``, N), approach speed (``impact_speed_max_m_s``) and compression
    (``compression_max_m``), 0 without contact; the (first) structure's top level's largest displacement
    and acceleration (``top_disp_max_m``, ``top_acc_max_g``: a single mass's own); the largest storey drift
    ratio (``drift_ratio_max``, NaN without storeys); ``status``.  A rigid stop's impact is an impulse: its
    force, and the acceleration of the level it strikes, are unbounded (inf), the rest exact.  The name
    before of ``disp_max_m``, ``base_disp_max_m``, still answers (``RunQuantities``)."""
    if hasattr(run, "link_table"):  # (two adjacent ones)
        return run_peaks([run.first, run.second], run.link_table, run.adjacent.links, run.status, g)
    return run_peaks([run], None, (), run.status, g)


def run_peaks(parts: list, link_table: Optional[np.ndarray], links: tuple, status: Status,
              g: float) -> dict[str, float]:
    """:func:`peaks_of` of a run's parts (each structure's :class:`StructureRun`, or its :class:`PartPeaks`
    alone), a pair's link rows and its links (``link_table`` None: one structure), its status; ``g`` the
    excitation's, m/s^2."""
    first = parts[0]

    def peak(part: Any, level: int) -> float:
        return max(abs(float(part.displacement_max[level])), abs(float(part.displacement_min[level])))

    ratios = [np.maximum(np.abs(part.drift_max), np.abs(part.drift_min))
              / np.array([s.height_m for s in part.structure.storeys])
              for part in parts if len(part.structure.storeys)]
    tables = [part.contact_table for part in parts] + ([link_table] if link_table is not None else [])
    rows = tables[0] if len(tables) == 1 else np.concatenate(tables)  # (never empty: the first part's)
    struck: list[set] = [set() for _ in parts]  # (each part's levels a rigid impact hit)
    if len(rows) and impulses(rows).any():
        for part, levels in zip(parts, struck):
            levels.update(part.structure.walls[int(slot) // 2].level
                          for slot in part.contact_table[impulses(part.contact_table), C_SLOT])
        if link_table is not None:
            for slot in link_table[impulses(link_table), C_SLOT]:
                link = links[int(slot)]
                struck[0].add(link.level_first)
                struck[1].add(link.level_second)
    top = len(first.structure.storeys)
    n = len(rows)
    acc = max(float(np.max(part.abs_acceleration_max)) for part in parts) / g
    return RunQuantities({
        "acc_max_g": math.inf if any(struck) else acc,
        "disp_max_m": peak(first, 0),
        "impacts": float(n),
        "impact_force_max_n": force_max(rows),
        "impact_speed_max_m_s": float(np.abs(rows[:, C_V_IN]).max()) if n else 0.0,
        "compression_max_m": float(rows[:, C_MAX_COMPRESSION].max()) if n else 0.0,
        "top_disp_max_m": peak(first, -1),
        "top_acc_max_g": math.inf if top in struck[0] else float(first.abs_acceleration_max[-1]) / g,
        "drift_ratio_max": float(max(np.max(r) for r in ratios)) if ratios else math.nan,
        "status": float(status)})


def part_extrema(structure: "Structure", b: int, asm: Any, asm_structures: tuple, excitation: Any, out: Any,
                 t0: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Structure ``b``'s exact extrema and contacts in a joint run (``out``: the core's ``RunOutput``;
    ``asm``: the assembly): each level's extrema, shape (levels, DOF_EXTREMA_LEN) (a fixed base's level 0
    the ground's, still and shaken by the table from ``t0`` to the run's last row), each storey's drift's,
    shape (storeys, PAIR_EXTREMA_LEN), and its contact rows, shape (contacts, columns), their slots numbered
    as its own."""
    n = asm.system.n
    t = out.samples[:, 0]
    dofs = asm.dofs[b]
    per_dof, tracked = out.per_dof(n), out.per_pair(n)
    first = sum(len(s.storeys) for s in asm_structures[:b])  # (this structure's storeys' drifts)
    drifts = tracked[first:first + len(structure.storeys)]
    if min(dofs, default=0) < 0:  # (a fixed base's level 0: the ground, still, shaken by the table)
        ground = np.full(DOF_EXTREMA_LEN, np.nan)
        ground[[X_D_MAX, X_D_MAX_T, X_D_MIN, X_D_MIN_T]] = (0.0, t0, 0.0, t0)
        ground[[X_A_MAX, X_A_MAX_T]] = ground_peak(excitation, t0, t[-1] if t.size else t0)
        ex = np.array([per_dof[d] if d >= 0 else ground for d in dofs]).reshape(len(dofs), DOF_EXTREMA_LEN)
    else:
        ex = per_dof[list(dofs)]
    mine = [c for c, (owner, _, _) in enumerate(asm.slots) if owner == b]
    contacts = out.contacts
    if len(mine) == len(asm.slots):  # (every contact slot its own, numbered as its)
        table = contacts.copy()
    else:
        slot = CORE_CONTACT_COLUMNS["contact"]
        owned = np.zeros(len(asm.slots), dtype=bool)
        owned[mine] = True
        table = contacts[owned[contacts[:, slot].astype(int)]]
        table[:, slot] = np.searchsorted(mine, table[:, slot])  # (slot numbers of this structure's own)
    return ex, drifts, table


@dataclass(frozen=True, slots=True)
class PartPeaks:
    """What :func:`run_peaks` reads of one structure's part of a run: its model, each level's largest and
    smallest displacement and largest absolute acceleration, each storey's largest and smallest drift, its
    contact rows (a :class:`StructureRun` has each of these; this is them alone, read off the core's run)."""

    structure: Any
    displacement_max: np.ndarray
    displacement_min: np.ndarray
    abs_acceleration_max: np.ndarray
    drift_max: np.ndarray
    drift_min: np.ndarray
    contact_table: np.ndarray

    @classmethod
    def of(cls, structure: "Structure", b: int, asm: Any, asm_structures: tuple, excitation: Any, out: Any,
           t0: float) -> "PartPeaks":
        ex, drifts, table = part_extrema(structure, b, asm, asm_structures, excitation, out, t0)
        return cls(structure=structure, displacement_max=ex[:, X_D_MAX], displacement_min=ex[:, X_D_MIN],
                   abs_acceleration_max=ex[:, X_A_MAX], drift_max=drifts[:, P_MAX],
                   drift_min=drifts[:, P_MIN], contact_table=table)
