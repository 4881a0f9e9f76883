"""A design from a TOML file: the site, the suite, the design grid, the target; run end to end.

``pounding design DESIGN.toml`` reads a :class:`DesignPlan` (every field checked before any work),
runs its stripe analysis into a resumable store and decides (:func:`run_plan`); the report is
written by :mod:`pounding.reports.design`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any


import numpy as np

from .._checks import float_array, integer, one_of, parse_toml, positive, read_text
from .._errors import InputError, Problem
from ..model import Oscillator
from ..model.oscillator import check_keys
from ..model.plan import PlanBuilding
from ..engine.assembly import MASS, STRUCTURE, is_single_mass, kind_of, structures_of
from ..studies.spec import check_table, system_from_table
from .hazard import HazardCurve
from .site import hazard_curve_of, site_spectra, text_field as _text
from .spectra import DesignSpectrum, asce7_displacement
from .moat_in_plan import asce7_bearings_displacement, asce7_torsion
from .bumper_types import BumperType, bumper_types, grid_of, typed_store
from .stripes import suite_sources

TOP_KEYS = ("title", "system", "bumpers", "site", "records", "design", "run")
RECORD_KEYS = ("suite", "period_s", "levels_g", "scale_range_s")
DESIGN_KEYS = ("gaps_m", "grid", "bumper_types", "target_probability", "level", "years", "t_m_s", "beta_m",
               "wall", "event", "limit")
# the demands a design file may target: one mass's, and a building's (pounding.design's EVENTS)
MASS_EVENTS = ("contact", "acceleration", "displacement")
BUILDING_EVENTS = ("contact", "displacement", "drift", "top_acceleration")
RUN_KEYS = ("scheduler", "workers", "store")
MAX_GAP_M = 2.0  # a design gap beyond this is a unit error (mm given for m)


@dataclass(frozen=True, eq=False)
class DesignPlan:
    """A design as its TOML file states it, checked (:meth:`from_toml`).

    Attributes
    ----------
    title : str
    system : Oscillator, Structure or PlanBuilding
        The base system, with its bumpers (the grid varies their gap and numbers); or a building
        with its moat's wall (the grid varies that wall's gaps, ``walls[w].gap_m``); or a building in
        plan with its moat (the grid varies its four gaps or a ring's, ``moat.gap_m``), under pairs of
        components.
    design_spectrum, mce_spectrum : DesignSpectrum
        The two levels (ASCE 7-16: design and MCE_R; EN 1998-1: the spectrum and ``mce_factor``
        times it; a user's: two tables).
    hazard : HazardCurve or None
        The site's hazard curve for Sa(``period_s``), if given.
    records : list of str
        The suite's record names (a building in plan's: pairs, ``fema-p695-pair:<set>:<index>``).
    period_s : float
        The intensity measure's period.
    levels_g : numpy.ndarray
        The stripes (g).
    scale_range_s : tuple of float
        The range over which the suite is shown scaled to the MCE_R spectrum.
    grid : dict
        The design grid (``bumpers.gap_m`` from ``gaps_m``, and any other dotted names).
    bumper_types : tuple of BumperType
        The ``[design.bumper_types.NAME]`` tables (each a law, optionally a capacity and its own
        grid), one stripe analysis each; empty: the base system's bumpers alone (:attr:`kinds`).
    target_probability : float
    level : str
    years : float
    code_minimum_gap_m : float or None
        ASCE 7-16's D_TM from ``t_m_s`` and ``beta_m`` (when given); a building in plan's with its
        torsion at its base's edge (:func:`asce7_torsion`), its D_M from ``t_m_s`` and ``beta_m`` or, at
        an ASCE 7-16 site without them, from its bearings' effective properties
        (:func:`asce7_bearings_displacement`).
    scheduler : str or None
    workers : int or None
    store : Path or None
        The store (default: beside the report).
    source : Path
        The TOML file.
    bumper_types : tuple of BumperType
        (above)
    gap_dim : str
        The grid's gap: ``bumpers.gap_m``, a building's ``walls[w].gap_m`` (``[design] wall``), or a
        building in plan's ``moat.gap_m``.
    event : str
        The demand the target is on: ``contact`` (pounding, default), or ``displacement``,
        ``acceleration`` (one mass), ``drift``, ``top_acceleration`` (a building) beyond ``limit``.
    limit : float or None
        The event's limit (m, g, or a drift ratio), for an event other than ``contact``.
    """

    title: str
    system: Oscillator
    design_spectrum: DesignSpectrum
    mce_spectrum: DesignSpectrum
    hazard: HazardCurve | None
    records: list
    period_s: float
    levels_g: np.ndarray
    scale_range_s: tuple
    grid: dict
    target_probability: float
    level: str
    years: float
    code_minimum_gap_m: float | None
    scheduler: str | None = None
    workers: int | None = None
    store: Path | None = None
    source: Path = field(default_factory=lambda: Path("."))
    bumper_types: tuple = ()
    gap_dim: str = "bumpers.gap_m"
    event: str = "contact"
    limit: float | None = None

    @property
    def building(self) -> bool:
        """Whether the system is a building (a Structure or a PlanBuilding) rather than one mass."""
        return not is_single_mass(self.system)

    @property
    def in_plan(self) -> bool:
        """Whether the system is a building in plan (its records pairs of components)."""
        return isinstance(self.system, PlanBuilding)

    @property
    def kinds(self) -> tuple:
        """The bumper types the plan runs: ``bumper_types``, or without them the system's own bumpers
        over ``grid`` (named by their law), read from the plan as it is now."""
        if self.bumper_types:
            return tuple(self.bumper_types)
        if not self.building and self.system.bumpers is None:
            raise InputError(
                Problem.MISSING_KEY,
                "system",
                None,
                choices="a system with bumpers (the design chooses their gap), or bumper_types",
            )
        return (own_kind(self.system, self.grid, self.gap_dim),)

    @classmethod
    def from_toml(cls, path: str | Path) -> "DesignPlan":
        """Read and check a design file (see ``examples/design_ups.toml``); relative paths in it are
        relative to the file."""
        text = read_text("path", path)
        return cls.from_dict(parse_toml(str(path), text), Path(path))

    @classmethod
    def from_dict(cls, table: Mapping[str, Any], source: Path = Path("design.toml")) -> "DesignPlan":
        """From the file's tables (see :meth:`from_toml`)."""
        base = source.parent
        check_keys(table, "", TOP_KEYS, ("system", "site", "records", "design"))
        system = system_from_table(table["system"], base)
        kind = kind_of(system)
        in_plan = isinstance(system, PlanBuilding)
        building = kind == STRUCTURE or in_plan
        if kind not in (MASS, STRUCTURE) and not in_plan:
            raise InputError(Problem.WRONG_MODE, "system", type(system).__name__,
                             mode="one mass (an Oscillator), one building (a Structure) or one building "
                                  "in plan (a PlanBuilding)",
                             fix="design the gap of one building at a time: give its file")
        if building and "bumpers" in table:
            raise InputError(Problem.WRONG_MODE, "bumpers", "[bumpers]", mode="one mass's design",
                             fix="a building in plan's moat is in its file: its design varies the moat's "
                                 "gaps (design.gaps_m)" if in_plan else
                                 "a building's walls are in its file: its design varies a wall's gaps "
                                 "(design.gaps_m, and design.wall for a wall other than walls[0])")
        if in_plan and system.moat is None:
            raise InputError(Problem.MISSING_KEY, "system", None,
                             choices="a building in plan with its [moat]: a design chooses its gap")
        if building and not in_plan and not system.walls:
            raise InputError(Problem.MISSING_KEY, "system", None,
                             choices="a building with a wall (walls[0], its moat): a design chooses its gap")
        if "bumpers" in table:
            tables = system.to_dict()
            tables["bumpers"] = dict(check_table("bumpers", table["bumpers"]))
            system = Oscillator.from_dict(tables)
        if not building and system.bumpers is None:
            raise InputError(
                Problem.MISSING_KEY,
                "bumpers",
                None,
                choices="a [bumpers] table (gap_left_m, gap_right_m, [bumpers.law]) or a system with "
                "bumpers: a design chooses their gap",
            )
        design_spec, mce_spec, hazard_file = site_spectra(check_table("site", table["site"]), base)
        rec = check_table("records", table["records"])
        check_keys(rec, "records.", RECORD_KEYS, ("suite", "period_s"))
        records = suite_sources(rec["suite"])
        records = [_path(r, base) for r in records]
        pairs = [isinstance(r, str) and r.startswith("fema-p695-pair:") for r in records]
        if (in_plan and not all(pairs)) or (not in_plan and any(pairs)):
            raise InputError(Problem.WRONG_MODE, "records.suite", rec["suite"],
                             mode="a building in plan" if not in_plan else "a system on a line",
                             fix=("a building in plan is designed under pairs of components: suite = "
                                  "\"fema-p695-pair:far_field\" (or near_field), or a list of "
                                  "\"fema-p695-pair:<set>:<index>\"") if in_plan else
                                 "give single components (\"fema-p695:far_field\") to a system on a line")
        period = positive("records.period_s", rec["period_s"], "s")
        try:
            design_sa, mce_sa = float(design_spec.sa_g(period)), float(mce_spec.sa_g(period))
        except InputError as exc:
            raise exc.relabel("period_s", "records.period_s") from None
        hazard = None if hazard_file is None else hazard_curve_of(hazard_file, base, period)
        levels = (
            # (by default 0.1 to 1.5 times the MCE intensity, with the design and MCE intensities themselves)
            np.unique(np.round(np.concatenate([np.linspace(0.1, 1.5, 8) * mce_sa, [design_sa, mce_sa]]), 6))
            if "levels_g" not in rec
            else float_array("records.levels_g", rec["levels_g"], 2)
        )
        if np.any(levels <= 0):
            i = int(np.flatnonzero(levels <= 0)[0])
            raise InputError(Problem.NOT_POSITIVE, f"records.levels_g[{i}]", float(levels[i]), unit="g")
        if np.any(np.diff(levels) <= 0):
            raise InputError(
                Problem.NOT_INCREASING,
                "records.levels_g",
                levels.tolist(),
                hint=" (positive Sa in g, increasing)",
            )
        scale_range = tuple(
            float_array("records.scale_range_s", rec.get("scale_range_s", [0.75 * period, 1.25 * period]), 2)
        )
        if len(scale_range) != 2 or not 0 < scale_range[0] < scale_range[1]:
            raise InputError(
                Problem.NOT_INCREASING,
                "records.scale_range_s",
                list(scale_range),
                hint=" (two periods, s: lo < hi)",
            )
        des = check_table("design", table["design"])
        check_keys(des, "design.", DESIGN_KEYS, ("gaps_m",))
        gaps = float_array("design.gaps_m", des["gaps_m"])
        if np.any(gaps <= 0):
            i = int(np.flatnonzero(gaps <= 0)[0])
            raise InputError(Problem.NOT_POSITIVE, f"design.gaps_m[{i}]", float(gaps[i]), unit="m")
        if np.any(np.diff(gaps) <= 0):
            raise InputError(Problem.NOT_INCREASING, "design.gaps_m", gaps.tolist())
        if np.any(gaps > MAX_GAP_M):
            i = int(np.flatnonzero(gaps > MAX_GAP_M)[0])
            raise InputError(
                Problem.TOO_LARGE,
                f"design.gaps_m[{i}]",
                float(gaps[i]),
                maximum=MAX_GAP_M,
                what=" m",
                fix=f"give the gaps in m ({gaps[i]:g} mm is {gaps[i] / 1e3:g})",
            )
        gap_dim = "bumpers.gap_m"
        if in_plan:
            if "wall" in des:
                raise InputError(Problem.WRONG_MODE, "design.wall", des["wall"],
                                 mode="a building on a line (a Structure)",
                                 fix="leave design.wall out: a building in plan's moat has its four gaps "
                                     "(moat.gap_m)")
            gap_dim = "moat.gap_m"
        elif building:
            wall = integer("design.wall", des.get("wall", 0), 0, len(system.walls) - 1,
                           f"the building has {len(system.walls)} wall(s): walls[0] ...")
            gap_dim = f"walls[{wall}].gap_m"
        elif "wall" in des:
            raise InputError(Problem.WRONG_MODE, "design.wall", des["wall"], mode="a building's design",
                             fix="leave design.wall out: one mass's gap is its bumpers' (design.gaps_m)")
        event = one_of("design.event", des.get("event", "contact"),
                       BUILDING_EVENTS if building else MASS_EVENTS)
        limit = None
        if event != "contact" or "limit" in des:
            if event == "contact":
                raise InputError(Problem.WRONG_MODE, "design.limit", des["limit"], mode="an event other than "
                                 "contact", fix="leave design.limit out, or name design.event (drift, ...)")
            if "limit" not in des:
                raise InputError(Problem.MISSING_KEY, "design.limit", None,
                                 choices=f"the limit of {event} (m, g, or a drift ratio such as 0.005)")
            limit = positive("design.limit", des["limit"], "(m, g, or a drift ratio)")
        grid = grid_of("design.grid", des.get("grid", {}), gaps, gap_dim)
        target = positive("design.target_probability", des.get("target_probability", 0.1), "(a probability)")
        if target >= 1.0:
            raise InputError(Problem.OUT_OF_RANGE, "design.target_probability", target, range="(0, 1)")
        level = one_of("design.level", des.get("level", "mce"), ("design", "mce"))
        years = positive("design.years", des.get("years", 50.0), "years")
        code_min = None
        if "t_m_s" in des or "beta_m" in des:
            if design_spec.kind != "asce7-16":
                raise InputError(
                    Problem.WRONG_MODE,
                    "design.t_m_s",
                    des.get("t_m_s"),
                    mode="an ASCE 7-16 site",
                    fix="leave t_m_s and beta_m out (the code minimum is ASCE 7-16's D_TM)",
                )
            if "t_m_s" not in des:
                raise InputError(Problem.MISSING_KEY, "design.t_m_s", None, choices="t_m_s with beta_m")
            s_m1 = 1.5 * design_spec.params["s_d1_g"]
            try:
                code = asce7_displacement(s_m1, des["t_m_s"], des.get("beta_m", 0.05))
                code_min = (asce7_torsion(system, code["d_m_m"], "edge")["d_tm_m"] if in_plan
                            else code["d_tm_m"])
            except InputError as exc:
                raise exc.relabel("damping_ratio", "design.beta_m").relabel(
                    "period_s", "design.t_m_s"
                ) from None
        elif in_plan and design_spec.kind == "asce7-16":  # (D_M from the bearings' effective properties)
            d_m = asce7_bearings_displacement(system, 1.5 * design_spec.params["s_d1_g"])["d_m_m"]
            code_min = asce7_torsion(system, d_m, "edge")["d_tm_m"]
        run = check_table("run", table.get("run", {}))
        check_keys(run, "run.", RUN_KEYS, ())
        store = None if "store" not in run else _path(_text("run.store", run["store"]), base)
        scheduler = run.get("scheduler")
        if scheduler is not None:
            from .._runner import scheduler_kind

            try:
                scheduler_kind(_text("run.scheduler", scheduler))
            except InputError as exc:
                raise exc.relabel("scheduler", "run.scheduler") from None
        workers = None if "workers" not in run else integer("run.workers", run["workers"], 1, 4096)
        if building and "bumper_types" in des:
            raise InputError(Problem.WRONG_MODE, "design.bumper_types", list(des["bumper_types"]),
                             mode="one mass's design",
                             fix=f"give the {'moat' if in_plan else 'wall'}'s law in the building's file "
                                 "(one design per law so far)")
        types = () if building else bumper_types(system, des, grid, gaps)
        for kind in types or (own_kind(system, grid, gap_dim),):
            try:
                _check_runs(kind.system, records, levels, period, kind.grid, gap_dim)
            except InputError as exc:
                if kind.grid is grid or not exc.field.startswith("design.grid."):
                    raise  # (the design's own grid, as the file names it)
                raise exc.relabel("design.grid.", f"design.bumper_types.{kind.name}.grid.") from None
        return cls(
            str(table.get("title", source.stem)),
            system,
            design_spec,
            mce_spec,
            hazard,
            records,
            period,
            levels,
            scale_range,
            grid,
            target,
            level,
            years,
            code_min,
            scheduler,
            workers,
            None if store is None else Path(store),
            source,
            types,
            gap_dim,
            event,
            limit,
        )


def own_kind(system: Any, grid: dict, gap_dim: str) -> BumperType:
    """The base system's own bumpers over the design grid, named by their law; a building's: the wall of
    ``gap_dim`` (``walls[w].gap_m``), named by its left side's law."""
    if isinstance(system, PlanBuilding):
        return BumperType(system.moat.law.TYPE, system, grid)
    wall = int(gap_dim.split("[")[1].split("]")[0]) if gap_dim.startswith("walls[") else 0  # (bumpers: 0)
    return BumperType(structures_of(system)[0][0].walls[wall].left.TYPE, system, grid)


def _check_runs(system: Any, records: list, levels: np.ndarray, period: float, grid: dict,
                gap_dim: str = "bumpers.gap_m") -> None:
    """The runs the plan asks for are valid, before any: the study's own checks (the grid's names and
    values, every record read and scaled), named by the design file's fields."""
    from ..studies import StudySpec

    try:
        StudySpec(
            system,
            {"kind": "record", "sa_period_s": period, "sa_damping_ratio": 0.05},
            {"sa_g": levels.tolist(), "record": records, **grid},
        )
    except InputError as exc:
        for old, new in (
            ("grid.record", "records.suite"),
            ("grid.sa_g", "records.levels_g"),
            (f"grid.{gap_dim}", "design.gaps_m"),
            ("grid.", "design.grid."),
            ("compute.", "records."),
        ):
            after = exc.field[len(old):len(old) + 1]  # (a name's end, not a longer name's: moat.gap_m[0])
            if exc.field.startswith(old) and (old.endswith(".") or exc.field == old or after not in "[."):
                raise exc.relabel(old, new) from None
        raise


def _path(value: Any, base: Path) -> Any:
    """A record file or a store, relative to the design file (names of built-in records kept)."""
    if not isinstance(value, str) or value == "el-centro" or value.startswith(("fema-p695:",
                                                                                "fema-p695-pair:")):
        return value
    return str((base / Path(value).expanduser()).resolve())


@dataclass(frozen=True, eq=False)
class DesignOutcome:
    """What :func:`run_plan` computed: the plan, the suite scaled to the MCE_R spectrum, the stripe
    analysis of each bumper type (by name), the fragility of pounding per design point (those with
    an estimate; keyed by the point's ``(dimension, value)`` pairs, the bumper type's first when the
    design has several) and the decision."""

    plan: DesignPlan
    suite: Any
    analyses: dict
    fragilities: dict
    decision: Any


def run_plan(
    plan: DesignPlan, store: str | Path, *, progress: Any = True, resume: bool = True
) -> DesignOutcome:
    """Run a design: the suite scaled to the MCE_R spectrum over ``scale_range_s`` (shown), the
    stripe analysis of each bumper type over its design grid into ``store`` (one type; with several,
    ``store`` with ``_NAME`` before ``.zarr`` per type; resumed when it holds this design), the runs
    without bumpers (:func:`free_store`), the fragility of pounding at every design point and the
    decision over them all."""
    from ..excitation.spectrum import check_records
    from ..studies.points import load_pair, load_record
    from .decision import decide
    from .stripes import stripe_analysis
    from .suite import scale_suite

    recs = [load_pair(r) for r in plan.records] if plan.in_plan else check_records([load_record(r)
                                                                                   for r in plan.records])
    suite = scale_suite(recs, plan.mce_spectrum, period_range_s=plan.scale_range_s, n_periods=21)
    common = dict(
        period_s=plan.period_s,
        scheduler=plan.scheduler,
        workers=plan.workers,
        resume=resume,
        progress=progress,
    )
    analyses, fragilities = {}, {}
    for kind in plan.kinds:
        where = store if len(plan.kinds) == 1 else typed_store(store, kind.name)
        analysis = stripe_analysis(
            kind.system, plan.records, plan.levels_g, store=where, grid=kind.grid, **common
        )
        analyses[kind.name] = analysis
        dims = analysis.design_dims
        for index in np.ndindex(*(analysis.data.sizes[d] for d in dims)):
            at = {d: float(analysis.data[d].values[i]) for d, i in zip(dims, index)}
            key = tuple(at.items()) if len(plan.kinds) == 1 else (("bumper", kind.name), *at.items())
            try:
                fragilities[key] = analysis.fragility(plan.event, plan.limit, at=at, n_bootstrap=500)
            except InputError:  # (no estimate: all or nothing, or separated stripes; the table says which)
                continue
    alone = (replace(plan.system, walls=()) if plan.building and not plan.in_plan
             else plan.system.moat_out_of_reach() if plan.in_plan else plan.system.without_bumpers())
    free = stripe_analysis(alone, plan.records, plan.levels_g, store=free_store(store), **common)
    decision = decide(
        analyses if len(analyses) > 1 else next(iter(analyses.values())),
        float(plan.design_spectrum.sa_g(plan.period_s)),
        float(plan.mce_spectrum.sa_g(plan.period_s)),
        target_probability=plan.target_probability,
        level=plan.level,
        hazard=plan.hazard,
        years=plan.years,
        code_minimum_gap_m=plan.code_minimum_gap_m,
        free=free,
        gap_dim=plan.gap_dim,
        event=plan.event,
        limit=plan.limit,
    )
    return DesignOutcome(plan, suite, analyses, fragilities, decision)


def free_store(store: str | Path) -> str:
    """The store of the runs without bumpers, beside the design's (``x.zarr`` -> ``x_free.zarr``)."""
    return typed_store(store, "free")
