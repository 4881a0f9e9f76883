"""How a pair's orientation changes a system's response: the system run under the pair turned to each angle
of a set, and the most critical orientation of each peak.

A system on one line (a single mass, a structure, a pair of structures) takes the pair's motion along its
line: turned by ``a``, the motion along x is ``pair.along(a)`` (:class:`~pounding.RecordPair`).  A building
in plan takes both components, the pair turned by ``a`` (``pair.rotated(a)``: its x along ``a``).  Codes
(ASCE 7-16 chapter 17, EN 1998-1 section 10) ask for the response to several orientations of each pair; a
gap checked against one orientation may be too small for another.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from .._checks import float_array, instance_of, integer, positive
from .._errors import InputError, Interrupted, Problem
from .._runner import Context, Progress, run_tasks
from ..excitation.pair import RecordPair

DEFAULT_STEP_DEG = 15.0
SMALLER_IS_CRITICAL = frozenset({"clearance_min_m"})  # (the quantities whose least value is the worst)


@dataclass(frozen=True, eq=False)
class Orientations:
    """A system's peaks under a pair turned to each angle (:func:`orientations`).

    Attributes
    ----------
    data : pandas.DataFrame
        One row per angle (index ``angle_deg``, degrees from x towards y), the run's quantities as every
        run gives them (``disp_max_m``, ``acc_max_g``, ``impacts``, ``drift_ratio_max``, ...; NaN where a
        run did not finish).
    pair_name : str
        The pair's name.
    duration_s : float
        Each run's length, s.
    attrs : dict
        What else is known (``complete``: 0 where a Ctrl-C stopped the runs).

    Examples
    --------
    A result as :func:`orientations` makes one, its critical orientation and its table:

    >>> import pandas as pd
    >>> from pounding.protocols.orientations import Orientations
    >>> table = pd.DataFrame({"disp_max_m": [0.10, 0.14, 0.12]},
    ...                      index=pd.Index([0.0, 90.0, 180.0], name="angle_deg"))
    >>> found = Orientations(table, "a pair", 10.0)
    >>> found.critical("disp_max_m")
    (90.0, 0.14)
    """

    data: pd.DataFrame
    pair_name: str = ""
    duration_s: float = math.nan
    attrs: dict = field(default_factory=dict, repr=False)

    @property
    def angles_deg(self) -> np.ndarray:
        """The angles, degrees, shape (a,)."""
        return self.data.index.to_numpy(dtype=float)

    def critical(self, quantity: str = "disp_max_m") -> tuple[float, float]:
        """The most critical orientation for ``quantity`` (a column of :attr:`data`): ``(angle_deg, its
        largest value)``; for a clearance (``clearance_min_m``: the smaller, the nearer a wall), its
        smallest."""
        column = self._column(quantity)
        if not np.isfinite(column).any():
            return math.nan, math.nan
        at = int(np.nanargmin(column) if quantity in SMALLER_IS_CRITICAL else np.nanargmax(column))
        return float(self.angles_deg[at]), float(column[at])

    def _column(self, quantity: str) -> np.ndarray:
        if quantity not in self.data.columns:
            raise InputError(Problem.NOT_IN_RESULT, "quantity", quantity,
                             choices=", ".join(self.data.columns))
        return self.data[quantity].to_numpy(dtype=float)

    def to_dataframe(self) -> pd.DataFrame:
        """:attr:`data` (a copy)."""
        return self.data.copy()

    def to_xarray(self) -> Any:
        """:attr:`data` as a Dataset along ``angle_deg``, with the pair's name and the runs' length."""
        import xarray as xr

        return xr.Dataset.from_dataframe(self.data).assign_attrs(
            pair=self.pair_name, duration_s=self.duration_s, **self.attrs)

    def plot(self, quantity: str = "disp_max_m", ax: Any = None) -> Any:
        """``quantity`` against the angle on a polar axes, the critical orientation marked; returns the
        Figure."""
        from ..plots import figure_of
        from ..plots.orientations import plot_orientations

        return figure_of(plot_orientations(self, quantity, ax=ax), ax)

    def __repr__(self) -> str:
        angle, value = self.critical()
        return (f"Orientations({self.pair_name!r}, {self.angles_deg.size} angles, disp_max_m largest "
                f"{value:.4g} at {angle:g} deg)")


def orientation_angles(angles_deg: Any) -> np.ndarray:
    """Angles (degrees) checked: finite, in [0, 360), strictly increasing; None gives every 15 degrees."""
    if angles_deg is None:
        return DEFAULT_STEP_DEG * np.arange(int(360.0 / DEFAULT_STEP_DEG))
    angles = float_array("angles_deg", angles_deg)
    bad = np.flatnonzero((angles < 0.0) | (angles >= 360.0))
    if bad.size:
        raise InputError(Problem.OUT_OF_RANGE, f"angles_deg[{int(bad[0])}]", float(angles[bad[0]]),
                         range="[0, 360) degrees", hint=" (a direction and its opposite both count: a "
                                                          "system on one line need not be symmetric)")
    if angles.size > 1 and (np.diff(angles) <= 0.0).any():
        raise InputError(Problem.NOT_INCREASING, "angles_deg", angles.tolist()[:6])
    return angles


def _one_angle(task: tuple, ctx: Context) -> dict:
    """One orientation's run: the system under the pair's motion along x turned by the task's angle."""
    from ..engine.simulate import peaks

    system, record, duration, max_steps = task
    if ctx.stopped():  # (a stop was asked for before this one began)
        raise Interrupted(None, 0, 1, "runs")
    return peaks(system, record, duration, max_steps=max_steps)


