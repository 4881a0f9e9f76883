"""Pounding spectra: the isolated mass under records, with bumpers behind a gap and without, over
isolation periods and gaps; a building in its moat, on a line or in plan, likewise.

For each record, period ``T`` and gap ``g`` (each side), the oscillator is the mass on an isolator
of period ``T`` (linear, or a given isolator's shape scaled to that initial period) with the damping
ratio given, and the bumpers at ``g`` on both sides; the same oscillator without bumpers is the
reference.  Each is one exact run of the engine over the record.  The records run on the
shared task runner (threads by default: the compiled kernels release the GIL; processes or Dask).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from .._checks import float_array, instance_of, integer, one_or_more, positive
from .._errors import InputError, Interrupted, Problem, Status
from ..excitation import Record, RecordPair
from ..excitation.spectrum import check_records, damping_ratio_value, periods_array
from .._units import GRAVITY_M_S2
from ..model import Bumpers, FrictionIsolator, Isolator, Oscillator, Structure
from ..model.plan import PlanBuilding
from .._runner import Context, run_tasks
from .._runner.progress import Progress
from .pounding_spectrum_result import PLAN_QUANTITIES, QUANTITIES, STRUCTURE_QUANTITIES, PoundingSpectrum

MAX_RUNS = 2_000_000  # records x periods x (gaps + 1): beyond, refused (hours of work)


def _scaled(iso: Isolator, factor: float, damping_n_s_m: float) -> Isolator:
    """``iso`` with every force of its law times ``factor``: its slopes and its Bouc-Wen spring's stiffness
    (its ``z`` is a function of the displacement alone, its yield displacement kept), its breakpoints and
    hysteresis kept; its dashpot ``damping_n_s_m``."""
    bw = iso.bouc_wen
    return replace(iso, slopes_n_m=tuple(k * factor for k in iso.slopes_n_m), damping_n_s_m=damping_n_s_m,
                   bouc_wen=None if bw is None else replace(bw, stiffness_n_m=bw.stiffness_n_m * factor))


def _isolator(template: Isolator | FrictionIsolator | None, mass_kg: float, period_s: float,
              zeta: float) -> Isolator | FrictionIsolator:
    """The isolator of initial period ``period_s``: linear, or ``template``'s shape scaled to it (its law's
    forces times one factor, a Bouc-Wen spring's with them; a friction pendulum's radius ``g (T / 2 pi)^2``,
    its friction kept)."""
    k = mass_kg * (2.0 * math.pi / period_s) ** 2
    c = 2.0 * zeta * math.sqrt(k * mass_kg)
    if template is None:
        return Isolator((k,), (), "elastic", c)
    if isinstance(template, FrictionIsolator):
        return replace(template, radius_m=GRAVITY_M_S2 * (period_s / (2.0 * math.pi)) ** 2, damping_n_s_m=c,
                       weight_n=None, weight_carried=False)
    return _scaled(template, k / template.initial_stiffness_n_m, c)


def superstructure_at(structure: Structure, period_s: float) -> Structure:
    """``structure`` with its storeys' stiffnesses (every slope) scaled so that its first fixed-base period
    is ``period_s``, their dashpots by the square root (each storey's damping ratio kept)."""
    factor = (structure.modes(fixed_base=True).periods_s[0] / period_s) ** 2
    root = math.sqrt(factor)
    storeys = tuple(replace(s, stiffness_n_m=s.stiffness_n_m * factor, damping_n_s_m=s.damping_n_s_m * root,
                            slopes_after_n_m=tuple(k * factor for k in s.slopes_after_n_m))
                    for s in structure.storeys)
    return replace(structure, storeys=storeys)


def _sliding(building: PlanBuilding) -> bool:
    """Whether a building in plan stands on friction pendulums alone (False: on no friction bearing; an
    InputError for a mixture or a flat slider, which have no one period to scale)."""
    friction = [b.is_friction for b in building.bearings]
    if not any(friction):
        return False
    for q, b in enumerate(building.bearings):
        if not b.is_friction or b.isolator.radius_m is None:
            raise InputError(Problem.BAD_STATE, f"structure.bearings[{q}].isolator", b.isolator,
                             why="is a flat slider: it has no period to scale" if b.is_friction else
                                 "is a rubber bearing beside friction bearings (a spectrum scales a "
                                 "friction pendulum's radius and a rubber bearing's stiffness: a mixture has "
                                 "no one isolated period)",
                             fix="give every bearing a friction pendulum (radius_m), or none a friction "
                                 "isolator")
    return True


def isolated_period_s(building: PlanBuilding) -> float:
    """A building in plan's isolated period along x, its floors moving as one rigid body: ``2 pi sqrt(sum m
    / sum k_x)``, s, on its bearings' initial stiffnesses (a Bouc-Wen spring's ``a k`` with its backbone's
    first slope), or on friction pendulums their restoring stiffnesses ``W / R`` (the sliding period)."""
    instance_of("building", building, PlanBuilding, "pounding.PlanBuilding")
    mass = sum(f.mass_kg for f in building.floors)
    if _sliding(building):
        stiffness = sum(b.isolator.restoring_stiffness_n_m for b in building.bearings)
    else:
        stiffness = sum(b.isolator.initial_stiffness_n_m for b in building.bearings)
    return 2.0 * math.pi * math.sqrt(mass / stiffness)


def bearings_at(building: PlanBuilding, period_s: float) -> PlanBuilding:
    """``building`` with its bearings' stiffnesses (every slope, along x and y, and a Bouc-Wen spring's)
    scaled so that its isolated period (:func:`isolated_period_s`) is ``period_s``, their dashpots by the
    square root (their damping ratios kept), their breakpoints, yield displacements and hysteresis kept; on
    friction pendulums their radii scaled instead, their friction and pre-slip kept."""
    period = positive("period_s", period_s, "s")
    factor = (isolated_period_s(building) / period) ** 2
    root = math.sqrt(factor)

    def scaled(iso: Any) -> Any:
        if iso is None:
            return None
        if isinstance(iso, FrictionIsolator):
            return replace(iso, radius_m=iso.radius_m / factor, damping_n_s_m=iso.damping_n_s_m * root)
        return _scaled(iso, factor, iso.damping_n_s_m * root)

    try:
        return replace(building, bearings=tuple(replace(b, isolator=scaled(b.isolator),
                                                        isolator_y=scaled(b.isolator_y))
                                                for b in building.bearings))
    except InputError as exc:  # (a period the bearings cannot have: the period named, the law's words kept)
        raise InputError(Problem.BAD_STATE, "period_s", period_s,
                         why=f"is beyond what the bearings can be scaled to (it makes {exc.field} "
                             f"{exc.value!r})",
                         fix="give a period the bearings can have") from None


def _systems(task: tuple, period: float) -> list:
    """A task's systems at one period: without bumpers (walls, moat), then with them at each gap (a
    building's walls each with its own laws, a building in plan's moat its four gaps or a ring's, or all with
    ``bumper``'s when one was given)."""
    _, _, bumpers, zeta, mass_kg, template, _, structure, override = task
    if isinstance(structure, PlanBuilding):  # (``bumpers``: its moat at each gap)
        building = bearings_at(structure, period)
        return [building.moat_out_of_reach()] + [replace(building, moat=moat) for moat in bumpers]
    if structure is not None:
        building = superstructure_at(structure, period)

        def at(w: Any, b: Bumpers) -> Any:
            laws = {"law": override, "law_right": None} if override is not None else {}
            return replace(w, gap_left_m=b.gap_left_m, gap_right_m=b.gap_right_m, **laws)

        return [replace(building, walls=())] + [
            replace(building, walls=tuple(at(w, b) for w in building.walls)) for b in bumpers]
    iso = _isolator(template, mass_kg, period, zeta)
    return [Oscillator(mass_kg, iso, b) for b in (None, *bumpers)]


def _one_record(task: tuple, ctx: Context) -> tuple[np.ndarray, np.ndarray]:
    """One record's free (periods, q) and pounding (periods, gaps, q) peaks; NaN where not run.
    ``task``: (record, periods, bumpers, damping ratio, mass kg, isolator template, max_steps, structure or
    None, the law every wall takes or None: their own); a structure's peaks are ``STRUCTURE_QUANTITIES``,
    the oscillator's ``QUANTITIES``."""
    from ..engine.simulate import peaks

    rec, periods, bumpers, _, _, _, max_steps, structure, _ = task
    names = _names(structure)
    free = np.full((periods.size, len(names)), np.nan)
    hit = np.full((periods.size, len(bumpers), len(names)), np.nan)
    duration = float(rec.t[-1])
    try:
        for i, period in enumerate(periods):
            for j, system in enumerate(_systems(task, float(period)), start=-1):
                if ctx.stopped():  # (a stop was asked for: what is done is kept)
                    raise Interrupted((free, hit), i, periods.size, "periods")
                try:
                    q = peaks(system, rec, duration, max_steps=max_steps)
                    row = tuple(q[k] for k in names)
                except InputError as exc:  # (refused up front: over its budget; the others go on)
                    if exc.problem not in (Problem.OVER_BUDGET, Problem.TOO_MUCH_WORK):
                        raise
                    row = tuple(float(Status.BUDGET) if k == "status" else math.nan for k in names)
                if j < 0:
                    free[i] = row
                else:
                    hit[i, j] = row
                ctx.advance(1)
    except KeyboardInterrupt as stop:  # (a progress callback's Ctrl-C, or a stop: keep what is done)
        if isinstance(stop, Interrupted):
            raise
        raise Interrupted((free, hit), 0, periods.size, "periods") from None
    return free, hit


def pounding_spectrum(records: Record | RecordPair | Sequence[Record] | Sequence[RecordPair], periods_s: Any,
                      *, gaps_m: Any, damping_ratio: float = 0.05, mass_kg: float = 500.0, bumper: Any = None,
                      isolator: Isolator | FrictionIsolator | None = None,
                      structure: Structure | PlanBuilding | None = None,
                      workers: int | None = None, scheduler: Any = None, progress: Progress = False,
                      max_steps: int = 10_000_000) -> PoundingSpectrum:
    """Peak responses of the isolated mass with bumpers and without, over records, periods and gaps; or of
    a building in its moat over its superstructure's period and the moat's gap; or of a building in plan
    over its isolated period and its moat's gap, under pairs of components.

    Parameters
    ----------
    records : Record, RecordPair or a sequence of either
        E.g. ``pounding.records.fema_p695("far_field")``; pairs (``fema_p695_pairs``) for a building in
        plan, which takes both components in its axes (one record: along x).
    periods_s : array_like, shape (p,)
        Isolation periods (s), > 0 and increasing: the isolator's initial period.
    gaps_m : array_like, shape (q,)
        Gaps (m) between the mass at rest and each bumper (the same both sides), > 0, increasing.
    damping_ratio : float
        The isolator's viscous damping, a fraction of critical at its initial stiffness, in [0, 1).
    mass_kg : float
        The isolated mass, kg (the spectra scale with it only through the bumper's stiffness).
    bumper : contact law, optional
        The bumpers' law (e.g. ``pounding.KelvinVoigt(1.46e6, 400.0)``); default the paper's
        (``presets.paper_damped()``).
    isolator : Isolator or FrictionIsolator, optional
        A nonlinear isolator's shape: its slopes (and a Bouc-Wen spring's stiffness) scaled by one
        factor so that its initial stiffness (the first slope, plus the spring's ``a k``) is ``m (2 pi /
        T)^2`` at each period, its breakpoints, yield displacement and hysteresis kept, its damping set by
        ``damping_ratio``.  Default: linear.  A friction pendulum's radius is
        the period's, ``g (T / 2 pi)^2``, its friction kept (``damping_ratio`` 0 for none besides it; a
        flat slider has no period: refused).
    structure : Structure, optional
        A building with its walls (a moat wall at its base, stops at floors): ``periods_s`` are then its
        superstructure's first fixed-base period (its storeys' stiffnesses scaled to it, their dashpots by
        the square root, the isolator kept), and every wall stands at each gap on both sides, with its own
        law (or ``bumper``); without walls is the reference.  Its peaks are ``STRUCTURE_QUANTITIES``:
        ``disp_max_m`` the base's (the moat's demand), ``acc_max_g`` the largest over the floors,
        ``top_acc_max_g``, ``drift_ratio_max``, the impacts.  ``damping_ratio``, ``mass_kg`` and
        ``isolator`` are the single mass's: left at their defaults.  Or a building in plan with its moat
        (:class:`pounding.PlanBuilding`): ``periods_s`` are then its isolated period on its bearings'
        initial stiffnesses, its floors rigid (:func:`isolated_period_s`; every bearing's slopes and
        Bouc-Wen spring scaled to it, its dashpot by the square root, :func:`bearings_at`; on friction
        pendulums their sliding period, their radii scaled), and its moat
        stands at each gap on its four sides (a ring: its one gap); its peaks are ``PLAN_QUANTITIES``: a
        building's, ``disp_max_m`` its largest bearing displacement in plan, ``theta_max_rad``,
        ``clearance_min_m`` (the smallest to a wall) and ``moat_demand_m`` (its floor's corners' largest
        displacement towards a wall, or a ring's demand; without the moat, or its ring out of reach,
        :meth:`PlanBuilding.moat_out_of_reach`, the gap it would need).
    workers : int, optional
        Worker threads or processes (default: every core).
    scheduler : str or dask.distributed.Client, optional
        Where the records run: ``"threads"`` (default), ``"serial"``, ``"processes"``, ``"local"``
        (a Dask ``LocalCluster``), a Dask scheduler's address (``"tcp://host:8786"``) or a ``Client``.
        Every scheduler gives the same spectrum.
    progress : bool or callable
        True: a progress bar over the runs; a callable gets the number of runs finished (on
        processes and Dask, as each record ends).
    max_steps : int
        Each run's work budget (see :func:`pounding.simulate`).

    Returns
    -------
    PoundingSpectrum
        ``.data`` (dims ``record``, ``period_s``, ``gap_m``), ``.summary()`` (median and 16/84 %
        over the records), ``.to_dataframe()``, ``.plot()``, ``.to_netcdf()``.

    Raises
    ------
    Interrupted
        On Ctrl-C, with ``.partial`` the spectrum of what finished (NaN elsewhere).

    Examples
    --------
    El Centro scaled to 0.3 g, isolation periods of 1 and 2 s, gaps of 20 and 50 mm each side:

    >>> import pounding
    >>> quake = pounding.records.el_centro().scaled(pga_g=0.3)
    >>> ps = pounding.pounding_spectrum([quake], [1.0, 2.0], gaps_m=[0.02, 0.05],
    ...                                 damping_ratio=0.05)
    >>> print(ps.data["impacts"].isel(record=0).to_pandas())
    gap_m     0.02  0.05
    period_s
    1.0       36.0   9.0
    2.0       60.0  22.0
    >>> # no bumpers, m
    >>> print(ps.data["disp_max_free_m"].isel(record=0).round(3).to_pandas())
    period_s
    1.0    0.106
    2.0    0.129
    Name: disp_max_free_m, dtype: float64
    """
    from ..presets import paper_damped

    in_plan = isinstance(structure, PlanBuilding)
    recs = (one_or_more("records", records, (Record, RecordPair), "pounding.Record or pounding.RecordPair")
            if in_plan else check_records(records))
    periods = periods_array(periods_s)
    if (periods <= 0.0).any():
        raise InputError(Problem.NOT_POSITIVE, "periods_s", periods.tolist()[:6], unit="s")
    gaps = float_array("gaps_m", gaps_m)
    if (gaps <= 0.0).any():
        raise InputError(Problem.NOT_POSITIVE, "gaps_m", gaps.tolist()[:6], unit="m")
    if gaps.size > 1 and (np.diff(gaps) <= 0.0).any():
        raise InputError(Problem.NOT_INCREASING, "gaps_m", gaps.tolist()[:6])
    zeta = damping_ratio_value(damping_ratio)
    mass_kg = positive("mass_kg", mass_kg, "kg")
    if structure is not None:
        _check_structure(structure, isolator, mass_kg, zeta)
    law = (paper_damped().bumpers.law if structure is None else structure.moat.law if in_plan
           else structure.walls[0].law) if bumper is None else bumper
    # (checked here, warned once, not in a worker; a building in plan's moat at each gap, 4 sides or a ring)
    bumpers = ([type(structure.moat)(float(g), law, structure.moat.level) for g in gaps] if in_plan
               else [Bumpers(float(g), float(g), law) for g in gaps])
    if isolator is not None:
        instance_of("isolator", isolator, (Isolator, FrictionIsolator),
                    "pounding.Isolator, pounding.FrictionIsolator or None (linear)")
        if isinstance(isolator, FrictionIsolator) and isolator.radius_m is None:
            raise InputError(Problem.BAD_STATE, "isolator", isolator,
                             why="is a flat slider: it has no period",
                             fix="give a friction pendulum (its radius_m is then each period's)")
    runs = len(recs) * periods.size * (gaps.size + 1)
    if runs > MAX_RUNS:
        raise InputError(Problem.TOO_MUCH_WORK, "periods_s",
                         f"{len(recs)} records x {periods.size} periods x "
                         f"{gaps.size + 1} systems", estimate=f"{runs:.3g}", unit="runs",
                         budget=f"{MAX_RUNS:.3g}", fix="fewer records, periods or gaps")
    max_steps = integer("max_steps", max_steps, 1)
    tasks = [(r, periods, bumpers, zeta, mass_kg, isolator, max_steps, structure, bumper) for r in recs]
    if structure is not None:  # (every system refused here, named, before any work)
        for period in periods:
            _systems(tasks[0], float(period))
    done = run_tasks(_one_record, tasks,
                     scheduler=scheduler, workers=workers, progress=progress, label="pounding spectrum",
                     total=runs)
    done.raise_first_error(lambda i: f"record {i} ({recs[i].name or 'unnamed'})")
    names = _names(structure)
    free = np.full((len(recs), periods.size, len(names)), np.nan)
    hit = np.full((len(recs), periods.size, gaps.size, len(names)), np.nan)
    for i, value in enumerate(done.values):
        if value is not None:
            free[i], hit[i] = value
    interrupted = not done.complete
    attrs = {"damping_ratio": zeta, "mass_kg": mass_kg, "bumper": repr(law),
             "isolator": "linear" if isolator is None else repr(isolator), "complete": int(not interrupted)}
    if structure is not None:
        attrs = {"structure": structure.to_toml_text(), "complete": int(not interrupted),
                 "bumper": "each wall's own laws" if bumper is None else repr(law),
                 "period": "the superstructure's first fixed-base period, s"}
    if in_plan:
        attrs["period"] = ("the isolated period along x on the bearings' initial stiffnesses, the floors "
                           "rigid, s")
        attrs["bumper"] = "the moat's own law" if bumper is None else repr(law)
    result = PoundingSpectrum.build(recs, periods, gaps, free, hit, attrs, names)
    if interrupted:
        finished = int(np.isfinite(hit[..., 0]).sum() + np.isfinite(free[..., 0]).sum())
        raise Interrupted(result, finished, runs, "runs")
    return result


def _names(structure: Any) -> tuple[str, ...]:
    """The peaks a spectrum keeps: the single mass's, a building's, or a building in plan's."""
    if structure is None:
        return QUANTITIES
    return PLAN_QUANTITIES if isinstance(structure, PlanBuilding) else STRUCTURE_QUANTITIES


def _check_structure(structure: Any, isolator: Any, mass_kg: float, zeta: float) -> None:
    """A building for the spectrum: a Structure with storeys and at least one wall, or a PlanBuilding with
    its moat; the single mass's arguments left alone."""
    instance_of("structure", structure, (Structure, PlanBuilding),
                "pounding.Structure (a building with its walls), pounding.PlanBuilding (with its moat) or "
                "None")
    if isinstance(structure, PlanBuilding):
        if structure.moat is None:
            raise InputError(Problem.BAD_STATE, "structure", "PlanBuilding(moat=None)",
                             why="has no moat to put at each gap",
                             fix="give the building in plan with its moat (RectangularMoat or CircularMoat)")
    elif not structure.storeys:
        raise InputError(Problem.BAD_STATE, "structure", "Structure(storeys=[])",
                         why="has no superstructure whose period could be varied",
                         fix="give a building with storeys, or use the single mass (structure=None)")
    elif structure.fixed:
        raise InputError(Problem.BAD_STATE, "structure", "Structure.fixed_base(...)",
                         why="has no isolated base: the spectrum's displacement is the base's in its moat",
                         fix="give a building on an isolator with its moat wall (or simulate the fixed-base "
                             "one under each record)")
    elif not structure.walls:
        raise InputError(Problem.BAD_STATE, "structure", "Structure(walls=[])",
                         why="has no wall to put at each gap",
                         fix="give the building with its moat wall (a Wall at level 0) or its stops")
    if isolator is not None or mass_kg != 500.0 or zeta != 0.05:
        raise InputError(Problem.WRONG_MODE, "isolator, mass_kg, damping_ratio", (isolator, mass_kg, zeta),
                         mode="the single mass (structure=None)",
                         fix="leave them at their defaults: the building's isolator, masses and dashpots are "
                             "its own")


__all__ = ["PLAN_QUANTITIES", "QUANTITIES", "STRUCTURE_QUANTITIES", "bearings_at", "isolated_period_s",
           "pounding_spectrum", "superstructure_at"]
