"""Data shipped with the package: the paper's measurements (``paper_measurements.csv``) and a
synthetic cyclic bumper test (``bumper_cyclic_test.csv``)."""

from __future__ import annotations

import math
from importlib import resources

import pandas as pd

__all__ = ["bumper_cyclic_test", "measured", "paper_gap_total_m", "paper_measurements"]

MEASUREMENTS_FILE = "paper_measurements.csv"
BUMPER_TEST_FILE = "bumper_cyclic_test.csv"


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
        ``value``, ``unit``, ``source`` (table or section) and ``note`` (where the paper is
        inconsistent or unclear, and how; empty otherwise).

    Examples
    --------
    >>> import pounding
    >>> m = pounding.data.paper_measurements()
    >>> m.shape, sorted(m["configuration"].unique())
    ((58, 8), ['NBs', 'YBs', 'YBs/NBs'])
    >>> m.loc[(m["quantity"] == "restitution") & (m["a_g"] == 0.1),
    ...       "value"].tolist()  # Table 4
    [0.75]
    """
    with resources.files(__package__).joinpath(MEASUREMENTS_FILE).open("r", encoding="utf-8") as fh:
        df = pd.read_csv(fh, dtype={"table": str})
    df["note"] = df["note"].fillna("")
    return df


PAPER_F_REF_HZ = 1.0  # the frequency the paper's nu = f / f_ref is measured against, Hz
# the table's slowest frequency its D_tmax values imply (docs/paper.md)
PAPER_OMEGA_MIN_RAD_S = 2.0 * math.pi * 0.6
PAPER_MASS_KG = 500.0  # the isolated mass of the paper's rig (Sect. 1), kg: its systems and its measurements


def paper_gap_total_m() -> float:
    """The rig's nominal total gap ``Delta = g_L + g_R`` (m, the paper's 2 x 15 mm): what its
    ``eta = E / Delta`` is measured over.

    Returns
    -------
    float
        The total gap, m.

    Examples
    --------
    >>> import pounding
    >>> pounding.data.paper_gap_total_m()  # m
    0.03
    """
    df = paper_measurements()
    return float(df.loc[df["quantity"] == "total_gap_m", "value"].iloc[0])


def measured(table: str) -> pd.DataFrame:
    """One of the paper's tables ("2", "3" or "4") wide: a row per (configuration, a_g).

    Parameters
    ----------
    table : {"2", "3", "4"}
        Table 2 (pseudo-resonance ``nu_r``, ``alpha``, ``d_tmax_m``, ``e``, ``eta``, contact
        range; NBs and YBs), 3 (contact time and mean impact force; YBs) or 4 (dissipated
        energy and restitution; YBs).

    Returns
    -------
    DataFrame
        ``configuration``, ``a_g`` and a column per quantity of that table (as in
        :func:`paper_measurements`; NaN where the paper gives none for that row).

    Examples
    --------
    >>> import pounding
    >>> t4 = pounding.data.measured("4")
    >>> t4[["a_g", "restitution"]].values.tolist()
    [[0.03, 1.0], [0.05, 0.89], [0.075, 0.8], [0.1, 0.75]]
    """
    from .._checks import one_of

    table = one_of("table", table, ("2", "3", "4"))
    df = paper_measurements()
    df = df[(df["table"] == table) & df["a_g"].notna()]
    return df.pivot_table(index=["configuration", "a_g"], columns="quantity", values="value").reset_index()


def bumper_cyclic_test() -> pd.DataFrame:
    """A synthetic cyclic force-displacement test of a bumper, for :func:`pounding.fit_contact_law`.

    The protocol of the paper's MTS tests (Sect. 2.2, Fig. 3): two cycles each at 0.5, 1.0,
    1.5 and 2.0 Hz of +-10 mm around 10 mm of compression, 100 samples a cycle.  The forces
    come from a Hunt-Crossley law (stiffness 1.46e7 N/m^1.5, exponent 1.5, damping 2e7
    N s/m^2.5) with 1 % noise (``scripts/make_bumper_test.py``): the paper publishes its loops
    as figures only, so this is not a measurement.

    Returns
    -------
    DataFrame
        ``time_s``, ``freq_hz``, ``compression_m`` (>= 0), ``force_n``, one row per sample (800).

    Examples
    --------
    >>> import pounding
    >>> test = pounding.data.bumper_cyclic_test()
    >>> len(test), sorted(test["freq_hz"].unique().tolist())  # samples, Hz
    (800, [0.5, 1.0, 1.5, 2.0])
    >>> round(float(test["compression_m"].max()), 3)  # m: 10 mm +- 10 mm
    0.02
    """
    with resources.files(__package__).joinpath(BUMPER_TEST_FILE).open("r", encoding="utf-8") as fh:
        return pd.read_csv(fh)
