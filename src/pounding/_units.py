"""Units that files come in, and their factors to SI (one table for every reader)."""

from __future__ import annotations

TIME_UNITS = {"s": 1.0, "ms": 1e-3}
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3}
ACC_UNITS = {"m/s2": 1.0, "cm/s2": 1e-2, "g": None}  # g: times the reader's g

# The acceleration of gravity behind every "in g" of the package: the table's a_G (A_t = a_G g), records
# and spectra in g, design formulas (ASCE 7's D_M = g S_M1 T_M / (4 pi^2 B_M)).  The paper's 9.81 m/s^2,
# one value everywhere (standard gravity, 9.80665 m/s^2, is 0.03 % less).
GRAVITY_M_S2 = 9.81
