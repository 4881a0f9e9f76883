"""What one point of a study computes: its quantities, by kind (``sweep``, ``simulate``, ``record``)."""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import Any

import numpy as np

from .._checks import positive
from .._errors import InputError, Problem, Status
from ..excitation import Harmonic, Record, RecordPair
from ..model import Oscillator
from ..protocols.campaign import TABLE2_QUANTITIES, TABLE3_QUANTITIES, TABLE4_QUANTITIES
from ..protocols.sweep_features import STRUCTURE_QUANTITIES as STRUCTURE_SWEEP_NAMES
from ..protocols.pounding_spectrum_result import UNITS as RUN_UNITS
from .._tables import RunQuantities
from ..engine.run_quantities import RUN_QUANTITIES

SWEEP_QUANTITIES = TABLE2_QUANTITIES + TABLE3_QUANTITIES + TABLE4_QUANTITIES + ("steps_done", "status")
STRUCTURE_SWEEP_QUANTITIES = STRUCTURE_SWEEP_NAMES + ("steps_done", "status")
# a run's point (``simulate``, ``record``) is every system's run's quantities(), one name, one meaning: a
# building's base is ``disp_max_m``, a single mass's top its own; a sweep's point, the sweep's few numbers
QUANTITIES = {"sweep": SWEEP_QUANTITIES, "simulate": RUN_QUANTITIES, "record": RUN_QUANTITIES}
STRUCTURE_QUANTITIES = {**QUANTITIES, "sweep": STRUCTURE_SWEEP_QUANTITIES}
# a building in plan's run: every system's, and its own (PlanRun.quantities); it has no sweep
PLAN_RUN_QUANTITIES = RUN_QUANTITIES[:-1] + ("theta_max_rad", "clearance_min_m", "moat_demand_m", "status")
PLAN_QUANTITIES = {"simulate": PLAN_RUN_QUANTITIES, "record": PLAN_RUN_QUANTITIES}
# a quantity's names before (a store written before keeps its array under them): new -> old
NAMES_BEFORE = {new: old for old, new in RunQuantities.OLD.items()}
UNITS = {**RUN_UNITS, "nu_r": "1", "alpha": "1", "eta": "1", "e": "1", "contact_nu_min": "1",
         "contact_nu_max": "1", "excursion_max_m": "m", "mean_force_over_mg": "1", "contact_time_ms": "ms",
         "peak_force_over_mg": "1", "dissipated_energy_per_mass": "m^2/s^2", "restitution": "1",
         "steps_done": "1", "compression_max_m": "m", "top_disp_max_m": "m",
         "top_acc_max_g": "g", "drift_ratio_max": "1", "nu_r_top": "1", "alpha_top_max": "1",
         "alpha_base_max": "1", "theta_max_rad": "rad", "clearance_min_m": "m", "moat_demand_m": "m"}
SWEEP_ARGS = ("steady", "cycles", "measure_cycles", "max_cycles", "steady_rtol", "f_ref_hz", "rtol")
SET_PREFIX = "fema-p695:"
PAIR_PREFIX = "fema-p695-pair:"


def quantities_of(kind: str, system: Any) -> tuple[str, ...]:
    """The quantities a point of ``kind`` keeps, in order, for ``system`` (a system, or its tables): a run's
    are every system's (:data:`RUN_QUANTITIES`; a building in plan's add its own, ``PLAN_QUANTITIES``), a
    sweep's a single mass's (the paper's) or a structure's (``STRUCTURE_QUANTITIES``)."""
    from ..model.plan import PlanBuilding
    from ..model.systems import system_type
    from ..engine.assembly import is_single_mass

    kind_of = system_type(system) if isinstance(system, dict) else type(system)
    if kind_of is PlanBuilding:
        return PLAN_QUANTITIES[kind]
    one = kind_of is Oscillator if isinstance(system, dict) else is_single_mass(system)
    return QUANTITIES[kind] if one else STRUCTURE_QUANTITIES[kind]


@functools.lru_cache(maxsize=64)
def load_record(source: str) -> Record:
    """A record by its study name: ``"el-centro"``, ``"fema-p695:<set>:<index>"`` (a component of a
    FEMA P695 set, from 0), or the path of a file (``.AT2``, or two columns: time s, acceleration g).
    Read once per process."""
    from ..excitation.records import el_centro

    if source == "el-centro":
        return el_centro()
    if source.startswith(SET_PREFIX):
        parts = source[len(SET_PREFIX):].split(":")
        if len(parts) != 2 or not parts[1].isdigit():
            raise InputError(Problem.NOT_ONE_OF, "record", source,
                             choices="'el-centro', 'fema-p695:<set>:<index>' (e.g. 'fema-p695:far_field:0'), "
                                     "or a file")
        records = _fema_set(parts[0])
        if int(parts[1]) >= len(records):
            raise InputError(Problem.OUT_OF_RANGE, "record", source, range=f"0 to {len(records) - 1}",
                             hint=f" (the {parts[0]} set has {len(records)} components)")
        return records[int(parts[1])]
    path = Path(source)
    if path.suffix.lower() == ".at2":
        return Record.from_at2(path)
    return Record.from_csv(path, time=0, accel=1)


