"""The decision table's rows: per design point of a stripe analysis, the probabilities of pounding (or of
a demand) at the two levels, the evidence at the target's stripe, and the medians at the MCE stripe
(:func:`decide` assembles them)."""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
from scipy import stats

from .._checks import instance_of
from .._errors import InputError, Problem
from .hazard import HazardCurve, probability_in_years
from .stripe_result import StripeAnalysis


def table_rows(
    analysis: StripeAnalysis,
    design_sa: float,
    mce_sa: float,
    level: str,
    target: float,
    hazard: HazardCurve | None,
    yrs: float,
    free: StripeAnalysis | None,
    event: str = "contact",
    limit: float | None = None,
) -> list[dict]:
    """The decision table's rows of one stripe analysis: one per design point."""
    p_design = analysis.probability(design_sa)
    p_mce = analysis.probability(mce_sa)
    demand = None if event == "contact" else (analysis.probability(design_sa, event, limit),
                                             analysis.probability(mce_sa, event, limit))
    p_cap = None if analysis.capacity_m is None else analysis.probability(mce_sa, "compression")
    stripe = int(np.argmin(np.abs(np.log(analysis.levels_g / mce_sa))))
    target_stripe = int(
        np.argmin(np.abs(np.log(analysis.levels_g / (mce_sa if level == "mce" else design_sa))))
    )
    n_runs, n_hits = (c.load() for c in analysis.counts(event, limit))
    at_stripe = analysis.data.isel(sa_g=stripe).load()
    ok = analysis.finished().isel(sa_g=stripe)
    acc = at_stripe["acc_max_g"].where(ok).median("record")
    with warnings.catch_warnings():  # (a design point where no run pounded: NaN, not a warning)
        warnings.simplefilter("ignore", RuntimeWarning)
        acc_pounding = at_stripe["acc_max_g"].where(ok & (at_stripe["impacts"] > 0)).median("record")
    penalty = None if free is None else _penalty(analysis, free, stripe, ok)
    force = at_stripe["impact_force_max_n"].where(ok).median("record")
    rows = []
    dims = analysis.design_dims
    for index in np.ndindex(p_design.shape):
        sel = dict(zip(dims, index))
        row = {d: float(analysis.data[d].values[i]) for d, i in sel.items()}
        row["p_contact_design"] = float(p_design.values[index])
        row["p_contact_mce"] = float(p_mce.values[index])
        row["p_capacity_mce"] = math.nan if p_cap is None else float(p_cap.values[index])
        row["p_contact_years"] = math.nan
        row[f"p_{event}_years"] = math.nan
        if demand is not None:
            row[f"p_{event}_design"] = float(demand[0].values[index])
            row[f"p_{event}_mce"] = float(demand[1].values[index])
        try:
            frag = analysis.fragility(event, limit, at=row_values(row, dims), n_bootstrap=0)
        except InputError:
            frag = None
        row["fitted"] = frag is not None
        # the evidence at the stripe nearest the target's level: runs, runs that pounded, and the
        # exact (Clopper-Pearson) 95 % upper bound of the probability they allow
        nn, kk = int(n_runs.isel(sel).values[target_stripe]), int(n_hits.isel(sel).values[target_stripe])
        row["runs_at_level"] = nn
        row["pounded_at_level"] = kk
        row["p_upper_95"] = (
            1.0 if nn == 0 else (1.0 if kk >= nn else float(stats.beta.ppf(0.95, kk + 1, nn - kk)))
        )
        if hazard is not None:
            if frag is not None:
                from .risk import annual_frequency

                row[f"p_{event}_years"] = float(probability_in_years(annual_frequency(frag, hazard), yrs))
        row["acc_median_g"] = float(acc.isel(sel).values)
        row["acc_pounding_median_g"] = float(acc_pounding.isel(sel).values)
        row["force_median_n"] = float(force.isel(sel).values)
        row["acc_penalty_median"] = math.nan if penalty is None else float(penalty.isel(sel).values)
        row["stripe_g"] = float(analysis.levels_g[stripe])
        row["meets_target"] = bool(row[f"p_{event}_{level}"] <= target)
        rows.append(row)
    return rows


def _penalty(analysis: StripeAnalysis, free: StripeAnalysis, stripe: int, ok: Any) -> Any:
    """Per design point, the median over the records of the peak acceleration with bumpers over the
    one without, at ``stripe`` (the two analyses must have the same stripes and records)."""
    instance_of("free", free, StripeAnalysis, "pounding.design.StripeAnalysis (without bumpers) or None")
    same = np.array_equal(free.levels_g, analysis.levels_g) and list(free.data["record"].values) == list(
        analysis.data["record"].values
    )
    if not same or free.has_bumpers or free.design_dims:
        raise InputError(
            Problem.BAD_STATE,
            "free",
            repr(free),
            why="is not the same stripes and records without bumpers and without a grid",
            fix="run stripe_analysis(system.without_bumpers(), the same records and levels_g)",
        )
    base = free.data.isel(sa_g=stripe).load()
    base_ok = free.finished().isel(sa_g=stripe)
    ratio = analysis.data.isel(sa_g=stripe)["acc_max_g"].load() / base["acc_max_g"].where(base_ok)
    return ratio.where(ok).median("record")


def row_values(row: dict, dims: tuple[str, ...]) -> dict[str, float]:
    """A table row's design point: its value for each design dimension."""
    return {d: row[d] for d in dims}
