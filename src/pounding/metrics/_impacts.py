"""Per-impact measurements (paper Sect. 3.5): one function, :func:`impact_row` (the core's), turns a row of
the engine's contact table into the paper's quantities; the Python tables and the compiled sweep steps use
it."""

from __future__ import annotations

from .._core import CONTACT_COLUMNS, LAYOUT, impact_row  # noqa: F401  (the core's)

# columns of the engine's contact table (the core's CONTACT_COLUMNS)
C_SIDE, C_TSTART, C_TEND, C_VIN, C_VOUT, C_IMPULSE, C_PEAK, C_MAXCOMP, C_WORK = (
    CONTACT_COLUMNS[k] for k in ("contact", "t_start_s", "t_end_s", "v_in_m_s", "v_out_m_s", "impulse_n_s",
                                 "peak_force_n", "max_compression_m", "work_j"))

IMPACT_COLUMNS = ("restitution", "contact_time_s", "impulse_n_s", "mean_force_n", "peak_force_n",
                  "dissipated_energy_j", "bumper_dissipation_j")
N_IMPACT = len(IMPACT_COLUMNS)
I_RESTITUTION = 0

# per side, the sums a sweep keeps over its measurement window (the core's): completed contacts, of which with
# a defined restitution, then the sums of the N_IMPACT columns
S_COUNT, S_N_RESTITUTION, S_SUMS, SIDE_SUMS = (LAYOUT[k] for k in ("S_COUNT", "S_N_RESTITUTION", "S_SUMS",
                                                                 "SIDE_SUMS"))
assert N_IMPACT == LAYOUT["N_IMPACT"]  # (IMPACT_COLUMNS names the core's N_IMPACT quantities)
