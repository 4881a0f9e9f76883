"""The Lyapunov spectrum of a response: what :func:`pounding.lyapunov` returns."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._errors import Status
from ..engine import State
from ..excitation import Harmonic

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr


@dataclass(frozen=True, eq=False)
class LyapunovSpectrum:
    """The Lyapunov exponents of a response (what :func:`lyapunov` returns).

    Attributes
    ----------
    exponents : ndarray, shape (n,)
        The exponents, 1/s, largest first (``-inf`` for a direction the map erases).
    coordinates : tuple of str
        The tangent coordinates, named as :attr:`PeriodicOrbit.coordinates` (a single mass's ``x_0``,
        ``v_0``, ``delta_wall0_left``, ``delta_wall0_right``, ``u_<i>``, ``z``): the exponents are of
        the state they make up.
    history : ndarray, shape (cycles, n)
        The running estimates after each counted period, 1/s, in the order of ``exponents`` (the last
        row is ``exponents`` but for a periodic response, whose exponents are its Floquet values).
    excitation : Harmonic
        The forcing.
    cycles : int
        Periods counted (fewer than asked when interrupted or stopped).
    method : str
        ``"exact"`` (state-transition and saltation matrices) or ``"finite-difference"``.
    period : int
        The response's period in forcing periods when its counted sections repeat (to 1e-9 of its
        size), 0 when they do not. A periodic response's exponents are exact: the logarithms of
        its Floquet multipliers over its period (``history`` keeps the running estimates).
    final_state : State
        Where the last counted period ended (continue from it).
    status : Status
        ``SUCCESS``, ``INTERRUPTED`` (Ctrl-C), or why the engine stopped.
    message : str
        What happened, for people.

    Examples
    --------
    The damped paper system settles on a stable orbit at a_G 0.05 and 1.5 Hz: every exponent
    negative.

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> spec = pounding.lyapunov(osc, pounding.Harmonic(0.05, 1.5), cycles=200)
    >>> spec.coordinates
    ('x_0', 'v_0', 'delta_wall0_left', 'delta_wall0_right', 'u_0')
    >>> spec.largest < 0.0, spec.chaotic
    (True, False)
    """

    exponents: np.ndarray = field(repr=False)
    coordinates: tuple[str, ...]
    history: np.ndarray = field(repr=False)
    excitation: Harmonic
    cycles: int
    method: str
    period: int
    final_state: State = field(repr=False)
    status: Status
    message: str

    @property
    def success(self) -> bool:
        """Every period asked for was counted."""
        return self.status == Status.SUCCESS

    @property
    def largest(self) -> float:
        """The largest exponent, 1/s (NaN when no period was counted)."""
        return float(self.exponents[0]) if self.exponents.size else math.nan

    @property
    def chaotic(self) -> bool:
        """Whether the largest exponent is positive beyond what a finite count can tell from zero:
        above its estimate's own wander over the last tenth of the count and above ``5 / (cycles
        T)`` (an estimate's bias from its start decays as 1 / t: a quasi-periodic or neutral
        response, whose largest exponent is 0, comes out slightly positive).  A periodic response
        is never chaotic."""
        if self.period or not self.cycles:
            return False
        floor = 5.0 * self.excitation.freq_hz / self.cycles
        return bool(self.largest > max(self.uncertainty, floor))

    @property
    def uncertainty(self) -> float:
        """How far the largest exponent's running estimate moved over the last tenth of the count,
        1/s: a measure of its convergence (NaN with fewer than 10 periods)."""
        h = self.history[:, 0] if self.history.size else np.zeros(0)
        if h.size < 10 or not np.isfinite(h[-(h.size // 10):]).all():
            return math.nan
        tail = h[-(h.size // 10):]
        return float(tail.max() - tail.min())

    @property
    def kaplan_yorke_dimension(self) -> float:
        """The Kaplan-Yorke (Lyapunov) dimension ``j + sum(lambda_1..j) / |lambda_j+1|``, ``j``
        the most exponents whose sum is not negative (0 when even the largest is negative)."""
        lam = self.exponents
        if lam.size == 0 or not lam[0] >= 0.0:
            return 0.0
        sums = np.cumsum(lam)
        j = int(np.flatnonzero(sums >= 0.0)[-1]) + 1
        if j == lam.size:
            return float(j)
        return float(j + sums[j - 1] / abs(lam[j])) if np.isfinite(lam[j]) else float(j)

    def to_dataframe(self) -> pd.DataFrame:
        """The running estimates, one row per period counted: ``cycle`` and ``lambda_1_1_s`` ...
        (1/s, the largest first)."""
        names = [f"lambda_{i + 1}_1_s" for i in range(self.history.shape[1])]
        hist = pd.DataFrame(self.history, columns=names)
        hist.insert(0, "cycle", np.arange(1, len(hist) + 1))
        return hist

    def to_xarray(self) -> "xr.Dataset":
        """``exponent`` (direction: 1 the largest) and ``history`` (cycle, direction), 1/s, with the
        tangent coordinates, the forcing and the method as attributes."""
        import xarray as xr

        ds = xr.Dataset(
            {"exponent": ("direction", self.exponents, {"units": "1/s"}),
             "history": (("cycle", "direction"), self.history, {"units": "1/s",
                                                                "long_name": "running estimate"})},
            coords={"direction": np.arange(1, self.exponents.size + 1),
                    "cycle": np.arange(1, self.history.shape[0] + 1)},
            attrs={"coordinates": " ".join(self.coordinates), "a_g": self.excitation.a_g,
                   "freq_hz": self.excitation.freq_hz, "phase_rad": self.excitation.phase,
                   "method": self.method, "cycles": self.cycles,
                   "kaplan_yorke_dimension": self.kaplan_yorke_dimension, "status": self.status.name,
                   "message": self.message})
        return ds

    def to_netcdf(self, path: str | Path) -> Path:
        """Write :meth:`to_xarray` to a netCDF file (atomically); returns its path."""
        from .._io import atomic_write, output_file

        return atomic_write(output_file("path", path), self.to_xarray().to_netcdf)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The running estimates against the periods counted, one line per exponent; returns the
        artists.

        Returns its Figure.
        """
        from ..plots.lyapunov import plot_lyapunov
        from ..plots import figure_of

        return figure_of(plot_lyapunov(self, ax=ax, **kwargs), ax)

    def __repr__(self) -> str:
        lam = ", ".join(f"{x:.4g}" for x in self.exponents)
        return (f"LyapunovSpectrum([{lam}] 1/s over {self.cycles} cycles at {self.excitation.freq_hz:g} Hz, "
                f"{self.method}; {self.status.name}: {self.message})")
