"""A sweep's features, for any system: its jumps, the paper's per-sweep quantities of a level (Tables 2-4)
and a structure's sweep in a few numbers (:class:`~pounding.SweepResult`'s ``jumps``,
``paper_quantities`` and ``quantities``)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from .._checks import positive
from .._errors import InputError, Problem

if TYPE_CHECKING:  # pragma: no cover
    from .sweep_result import SweepResult

DEFAULT_JUMP_RATIO = 1.5
# a sweep's paper quantities (``SweepResult.paper_quantities``): the paper's Table 2, 3 and 4 rows
PAPER_QUANTITIES = ("nu_r", "alpha", "eta", "e", "contact_nu_min", "contact_nu_max", "excursion_max_m",
                    "mean_force_over_mg", "contact_time_ms", "peak_force_over_mg",
                    "dissipated_energy_per_mass", "restitution")
# a structure's sweep in a few numbers (``SweepResult.quantities`` of a structure)
STRUCTURE_QUANTITIES = ("nu_r_top", "alpha_top_max", "alpha_base_max", "drift_ratio_max", "contact_nu_min",
                        "contact_nu_max")
JUMP_COLUMNS = ["freq_from_hz", "freq_to_hz", "alpha_from", "alpha_to", "excursion_from_m", "excursion_to_m",
                "contact_from", "contact_to", "kind"]


def jumps_of(df: pd.DataFrame, ratio: float) -> pd.DataFrame:
    """The jumps along one level's rows ``df`` of a sweep's table (stepping order): each step-to-step change
    of alpha or of the excursion by a factor ``ratio`` or more (see ``SweepResult.jumps``)."""
    ratio = positive("ratio", ratio, "(a factor > 1)")
    if ratio <= 1.0:
        raise InputError(Problem.TOO_SMALL, "ratio", ratio, minimum="1 (exclusive)", hint="")
    a = df["alpha"].to_numpy()
    e = df["excursion_m"].to_numpy()
    rows = []
    for i in range(len(df) - 1):
        ra = a[i + 1] / a[i]
        re = e[i + 1] / e[i]
        if max(ra, 1 / ra, re, 1 / re) >= ratio:
            rows.append({
                "freq_from_hz": df["freq_hz"].iloc[i], "freq_to_hz": df["freq_hz"].iloc[i + 1],
                "alpha_from": a[i], "alpha_to": a[i + 1],
                "excursion_from_m": e[i], "excursion_to_m": e[i + 1],
                "contact_from": bool(df["contact"].iloc[i]),
                "contact_to": bool(df["contact"].iloc[i + 1]),
                "kind": "up" if max(ra, re) >= max(1 / ra, 1 / re) else "down"})
    return pd.DataFrame(rows, columns=JUMP_COLUMNS)


def paper_quantities_of(sw: "SweepResult", q: int) -> dict[str, float]:
    """The paper's quantities of the moving level ``q`` of ``sw`` (see ``SweepResult.paper_quantities``)."""
    out = dict.fromkeys(PAPER_QUANTITIES, math.nan)
    if sw.steps_done == 0:
        return out
    df = sw.to_dataframe().iloc[q::len(sw.levels)].iloc[: sw.steps_done]
    alpha = df["alpha"].to_numpy()
    if not np.any(np.isfinite(alpha)):
        return out
    i = int(np.nanargmax(alpha))
    hit = np.sort(df.loc[df["contact"], "freq_hz"].to_numpy())
    step = df.iloc[i]
    mass = float(sw.level_masses_kg[q])
    mg = mass * sw.g
    out.update({
        "nu_r": float(df["freq_hz"].iloc[i]) / sw.f_ref_hz, "alpha": float(np.nanmax(alpha)),
        "eta": df["eta"].max(), "e": df["e"].max(), "excursion_max_m": df["excursion_m"].max(),
        "contact_nu_min": float(hit[0]) / sw.f_ref_hz if hit.size else math.nan,
        "contact_nu_max": float(hit[-1]) / sw.f_ref_hz if hit.size else math.nan,
        "mean_force_over_mg": step["mean_force_n"] / mg,
        "contact_time_ms": step["contact_time_s"] * 1e3,
        "peak_force_over_mg": step["peak_force_n"] / mg,
        "dissipated_energy_per_mass": step["dissipated_energy_j"] / mass,
        "restitution": step["restitution"]})
    return out


def structure_quantities_of(sw: "SweepResult") -> dict[str, float]:
    """A structure's sweep in a few numbers (see ``SweepResult.quantities``); NaN with no step done."""
    if sw.steps_done == 0:
        return dict.fromkeys(STRUCTURE_QUANTITIES, math.nan)
    done = slice(0, sw.steps_done)
    rng = sw.contact_range_hz

    def largest(values: np.ndarray) -> float:  # (NaN where no step measured it: no warning)
        return float(np.nanmax(values)) if np.any(np.isfinite(values)) else math.nan

    drift = sw.to_dataframe()["drift_ratio_peak"].to_numpy()[: sw.steps_done * len(sw.levels)]
    lo, hi = (math.nan, math.nan) if rng is None else (rng[0] / sw.f_ref_hz, rng[1] / sw.f_ref_hz)
    return dict(zip(STRUCTURE_QUANTITIES, (
        sw.resonance_hz / sw.f_ref_hz, largest(sw.alpha_top[done]), largest(sw.alpha_base[done]),
        largest(drift) if sw.storeys else math.nan, lo, hi)))
