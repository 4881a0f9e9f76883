"""What a sweep measures over a step's window, for any system: the labels of its levels, storeys and contact
slots, and the window's metrics (each level's exact extrema, each storey's drift, each contact slot's impact
sums, the strobes) - from the core's step alone where its window covers everything (one moving level, one
wall), else from the window run once more from its exact start.

The impact sums are the core step's own (``S_*`` of :mod:`pounding.metrics.impacts`): per slot, the contacts
that ended in the window, those with a restitution, and the sums of the ``IMPACT_COLUMNS``; a sweep's table
takes their means.
"""

from __future__ import annotations

import numpy as np

from .._checks import positive
from .._errors import InputError, Problem
from ..engine.kernels import (CONTACT_COLUMNS, DOF_EXTREMA, PAIR_EXTREMA, W_AMAX, W_DMAX, W_DMIN, W_SUMS,
                              RunOutput)
from ..metrics.impacts import IMPACT_COLUMNS, S_COUNT, S_N_RESTITUTION, S_SUMS, SIDE_SUMS, impact_values

# the core's columns: a level's extrema, a storey's drift, a contact's slot and end
_LEVEL = [DOF_EXTREMA[k] for k in ("d_max", "d_min", "a_abs_max")]
_DRIFT = [PAIR_EXTREMA[k] for k in ("max", "min")]
_SLOT, _T_END = CONTACT_COLUMNS["contact"], CONTACT_COLUMNS["t_end_s"]
NAMES = ("first", "second")  # (a pair's structures)


def check_adaptive_window(max_cycles: int, measure_cycles: int) -> None:
    """Refuse an adaptive step whose window cannot be compared with the cycles before it (``max_cycles``
    below ``2 measure_cycles + 1``)."""
    if max_cycles < 2 * measure_cycles + 1:
        raise InputError(Problem.TOO_SMALL, "max_cycles", max_cycles, minimum=2 * measure_cycles + 1,
                         hint=" (steadiness compares the window with the cycles before it)")


def check_steady_rtol(steady_rtol: object) -> float:
    """``steady_rtol`` (relative to the response amplitude) as a float in [1e-13, 0.1]."""
    rtol = positive("steady_rtol", steady_rtol, "(relative to the response amplitude)")
    if not 1e-13 <= rtol <= 0.1:
        raise InputError(Problem.OUT_OF_RANGE, "steady_rtol", rtol, range="[1e-13, 0.1]",
                         hint=" (below 1e-12 is rounding noise)")
    return float(rtol)


def labels_of(model: object, asm: object) -> tuple[tuple, tuple, tuple]:
    """(levels, storeys, contact slots) of a system, as rows of labels: a level ``(structure, level)``, a
    storey ``(structure, storey)`` (storey ``s`` under level ``s``), a slot ``(structure, "wall", wall, level,
    side)`` or ``(-1, "link", link, level_first, "")`` (a single mass: one level, its bumpers wall 0)."""
    from ..engine.assembly import structures_of

    structures, links = structures_of(model)
    levels = tuple((b, q) for b, s in enumerate(structures) for q in range(s.n_levels))
    storeys = tuple((b, q + 1) for b, s in enumerate(structures) for q in range(len(s.storeys)))
    slots = []
    for b, wall, side in asm.slots:
        if b >= 0:
            slots.append((b, "wall", wall, structures[b].walls[wall].level, ("left", "right")[side]))
        else:
            slots.append((-1, "link", wall, links[wall].level_first, ""))
    return levels, storeys, tuple(slots)


def step_measures_all(asm: object) -> bool:
    """Whether the core's step, which measures its window's first mass and first two contact slots, measures
    all of a system: one mass (no stand), one moving level, one wall (a single mass, a one-level structure);
    else a sweep or a basin runs the settled window once more (:func:`measure`)."""
    level_dof = [d for dofs in asm.dofs for d in dofs]
    return level_dof == [0] and asm.system.n == 1 and len(asm.slots) <= 2


