"""The paper's test matrix (docs/paper.md): NBs and YBs sweeps up and down, in parallel.

Independent sweeps run on worker threads: the compiled kernels release the GIL, so the
threads use every core without copying anything.  A sweep is a :class:`SweepPlan`, plain
data, so another executor (processes, Dask) can run the same plans.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._checks import instance_of, one_of, real_tuple
from .._errors import InputError, Interrupted, Problem
from ..model import Adjacent, Oscillator, Structure
from .._runner import Context, run_tasks
from ..engine.assembly import is_single_mass, structures_of
from .._runner.progress import Progress
from .sweep import SweepPlan, check_sweep_options, make_plan, run_plan
from .sweep_result import LEVEL_COLUMNS, STEP_COLUMNS, SweepResult
from .sweep_features import STRUCTURE_QUANTITIES
from .sweep_table import SIDE_COLUMNS

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

PAPER_NBS_A_G = (0.03, 0.05, 0.1)
PAPER_YBS_A_G = (0.03, 0.05, 0.075, 0.1)
CONFIGURATIONS = ("NBs", "YBs")
DIRECTIONS = ("up", "down")
_BOOL_COLUMNS = ("contact", "steady")
_DATA_COLUMNS = tuple(c for c in STEP_COLUMNS if c not in ("freq_hz", "nu")) + tuple(
    f"{c}{s}" for s in ("_left", "_right") for c in SIDE_COLUMNS) + LEVEL_COLUMNS


TABLE2_QUANTITIES = ("nu_r", "alpha", "eta", "e", "contact_nu_min", "contact_nu_max", "excursion_max_m")
TABLE3_QUANTITIES = ("mean_force_over_mg", "contact_time_ms", "peak_force_over_mg")
TABLE4_QUANTITIES = ("dissipated_energy_per_mass", "restitution")
STRUCTURE_TABLE2_QUANTITIES = STRUCTURE_QUANTITIES  # (a structure's sweep's quantities)


def sweep_quantities(sw: Any) -> dict[str, float]:
    """The paper's per-sweep quantities (Tables 2-4) of one sweep, by their table names: its lowest moving
    level's (:meth:`SweepResult.paper_quantities`; a single mass: its own)."""
    return sw.paper_quantities()


