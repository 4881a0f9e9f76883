"""Hysteresis loops of the inertia force (paper Figs. 7 and 15)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

if TYPE_CHECKING:  # pragma: no cover
    from ..engine.result import Run


@dataclass(frozen=True, eq=False)
class HysteresisLoop:
    """``r = F_I / (M g)`` against ``d = D / Delta`` over whole steady cycles.

    Attributes
    ----------
    d, r : ndarray, shape (n,)
        Normalized displacement and inertia force (``F_I = M a_abs``), every event
        instant included.
    t : ndarray, shape (n,)
        Times, s.
    freq_hz, a_g, total_gap_m : float
        The step and the length ``Delta`` that normalizes ``D``.
    cycles : int
        Forcing cycles covered (the period multiple of the response).
    bumper_surfaces_d : tuple of float or None
        Where the bumpers' free surfaces are in ``d``: ``(-g_L / Delta, g_R / Delta)``.

    Examples
    --------
    The loop of a pounding step (Figs. 7 and 15), from a sweep:

    >>> import pounding
    >>> sw = pounding.sweep(pounding.presets.paper_damped(), 0.05, [1.5, 2.0])
    >>> loop = sw.hysteresis_loop(1.5)
    >>> loop.cycles, loop.total_gap_m, loop.bumper_surfaces_d
    (1, 0.03, (-0.5, 0.5))
    >>> # past the surfaces: contact
    >>> round(float(loop.d.min()), 2), round(float(loop.d.max()), 2)
    (-0.53, 0.53)
    >>> round(float(loop.r.max()), 2)  # peak F_I / (M g)
    0.42
    >>> list(loop.to_dataframe().columns)
    ['t', 'd', 'r']
    """

    d: np.ndarray = field(repr=False)
    r: np.ndarray = field(repr=False)
    t: np.ndarray = field(repr=False)
    freq_hz: float
    a_g: float
    total_gap_m: float
    cycles: int
    bumper_surfaces_d: tuple[float, float] | None = None

    @classmethod
    def from_run(cls, run: "Run", total_gap_m: float, freq_hz: float, a_g: float,
                 cycles: int) -> "HysteresisLoop":
        """The loop of the whole ``run`` (the caller runs just the ``cycles`` it wants drawn),
        normalised by ``total_gap_m`` (m) and the run's ``g``."""
        g = run.excitation.g
        b = run.oscillator.bumpers
        surfaces = None if b is None else (-b.gap_left_m / total_gap_m, b.gap_right_m / total_gap_m)
        return cls(d=run.displacement / total_gap_m, r=run.abs_acceleration / g, t=run.t,
                   freq_hz=freq_hz, a_g=a_g, total_gap_m=total_gap_m, cycles=cycles,
                   bumper_surfaces_d=surfaces)

    def to_xarray(self) -> Any:
        """The loop of :meth:`to_dataframe` as a Dataset along ``sample``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "sample")

    def to_dataframe(self) -> pd.DataFrame:
        """Columns ``t`` (s), ``d`` and ``r`` (dimensionless)."""
        return pd.DataFrame({"t": self.t, "d": self.d, "r": self.r})

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Draw the loop; see :func:`pounding.plots.plot_hysteresis`. Returns its Figure."""
        from ..plots import plot_hysteresis, figure_of

        return figure_of(plot_hysteresis(self, ax=ax, **kwargs), ax)
