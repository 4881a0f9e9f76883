"""What :func:`pounding.periodic_orbit` returns for a structure of several masses (or two adjacent ones):
the orbit, its stability and its levels' numbers (the search itself is every system's: ``periodic``,
``_shooter``)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..engine.state import State
from ._shooting import Floquet


@dataclass(frozen=True, eq=False)
class StructurePeriodicOrbit(Floquet):
    """A periodic response of a structure (or two adjacent ones) and its stability.

    Attributes
    ----------
    state : State
        The orbit's state at the section time (``state.time_s``).
    period_s : float
        Its period, s: ``period_multiple`` periods of the forcing.
    multipliers : ndarray of complex, shape (r,)
        Floquet multipliers: the eigenvalues of ``monodromy``, largest modulus first.
    max_abs_multiplier : float
        The largest ``|multiplier|`` (NaN without a monodromy: a search that stopped early).
    stable : bool
        Whether every multiplier lies inside the unit circle.
    monodromy : ndarray, shape (r, r)
        Jacobian of the stroboscopic map in the shooting coordinates ``coordinates``.
    coordinates : tuple of str
        Names of the shooting coordinates: ``x_<level>`` and ``v_<level>`` for each moving level
        (``first.``/``second.`` for a pair; ``stand_<wall>_<side>`` for a wall's stand),
        ``delta_wall<w>_<side>`` and ``delta_link<k>`` for a relaxing contact's compression,
        ``u_<spring>`` for a spring's slip.
    residual : float
        Largest difference between the state and its image a period later, each coordinate over its scale
        (lengths over the largest ``|x|`` of any level over the guess's period, velocities over that times
        Omega).
    converged : bool
        Whether ``residual <= tol``.
    iterations : int
        Newton iterations made.
    method : str
        ``"exact"`` (state-transition and saltation matrices) or ``"finite-difference"``.
    run : StructureRun or AdjacentRun
        One period from ``state``, densely sampled.
    message : str
        What happened, for people.

    Examples
    --------
    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=4.0e3)
    >>> stop = pounding.Wall(0, 0.02, 0.02, pounding.KelvinVoigt(1.0e8, 2.0e4))
    >>> b = pounding.Structure(2.0e3, iso,
    ...                        [pounding.Storey(1.0e3, 2.0e6, 2.0e3)], [stop])
    >>> orbit = pounding.periodic_orbit(b, pounding.Harmonic(0.1, 1.5))
    >>> orbit.converged, orbit.method, orbit.coordinates[:4]
    (True, 'exact', ('x_0', 'x_1', 'v_0', 'v_1'))
    >>> orbit.contacts_per_period, orbit.stable
    (2, True)
    """

    state: State
    period_s: float
    multipliers: np.ndarray = field(repr=False)
    monodromy: np.ndarray = field(repr=False)
    coordinates: tuple[str, ...]
    residual: float
    converged: bool
    iterations: int
    method: str
    run: Any = field(repr=False)
    message: str

    def _contact_tables(self) -> list:
        return contact_tables(self.run)

    @property
    def alpha(self) -> np.ndarray:
        """Each level's peak absolute acceleration over the table's peak, shape (levels,) (a pair's: the
        first's levels, then the second's)."""
        peak = abs(self.run.excitation.peak_m_s2)
        acc = np.concatenate([part.abs_acceleration_max for part in run_parts(self.run)])
        return acc / peak if peak > 0.0 else np.full(acc.shape, math.nan)

    @property
    def excursion_m(self) -> np.ndarray:
        """Each level's ``D_max - D_min`` over the period, m, shape (levels,) (a pair's: the first's levels,
        then the second's)."""
        return np.concatenate([part.excursion_m for part in run_parts(self.run)])

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Each level's orbit in its phase plane (x, v), its contacts marked; returns its Figure."""
        from ..plots.periodic import plot_structure_orbit
        from ..plots import figure_of

        return figure_of(plot_structure_orbit(self, ax=ax, **kwargs), ax)


def run_parts(run: Any) -> tuple:
    """The structures' runs of a run: a structure's itself, a pair's first and second."""
    return (run.first, run.second) if hasattr(run, "first") else (run,)


def contact_tables(run: Any) -> list:
    """A run's contact tables (the core's columns): each structure's walls', then a pair's links'."""
    parts = run_parts(run)
    return [p.contact_table for p in parts] + ([run.link_table] if len(parts) > 1 else [])
