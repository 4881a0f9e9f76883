"""The paper's measurements, shipped with the package (``paper_measurements.csv``)."""

from __future__ import annotations

from importlib import resources

import pandas as pd

MEASUREMENTS_FILE = "paper_measurements.csv"


def paper_measurements() -> pd.DataFrame:
    """Every number the paper reports from its shaking-table tests, one row each.

    Returns
    -------
    DataFrame
        ``table`` ("2", "3", "4", or "-" for values given in the text), ``configuration``
        ("NBs", "YBs", or "YBs/NBs" for ratios), ``a_g`` (NaN for the gap), ``quantity``
        (the names used by :class:`pounding.CampaignResult` tables: ``nu_r``, ``alpha``,
        ``eta``, ``e``, ``contact_nu_min``, ``contact_nu_max``, ``mean_force_over_mg``,
        ``contact_time_ms``, ``dissipated_energy_per_mass``, ``restitution``, ...),
        ``value``, ``unit``, ``source`` (table or section) and ``note`` (where MODEL.md §5
        says the paper is inconsistent or unclear; empty otherwise).
    """
    with resources.files(__package__).joinpath(MEASUREMENTS_FILE).open("r", encoding="utf-8") as fh:
        df = pd.read_csv(fh, dtype={"table": str})
    df["note"] = df["note"].fillna("")
    return df


def measured(table: str) -> pd.DataFrame:
    """One of the paper's tables ("2", "3" or "4") wide: a row per (configuration, a_g)."""
    df = paper_measurements()
    df = df[(df["table"] == table) & df["a_g"].notna()]
    return df.pivot_table(index=["configuration", "a_g"], columns="quantity", values="value").reset_index()
