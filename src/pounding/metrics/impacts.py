"""Per-impact tables from a run's contacts."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ._impacts import CONTACT_COLUMNS, IMPACT_COLUMNS, N_IMPACT, impact_row


def impact_table(contact_table: np.ndarray, mass_kg: float) -> pd.DataFrame:
    """The paper's per-impact quantities (Sect. 3.5), one row per contact.

    Parameters
    ----------
    contact_table : ndarray, shape (n, 9)
        ``Run.contact_table`` (side coded 0 left, 1 right).
    mass_kg : float
        The impacting mass ``M``.

    Returns
    -------
    DataFrame
        ``side``, ``t_start_s`` and the columns of
        :data:`~pounding.metrics._impacts.IMPACT_COLUMNS`; see :func:`impact_row`.

    Examples
    --------
    The damped paper system pounding at 1.5 Hz, a_G = 0.05 g, 5 s from rest:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> run = pounding.simulate(osc, pounding.Harmonic(0.05, 1.5), 5.0)
    >>> # what run.impacts holds
    >>> table = pounding.impact_table(run.contact_table, osc.mass_kg)
    >>> len(table), table["side"].value_counts().to_dict()
    (13, {'left': 7, 'right': 6})
    >>> last = table.iloc[-1]
    >>> print(f"s = {last.restitution:.3f}, dt_c = {last.contact_time_s * 1e3:.1f} "
    ...       f"ms, F_peak = {last.peak_force_n:.0f} N")
    s = 0.974, dt_c = 50.0 ms, F_peak = 1446 N
    """
    values = np.empty((contact_table.shape[0], N_IMPACT))
    for i in range(contact_table.shape[0]):
        impact_row(contact_table[i], float(mass_kg), values[i])
    df = pd.DataFrame(values, columns=list(IMPACT_COLUMNS))
    df.insert(0, "t_start_s", contact_table[:, CONTACT_COLUMNS["t_start_s"]])
    df.insert(0, "side", np.where(contact_table[:, CONTACT_COLUMNS["contact"]] == 0.0, "left", "right"))
    return df