def slot_masses(asm: object) -> np.ndarray:
    """Each contact slot's impacting mass, kg, shape (n_slots,): its level's mass against the ground, the
    pair's effective mass ``m_i m_j / (m_i + m_j)`` against another mass (a link, a bumper on its stand)."""
    m = asm.masses
    return np.array([m[p.i] if p.j < 0 else m[p.i] * m[p.j] / (m[p.i] + m[p.j]) for p in asm.pairs])


def level_name(levels: tuple, q: int) -> str:
    """A level's name in a legend: ``"level 2"``, ``"second level 2"`` for a pair's second structure."""
    b, level = levels[q]
    pair = len({s for s, _ in levels}) > 1
    return f"{NAMES[b]} level {level}" if pair else f"level {level}"


def slot_name(slots: tuple, c: int) -> str:
    """A contact slot's name in a legend and a Dataset: ``"wall 0 left"``, ``"second wall 1 right"``,
    ``"link 0"``."""
    b, kind, index, _level, side = slots[c]
    if kind == "link":
        return f"link {index}"
    who = f"{NAMES[b]} " if b > 0 else ""
    return f"{who}wall {index} {side}"


def from_step(window: np.ndarray, n_slots: int) -> tuple[np.ndarray, np.ndarray]:
    """A step's own window (the core's ``W_*`` row) as a one-level system's metrics: its level's (d_max,
    d_min, a_abs_max), shape (1, 3), and its slots' impact sums, shape (n_slots, SIDE_SUMS) (the core sums
    the first two slots: one wall's left and right sides)."""
    level = np.array([[window[W_DMAX], window[W_DMIN], window[W_AMAX]]])
    sums = window[W_SUMS:W_SUMS + 2 * SIDE_SUMS].reshape(2, SIDE_SUMS)[:n_slots]
    return level, sums


def measure(out: RunOutput, level_dof: list, peak_m_s2: float, masses: np.ndarray, level: np.ndarray,
            drift: np.ndarray, sums: np.ndarray, n_dof: int) -> None:
    """A window's second run (the core's output) into a step's rows: each level's extrema (a fixed base's:
    the ground's), each storey's drift, each contact slot's impact sums over the contacts that ended in the
    window (one already on at its start has its true start: the state carries it)."""
    per_dof, pairs = out.per_dof(n_dof), out.per_pair(n_dof)
    for q, d in enumerate(level_dof):
        level[q] = per_dof[d, _LEVEL] if d >= 0 else (0.0, 0.0, peak_m_s2)
    drift[:] = pairs[:len(drift)][:, _DRIFT]
    ended = out.contacts[np.isfinite(out.contacts[:, _T_END])]
    slot = ended[:, _SLOT].astype(int)
    values = impact_values(ended, masses[slot]) if len(ended) else np.zeros((0, len(IMPACT_COLUMNS)))
    sums[:] = 0.0
    for c in range(sums.shape[0]):
        mine = values[slot == c]
        sums[c, S_COUNT] = len(mine)
        moving = mine[np.isfinite(mine[:, 0])]  # (a contact met at rest has no restitution)
        sums[c, S_N_RESTITUTION] = len(moving)
        sums[c, S_SUMS] = float(np.sum(moving[:, 0]))
        sums[c, S_SUMS + 1:S_SUMS + len(IMPACT_COLUMNS)] = np.sum(mine[:, 1:], axis=0)


def strobes(samples: np.ndarray, level_dof: list, t0: float, period: float, m: int,
            n_dof: int) -> np.ndarray:
    """Each level's (displacement, velocity) at the end of each of a window's ``m`` cycles, from its second
    run's samples (uniform at the period, and one at each event), shape (m, 2, levels)."""
    out = np.full((m, 2, len(level_dof)), np.nan)
    j = np.rint((samples[:, 0] - t0) / period)
    on = (np.abs(samples[:, 0] - (t0 + j * period)) <= 1e-9 * period) & (j >= 1) & (j <= m)
    for row in samples[on]:
        k = int(round((row[0] - t0) / period)) - 1
        for q, d in enumerate(level_dof):
            out[k, :, q] = (row[1 + d], row[1 + n_dof + d]) if d >= 0 else (0.0, 0.0)
    return out
