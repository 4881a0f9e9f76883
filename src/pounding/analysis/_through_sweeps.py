"""Branches through the sweeps' own settled steps.

A branch continued from one start finds the orbits connected to that start.  A sweep's settled steps
may lie elsewhere: on another branch, on an isola, on another member of a family of orbits that
differ by a kinematic element's frozen slips, or on a response of another period.  Each settled
period-1 step that no branch passes through (within ``ON_BRANCH_RTOL`` on alpha and the excursion,
read along the branch between its points) starts a short branch of its own, continued from the step's
exact window state to half way to its neighbouring steps on either side: every settled period-1 step
then lies on a drawn branch, exactly at its own frequency.  A step of another period, or whose orbit
Newton cannot solve from its state, is said to lie off every branch, with why.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from typing import Any

import numpy as np
import pandas as pd

from .._errors import InputError
from .witnesses import _witness_table, branch_responses

ON_BRANCH_RTOL = 1e-3   # a step lies on a branch when alpha and the excursion agree this closely
LOCAL_MAX_STEP = 0.5    # a step's own branch: at least 2 points each side (more where it bends)
STEP_COLUMNS = ("a_g", "direction", "freq_hz", "alpha", "excursion_m", "period_multiple", "steady",
                "on_branch", "branch", "why")


def window_states(system: Any, sweep: Any) -> Iterator[tuple[int, float, Any]]:
    """``(step, freq_hz, state)`` of each finished step of a sweep: the exact state at the start of
    its window, moved to the section (time 0, table phase 0; a contact in progress keeps its start
    relative to it), as a guess for :func:`periodic_orbit`, :func:`continuation` or :func:`lyapunov`
    under ``Harmonic(sweep.a_g, freq_hz)``."""
    from ..engine.state import State
    from ..engine.assembly import assemble
    from ._shooting import at_section

    asm = assemble(system)
    layout, n_contacts = asm.layout, len(asm.pairs)
    for i in range(int(sweep.steps_done)):
        vec = at_section(np.array(sweep.window_states[i], dtype=float), layout, n_contacts)
        yield i, float(sweep.freqs_hz[i]), State._of(vec, asm.dofs, layout)


def _on(branch: Any, freq_hz: float, alpha: float, excursion_m: float) -> bool:
    return any(math.isclose(a, alpha, rel_tol=ON_BRANCH_RTOL)
               and math.isclose(e, excursion_m, rel_tol=ON_BRANCH_RTOL, abs_tol=1e-12)
               for _p, _h, a, e, _s in branch_responses(branch, freq_hz))


def _window(freqs: np.ndarray, f: float, f_box: tuple[float, float]) -> tuple[float, float]:
    """Half way to the neighbouring frequencies of the sweep (its step at the ends), inside the box."""
    grid = np.unique(freqs)
    below, above = grid[grid < f], grid[grid > f]
    step = float(np.min(np.diff(grid))) if grid.size > 1 else 0.1
    lo = f - 0.5 * ((f - below[-1]) if below.size else step)
    hi = f + 0.5 * ((above[0] - f) if above.size else step)
    return max(lo, min(f_box)), min(hi, max(f_box))


def through_sweeps(system: Any, sweeps: Sequence[Any], branches: Sequence[Any], f_box: tuple[float, float],
                   method: str = "auto") -> tuple[tuple[Any, ...], pd.DataFrame]:
    """Branches through the settled steps of ``sweeps`` that no branch of ``branches`` (nor one
    started here) passes through, and every step's place.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The sweeps' system.
    sweeps : sequence of SweepResult
        Harmonic sweeps of ``system`` (any a_G, up or down).
    branches : sequence of Branch
        Branches in the frequency already found (a level's, at the sweeps' a_G).
    f_box : (float, float)
        The frequencies the branches may span, Hz.
    method : {"auto", "exact", "finite-difference"}
        The monodromy, as in :func:`continuation`.

    Returns
    -------
    seeded : tuple of Branch
        The branches started at steps, two per step (up and down in frequency, to half way to the
        neighbouring steps), in the order of the sweeps and their steps.
    steps : DataFrame
        One row per finished step (``STEP_COLUMNS``): ``on_branch``, ``branch`` (``"level"`` for a
        branch of ``branches``, ``"seeded"`` for one started here, ``""`` off every branch) and
        ``why`` (in words, for a step off every branch: another period, not settled, no orbit).
    """
    from .continuation import continuation

    seeded: list[Any] = []
    rows = []
    for sw in sweeps:
        table = _witness_table(sw)
        level = [br for br in branches if math.isclose(br.a_g, sw.a_g, rel_tol=1e-9)]
        for (i, f, state), (_, row) in zip(window_states(system, sw), table.iterrows()):
            alpha, exc, period = float(row["alpha"]), float(row["excursion_m"]), int(row["period_multiple"])
            out = {"a_g": float(sw.a_g), "direction": sw.direction, "freq_hz": f, "alpha": alpha,
                   "excursion_m": exc, "period_multiple": period, "steady": bool(row["steady"]),
                   "on_branch": False, "branch": "", "why": ""}
            rows.append(out)
            if not row["steady"]:
                out["why"] = "not settled: a motion still changing, on no periodic orbit"
                continue
            if period != 1:
                out["why"] = f"a response of period {period}: off every period-1 branch"
                continue
            if not min(f_box) <= f <= max(f_box):
                out["why"] = "outside the branches' frequencies"
                continue
            if any(_on(br, f, alpha, exc) for br in level):
                out.update(on_branch=True, branch="level")
                continue
            if any(_on(br, f, alpha, exc) for br in seeded if math.isclose(br.a_g, sw.a_g, rel_tol=1e-9)):
                out.update(on_branch=True, branch="seeded")
                continue
            lo, hi = _window(sw.freqs_hz[: sw.steps_done], f, f_box)
            try:
                own = [continuation(system, sw.a_g, (f, end), guess=state, max_step=LOCAL_MAX_STEP,
                                    method=method) for end in (hi, lo) if end != f]
            except InputError as exc_:
                why = exc_._details.get("why", "Newton did not converge")
                out["why"] = f"no period-1 orbit solved from its state: {why}"
                continue
            seeded.extend(own)
            out.update(on_branch=True, branch="seeded")
    return tuple(seeded), pd.DataFrame(rows, columns=list(STEP_COLUMNS))
