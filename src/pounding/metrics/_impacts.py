"""Per-impact measurements (paper Sect. 3.5): one function, :func:`impact_row` (the core's), turns a row of
the engine's contact table into the paper's quantities; the Python tables and the compiled sweep steps use
it."""

from __future__ import annotations

from .._core import LAYOUT, impact_row  # noqa: F401  (the core's)

# columns of the engine's contact table (engine/_layout.py CONTACT_COLS)
C_SIDE, C_TSTART, C_TEND, C_VIN, C_VOUT, C_IMPULSE, C_PEAK, C_MAXCOMP, C_WORK = range(9)

IMPACT_COLUMNS = ("restitution", "contact_time_s", "impulse_n_s", "mean_force_n", "peak_force_n",
                  "dissipated_energy_j", "bumper_dissipation_j")
N_IMPACT = len(IMPACT_COLUMNS)
I_RESTITUTION = 0

# per side, the sums a sweep keeps over its measurement window
S_COUNT = 0          # completed contacts
S_N_RESTITUTION = 1  # of which with a defined restitution
S_SUMS = 2           # then the sums of the N_IMPACT columns
SIDE_SUMS = S_SUMS + N_IMPACT
assert (N_IMPACT, SIDE_SUMS) == (LAYOUT["N_IMPACT"], LAYOUT["SIDE_SUMS"])