@functools.lru_cache(maxsize=64)
def load_pair(source: str) -> RecordPair:
    """A pair by its study name, ``"fema-p695-pair:<set>:<index>"`` (an event of a FEMA P695 set, from 0);
    read once per process."""
    parts = source[len(PAIR_PREFIX):].split(":")
    if len(parts) != 2 or not parts[1].isdigit():
        raise InputError(Problem.NOT_ONE_OF, "record", source,
                         choices="'fema-p695-pair:<set>:<index>' (e.g. 'fema-p695-pair:far_field:0')")
    pairs = _fema_pairs(parts[0])
    if int(parts[1]) >= len(pairs):
        raise InputError(Problem.OUT_OF_RANGE, "record", source, range=f"0 to {len(pairs) - 1}",
                         hint=f" (the {parts[0]} set has {len(pairs)} pairs)")
    return pairs[int(parts[1])]


@functools.lru_cache(maxsize=1024)
def pair_factor(source: str, scale_pga_g: float | None, sa_g: float | None, period_s: float | None,
                damping_ratio: float) -> float:
    """The one factor that scales a pair's largest direction (RotD100: its peak vector for a PGA, its RotD100
    pseudo-acceleration at ``period_s`` for ``sa_g``) to the value asked for; 1 when none is."""
    from ..excitation.rotd import rotd_spectrum

    pair = load_pair(source)
    if scale_pga_g is not None:
        return scale_pga_g / pair.peak_vector_g
    if sa_g is None:
        return 1.0
    now = float(rotd_spectrum(pair, [period_s], damping_ratio)["rotd100_psa_g"].values[0, 0])
    if now <= 0.0:
        raise InputError(Problem.NO_FIT, "record", source,
                         why=f"has no spectral acceleration at {period_s:g} s, so no factor scales it "
                             "to sa_g",
                         fix="leave it out of the study")
    return sa_g / now


@functools.lru_cache(maxsize=1024)
def record_psa_g(source: str, period_s: float, damping_ratio: float) -> float:
    """A record's pseudo-spectral acceleration (g) at a period: computed once per process."""
    from ..excitation.spectrum import response_spectrum

    return float(response_spectrum(load_record(source), [period_s], damping_ratio)["psa_g"].values[0, 0])


@functools.lru_cache(maxsize=16)
def record_at_sa(source: str, sa_g: float, period_s: float, damping_ratio: float) -> Record:
    """A record scaled to a pseudo-spectral acceleration (the points of one stripe and record share it:
    its samples and kernel arrays are made once)."""
    psa = record_psa_g(source, period_s, damping_ratio)
    if psa <= 0.0:
        raise InputError(Problem.NO_FIT, "record", source,
                         why=f"has no spectral acceleration at {period_s:g} s, so no factor scales it "
                             "to sa_g",
                         fix="leave it out of the study")
    return load_record(source).scaled(factor=sa_g / psa)


@functools.lru_cache(maxsize=4)
def _fema_pairs(name: str) -> tuple[RecordPair, ...]:
    """A FEMA P695 set's pairs, read once per process."""
    from ..excitation.records import fema_p695_pairs

    return tuple(fema_p695_pairs(name))


@functools.lru_cache(maxsize=4)
def _fema_set(name: str) -> tuple[Record, ...]:
    """A FEMA P695 set, read once per process (its components are points of many studies)."""
    from ..excitation.records import fema_p695

    return tuple(fema_p695(name))


def excitation_of(options: dict[str, Any], plan: bool = False) -> Harmonic | Record | RecordPair | None:
    """The excitation of a point (None for a sweep, whose steps make their own); for a building in plan
    (``plan``), the motion's axes turned by ``angle_deg`` against the building's (:meth:`RecordPair.rotated`,
    as :func:`pounding.orientations` turns them): a pair's two components, or one record, its x component
    then acting along ``-angle_deg`` in the building's axes."""
    kind = options["kind"]
    if kind == "simulate":
        return Harmonic(options["a_g"], options["freq_hz"], options.get("phase_rad", 0.0))
    if kind == "record" and options["record"].startswith(PAIR_PREFIX):  # (along x, or both, turned)
        from .._checks import positive

        if options.get("scale_pga_g") is not None:
            positive("scale_pga_g", options["scale_pga_g"], "g")
        zeta = options.get("sa_damping_ratio")
        factor = pair_factor(options["record"], options.get("scale_pga_g"), options.get("sa_g"),
                             options.get("sa_period_s"), 0.05 if zeta is None else zeta)
        pair = load_pair(options["record"])
        pair = pair if factor == 1.0 else pair.scaled(factor)
        angle = options.get("angle_deg") or 0.0
        return (pair.rotated(angle) if angle else pair) if plan else pair.along(angle)
    if kind == "record" and options.get("angle_deg") is not None and not plan:
        raise InputError(Problem.WRONG_MODE, "angle_deg", options["angle_deg"],
                         mode="a pair of components (record = 'fema-p695-pair:<set>:<index>')",
                         fix="leave angle_deg out for one component, or give a pair")
    if kind == "record":
        rec = load_record(options["record"])
        if options.get("scale_pga_g") is not None:
            rec = rec.scaled(pga_g=options["scale_pga_g"])
        elif options.get("sa_g") is not None:
            zeta = options.get("sa_damping_ratio")
            rec = record_at_sa(options["record"], options["sa_g"], options["sa_period_s"],
                               0.05 if zeta is None else zeta)
        # (one record turned as a pair is, its second component nil: along -angle_deg in the building's axes)
        return RecordPair.of_direction(rec, -options["angle_deg"]) if options.get("angle_deg") else rec
    return None


