"""The free numbers of a fit on the unit cube the search works in."""

from __future__ import annotations

import numpy as np


class Scale:
    """Free numbers <-> unit cube (logarithmic where a bound spans a decade or more)."""

    def __init__(self, bounds: dict[str, tuple[float, float]]):
        self.names = tuple(bounds)
        lo = np.array([b[0] for b in bounds.values()])
        hi = np.array([b[1] for b in bounds.values()])
        self.log = (lo > 0.0) & (hi >= 10.0 * lo)
        self.lo = np.where(self.log, np.log(np.where(self.log, lo, 1.0)), lo)
        self.hi = np.where(self.log, np.log(np.where(self.log, hi, 1.0)), hi)

    def values(self, u: np.ndarray) -> dict[str, float]:
        x = self.lo + np.clip(u, 0.0, 1.0) * (self.hi - self.lo)
        x[self.log] = np.exp(x[self.log])
        return {n: float(v) for n, v in zip(self.names, x)}

    def units(self, values: dict[str, float]) -> np.ndarray:
        x = np.array([values[n] for n in self.names], dtype=float)
        x[self.log] = np.log(np.maximum(x[self.log], np.exp(self.lo[self.log])))
        return np.clip((x - self.lo) / (self.hi - self.lo), 0.0, 1.0)
