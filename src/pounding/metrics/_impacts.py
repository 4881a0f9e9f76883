"""Per-impact measurements (paper Sect. 3.5), compiled so that sweeps sum them in place.

One function, :func:`impact_row`, turns a row of the engine's contact table into the
paper's quantities; both the Python tables and the compiled sweep kernel use it.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit_alloc, jit_entry

# columns of the engine's contact table (see engine/_layout.py CONTACT_COLS)
C_SIDE, C_TSTART, C_TEND, C_VIN, C_VOUT, C_IMPULSE, C_PEAK, C_MAXCOMP, C_WORK = range(9)

IMPACT_COLUMNS = ("restitution", "contact_time_s", "impulse_n_s", "mean_force_n", "peak_force_n",
                  "dissipated_energy_j", "bumper_dissipation_j")
N_IMPACT = len(IMPACT_COLUMNS)
I_RESTITUTION = 0


@jit_entry
def impact_row(contact, mass, out):
    """Fill ``out`` (length ``N_IMPACT``) from one contact-table row.

    ``restitution`` ``s = -v_o / v_i`` (NaN when the contact began at zero normal
    velocity), ``contact_time_s`` ``dt_c``, ``impulse_n_s`` ``I``, ``mean_force_n``
    ``F_m = I / dt_c``, ``peak_force_n``, ``dissipated_energy_j`` ``E_d = M (v_i^2 -
    v_o^2) / 2`` (the mass's loss of kinetic energy over the impact) and
    ``bumper_dissipation_j`` (what the bumper's own dashpot took).  A contact still going
    on (NaN end) gives NaN everywhere but the impulse and peak so far.
    """
    v_in = contact[C_VIN]
    v_out = contact[C_VOUT]
    dt = contact[C_TEND] - contact[C_TSTART]
    out[0] = -v_out / v_in if v_in != 0.0 else np.nan
    out[1] = dt
    out[2] = contact[C_IMPULSE]
    out[3] = contact[C_IMPULSE] / dt if dt > 0.0 else np.nan
    out[4] = contact[C_PEAK]
    out[5] = 0.5 * mass * (v_in * v_in - v_out * v_out)
    out[6] = contact[C_WORK]


# per side, the sums a sweep keeps over its measurement window
S_COUNT = 0          # completed contacts
S_N_RESTITUTION = 1  # of which with a defined restitution
S_SUMS = 2           # then the sums of the N_IMPACT columns
SIDE_SUMS = S_SUMS + N_IMPACT


@jit_alloc
def add_impacts(contacts, mass, sums, row):
    """Add the completed contacts of ``contacts`` to ``sums[row, side * SIDE_SUMS + ...]``."""
    vals = np.empty(N_IMPACT)
    for i in range(contacts.shape[0]):
        if math.isnan(contacts[i, C_TEND]):
            continue  # still going on: counted by the run that sees it end
        impact_row(contacts[i], mass, vals)
        base = int(contacts[i, C_SIDE]) * SIDE_SUMS
        sums[row, base + S_COUNT] += 1.0
        for j in range(N_IMPACT):
            if j == I_RESTITUTION and math.isnan(vals[j]):
                continue
            if j == I_RESTITUTION:
                sums[row, base + S_N_RESTITUTION] += 1.0
            sums[row, base + S_SUMS + j] += vals[j]
