"""``identify``: fit a model family's free numbers so that the simulated campaign matches
measured targets (weighted least squares, or a smooth count of the targets missed;
differential evolution, then local refinement).

One evaluation runs every sweep the targets need (``Targets.cases``) with the candidate
system and compares the per-sweep quantities (:func:`pounding.protocols.campaign.sweep_quantities`)
with the targets.  Candidates of one generation are evaluated on worker threads (the
compiled kernels release the GIL).  The free numbers are searched on ``[0, 1]`` scaled
from their bounds, logarithmically when a bound spans a decade or more.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .._checks import boolean, instance_of, integer, one_of, real
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from ..model import MeasurementChain, Oscillator, Structure
from .._runner import run_tasks, scheduler_kind, task_pool
from .._runner.progress import Progress, progress_reporter
from ..protocols.campaign import sweep_quantities
from ..protocols.sweep import check_sweep_options
from ..protocols.sweep import make_plan, paper_frequencies_hz, sweep
from ._scale import Scale as _Scale
from .family import ModelFamily, check_bounds
from .system_family import SystemFamily
from .measured import CUTOFF, apply_cutoff, split_cutoff
from .targets import Targets

# residual of a target the candidate cannot produce (NaN: no contact, failed run), in tolerances
MISSING_RESIDUAL = 10.0
DEFAULT_SWEEP = {"steady": "fixed", "cycles": 30, "measure_cycles": 5}
MAX_EVALUATIONS = 1_000_000  # campaign evaluations at most (each runs every sweep the targets need)
MAX_WORKERS = 1024
WITHIN_SLACK = 1e-9  # a target is met when |normalized residual| <= 1 + this (rounding)
LOSSES = ("squared", "misses")
MISSES_WITHIN = 0.9  # the "misses" loss is zero within this many tolerances (a margin below 1)


@dataclass(frozen=True, eq=False)
class Identification:
    """Result of :func:`pounding.identify`.

    Attributes
    ----------
    parameters : dict
        The fitted free numbers, ``name -> value`` (units in :mod:`~pounding.identification.family`).
    oscillator : Oscillator
        The fitted YBs system (``.without_bumpers()`` for NBs); ``to_toml`` writes it.
    residuals : pandas.DataFrame
        One row per target: ``configuration``, ``a_g``, ``direction``, ``quantity``,
        ``target``, ``model``, ``difference`` (model - target), ``allowed`` (the tolerance in
        the quantity's unit), ``normalized`` (difference / allowed, times the weight) and
        ``within`` (``|normalized| <= 1``, up to rounding).
    cost : float
        The minimised loss (``identify``'s ``loss``): for ``"squared"`` the sum of squared
        normalized residuals (a NaN model value counts as :data:`MISSING_RESIDUAL` tolerances).
    n_evaluations : int
        Campaign evaluations used.
    status, message : Status, str
        ``Status.SUCCESS``, and what was reached.
    complete : bool
        False for the ``partial`` of the :class:`~pounding.Interrupted` that Ctrl-C raises:
        the best candidate so far.
    family, bounds : ModelFamily, dict
        What was fitted.
    loss : str
        What was minimised (``identify``'s ``loss``).
    measurement : MeasurementChain or None
        The chain the metrics were measured through (with a fitted cutoff when
        ``measurement_cutoff_hz`` was free), or None: the exact metrics.

    Examples
    --------
    The printed system's isolator damping ``C_d`` fitted to the NBs resonant amplification at
    a_G = 0.05 g (a tiny search over five sweep steps):

    >>> import pounding
    >>> damped = pounding.presets.paper_damped()
    >>> fixed = pounding.ModelFamily(500.0).values_of(damped)
    >>> del fixed["isolator_damping"]  # fitted; every other number as printed
    >>> targets = pounding.Targets.from_records([{"configuration": "NBs",
    ...                                           "a_g": 0.05, "quantity": "alpha",
    ...                                           "value": 2.99}])
    >>> fit = pounding.identify(targets, pounding.ModelFamily(500.0, fixed=fixed),
    ...                         {"isolator_damping": (100.0, 5000.0)},
    ...                         freqs_hz=[0.9, 1.0, 1.1, 1.2, 1.3],
    ...                         popsize=4, maxiter=3)
    >>> fit.status.name, fit.n_within
    ('SUCCESS', 1)
    >>> round(fit.oscillator.isolator.damping_n_s_m)  # N s/m
    548
    >>> # read back with pounding.Oscillator.from_toml
    >>> fit.to_toml("fitted.toml").name
    'fitted.toml'
    """

    parameters: dict[str, float]
    oscillator: Oscillator
    residuals: pd.DataFrame = field(repr=False)
    cost: float
    n_evaluations: int
    status: Status
    message: str
    family: ModelFamily = field(repr=False)
    bounds: dict[str, tuple[float, float]] = field(repr=False)
    complete: bool = True
    loss: str = "squared"
    measurement: MeasurementChain | None = None

    @property
    def success(self) -> bool:
        """True when the fit finished normally (``status`` ``SUCCESS``), met targets or not."""
        return self.status == Status.SUCCESS

    @property
    def n_within(self) -> int:
        """How many targets are met."""
        return int(self.residuals["within"].sum())

    def to_xarray(self) -> Any:
        """The residual table of :meth:`to_dataframe` as a Dataset along ``target``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "target", {"message": self.message})

    def to_dataframe(self) -> pd.DataFrame:
        """The residual table (a copy of :attr:`residuals`)."""
        return self.residuals.copy()

    def parameter_table(self) -> pd.DataFrame:
        """``name``, ``value``, ``low``, ``high`` and ``at_bound`` (within 0.1 % of the searched
        range, logarithmic for bounds a decade or more apart) per free number."""
        units = _Scale(self.bounds).units(self.parameters)  # the searched scale (log for wide bounds)
        rows = []
        for (name, value), u in zip(self.parameters.items(), units):
            low, high = self.bounds[name]
            rows.append({"name": name, "value": value, "low": low, "high": high,
                         "at_bound": min(u, 1.0 - u) <= 1e-3})
        return pd.DataFrame(rows)

    def to_toml(self, path: str | Path) -> Path:
        """Write the fitted system (YBs) to TOML (read back with ``Oscillator.from_toml``).

        A ``[meta]`` table says how it was made: ``partial = true`` for an interrupted fit
        (the best candidate so far), the loss and its cost, the evaluations and the targets met.
        """
        meta = {"written_by": "pounding identify", "partial": not self.complete, "loss": self.loss,
                "cost": float(self.cost),
                "evaluations": int(self.n_evaluations),
                "targets_met": f"{self.n_within} of {len(self.residuals)}",
                "measurement": "exact" if self.measurement is None else self.measurement.describe()}
        return self.oscillator.to_toml(path, meta=meta)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Normalized residual per target against the +-1 band; see
        :func:`pounding.plots.plot_identification`.

        Returns its Figure.
        """
        from ..plots import plot_identification, figure_of

        return figure_of(plot_identification(self, ax=ax, **kwargs), ax)


@renamed_keyword("oscillator", "system")
def evaluate(system: Oscillator, targets: Targets, *, freqs_hz: Any = None,
             workers: int | None = None, progress: Progress = False, label: str = "targets",
             **sweep_options: Any) -> pd.DataFrame:
    """Run the sweeps the targets need with ``system`` (YBs; NBs is it without bumpers)
    and return the residual table of :class:`Identification`.

    The sweeps run in parallel on ``workers`` threads (default: every core), with a progress bar
    (``progress``, described by ``label``).  ``sweep_options`` are :func:`pounding.sweep`'s (default:
    fixed 30 cycles, last 5 measured).  Ctrl-C raises :class:`~pounding.Interrupted` (no table).
    """
    from ..protocols.campaign import sweep_task

    instance_of("system", system, (Oscillator, Structure),
                "pounding.Oscillator or pounding.Structure (a rig: one mass, or a structure whose base is "
                "the measured mass)")
    options = {**DEFAULT_SWEEP, **sweep_options}
    cases = list(targets.cases)
    plans = [make_plan(system if conf == "YBs" else bare(system), a_g, freqs_hz,
                       direction, **options) for conf, a_g, direction in cases]
    ran = run_tasks(sweep_task, plans, workers=workers, progress=progress, label=label,
                    total=sum(p.freqs_hz.size for p in plans), budget=[p.max_steps for p in plans],
                    on_error="stop")
    ran.raise_first_error(lambda i: "the {} sweep at a_G {:g} g, {}".format(*cases[i]))
    if ran.interrupted or any(v is None for v in ran.values):
        raise Interrupted(None, sum(v is not None for v in ran.values), len(plans), "sweeps")
    model = {(c, float(a), d): sweep_quantities(sw) for (c, a, d), sw in zip(cases, ran.values)}
    return _residual_table(targets, model)


def identify(targets: Targets, family: ModelFamily, bounds: dict[str, Any], *, seed: int = 0,
             workers: int | None = None, scheduler: Any = None, freqs_hz: Any = None, popsize: int = 10,
             maxiter: int = 30, refine: bool = True, x0: dict[str, float] | None = None,
             progress: Progress = False, loss: str = "squared", **sweep_options: Any) -> Identification:
    """Fit the free numbers of ``family`` to measured ``targets``.

    Minimises a loss of the normalized residuals (see :class:`~pounding.Targets`):
    differential evolution over the bounds (global, reproducible with ``seed``), then
    trust-region least squares from its best point (``refine``).

    Parameters
    ----------
    targets : Targets
        E.g. :func:`pounding.paper_targets` or ``Targets.from_toml``.
    family : ModelFamily or SystemFamily
        Structure and fixed numbers; or a structure of several masses whose numbers are named as in
        its file (``walls[0].stand.mass_kg``), the targets its base's (level 0).
    bounds : dict
        ``name -> (low, high)`` for every free number (low < high, finite); with
        ``"measurement_cutoff_hz"``, the low-pass corner (Hz) of the accelerometers of the
        ``measurement`` chain (default: a 4th-order zero-phase low-pass at 1 kHz) is fitted too
        (:mod:`pounding.identification.measured`).
    seed : int
        Seed of the global stage; the same seed gives the same result.
    workers : int, optional
        Threads or processes evaluating candidates (default: the machine's cores).
    scheduler : str or dask.distributed.Client, optional
        Where a generation's candidates run: ``"threads"`` (default), ``"serial"``,
        ``"processes"``, ``"local"`` (a Dask ``LocalCluster``), a Dask scheduler's address or a
        ``Client``; the workers start once for the whole fit.  Every scheduler gives the same fit.
    freqs_hz : array_like, optional
        Sweep steps (default the paper's 0.5 to 5.0 Hz by 0.1).
    popsize, maxiter : int
        Differential evolution's population per free number and generations.
    refine : bool
        Polish the best candidate with ``scipy.optimize.least_squares``.
    x0 : dict, optional
        A starting guess for every free number (joins the first population).
    progress : bool or callable
        True: a progress bar over the generations.
    loss : {"squared", "misses"}
        ``"squared"``: the sum of squared normalized residuals ``r`` (least squares).
        ``"misses"``: counts the targets missed, smoothly: each residual costs
        ``h^2 / (1 + h^2)`` with ``h = max(|r| - 0.9, 0)`` its excess over 90 % of the
        tolerance: nothing within 0.9 tolerances, 0.01 just outside the tolerance, 1/2 at 1.9
        and at most 1 far off.  A far miss costs about as much as any other, so the fit spends
        no effort on targets out of reach (e.g. inconsistent ones) and meets more targets than
        least squares, which trades a met target for a smaller large miss.  It is smooth, not
        a step: a target just outside its tolerance costs little, and may be left there.
    **sweep_options
        :func:`pounding.sweep`'s options (default: fixed 30 cycles, last 5 measured).

    Returns
    -------
    Identification
        The fitted free numbers, the fitted system and one residual row per target.

    Raises
    ------
    InputError
        Bad targets, family or bounds (names the field and the fix).
    Interrupted
        On Ctrl-C; ``partial`` is the Identification of the best candidate so far.

    Examples
    --------
    Which isolator damping ``C_d`` (N s/m) gives the printed system the measured NBs resonant
    amplification alpha = 2.99 at a_G = 0.05 g? One free number, named by its path in the system's
    file, one target, five sweep steps and a tiny search (a real fit uses the defaults and many
    targets: docs/calibration.md):

    >>> import pounding
    >>> family = pounding.SystemFamily(pounding.presets.paper_damped())
    >>> alpha = pounding.Targets.from_records([{"configuration": "NBs",
    ...                                         "a_g": 0.05, "quantity": "alpha",
    ...                                         "value": 2.99}])
    >>> fit = pounding.identify(alpha, family,
    ...                         {"isolator.damping_n_s_m": (100.0, 5000.0)},
    ...                         freqs_hz=[0.9, 1.0, 1.1, 1.2, 1.3],
    ...                         popsize=4, maxiter=3)
    >>> round(fit.parameters["isolator.damping_n_s_m"]), fit.n_within
    (548, 1)
    """
    instance_of("targets", targets, Targets, "pounding.Targets (paper_targets() or Targets.from_toml)")
    instance_of("family", family, (ModelFamily, SystemFamily),
                "pounding.ModelFamily, or pounding.SystemFamily (any system's numbers by their paths)")
    check_sweep_options(sweep_options, also="identify's own")
    if isinstance(family, SystemFamily) and isinstance(bounds, dict) and CUTOFF in bounds:
        raise InputError(Problem.WRONG_MODE, f"bounds.{CUTOFF}", bounds[CUTOFF], mode="a ModelFamily's fit",
                         fix="leave it out (a SystemFamily's metrics are its exact ones: no measurement "
                             "chain), or fit a single mass's cutoff with a pounding.ModelFamily")
    bounds, cutoff, sweep_options = split_cutoff(bounds, sweep_options)
    if cutoff is not None and not bounds:
        family.free_names({})  # (every number fixed: only the cutoff is fitted)
    else:
        bounds = check_bounds(family, bounds)
    if cutoff is not None:
        bounds = {**bounds, CUTOFF: cutoff}
    names = tuple(bounds)
    n_workers = integer("workers", (os.cpu_count() or 1) if workers is None else workers, 1, MAX_WORKERS)
    scheduler_kind(scheduler)  # (a wrong one refused before any work)
    popsize = integer("popsize", popsize, 2, MAX_EVALUATIONS)
    maxiter = integer("maxiter", maxiter, 0, MAX_EVALUATIONS)
    seed = integer("seed", seed, 0, 2**32 - 1)
    refine = boolean("refine", refine)
    loss = one_of("loss", loss, LOSSES)
    evaluations = (maxiter + 1) * popsize * len(names) + (40 * len(names) if refine else 0)
    if evaluations > MAX_EVALUATIONS:
        raise InputError(Problem.TOO_MUCH_WORK, "maxiter", maxiter, estimate=f"{evaluations:.3g}",
                         unit=f"evaluations ((maxiter + 1) x popsize x {len(names)} free numbers, each "
                              "running "
                              "the targets' sweeps)", budget=f"{MAX_EVALUATIONS:.3g}",
                         fix="lower maxiter or popsize (30 and 10 are the defaults)")
    options = {**DEFAULT_SWEEP, **sweep_options}
    scale = _Scale(bounds)
    cases_freqs = paper_frequencies_hz() if freqs_hz is None else freqs_hz
    if x0 is not None:
        instance_of("x0", x0, dict, "dict name -> value")
        unknown = sorted(set(x0) ^ set(names))
        if unknown:
            raise InputError(Problem.UNKNOWN_KEY if unknown[0] in x0 else Problem.MISSING_KEY,
                             f"x0.{unknown[0]}", x0.get(unknown[0]), choices=", ".join(names))
        for k in names:
            low, high = bounds[k]
            if not low <= real(f"x0.{k}", x0[k]) <= high:
                raise InputError(Problem.OUT_OF_RANGE, f"x0.{k}", x0[k],
                                 range=f"the bounds [{low:g}, {high:g}]", hint="")
    try:  # bad sweep options fail here, not in a worker
        middle, probe_options = apply_cutoff(scale.values(np.full(len(names), 0.5)), options)
        probe = family.oscillator(middle)
    except InputError:
        probe = None  # the middle of the bounds is no valid system (breakpoints out of order)
    if probe is not None:
        _model_values(probe, targets, cases_freqs, probe_options, check_only=True)
    best: dict[str, Any] = {"cost": math.inf, "u": None, "n": 0, "valid": 0, "error": None}
    problem = (family, targets, cases_freqs, options, loss, scale)  # (what a candidate's task carries)

    def keep(u: np.ndarray, r: np.ndarray, valid: bool, error: Any) -> float:
        """Count a candidate's evaluation and keep the best (ties to the smaller u: the result does
        not depend on where or in which order the candidates ran)."""
        cost = float(r @ r)
        best["n"] += 1
        best["valid"] += valid
        if error is not None:
            best["error"] = error
        if cost < best["cost"] or (cost == best["cost"] and tuple(u) < tuple(best["u"])):
            best["cost"], best["u"] = cost, np.array(u, dtype=float)
        return cost

    def residuals(u: np.ndarray) -> np.ndarray:  # (one candidate, here: least_squares' own steps)
        r, valid, error = _candidate((problem, u), None)
        keep(u, r, valid, error)
        return r

    def cost(u: np.ndarray) -> float:
        r = residuals(u)
        return float(r @ r)

    init: Any = "latinhypercube"
    if x0 is not None:
        rng = np.random.default_rng(seed)
        pop = rng.uniform(size=(popsize * len(names), len(names)))
        pop[0] = scale.units({k: x0[k] for k in names})
        init = pop
    from scipy.optimize import differential_evolution, least_squares  # (0.3 s of import: here)

    interrupted = False
    with progress_reporter(progress, maxiter + int(refine), "identify") as advance, \
            task_pool(scheduler, n_workers) as pool:

        def generation(_func: Any, population: Any) -> list[float]:
            """scipy's ``workers``: a generation's costs, its candidates run on the shared runner
            (``_func``, scipy's wrapper of the cost, is not needed: the task computes it)."""
            us = [np.array(u, dtype=float) for u in population]
            ran = run_tasks(_candidate, [(problem, u) for u in us], pool=pool, on_error="stop")
            ran.raise_first_error(lambda i: f"the candidate {scale.values(us[i])}")
            if not ran.complete:
                raise KeyboardInterrupt
            return [keep(u, *value) for u, value in zip(us, ran.values)]

        try:
            if maxiter > 0:
                differential_evolution(
                    cost, [(0.0, 1.0)] * len(names), seed=seed,
                    popsize=popsize, maxiter=maxiter, init=init, polish=False, tol=0.0, updating="deferred",
                    workers=generation, callback=lambda *a, **k: advance(1))
            else:
                residuals(scale.units({k: (x0 or {}).get(k, 0.5 * sum(bounds[k])) for k in names}))
            if refine:
                least_squares(residuals, np.clip(best["u"], 0.0, 1.0), bounds=(0.0, 1.0), diff_step=1e-3,
                              x_scale=1.0, xtol=1e-10, ftol=1e-10, max_nfev=40 * len(names))
                advance(1)
        except KeyboardInterrupt:
            interrupted = True
    if best["u"] is None:
        raise Interrupted(None, 0, None, "evaluations")
    if best["valid"] == 0 and best["error"] is not None:
        raise best["error"]  # no candidate made a valid system: the family's fixed numbers or bounds
    params = scale.values(best["u"])
    family_params, final_options = apply_cutoff(params, options)
    osc = family.oscillator(family_params)
    table = evaluate(osc, targets, freqs_hz=cases_freqs, **final_options)
    n_ok = int(table["within"].sum())
    message = (f"{n_ok} of {len(table)} targets within tolerance after {best['n']} evaluations; "
               f"cost {best['cost']:.4g}.")
    if interrupted:
        message = "Interrupted: the best candidate so far. " + message
    result = Identification(params, osc, table, best["cost"], best["n"], Status.SUCCESS, message, family,
                            bounds, complete=not interrupted, loss=loss,
                            measurement=final_options.get("measurement"))
    if interrupted:
        raise Interrupted(result, best["n"], None, "evaluations")
    return result


def _candidate(task: tuple, ctx: Any) -> tuple[np.ndarray, bool, Any]:
    """One candidate's residuals, as a task of the shared runner (any process): ``task`` is
    ``((family, targets, freqs, sweep options, loss, scale), u)``; returns ``(residuals, whether
    it made a valid system, the InputError of one that did not)``."""
    (family, targets, freqs, options, loss, scale), u = task
    values, options = apply_cutoff(scale.values(u), options)
    error = None
    try:
        model = _model_values(family.oscillator(values), targets, freqs, options)
    except InputError as exc:  # no valid system (e.g. breakpoints out of order): all missing
        model, error = None, exc
    return _loss_residuals(_normalized(targets, model), loss), model is not None, error


def _loss_residuals(r: np.ndarray, loss: str) -> np.ndarray:
    """Residuals whose sum of squares is the loss (so ``least_squares`` refines the same loss)."""
    if loss == "squared":
        return r
    h = np.maximum(np.abs(r) - MISSES_WITHIN, 0.0)  # the excess over 90 % of the tolerance
    return np.sign(r) * h / np.sqrt(1.0 + h * h)


def bare(system: Any) -> Any:
    """The NBs configuration of a system: one mass without its bumpers, a structure without its walls."""
    return system.without_bumpers()


def _model_values(oscillator: Any, targets: Targets, freqs_hz: Any, options: dict,
                  check_only: bool = False) -> dict:
    """``(configuration, a_g, direction) -> sweep_quantities`` for every case of the targets."""
    out = {}
    for conf, a_g, direction in targets.cases:
        osc = oscillator if conf == "YBs" else bare(oscillator)
        if check_only:
            make_plan(osc, a_g, freqs_hz, direction, **options)
            continue
        out[(conf, a_g, direction)] = sweep_quantities(sweep(osc, a_g, freqs_hz, direction, **options))
    return out


def _model_column(targets: Targets, model: dict | None) -> np.ndarray:
    t = targets.data
    if model is None:
        return np.full(len(t), np.nan)
    delta = targets.eta_gap_total_m  # eta measured over the rig's nominal gap: the model's excursion over it
    return np.array([model[(c, float(a), d)]["excursion_max_m"] / delta
                     if q == "eta" and c == "YBs" and delta is not None
                     else model[(c, float(a), d)][q] for c, a, d, q in
                     t[["configuration", "a_g", "direction", "quantity"]].itertuples(index=False)],
                    dtype=float)


def _normalized(targets: Targets, model: dict | None) -> np.ndarray:
    r = (_model_column(targets, model) - targets.data["value"].to_numpy()) / targets.allowed
    r = r * targets.data["weight"].to_numpy()
    return np.where(np.isfinite(r), r, MISSING_RESIDUAL)


def _residual_table(targets: Targets, model: dict) -> pd.DataFrame:
    t = targets.data
    values = _model_column(targets, model)
    out = t[["configuration", "a_g", "direction", "quantity"]].copy()
    out["target"] = t["value"]
    out["model"] = values
    out["difference"] = values - t["value"].to_numpy()
    out["allowed"] = targets.allowed
    out["normalized"] = out["difference"] / out["allowed"] * t["weight"]
    # (1 + 1e-9: a nu_R one 0.1 step off is (1.1 - 1.0) / 0.1 = 1.0000000000000009, and met)
    out["within"] = out["normalized"].abs() <= 1.0 + WITHIN_SLACK
    return out.reset_index(drop=True)

