"""Basin stability over a test matrix: at each level and frequency, the share of random initial
states whose response ends in contact with the bumpers, the probability that the equipment pounds
there, with its standard error."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._checks import float_array, integer, positive
from .._errors import InputError, Interrupted, Problem, renamed_keyword
from .._runner import run_tasks
from .._runner.progress import Progress
from ..engine.simulate import check_rtol
from ..engine.assembly import assemble, check_system
from ..excitation import Harmonic
from ..model import Oscillator
from .basins import (MAX_STATES, N_ROW, R_LEFT, R_PERIOD, R_RIGHT, ROWS_PER_TASK, SIGNATURE, initial_states,
                     run_states, state_box, steady_options, core_view)

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr


@renamed_keyword("oscillator", "system")
def basin_stability_map(system: Any, a_g_levels: Any, freqs_hz: Any, *, samples: int = 200,
                        displacement_m: Any = None, velocity_m_s: Any = None, seed: int = 0,
                        max_cycles: int = 500, measure_cycles: int = 5, max_period: int = 8,
                        steady_rtol: float = 1e-8, rtol: float = 1e-10, scheduler: Any = None,
                        workers: Any = None, progress: Progress = False) -> "BasinStabilityMap":
    """The probability that the equipment pounds, over a test matrix: at each a_G and frequency,
    the share of ``samples`` random initial states (the same ones at every point) whose response
    ends touching the bumpers (over its last cycles, whether it settled or not).

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system (with bumpers; a structure with walls or links: its states shifted as one
        body, as :func:`pounding.basins` has them).
    a_g_levels : array_like, shape (m,)
        Peak table accelerations, g.
    freqs_hz : array_like, shape (n,)
        Frequencies, Hz.
    samples : int
        Random initial states per point (default 200): the standard error of a probability ``p``
        is ``sqrt(p (1 - p) / samples)``, 0.035 at most for 200.
    displacement_m, velocity_m_s : (float, float), optional
        The box the initial states are drawn from (m, m/s; see :func:`pounding.basins`).
    seed : int
        The random states' seed.
    max_cycles, measure_cycles, max_period : int
        When a state has settled, and when it is called not settled (see :func:`pounding.basins`).
    steady_rtol, rtol : float
        The settling test's tolerance, and the nonlinear laws' integration tolerance.
    scheduler : str or dask.distributed.Client, optional
        How the states run (``"threads"`` by default; see :func:`pounding.basins`).
    workers : int, optional
        Threads or processes (default: the machine's cores).
    progress : bool or callable
        True: a progress bar over all the states.

    Returns
    -------
    BasinStabilityMap
        ``data`` over (a_g, freq_hz): ``pounding_probability``, ``standard_error``,
        ``not_settled`` (the share of states that did not settle) and ``impacting_attractors`` /
        ``free_attractors`` (how many responses of each kind were found); ``.plot(curves=...)``.

    Raises
    ------
    InputError
        For a bad argument (names it, the value and the fix).
    Interrupted
        On Ctrl-C; its ``partial`` holds the map of the states finished.

    Examples
    --------
    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> m = pounding.basin_stability_map(osc, [0.05], [1.5, 1.8, 2.6], samples=40)
    >>> m.data["pounding_probability"].values.round(2).tolist()
    [[1.0, 0.5, 0.0]]
    """
    check_system(system)
    if not assemble(system).pairs:
        raise InputError(Problem.MISSING_INPUT, "system", "no bumpers",
                         what="bumpers, walls or links (without them nothing pounds)")
    levels = np.atleast_1d(float_array("a_g_levels", a_g_levels))
    freqs = np.atleast_1d(float_array("freqs_hz", freqs_hz))
    for name, values in (("a_g_levels", levels), ("freqs_hz", freqs)):
        unique, counts = np.unique(values, return_counts=True)
        if np.any(counts > 1):
            raise InputError(Problem.DUPLICATE, name, values.tolist(), repeated=unique[counts > 1].tolist())
    levels, freqs = np.sort(levels), np.sort(freqs)
    for i, v in enumerate(levels):  # (each checked as a Harmonic checks it: sign, size, unit)
        Harmonic(positive(f"a_g_levels[{i}]", v, "g"), 1.0)
    for i, v in enumerate(freqs):
        Harmonic(0.05, positive(f"freqs_hz[{i}]", v, "Hz"))
    samples = integer("samples", samples, 1, MAX_STATES)
    n_points = levels.size * freqs.size
    if samples * n_points > MAX_STATES:
        raise InputError(Problem.TOO_LARGE, "samples", samples, maximum=MAX_STATES // n_points,
                         what=f" states at each of {n_points} points",
                         fix="give fewer samples or a coarser matrix")
    d_box, v_box = state_box(system, displacement_m, velocity_m_s)
    steady = steady_options(max_cycles, measure_cycles, max_period, steady_rtol)
    rtol = check_rtol(rtol)
    rng = np.random.default_rng(integer("seed", seed, 0))
    starts = initial_states(system, rng.uniform(*d_box, samples), rng.uniform(*v_box, samples))
    core_system, view = core_view(system)
    points = [(i, j) for i in range(levels.size) for j in range(freqs.size)]
    tasks, where = [], []
    for i, j in points:
        exc = Harmonic(float(levels[i]), float(freqs[j]))
        for k in range(0, samples, ROWS_PER_TASK):
            chunk = starts[k:k + ROWS_PER_TASK]
            tasks.append((core_system, exc.peak_m_s2, exc.omega_rad_s, chunk, steady, float(rtol), view))
            where.append((i, j, k))
    ran = run_tasks(run_states, tasks, scheduler=scheduler, workers=workers, progress=progress,
                    label="basin stability", total=len(points) * samples, on_error="stop")
    ran.raise_first_error(lambda t: f"the states {where[t][2]}+ at a_G {levels[where[t][0]]:g}, "
                                    f"{freqs[where[t][1]]:g} Hz")
    rows = np.full((levels.size, freqs.size, samples, N_ROW), np.nan)
    for (i, j, k), value in zip(where, ran.values):
        if value is not None:
            rows[i, j, k:k + len(value)] = value
    result = _map(system, levels, freqs, samples, rows, not ran.complete)
    if ran.interrupted:
        raise Interrupted(result, int(np.isfinite(rows[..., R_PERIOD]).sum()), rows[..., 0].size, "states")
    return result


@dataclass(frozen=True, eq=False)
class BasinStabilityMap:
    """What :func:`basin_stability_map` found.

    Attributes
    ----------
    oscillator : Oscillator
    data : xarray.Dataset
        Over ``a_g`` and ``freq_hz``: ``pounding_probability`` (the share of the states whose
        response touches the bumpers over its last cycles, settled or not: a chaotic impacting
        response pounds too), ``standard_error`` (its sampling error),
        ``not_settled``, ``impacting_attractors`` and ``free_attractors``; NaN where no state ran.
    complete : bool
        Every state ran (False after Ctrl-C).

    Examples
    --------
    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> m = pounding.basin_stability_map(osc, [0.05], [1.8, 2.6], samples=20)
    >>> m.data["impacting_attractors"].values.tolist()  # at 1.8 and 2.6 Hz
    [[1, 0]]
    """

    oscillator: Oscillator
    data: "xr.Dataset"
    complete: bool

    def to_dataframe(self) -> pd.DataFrame:
        """One row per test point (a_g, freq_hz) with its variables."""
        from .._tables import xarray_to_frame

        return xarray_to_frame(self.data)

    def to_xarray(self) -> "xr.Dataset":
        """The labelled data (``data``)."""
        return self.data

    def plot(self, ax: Any = None, *, curves: Any = None, **kwargs: Any) -> Any:
        """The probability of pounding over frequency and a_G; ``curves`` (a
        :class:`~pounding.CoexistenceMap`) drawn over it: the folds and grazings that bound where
        responses coexist.

        Returns its Figure.
        """
        from ..plots.basins import plot_basin_stability
        from ..plots import figure_of

        return figure_of(plot_basin_stability(self, ax=ax, curves=curves, **kwargs), ax)


def _map(osc: Oscillator, levels: np.ndarray, freqs: np.ndarray, samples: int, rows: np.ndarray,
         interrupted: bool) -> BasinStabilityMap:
    import xarray as xr

    ran = np.isfinite(rows[..., R_PERIOD])
    settled = ran & (rows[..., R_PERIOD] > 0)
    # (pounding: contacts over its last cycles, settled or not: a chaotic impacting response pounds)
    hits = ran & (rows[..., R_LEFT] + rows[..., R_RIGHT] > 0)
    n_ran = ran.sum(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        p = np.where(n_ran > 0, hits.sum(axis=-1) / n_ran, np.nan)
        se = np.sqrt(p * (1.0 - p) / n_ran)
        unsettled = np.where(n_ran > 0, (ran & ~settled).sum(axis=-1) / n_ran, np.nan)
    counts = np.zeros(p.shape + (2,), dtype=np.int64)
    for i in range(levels.size):
        for j in range(freqs.size):
            for impacting, col in ((True, 0), (False, 1)):
                keep = settled[i, j] & ((rows[i, j, :, R_LEFT] + rows[i, j, :, R_RIGHT] > 0) == impacting)
                counts[i, j, col] = _distinct(rows[i, j][keep])
    dims = ("a_g", "freq_hz")
    ds = xr.Dataset({"pounding_probability": (dims, p), "standard_error": (dims, se),
                     "not_settled": (dims, unsettled), "impacting_attractors": (dims, counts[..., 0]),
                     "free_attractors": (dims, counts[..., 1])},
                    coords={"a_g": levels, "freq_hz": freqs})
    ds["freq_hz"].attrs["units"] = "Hz"
    ds["a_g"].attrs["units"] = "g"
    ds.attrs.update({"samples": samples, "complete": int(not interrupted), "system": osc.to_toml_text()})
    return BasinStabilityMap(osc, ds, not interrupted)


def _distinct(rows: np.ndarray, rtol: float = 1e-4) -> int:
    """How many distinct responses (period, alpha, excursion, contacts per cycle) among ``rows``."""
    found: list[np.ndarray] = []
    for row in rows:
        if not any(a[R_PERIOD] == row[R_PERIOD] and all(math.isclose(x, y, rel_tol=rtol, abs_tol=1e-12)
                                                        for x, y in zip(a[SIGNATURE], row[SIGNATURE]))
                   for a in found):
            found.append(row)
    return len(found)