@dataclass(frozen=True, eq=False)
class CampaignResult:
    """Result of :func:`pounding.campaign`.

    Attributes
    ----------
    data : xarray.Dataset
        Every step's metrics on dims ``(configuration, a_g, direction, freq_hz)``; NaN
        (and ``ran`` False) where a sweep is not part of the matrix or did not finish.
    sweeps : dict
        ``(configuration, a_g, direction) -> SweepResult`` for the sweeps that ran.
    complete : bool
        False after an interruption.

    Examples
    --------
    A tiny matrix (one a_G, three frequencies, up only, 10 cycles a step; the paper's has 14 sweeps
    of 46 steps):

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> res = pounding.campaign(ybs.without_bumpers(), ybs, nbs_a_g=[0.05],
    ...                         ybs_a_g=[0.05],
    ...                         freqs_hz=[1.5, 2.0, 2.5], directions=["up"],
    ...                         steady="fixed", cycles=10)
    >>> res.complete, list(res.sweeps)
    (True, [('NBs', 0.05, 'up'), ('YBs', 0.05, 'up')])
    >>> print(res.data["alpha"].sel(a_g=0.05,
    ...                                direction="up").round(2).to_pandas())
    freq_hz         1.5   2.0   2.5
    configuration
    NBs            2.63  0.99  0.51
    YBs            8.39  1.23  0.51
    >>> res.sweep("YBs", 0.05, "up").contact_range_hz
    (1.5, 1.5)
    >>> print(res.table3()[["configuration", "nu_r",
    ...                     "contact_time_ms"]].round(1).to_string(index=False))
    configuration  nu_r  contact_time_ms
              YBs   1.5             50.0
    >>> res.to_netcdf("campaign.nc").name
    'campaign.nc'
    """

    data: "xr.Dataset" = field(repr=False)
    sweeps: dict = field(repr=False)
    complete: bool

    def sweep(self, configuration: str, a_g: float, direction: str) -> SweepResult:
        """One sweep of the campaign."""
        for (conf, ag, d), sw in self.sweeps.items():
            if conf == configuration and d == direction and abs(ag - a_g) <= 1e-12:
                return sw
        keys = ", ".join(f"({c!r}, {a:g}, {d!r})" for c, a, d in self.sweeps)
        raise InputError(Problem.NOT_IN_RESULT, "(configuration, a_g, direction)",
                         (configuration, a_g, direction), choices=keys)

    def _started(self) -> list:
        """The sweeps with at least one finished step (all of them unless interrupted)."""
        return [(key, sw) for key, sw in self.sweeps.items() if sw.steps_done > 0]

    def to_xarray(self) -> "xr.Dataset":
        """The campaign's steps (:attr:`data`): dims configuration, a_g, direction, freq_hz."""
        return self.data

    def to_dataframe(self) -> pd.DataFrame:
        """One row per step that ran: configuration, a_g, direction, freq_hz, nu and the metrics."""
        from .._tables import xarray_to_frame

        df = xarray_to_frame(self.data)
        return df[df["ran"]].drop(columns="ran").reset_index(drop=True)

    def to_netcdf(self, path: str | Path) -> Path:
        """Save :attr:`data` to netCDF (read back with ``xarray.open_dataset``)."""
        from .._io import atomic_write, output_file

        return atomic_write(output_file("path", path), self.data.to_netcdf)

    @property
    def of_one_mass(self) -> bool:
        """Whether the campaign's systems are single masses: the paper's Tables 3 and 4 (one mass's impacts)
        apply; a structure's campaign has :meth:`table2` per level."""
        return all(is_single_mass(sw.system) for sw in self.sweeps.values())

    def table2(self) -> pd.DataFrame:
        """Analogue of the paper's Table 2: maximum alpha and excursion, resonance, contact range.

        One row per sweep: ``configuration``, ``a_g``, ``direction``, ``nu_r``, ``alpha``
        (max), ``eta`` (max E / Delta, YBs), ``e`` (max E / D_tmax), ``contact_nu_min``,
        ``contact_nu_max`` (the contact range ``Delta nu_C``, NaN without contact) and
        ``excursion_max_m`` (max E, m).  A structure's campaign: ``nu_r_top``, ``alpha_top_max``,
        ``alpha_base_max``, ``drift_ratio_max``, ``contact_nu_min``, ``contact_nu_max``
        (:meth:`SweepResult.quantities`).
        """
        return self._rows(TABLE2_QUANTITIES, yb_only=False)

    def _rows(self, quantities: tuple[str, ...], yb_only: bool) -> pd.DataFrame:
        if not self.of_one_mass:
            if yb_only:
                raise InputError(Problem.WRONG_MODE, "table", "table3/table4", mode="one mass's campaign",
                                 fix="a structure's campaign has table2() (its alpha per level) and its "
                                     "sweeps' contacts_dataframe()")
            quantities = STRUCTURE_TABLE2_QUANTITIES
        columns = ["configuration", "a_g", "direction", *quantities]
        rows = []
        for (conf, ag, d), sw in self._started():
            if yb_only and conf != "YBs":
                continue
            q = sweep_quantities(sw) if self.of_one_mass else sw.quantities()
            rows.append([conf, ag, d, *(q[k] for k in quantities)])
        # the columns even without rows: an NBs-only campaign, or one interrupted before any
        # YBs step finished, has empty Tables 3 and 4
        return pd.DataFrame(rows, columns=columns)

    def table3(self) -> pd.DataFrame:
        """Analogue of Table 3 (YBs, at the resonance step): ``mean_force_over_mg``
        (``F_m / (M g)``), ``contact_time_ms`` and ``peak_force_over_mg``."""
        return self._rows(("nu_r",) + TABLE3_QUANTITIES, yb_only=True)

    def table4(self) -> pd.DataFrame:
        """Analogue of Table 4 (YBs, at the resonance step): ``dissipated_energy_per_mass``
        (``E_d / M``, m^2/s^2) and ``restitution`` ``s``."""
        return self._rows(("nu_r",) + TABLE4_QUANTITIES, yb_only=True)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """alpha and eta/e against nu for both configurations; see :func:`pounding.plots.plot_campaign`.
        Returns its Figure."""
        from ..plots import plot_campaign, figure_of

        return figure_of(plot_campaign(self, ax=ax, **kwargs), ax)


