"""Units that files come in, and their factors to SI (one table for every reader)."""

from __future__ import annotations

TIME_UNITS = {"s": 1.0, "ms": 1e-3}
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3}
ACC_UNITS = {"m/s2": 1.0, "cm/s2": 1e-2, "g": None}  # g: times the reader's g
