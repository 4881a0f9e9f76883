"""Per-impact measurements (paper Sect. 3.5): one function, :func:`impact_row` (the core's), turns a row of
the engine's contact table into the paper's quantities; :func:`impact_table` makes a run's table of them, and
the compiled sweep steps sum them per side (the ``S_*`` places)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .._core import CONTACT_COLUMNS, LAYOUT, impact_row  # noqa: F401  (the core's)

IMPACT_COLUMNS = ("restitution", "contact_time_s", "impulse_n_s", "mean_force_n", "peak_force_n",
                  "dissipated_energy_j", "bumper_dissipation_j")
N_IMPACT = len(IMPACT_COLUMNS)

# per side, the sums a sweep keeps over its measurement window (the core's): completed contacts, of which with
# a defined restitution, then the sums of the N_IMPACT columns
S_COUNT, S_N_RESTITUTION, S_SUMS, SIDE_SUMS = (LAYOUT[k] for k in ("S_COUNT", "S_N_RESTITUTION", "S_SUMS",
                                                                 "SIDE_SUMS"))
assert N_IMPACT == LAYOUT["N_IMPACT"]  # (IMPACT_COLUMNS names the core's N_IMPACT quantities)


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
        :data:`~pounding.metrics.impacts.IMPACT_COLUMNS`; see :func:`impact_row`.

    Examples
    --------
    The damped paper system pounding at 1.5 Hz, a_G = 0.05 g, 5 s from rest:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> run = pounding.simulate(osc, pounding.Harmonic(0.05, 1.5), 5.0)
    >>> # what run.impacts holds (there with its wall and level too)
    >>> table = pounding.impact_table(run.contact_table, osc.mass_kg)
    >>> len(table), table["side"].value_counts().to_dict()
    (13, {'left': 7, 'right': 6})
    >>> last = table.iloc[-1]
    >>> print(f"s = {last.restitution:.3f}, dt_c = {last.contact_time_s * 1e3:.1f} "
    ...       f"ms, F_peak = {last.peak_force_n:.0f} N")
    s = 0.974, dt_c = 50.0 ms, F_peak = 1446 N
    """
    df = pd.DataFrame(impact_values(contact_table, mass_kg), columns=list(IMPACT_COLUMNS))
    df.insert(0, "t_start_s", contact_table[:, CONTACT_COLUMNS["t_start_s"]])
    df.insert(0, "side", np.where(contact_table[:, CONTACT_COLUMNS["contact"]] == 0.0, "left", "right"))
    return df


def impact_values(contact_table: np.ndarray, mass_kg: float | np.ndarray) -> np.ndarray:
    """The per-impact quantities of :data:`IMPACT_COLUMNS` of each row of an engine's contact table, shape
    (n, N_IMPACT): ``mass_kg`` the impacting mass (kg), one for every row or one per row, shape (n,) (a
    pair's effective mass ``m_i m_j / (m_i + m_j)``, the mass itself against the ground)."""
    n = contact_table.shape[0]
    masses = np.broadcast_to(np.asarray(mass_kg, dtype=float), (n,))
    values = np.empty((n, N_IMPACT))
    for i in range(n):
        impact_row(contact_table[i], float(masses[i]), values[i])
    return values


def impact_summary(impacts: pd.DataFrame, rigid: int) -> dict[str, float]:
    """A run's contacts in a few numbers (its ``summary()``'s), from its per-impact table and its number of
    rigid impacts: ``restitution_mean`` over the finished contacts, ``contact_time_mean_s`` over those that
    last (holds and deformable contacts), ``peak_force_max_n`` (inf with rigid impacts; NaN without
    contacts)."""
    done = impacts.dropna(subset=["contact_time_s"])
    lasting = done[done["contact_time_s"] > 0.0]
    nan = float("nan")
    return {"restitution_mean": float(done["restitution"].mean()) if len(done) else nan,
            "contact_time_mean_s": float(lasting["contact_time_s"].mean()) if len(lasting) else nan,
            "peak_force_max_n": (math.inf if rigid else float(done["peak_force_n"].max()) if len(done)
                                 else nan)}