def sweep_task(plan: SweepPlan, ctx: Context) -> Any:
    """One sweep of the campaign, as a task of the shared runner."""
    return run_plan(plan, ctx.advance, ctx.control)


def _touches(system: Any) -> bool:
    """Whether a system can pound: an oscillator's bumpers (its one level's wall), a structure's walls, a
    pair's links or walls."""
    structures, links = structures_of(system)
    return bool(links) or any(s.walls for s in structures)


def campaign(
    nbs_system: Oscillator | None,
    ybs_system: Oscillator | None,
    *,
    nbs_a_g: Sequence[float] = PAPER_NBS_A_G,
    ybs_a_g: Sequence[float] = PAPER_YBS_A_G,
    freqs_hz: np.ndarray | None = None,
    directions: Sequence[str] = DIRECTIONS,
    workers: int | None = None,
    scheduler: Any = None,
    progress: Progress = False,
    label: str = "campaign",
    **sweep_options: Any,
) -> CampaignResult:
    """The shaking-table campaign: every (configuration, a_G, direction) sweep, in parallel.

    Each sweep starts from rest (down sweeps at the highest frequency).

    Parameters
    ----------
    nbs_system, ybs_system : Oscillator, Structure, Adjacent or None
        The system without bumpers (NBs) and with them (YBs); None leaves that
        configuration out.  Two structures (without walls or links, and with them; the same levels) make
        a structure's campaign: its data has a ``level`` dim (but for a one-level structure's), its Table 2
        the top floor's and the base's alpha (:meth:`SweepResult.quantities`); Tables 3 and 4 are one
        mass's.
    nbs_a_g, ybs_a_g : sequence of float
        Table accelerations in g (default the paper's: 0.03, 0.05, 0.1 and 0.03, 0.05,
        0.075, 0.1).
    freqs_hz : array_like, optional
        Step frequencies, Hz (default: 0.5 to 5.0 by 0.1).
    directions : sequence of {"up", "down"}
        The directions swept at each a_G (default both, as the paper).
    workers : int, optional
        Worker threads or processes (default: the machine's cores).
    scheduler : str or dask.distributed.Client, optional
        Where the sweeps run: ``"threads"`` (default; the kernels release the GIL), ``"serial"``,
        ``"processes"``, ``"local"`` (a Dask ``LocalCluster``), a Dask scheduler's address or a
        ``Client``.  Every scheduler gives the same campaign.
    progress : bool or callable
        True: a progress bar over all steps; a callable gets the number of steps finished (on
        processes and Dask, a sweep's steps as it ends).
    label : str
        The progress bar's description (two campaigns at once, told apart).
    **sweep_options
        The keyword arguments of :func:`pounding.sweep`, the same for every sweep:
        ``steady``, ``cycles``, ``measure_cycles``, ``max_cycles``, ``steady_rtol``,
        ``max_period``, ``omega_min_rad_s``, ``f_ref_hz``, ``rtol``,
        ``max_events_per_cycle`` and ``max_steps`` (each sweep's own budget); default: adaptive.

    Returns
    -------
    CampaignResult
        ``.data`` (dims configuration, a_g, direction, freq_hz; saves to netCDF),
        ``.sweeps``, ``.table2()``, ``.table3()``, ``.table4()``.

    Raises
    ------
    Interrupted
        On Ctrl-C; ``partial`` is a CampaignResult with the finished steps.

    Examples
    --------
    The YBs sweeps alone (no NBs system) at a_G = 0.05 g, up and down over three frequencies, a
    fixed 10 cycles a step (a tiny version of the paper's matrix, which the defaults run):

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> res = pounding.campaign(None, ybs, ybs_a_g=[0.05], freqs_hz=[1.5, 2.0, 2.5],
    ...                         directions=["up", "down"], steady="fixed",
    ...                         cycles=10)
    >>> dict(res.data.sizes)
    {'configuration': 1, 'a_g': 1, 'direction': 2, 'freq_hz': 3}
    >>> alpha = res.data["alpha"].sel(configuration="YBs", a_g=0.05)
    >>> print(alpha.round(2).to_pandas())
    freq_hz     1.5   2.0   2.5
    direction
    up         8.39  1.23  0.51
    down       8.37  0.96  0.55
    """
    check_sweep_options(sweep_options)
    systems = {"NBs": (nbs_system, nbs_a_g), "YBs": (ybs_system, ybs_a_g)}
    if nbs_system is None and ybs_system is None:
        raise InputError(Problem.MISSING_KEY, "nbs_system, ybs_system", (None, None),
                         choices="at least one of the two systems")
    if isinstance(directions, str) or not isinstance(directions, (list, tuple)) or not directions:
        raise InputError(Problem.WRONG_TYPE, "directions", directions, got=type(directions).__name__,
                         expected="list of 'up' and/or 'down', e.g. ['up', 'down']")
    for i, d in enumerate(directions):
        one_of(f"directions[{i}]", d, DIRECTIONS)
    if len(set(directions)) != len(directions):
        raise InputError(Problem.DUPLICATE, "directions", list(directions), repeated="a direction")
    plans: list[tuple[tuple[str, float, str], SweepPlan]] = []
    kinds = {type(osc) for osc, _ in systems.values() if osc is not None}
    for conf, (osc, a_gs) in systems.items():
        if osc is None:
            continue
        field_name = f"{conf.lower()}_system"
        instance_of(field_name, osc, (Oscillator, Structure, Adjacent),
                    "pounding.Oscillator (or a Structure, or an Adjacent pair)")
        if _touches(osc) != (conf == "YBs"):
            what = "bumpers, walls or links"
            fix = (f"give the system without {what} (a single mass's or a structure's "
                   "without_bumpers()); were the NBs and YBs systems swapped?" if conf == "NBs" else
                   f"give a system with {what}; were the NBs and YBs systems swapped?")
            raise InputError(Problem.WRONG_CONFIGURATION, field_name, type(osc).__name__,
                             got=f"with {what}" if _touches(osc) else f"without {what}", fix=fix)
        other = nbs_system is not None and (len(kinds) > 1 or _levels(osc) != _levels(nbs_system))
        if conf == "YBs" and other:
            raise InputError(Problem.WRONG_CONFIGURATION, field_name, type(osc).__name__,
                             got=f"of other levels than nbs_system's, or of another kind "
                                 f"({type(osc).__name__} against {type(nbs_system).__name__})",
                             fix="give the same system without and with its walls (or bumpers)")
        levels = real_tuple(f"{conf.lower()}_a_g", a_gs)
        if not levels:
            raise InputError(Problem.EMPTY, f"{conf.lower()}_a_g", list(levels),
                             hint=f", or give {field_name}=None to leave the {conf} sweeps out")
        for ag in levels:
            for d in directions:
                plan = make_plan(osc, ag, freqs_hz, d, **sweep_options)
                plans.append(((conf, ag, d), plan))
    total = sum(p.freqs_hz.size for _, p in plans)
    done = run_tasks(sweep_task, [plan for _, plan in plans], scheduler=scheduler, workers=workers,
                     progress=progress, label=label, total=total,
                     budget=[plan.max_steps for _, plan in plans], on_error="finish")
    done.raise_first_error(lambda i: "the {} sweep at a_G {:g} g, {}".format(*plans[i][0]))
    sweeps = {key: sw for (key, _), sw in zip(plans, done.values) if sw is not None}
    interrupted = done.interrupted or bool(done.partial)
    ordered = {key: sweeps[key] for key, _ in plans if key in sweeps}
    # A Ctrl-C that came after the last step (while the pool was winding up) loses nothing: the
    # campaign is complete when every sweep ended by itself, whatever the interrupt
    complete = not interrupted or all(
        key in ordered and (ordered[key].steps_done == plan.freqs_hz.size or ordered[key].status != 0)
        for key, plan in plans)
    while True:  # (assembling is short and pure: a Ctrl-C meanwhile is held until it is done)
        try:
            result = CampaignResult(_dataset(ordered, plans, complete), ordered, complete)
            break
        except KeyboardInterrupt:
            interrupted = True
    if not complete:
        raise Interrupted(result, sum(sw.steps_done for sw in ordered.values()), total)
    return result