def orientations(system: Any, pair: RecordPair, angles_deg: Any = None, duration_s: float | None = None, *,
                 workers: int | None = None, scheduler: Any = None, progress: Progress = False,
                 max_steps: int = 10_000_000) -> Orientations:
    """The system's response to a pair of components turned to each angle, and the most critical one.

    Parameters
    ----------
    system : Oscillator, Structure, Adjacent or PlanBuilding
        Any system on one line: it takes the pair's motion along its line, x, with the pair turned by each
        angle (the motion ``cos(a) x + sin(a) y``: :meth:`RecordPair.along`).  A building in plan takes
        both components, the pair turned by each angle (:meth:`RecordPair.rotated`): its peaks are its
        run's (``disp_max_m`` the largest bearing displacement in plan, ``theta_max_rad``,
        ``clearance_min_m``, ...: :meth:`PlanRun.quantities`).
    pair : RecordPair
        The ground motion's two components.
    angles_deg : array_like, shape (a,), optional
        Angles in [0, 360), degrees from x towards y, increasing (default: every 15 degrees; a direction
        and its opposite differ where the system is not symmetric).
    duration_s : float, optional
        Each run's length, s (default: the pair's).
    workers : int, optional
        Threads or processes (default: every core).
    scheduler : str or dask.distributed.Client, optional
        As :func:`pounding.pounding_spectrum`'s: the runs on threads by default.
    progress : bool or callable
        A progress bar, or a callable taking the runs finished.
    max_steps : int
        Each run's budget of engine sub-intervals.

    Returns
    -------
    Orientations
        The peaks at each angle (``data``), ``critical(quantity)``, ``plot()``, ``to_dataframe()``,
        ``to_xarray()``.

    Raises
    ------
    InputError
        A bad argument (named), or a run the engine refuses.
    Interrupted
        On Ctrl-C: ``partial`` holds the angles done (the others NaN).

    Examples
    --------
    A single mass between bumpers under El Centro and the same motion turned by 90 degrees as its second
    component: the largest displacement where the motion along x is largest, at 45 (and 225) degrees:

    >>> import pounding
    >>> quake = pounding.records.el_centro()
    >>> pair = pounding.RecordPair(quake, quake)
    >>> found = pounding.orientations(pounding.presets.paper_damped(), pair,
    ...                               [0.0, 45.0, 90.0], duration_s=5.0)
    >>> found.critical("disp_max_m")[0]
    45.0
    """
    instance_of("pair", pair, RecordPair, "pounding.RecordPair")
    angles = orientation_angles(angles_deg)
    duration = pair.duration_s if duration_s is None else positive("duration_s", duration_s, "s")
    max_steps = integer("max_steps", max_steps, 1)
    from ..engine.assembly import is_plan
    from ..engine.simulate import simulate

    turned = pair.rotated if is_plan(system) else pair.along  # (a building in plan takes both components)
    simulate(system, turned(float(angles[0])), min(duration, 1e-3), sample_rate_hz=0)  # (refused here)
    tasks = [(system, turned(float(a)), duration, max_steps) for a in angles]
    done = run_tasks(_one_angle, tasks, scheduler=scheduler, workers=workers, progress=progress,
                     label="orientations")
    done.raise_first_error(lambda i: f"angle {angles[i]:g} deg")
    rows = [value if value is not None else {} for value in done.values]
    table = pd.DataFrame(rows, index=pd.Index(angles, name="angle_deg"), dtype=float)
    out = Orientations(table, pair.name, float(duration), {"complete": int(done.complete)})
    if not done.complete:
        raise Interrupted(out, int(table.notna().all(axis=1).sum()), angles.size, "angles")
    return out


__all__ = ["Orientations", "orientation_angles", "orientations"]
