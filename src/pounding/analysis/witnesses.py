"""How many responses exist at each point of a test matrix, and what shows it.

A branch followed by continuation counts the stable period-1 orbits *on that branch*: it cannot show
that a point has one response only (another branch, an isola, a response of another period is not
followed), and where the branch did not reach it says nothing.  So each test point is judged by its
witnesses:

- the branch: its stable orbits there (where it reached the frequency), and those of the branches
  started at the sweeps' settled steps that lie off it (:func:`through_sweeps`);
- the sweeps (an up and a down sweep at the point's a_G, when given): two steps that both settled on
  responses that differ (in alpha, excursion or period) show two responses; one settled step shows one;
- a basin sample: a small grid of initial states at table phase 0, each run until it settles
  (:func:`pounding.basins`); two attractors show two responses.

The point's ``responses`` is the most any witness shows, or the distinct responses all of them show
together where that is more (a stable orbit of the branch and a sweep's step settled on another response
are two, though each witness shows one).  Two or more is coexistence, whoever shows
it.  One response is said (``verdict`` "one") only where the basin sample ran, every state of it settled
on the same response, and the branch or the sweeps agree; without a sample, a branch's single stable
orbit is "one on the branch" (others not sought); anything else is "not assessed", and ``evidence``
says why.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._errors import InputError, Interrupted, Problem
from .._runner.progress import Progress, progress_reporter
from ..excitation import Harmonic

if TYPE_CHECKING:  # pragma: no cover
    from .branch import Branch

DIFFER_RTOL = 0.05  # two settled responses differ when alpha or the excursion differ by more (relative)
MATRIX_COLUMNS = ("a_g", "freq_hz", "stable_orbits", "branch_reached", "sweep_responses", "basin_responses",
                  "basin_not_settled", "responses", "verdict", "evidence")
VERDICTS = ("coexist", "one", "one on the branch", "not assessed")


def branch_counts(branches: Sequence["Branch"], freqs: np.ndarray) -> pd.DataFrame:
    """Per branch and frequency: the stable orbits of the branch there (``stable_orbits``: its stable
    segments spanning the frequency; NaN where the branch does not reach it) and ``branch_reached``."""
    rows = []
    for br in branches:
        df = br.to_dataframe()
        f = df["freq_hz"].to_numpy(float)
        st = df["stable"].to_numpy(bool)
        lo, hi = np.minimum(f[:-1], f[1:]), np.maximum(f[:-1], f[1:])
        both = st[:-1] & st[1:]
        top = f.max() if f.size else np.nan
        for fq in freqs:
            # a segment spans fq when lo <= fq < hi (half-open: a point at a row is counted once);
            # at the branch's end, the segment ending there
            spans = (lo <= fq) & ((fq < hi) | ((fq == hi) & (hi == top)))
            reached = bool(np.any(spans)) or bool(np.any(np.isclose(f, fq, rtol=0.0, atol=1e-12)))
            count = float(np.count_nonzero(spans & both)) if reached else math.nan
            rows.append({"a_g": float(br.a_g), "freq_hz": float(fq), "stable_orbits": count,
                         "branch_reached": reached})
    return pd.DataFrame(rows, columns=["a_g", "freq_hz", "stable_orbits", "branch_reached"])


def branch_responses(branch: "Branch", freq_hz: float) -> list[tuple[int, bool, float, float, bool]]:
    """The branch's orbits at ``freq_hz``, read along its segments that span it (linear between its
    points): ``(period, impacts, alpha, excursion_m, stable)`` each (stable: both ends of the segment)."""
    f, alpha, exc, hits, stable = _reading(branch)
    period = int(branch.period_multiple)
    lo, hi = np.minimum(f[:-1], f[1:]), np.maximum(f[:-1], f[1:])
    out = []
    for j in np.flatnonzero((lo <= freq_hz) & (freq_hz <= hi)):
        w = 0.0 if hi[j] == lo[j] else (freq_hz - f[j]) / (f[j + 1] - f[j])
        near = j if w <= 0.5 else j + 1
        a = alpha[j] + w * (alpha[j + 1] - alpha[j])
        e = exc[j] + w * (exc[j + 1] - exc[j])
        out.append((period, bool(hits[near]), float(a), float(e), bool(stable[j] and stable[j + 1])))
    if f.size == 1 and math.isclose(f[0], freq_hz, rel_tol=0.0, abs_tol=1e-12):
        out.append((period, bool(hits[0]), float(alpha[0]), float(exc[0]), bool(stable[0])))
    return out


_READINGS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def _reading(branch: "Branch") -> tuple[np.ndarray, ...]:
    """A branch's ``freq_hz``, ``alpha``, ``excursion_m``, impacts and ``stable`` as arrays, read once per
    branch (a branch is frozen; a map reads each one at hundreds of frequencies)."""
    if branch not in _READINGS:
        df = branch.data
        _READINGS[branch] = (df["freq_hz"].to_numpy(float), df["alpha"].to_numpy(float),
                             df["excursion_m"].to_numpy(float), df["contacts_per_period"].to_numpy(float) > 0,
                             df["stable"].to_numpy(bool))
    return _READINGS[branch]


def sweep_witness(sweeps: Sequence[Any], a_g: float, freq_hz: float) -> tuple[float, str]:
    """``(responses, words)``: the distinct settled responses the sweeps at ``a_g`` show at ``freq_hz``
    (NaN when no step there settled), and what they were."""
    settled, words = sweep_responses(sweeps, a_g, freq_hz)
    if not settled:
        return math.nan, ""
    return float(distinct(settled)), f"sweeps settled: {', '.join(words)}"


def sweep_responses(sweeps: Sequence[Any], a_g: float, freq_hz: float) -> tuple[list[tuple], list[str]]:
    """The settled steps of the sweeps at ``a_g`` at ``freq_hz``: their responses ``(period, impacts,
    alpha, excursion_m)`` and each in words."""
    settled, words = [], []
    for sw in sweeps:
        if not math.isclose(sw.a_g, a_g, rel_tol=1e-9):
            continue
        df = _witness_table(sw)
        at = df[np.isclose(df["freq_hz"].to_numpy(float), freq_hz, rtol=0.0, atol=1e-9) & df["steady"]]
        for _, row in at.iterrows():
            settled.append((int(row["period_multiple"]), bool(row["contact"]), float(row["alpha"]),
                            float(row["excursion_m"])))
            words.append(f"{sw.direction} alpha {float(row['alpha']):.3g}")
    return settled, words


def _witness_table(sweep: Any) -> pd.DataFrame:
    """One row per step of a sweep: ``freq_hz``, ``steady``, ``period_multiple``, ``contact``, ``alpha``
    and ``excursion_m``: a one-level system's exact table's; a structure's largest alpha over every level,
    its first moving mass's excursion, and whether any wall side or link was hit in the window (what a
    branch's and a basin's rows read of it)."""
    if len(sweep.levels) == 1:
        return sweep.exact_dataframe()
    structure0 = sweep.levels.index((0, 1 if _fixed(sweep.system) else 0))
    m = sweep.level_metrics
    contacts = (np.nan_to_num(sweep.contacts_per_cycle) if sweep.contact_slots
                else np.zeros((len(sweep.freqs_hz), 1)))
    with np.errstate(all="ignore"):
        alpha = np.nanmax(np.where(np.isfinite(sweep.alpha), sweep.alpha, -np.inf), axis=1)
    # (a step whose window was not measured again has no metrics: not a settled response)
    steady = (sweep.period_multiple > 0) & np.isfinite(alpha)
    return pd.DataFrame({"freq_hz": sweep.freqs_hz, "steady": steady,
                         "period_multiple": sweep.period_multiple, "contact": contacts.max(axis=1) > 0.0,
                         "alpha": alpha, "excursion_m": m[:, structure0, 0] - m[:, structure0, 1]})


def _fixed(model: Any) -> bool:
    """Whether a structure (or a pair's first) stands on the ground (its level 0 does not move)."""
    from ..engine.assembly import structures_of

    return bool(structures_of(model)[0][0].fixed)


def distinct(responses: Sequence[tuple]) -> int:
    """How many different responses ``(period, impacts, alpha, excursion)`` are: the same period and
    contact, and alpha and excursion within ``DIFFER_RTOL`` of a response of the group, make one
    (single linkage: a family of orbits shifted by a kinematic element's slips, whose alphas spread by
    a few percent in small steps, is one response; mirror images, with the same numbers, are one)."""
    groups: list[list[tuple]] = []
    for r in responses:
        joined = [g for g in groups if any(_near(r, m) for m in g)]
        merged = [r] + [m for g in joined for m in g]
        groups = [g for g in groups if g not in joined] + [merged]
    return len(groups)


def _near(a: tuple, b: tuple) -> bool:
    return (a[0] == b[0] and a[1] == b[1] and math.isclose(a[2], b[2], rel_tol=DIFFER_RTOL)
            and math.isclose(a[3], b[3], rel_tol=DIFFER_RTOL, abs_tol=1e-12))


def judge_matrix(oscillator: Any, branches: Sequence["Branch"], freqs: np.ndarray, *,
                sweeps: Sequence[Any] = (), basin_sample: int = 4, max_cycles: int = 500,
                progress: Progress = False, seeded: Sequence["Branch"] = ()) -> pd.DataFrame:
    """The test matrix (one row per branch's a_G and frequency) with every point judged by its witnesses
    (see the module's docstring for the rule): columns ``MATRIX_COLUMNS``.

    ``seeded`` are branches through the sweeps' settled steps (:func:`through_sweeps`): their stable
    orbits that differ from every orbit of the level's branch count among ``stable_orbits`` too.
    ``basin_sample`` is the basin grid's points per axis (``n x n`` states over the gaps, or a
    structure's shifts that leave its walls and links open, and +-1 m/s;
    0: no sample), run at every point.  A Ctrl-C keeps the points judged so far: :class:`Interrupted`
    with the matrix as ``partial``, the points not reached "not assessed".
    """
    from ..protocols import basins

    matrix = branch_counts(branches, np.asarray(freqs, dtype=float))
    level_of = {float(br.a_g): br for br in branches}
    sweeps = tuple(sweeps)
    out = []
    todo = []
    for row in matrix.to_dict("records"):
        a_g, f = row["a_g"], row["freq_hz"]
        on_level = branch_responses(level_of[a_g], f) if a_g in level_of else []
        found = [r[:4] for r in on_level if r[4]]
        others = [r[:4] for br in seeded if math.isclose(br.a_g, a_g, rel_tol=1e-9)
                  for r in branch_responses(br, f) if r[4]]
        others = [r for r in others if not any(_near(r, m[:4]) for m in on_level)]
        if others:  # (stable orbits of the steps' own branches, none of the level branch's)
            row["stable_orbits"] = (0.0 if math.isnan(row["stable_orbits"]) else row["stable_orbits"]) \
                + distinct(others)
            row["branch_reached"] = True
        settled, sw_words = sweep_responses(sweeps, a_g, f) if sweeps else ([], [])
        row.update(sweep_responses=float(distinct(settled)) if settled else math.nan,
                   basin_responses=math.nan, basin_not_settled=math.nan,
                   evidence_sweeps=f"sweeps settled: {', '.join(sw_words)}" if sw_words else "",
                   seen=found + others + settled)
        out.append(row)
        if basin_sample:  # (at every point: where another witness shows two, a third one more)
            todo.append(row)
    interrupted = None
    try:
        with progress_reporter(progress, len(todo), "coexistence: basin samples") as advance:
            for row in todo:
                b = basins(oscillator, Harmonic(row["a_g"], row["freq_hz"]), n=(basin_sample, basin_sample),
                           max_cycles=max_cycles, scheduler="serial")
                att = b.attractors
                seen = list(zip(att["period"], att["impacts"], att["alpha"], att["excursion_m"]))
                row["basin_responses"] = float(distinct(seen))
                row["basin_not_settled"] = b.not_settled
                row["seen"] = row["seen"] + seen
                advance(1)
    except (Interrupted, KeyboardInterrupt) as exc:
        interrupted = exc
    table = pd.DataFrame([_judged(row, basin_sample) for row in out], columns=list(MATRIX_COLUMNS))
    if interrupted is not None:
        raise Interrupted(table, int(table["basin_responses"].notna().sum()), len(todo), "basin samples") \
            from None
    return table


def _max(*values: float) -> float:
    finite = [v for v in values if not math.isnan(v)]
    return max(finite) if finite else math.nan


def _judged(row: dict, basin_sample: int) -> dict:
    """The point's responses, verdict and evidence from its witnesses."""
    stable, sweeps, basin = row["stable_orbits"], row["sweep_responses"], row["basin_responses"]
    # the most any witness shows, or more: the witnesses' responses together (a branch's stable orbit
    # and a sweep's settled step on another response are two)
    responses = _max(stable, sweeps, basin, float(distinct(row["seen"])) if row.get("seen") else math.nan)
    words = []
    if row["branch_reached"]:
        words.append(f"branch: {int(stable)} stable orbit{'s' if stable != 1 else ''}")
    else:
        words.append("branch: did not reach this frequency")
    if row["evidence_sweeps"]:
        words.append(row["evidence_sweeps"])
    if not math.isnan(basin):
        unsettled = row["basin_not_settled"]
        words.append(f"basin sample of {basin_sample}x{basin_sample} states: {int(basin)} response"
                     f"{'s' if basin != 1 else ''}" + (f", {100 * unsettled:.0f} % not settled" if unsettled
                                                         else ""))
    if responses >= 2:
        verdict = "coexist"
    elif (basin == 1 and not row["basin_not_settled"]
          and (stable == 1 or sweeps == 1)):
        verdict = "one"
    elif math.isnan(basin) and not basin_sample and stable == 1:
        verdict = "one on the branch"
    else:
        verdict = "not assessed"
    return {**{k: row[k] for k in MATRIX_COLUMNS[:7]}, "responses": responses, "verdict": verdict,
            "evidence": "; ".join(words)}


def check_basin_sample(value: Any) -> int:
    """``basin_sample``: 0 (none) or the grid's points per axis, 2 to 50."""
    if (isinstance(value, bool) or not isinstance(value, (int, np.integer))
            or not (value == 0 or 2 <= value <= 50)):
        raise InputError(Problem.OUT_OF_RANGE, "basin_sample", value, range="0 (no sample) or 2 to 50",
                         hint=" (points per axis of the basin grid at each test point; 4: 16 states)")
    return int(value)


def check_sweeps(value: Any, system: Any) -> tuple:
    """``sweeps``: SweepResults of ``system``'s levels (or a CampaignResult: its sweeps with bumpers)."""
    from ..engine.assembly import structures_of
    from ..protocols import CampaignResult, SweepResult

    if value is None:
        return ()
    given = value
    if isinstance(value, CampaignResult):
        value = tuple(sw for (conf, _a, _d), sw in value.sweeps.items() if conf == "YBs")
    if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, Sequence) or not all(
            isinstance(s, SweepResult) for s in value):
        got = (f"a CampaignResult of {type(value[0]).__name__}s"
               if isinstance(given, CampaignResult) and value else type(given).__name__)
        raise InputError(Problem.WRONG_TYPE, "sweeps", given, got=got,
                         expected="a sequence of SweepResult, or a CampaignResult of this system")
    levels = tuple((b, q) for b, s in enumerate(structures_of(system)[0]) for q in range(s.n_levels))
    for k, sw in enumerate(value):
        if tuple(sw.levels) != levels:
            raise InputError(Problem.WRONG_CONFIGURATION, f"sweeps[{k}]",
                             f"a sweep at {sw.a_g:g} g of {len(sw.levels)} level(s)",
                             got=f"of {len(sw.levels)} level(s) where this one has {len(levels)}",
                             fix="give sweeps of this system (pounding.sweep of it)")
    return tuple(value)
