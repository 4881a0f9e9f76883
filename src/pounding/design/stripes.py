"""Multiple-stripe analysis over a design grid, on the study runner (a resumable Zarr store).

Each record of a suite is scaled to each intensity level (its pseudo-spectral acceleration at one
period) and run on each system of a design grid (gaps, bumper stiffnesses, isolator numbers, by
dotted name).  The runs are a parameter study of kind ``record``: they go to a Zarr store chunk by
chunk, a rerun computes only what is missing, and they run on threads, processes or Dask.
:class:`StripeAnalysis` turns the runs into the events a designer names, their fractions per
stripe, and fragility curves.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import float_array, instance_of, positive
from .._errors import InputError, Interrupted, Problem
from ..model import Oscillator, Structure
from ..model.plan import PlanBuilding
from ..model.systems import system_type
from ..engine.assembly import is_single_mass, structures_of
from ..studies import StudySpec, study
from .stripe_result import RESERVED, StripeAnalysis

SUITES = {"fema-p695:far_field": ("far_field", 44), "fema-p695:near_field": ("near_field", 56),
          "fema-p695-pair:far_field": ("far_field", 22), "fema-p695-pair:near_field": ("near_field", 28)}


def suite_sources(records: str | Sequence[str]) -> list[str]:
    """The study names of a suite's records: ``"fema-p695:far_field"`` (44 components),
    ``"fema-p695:near_field"`` (56), their pairs (``"fema-p695-pair:far_field"``, 22 events;
    ``"fema-p695-pair:near_field"``, 28), ``"el-centro"``, or a list of record names
    (``"fema-p695:far_field:3"``, ``"fema-p695-pair:far_field:3"``, ``"el-centro"``, paths of ``.AT2`` or
    two-column files)."""
    if isinstance(records, str):
        if records in SUITES:
            name, n = SUITES[records]
            return [f"{records.split(':')[0]}:{name}:{i}" for i in range(n)]
        return [records]
    if isinstance(records, (list, tuple)) and records:
        for i, r in enumerate(records):
            instance_of(f"records[{i}]", r, (str, Path),
                        "str (a record's name, e.g. 'fema-p695:far_field:0' or 'el-centro', or a file's "
                    "path: each worker reads it)")
        return [str(r) for r in records]
    raise InputError(
        Problem.WRONG_TYPE,
        "records",
        records,
        got=type(records).__name__,
        expected="'fema-p695:far_field', 'fema-p695:near_field', 'el-centro' or a list of "
        "record names and paths",
    )


def stripe_analysis(
    system: Oscillator | Structure | PlanBuilding,
    records: str | Sequence[str],
    levels_g: Any,
    *,
    period_s: float,
    store: str | Path,
    grid: Mapping[str, Sequence[float]] | None = None,
    damping_ratio: float = 0.05,
    scheduler: Any = None,
    workers: int | None = None,
    resume: bool = True,
    progress: Any = True,
    max_steps: int | None = None,
) -> StripeAnalysis:
    """Run a multiple-stripe analysis over a design grid into a resumable Zarr store.

    Parameters
    ----------
    system : Oscillator, Structure or PlanBuilding
        The base system (its bumpers, or none: then a contact is the peak displacement reaching a
        gap, for every gap at once); or a building with its walls (a moat wall: a grid over
        ``walls[0].gap_m``), its runs' events its drift ratio and floor accelerations besides contact;
        or a building in plan (its moat's four gaps or a ring's: a grid over ``moat.gap_m``; without a
        moat, or with its ring out of reach, a contact is its corners reaching a gap, ``moat_demand_m``)
        under pairs of components.
    records : str or sequence of str
        The suite: ``"fema-p695:far_field"``, ``"fema-p695:near_field"``, ``"el-centro"``, the sets'
        pairs for a building in plan (``"fema-p695-pair:far_field"``: both components at once; refused
        for a system on a line), or record names and paths (:func:`suite_sources`).
    levels_g : array_like, shape (s,)
        The stripes: pseudo-spectral accelerations (g) at ``period_s``, > 0, increasing.  Each
        record is scaled to each (:func:`stripe_factors`; a pair by one factor, to its RotD100).
    period_s : float
        The intensity measure's period (s), e.g. the isolated period.
    store : str or Path
        The Zarr store (created, or resumed when it holds this analysis).
    grid : dict, optional
        The design grid: dotted names of the system's numbers and their values, e.g.
        ``{"bumpers.gap_m": [0.05, 0.1], "bumpers.law.stiffness": [1e6, 3e6]}``.
    damping_ratio : float
        The intensity measure's spectral damping.
    scheduler : None, str or dask.distributed.Client
        Where the runs go (as :func:`pounding.study`): threads (None), "serial", "processes",
        "local" (a Dask ``LocalCluster``), a scheduler's address or a ``Client``.
    workers : int, optional
        Threads or processes (default: the machine's cores).
    resume : bool
        Complete an existing store of this analysis (True), or write it anew.
    progress : bool or callable
        A progress bar over the runs, or a callable given the runs just finished.
    max_steps : int, optional
        Each run's work budget; a run over it is kept with status BUDGET (and not counted).

    Returns
    -------
    StripeAnalysis

    Raises
    ------
    Interrupted
        On Ctrl-C: ``partial`` is the :class:`StripeAnalysis` of the runs finished (the store
        keeps them; run again to complete it).

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> msa = design.stripe_analysis(pounding.presets.paper_damped(), "el-centro",
    ...                              [0.2, 0.5], period_s=1.0, store="one.zarr",
    ...                              progress=False)
    >>> msa.data["impacts"].values.ravel().tolist()
    [7.0, 27.0]
    """
    instance_of("system", system, (Oscillator, Structure, PlanBuilding),
                "pounding.Oscillator, pounding.Structure (a building with its walls) or "
                "pounding.PlanBuilding")
    sources = suite_sources(records)
    if not isinstance(system, PlanBuilding) and any(s.startswith("fema-p695-pair:") for s in sources):
        raise InputError(Problem.WRONG_MODE, "records", records, mode="a building in plan",
                         fix="give a system on a line single components (\"fema-p695:far_field\"): a pair is "
                             "scaled by its RotD100, which its motion along one line does not reach")
    levels = float_array("levels_g", levels_g)
    for i, v in enumerate(levels):
        positive(f"levels_g[{i}]", v, "g")
    if levels.size > 1 and np.any(np.diff(levels) <= 0.0):
        raise InputError(Problem.NOT_INCREASING, "levels_g", levels.tolist())
    period = positive("period_s", period_s, "s")
    from ..excitation.spectrum import damping_ratio_value

    zeta = damping_ratio_value(damping_ratio)
    design_grid = {} if grid is None else dict(grid)
    for name in design_grid:
        if name in RESERVED:
            raise InputError(
                Problem.DUPLICATE,
                f"grid.{name}",
                design_grid[name],
                repeated="the stripes' axis (levels_g and records are given on their own)",
            )
    spec = StudySpec(
        system,
        {"kind": "record", "sa_period_s": period, "sa_damping_ratio": zeta},
        {"sa_g": levels.tolist(), "record": sources, **design_grid},
    )
    if isinstance(system, PlanBuilding):
        has_bumpers, capacity = system.moat_in_reach, None
    else:
        has_bumpers = any(s.walls for s in structures_of(system)[0])
        capacity = system.bumpers.capacity_m if has_bumpers and is_single_mass(system) else None
    try:
        ds = study(
            spec,
            store,
            scheduler=scheduler,
            workers=workers,
            resume=resume,
            progress=progress,
            max_steps=max_steps,
        )
    except Interrupted as stop:
        raise Interrupted(
            StripeAnalysis(stop.partial, period, zeta, has_bumpers, capacity), stop.done, stop.total, "runs"
        ) from None
    return StripeAnalysis(ds.load(), period, zeta, has_bumpers, capacity)  # (small: read once, not lazily)


def open_stripe_analysis(store: str | Path) -> StripeAnalysis:
    """A stripe analysis from its store (finished or not), without running anything.

    Parameters
    ----------
    store : str or Path
        The store :func:`stripe_analysis` wrote.

    Returns
    -------
    StripeAnalysis

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> ybs = pounding.presets.paper_damped()
    >>> _ = design.stripe_analysis(ybs, "el-centro", [0.2], period_s=1.0,
    ...                            store="again.zarr", progress=False)
    >>> design.open_stripe_analysis("again.zarr").period_s
    1.0
    """
    from ..studies.store import SPEC_ATTR, open_dataset

    try:
        ds = open_dataset(str(store)).load()
    except (FileNotFoundError, KeyError, ValueError) as exc:
        raise InputError(
            Problem.BAD_OUTPUT,
            "store",
            str(store),
            why=f"is not a stripe analysis's store ({exc})",
            fix="give the folder stripe_analysis (or pounding design) wrote",
        ) from None
    if SPEC_ATTR not in ds.attrs:
        raise InputError(
            Problem.BAD_OUTPUT,
            "store",
            str(store),
            why="is a Zarr store, but not a study's",
            fix="give the folder stripe_analysis (or pounding design) wrote",
        )
    tables = json.loads(ds.attrs[SPEC_ATTR])
    compute = tables["compute"]
    if compute.get("kind") != "record" or "sa_period_s" not in compute:
        raise InputError(
            Problem.BAD_OUTPUT,
            "store",
            str(store),
            why="is a study, but not a stripe analysis",
            fix="open it with pounding.open_study",
        )
    zeta = compute.get("sa_damping_ratio")
    system = tables["system"]
    return StripeAnalysis(
        ds,
        float(compute["sa_period_s"]),
        0.05 if zeta is None else float(zeta),
        (system.get("bumpers") is not None if system_type(system) is Oscillator
         else system.get("moat") is not None if system_type(system) is PlanBuilding
         else bool(system.get("walls"))),
        (system.get("bumpers") or {}).get("capacity_m"),
    )