def compute_point(system: Any, options: dict[str, Any], max_steps: int | None = None) -> np.ndarray:
    """The quantities (:func:`quantities_of`, in order) of one point: float64, NaN where a quantity
    does not exist.  A run refused over its budget is kept as ``status`` BUDGET, not raised."""
    from ..engine.simulate import DEFAULT_MAX_STEPS, peaks
    from ..model.plan import PlanBuilding
    from ..protocols.sweep import sweep

    kind = options["kind"]
    steps = DEFAULT_MAX_STEPS if max_steps is None else max_steps
    names = quantities_of(kind, system)
    try:
        if kind == "sweep":
            kwargs = {k: options[k] for k in SWEEP_ARGS if options.get(k) is not None}
            freqs = options.get("freqs_hz")
            res = sweep(system, options["a_g"], None if freqs is None else np.asarray(freqs, dtype=float),
                        options.get("direction", "up"), max_steps=steps, **kwargs)
            q = {**res.quantities(), "steps_done": float(res.steps_done), "status": float(res.status)}
        else:
            exc = excitation_of(options, isinstance(system, PlanBuilding))
            duration = options.get("duration_s")
            if duration is None:  # (a record's own length)
                duration = float(exc.t[-1])
            state = None
            if options.get("v0_m_s"):
                from ..engine import State

                state = State.at_rest(system, velocity_m_s=options["v0_m_s"])
            q = peaks(system, exc, duration, state, max_steps=steps)
        return np.array([q[k] for k in names], dtype=float)
    except InputError as exc:
        if exc.problem not in (Problem.OVER_BUDGET, Problem.TOO_MUCH_WORK):
            raise
        out = np.full(len(names), math.nan)
        out[-1] = float(Status.BUDGET)
        return out


def check_options(system: Any, options: dict[str, Any]) -> None:
    """The compute options of one point are valid: its excitation builds (a record reads) and
    its duration is positive; a sweep's plan is made (every sweep option checked)."""
    if options["kind"] == "sweep":
        from ..protocols.sweep import make_plan

        kwargs = {k: options[k] for k in SWEEP_ARGS if options.get(k) is not None}
        freqs = options.get("freqs_hz")
        make_plan(system, options["a_g"], None if freqs is None else np.asarray(freqs, dtype=float),
                  options.get("direction", "up"), **kwargs)
        return
    from ..model.plan import PlanBuilding

    if options["kind"] == "record":
        _check_sa(options)
    excitation_of(options, isinstance(system, PlanBuilding))
    if isinstance(system, PlanBuilding) and options.get("v0_m_s"):
        raise InputError(Problem.WRONG_MODE, "v0_m_s", options["v0_m_s"], mode="a structure on a line",
                         fix="leave v0_m_s out: a building in plan starts at rest")
    if options.get("duration_s") is not None:
        positive("duration_s", options["duration_s"], "s")


def _check_sa(options: dict[str, Any]) -> None:
    """A record point's scaling: ``scale_pga_g`` or ``sa_g`` (with ``sa_period_s``), not both."""
    if options.get("sa_g") is None:
        for key in ("sa_period_s", "sa_damping_ratio"):
            if options.get(key) is not None:
                raise InputError(Problem.MISSING_INPUT, "sa_g", None,
                                 what=f"sa_g (g) with {key}, or leave {key} out")
        return
    if options.get("scale_pga_g") is not None:
        raise InputError(Problem.DUPLICATE, "sa_g", options["sa_g"],
                         repeated="scale_pga_g (a record is scaled to a PGA or to a spectral acceleration)")
    positive("sa_g", options["sa_g"], "g")
    if options.get("sa_period_s") is None:
        raise InputError(Problem.MISSING_INPUT, "sa_period_s", None, what="the period (s) of sa_g")
    positive("sa_period_s", options["sa_period_s"], "s")
    zeta = options.get("sa_damping_ratio")
    if zeta is not None and not 0.0 <= zeta < 1.0:
        raise InputError(Problem.OUT_OF_RANGE, "sa_damping_ratio", zeta, range="[0, 1)")
