"""Model beside measurement: the paper's Tables 2, 3 and 4 with the differences."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..data import measured, paper_gap_total_m, paper_measurements
from ..protocols.campaign import CampaignResult

# per table: the quantities compared, as named in CampaignResult.tableN() and in the data
TABLE_QUANTITIES = {
    "2": ("nu_r", "alpha", "eta", "e", "contact_nu_min", "contact_nu_max"),
    "3": ("mean_force_over_mg", "contact_time_ms"),
    "4": ("dissipated_energy_per_mass", "restitution"),
}
# quantities whose printed values cannot be compared numerically (Table 3's scale factor is unclear)
NOT_COMPARABLE = {"mean_force_over_mg"}


def comparison(result: CampaignResult, table: str) -> pd.DataFrame:
    """One of Tables 2-4: model (each sweep direction) beside measured, with ``model - measured``.

    Parameters
    ----------
    result : CampaignResult
        A campaign (:func:`pounding.campaign`); only its (configuration, a_g) pairs that the
        paper measured make rows.
    table : {"2", "3", "4"}
        The paper's table: 2 (``nu_r``, ``alpha``, ``eta``, ``e``, the contact range), 3 (mean
        contact force over ``M g``, contact time in ms) or 4 (dissipated energy per mass,
        restitution).

    Returns
    -------
    DataFrame
        ``configuration``, ``a_g``, ``direction``, then per quantity ``<q>_model``,
        ``<q>_measured``, ``<q>_diff`` (model - measured) and ``<q>_diff_pct`` (the difference
        in percent of the measured value, NaN where that is 0); rows only for the
        (configuration, a_g) pairs the paper measured.  Quantities whose printed scale is
        unclear have NaN differences.  The model's YBs ``eta`` is its largest excursion over
        the rig's nominal gap (``paper_gap_total_m``), as the paper measured it, whatever the
        model's own gap.

    Examples
    --------
    Table 2 at a_G = 0.05 g from a small campaign (sweeps up, four steps of 10 cycles):

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> nbs = ybs.without_bumpers()
    >>> result = pounding.campaign(nbs, ybs, nbs_a_g=(0.05,), ybs_a_g=(0.05,),
    ...                            freqs_hz=[1.0, 1.1, 1.5, 2.0],
    ...                            directions=("up",), steady="fixed", cycles=10)
    >>> table2 = pounding.reports.comparison(result, "2")
    >>> table2[["configuration", "alpha_model", "alpha_measured",
    ...         "alpha_diff_pct"]].round(2).values.tolist()
    [['NBs', 2.63, 2.99, -11.99], ['YBs', 8.32, 16.8, -50.47]]
    """
    model = {"2": result.table2, "3": result.table3, "4": result.table4}[table]()
    if table == "2":
        model["eta"] = (model["excursion_max_m"] / paper_gap_total_m()).where(model["configuration"] == "YBs")
    meas = measured(table)
    merged = model.merge(meas, on=["configuration", "a_g"], how="inner", suffixes=("_model", "_measured"))
    out = merged[["configuration", "a_g", "direction"]].copy()
    for q in TABLE_QUANTITIES[table]:
        m = merged[q + "_model"] if q + "_model" in merged else pd.Series(np.nan, index=merged.index)
        x = merged[q + "_measured"] if q + "_measured" in merged else pd.Series(np.nan, index=merged.index)
        out[q + "_model"] = m
        out[q + "_measured"] = x
        out[q + "_diff"] = np.nan if q in NOT_COMPARABLE else m - x
        with np.errstate(divide="ignore", invalid="ignore"):
            pct = 100.0 * (m - x) / x.abs()
        out[q + "_diff_pct"] = np.nan if q in NOT_COMPARABLE else pct.where(x != 0)
    return out.reset_index(drop=True)


def inconsistency_notes() -> pd.DataFrame:
    """The measured values that carry a note (inconsistent or unclear in the paper), for the report."""
    df = paper_measurements()
    return df[df["note"] != ""][["source", "configuration", "a_g", "quantity", "value", "note"]]