def _levels(system: Any) -> tuple:
    """A system's levels: how many each of its structures has (a single mass: one)."""
    return tuple(s.n_levels for s in structures_of(system)[0])


def _dataset(sweeps: dict, plans: list, complete: bool) -> "xr.Dataset":
    """The campaign as a Dataset: every column of the sweeps' tables on configuration, a_g, direction,
    freq_hz and level (a one-level system's without the level: one value per step), and ``ran``."""
    import xarray as xr

    confs = [c for c in CONFIGURATIONS if any(k[0] == c for k, _ in plans)]
    a_gs = sorted({k[1] for k, _ in plans})
    dirs = [d for d in DIRECTIONS if any(k[2] == d for k, _ in plans)]
    freqs = np.unique(np.concatenate([p.freqs_hz for _, p in plans]))
    levels = _levels(plans[0][1].oscillator)
    n_levels = sum(levels)
    shape = (len(confs), len(a_gs), len(dirs), freqs.size, n_levels)
    data = {c: np.zeros(shape, dtype=bool) if c in _BOOL_COLUMNS else np.full(shape, np.nan)
            for c in _DATA_COLUMNS}
    ran = np.zeros(shape[:4], dtype=bool)
    for (conf, ag, d), sw in sweeps.items():
        idx = (confs.index(conf), a_gs.index(ag), dirs.index(d))
        df = sw.to_dataframe().iloc[: sw.steps_done * n_levels]
        cols = np.searchsorted(freqs, sw.freqs_hz[: sw.steps_done])
        for c in data:
            data[c][idx + (cols,)] = df[c].to_numpy().reshape(-1, n_levels)
        ran[idx + (cols,)] = True
    dims = ("configuration", "a_g", "direction", "freq_hz", "level")
    names = [f"{b}:{q}" if len(levels) > 1 else str(q) for b, n in enumerate(levels) for q in range(n)]
    ds = xr.Dataset({**{c: (dims, v) for c, v in data.items()}, "ran": (dims[:4], ran)},
                    coords={"configuration": confs, "a_g": a_gs, "direction": dirs, "freq_hz": freqs,
                            "level": names})
    if n_levels == 1:  # (a single mass: one value per step)
        ds = ds.isel(level=0, drop=True)
    first = plans[0][1]
    ds = ds.assign_coords(nu=("freq_hz", freqs / first.f_ref_hz))
    ds["freq_hz"].attrs["units"] = "Hz"
    ds.attrs.update({"steady_mode": first.steady, "cycles": first.cycles,
                     "measure_cycles": first.measure_cycles, "f_ref_hz": first.f_ref_hz,
                     "omega_min_rad_s": first.omega_min_rad_s, "complete": int(complete),
                     "measurement": _measurement_attr(first.measurement, sweeps)})
    for conf in confs:
        ds.attrs[f"system_{conf}"] = next(p.oscillator for k, p in plans if k[0] == conf).to_toml_text()
    return ds


def _measurement_attr(chain: Any, sweeps: dict) -> str:
    """What the campaign's metrics are: "exact", the chain's description, or (a sweep interrupted
    while measuring kept its exact metrics) both said."""
    if chain is None:
        return "exact"
    exact = [key for key, sw in sweeps.items() if sw.measurement is None]
    if not exact:
        return chain.describe()
    return f"{chain.describe()}; exact for {len(exact)} interrupted sweep(s): " + ", ".join(
        f"{c} {a:g} {d}" for c, a, d in exact)
