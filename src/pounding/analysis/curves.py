"""Two-parameter continuation: folds and grazings followed in (a_G, f), and the map of where two
responses coexist (:func:`bifurcation_curve`, :func:`coexistence_map`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, Optional, Sequence

import numpy as np
import pandas as pd

from .._checks import instance_of, integer, one_of, real
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from ..engine.assembly import check_system
from ..engine.simulate import check_state
from ..excitation import Harmonic
from ..model import Oscillator
from ..protocols.campaign import PAPER_YBS_A_G
from . import _hybrid as hy
from ._arclength import Family
from ._curve import CurveFollower, CurvePoint
from .branch import Bifurcation, Branch
from .continuation import continuation
from .curve_result import BifurcationCurve, CoexistenceMap, curve_table
from .witnesses import check_basin_sample, check_sweeps, judge_matrix
from ._through_sweeps import STEP_COLUMNS, through_sweeps
from ._shooter import _Shooter
from ._shooting import _Failed
from ._args import exact_monodromy, length_scale, step_size, tolerance

CURVE_KINDS = ("fold", "grazing")
MAX_TEST_FREQS = 100_000  # the test matrix's frequencies at most


@renamed_keyword("oscillator", "system")
def bifurcation_curve(
    system: Any,
    bifurcation: Bifurcation,
    *,
    a_g: Any = (0.02, 0.12),
    freqs_hz: Any = (0.5, 5.0),
    tol: float = 1e-9,
    max_step: float = 0.02,
    max_points: int = 2000,
    method: str = "auto",
) -> BifurcationCurve:
    """Follow a fold or a grazing of a branch in two parameters, the frequency and a_G.

    A fold curve bounds the forcings at which two responses coexist (where up and down sweeps
    differ); a grazing curve, those at which a contact appears.  The curve is followed through
    its cusps (where a fold curve turns back in a_G and its two folds meet) until it leaves the
    box ``freqs_hz`` x ``a_g`` or closes.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system of the branch the bifurcation is on (a structure's grazing names its wall side
        or link: ``Bifurcation.side``).
    bifurcation : Bifurcation
        A ``"fold"`` or ``"grazing"`` of a :class:`Branch` in ``freq_hz`` or ``a_g``.
    a_g : (float, float)
        The box's range of the table's peak acceleration, g.
    freqs_hz : (float, float)
        The box's range of the frequency, Hz.
    tol : float
        Largest scaled residual of the orbit's equations at each point (the fold's test,
        the multiplier minus 1, to ``max(100 tol, 1e-8)``).
    max_step : float
        Largest arclength step, in units where each range is 1.
    max_points : int
        Points at most (status ``BUDGET`` there).
    method : {"auto", "exact", "finite-difference"}
        The monodromy, as in :func:`periodic_orbit`.

    Returns
    -------
    BifurcationCurve
        ``status`` ``SUCCESS`` when both ends reached the box's edge or the curve closed.

    Raises
    ------
    Interrupted
        On Ctrl-C; ``.partial`` is the curve followed so far.

    Examples
    --------
    The fold at 2.014 Hz of the damped paper system's branch at a_G = 0.05, followed from
    a_G = 0.04 to 0.06:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> fold = pounding.continuation(osc, 0.05, (1.5, 2.5)).folds()[0]
    >>> curve = pounding.bifurcation_curve(osc, fold, a_g=(0.04, 0.06),
    ...                                    freqs_hz=(1.0, 3.0))
    >>> curve.status.name
    'SUCCESS'
    >>> df = curve.to_dataframe()
    >>> round(float(df["freq_hz"].min()), 3), round(float(df["freq_hz"].max()), 3)
    (1.746, 2.276)
    """
    check_system(system)
    instance_of("bifurcation", bifurcation, Bifurcation,
                "pounding.Bifurcation (from Branch.bifurcations or Branch.folds())")
    if bifurcation.kind not in CURVE_KINDS:
        raise InputError(Problem.BAD_STATE, "bifurcation", bifurcation.kind,
                         why="is followed in one parameter only",
                         fix="pass a fold or a grazing (Branch.folds(), or kind 'grazing' in "
                             "Branch.bifurcations)")
    on_forcing = (bifurcation.parameter in ("freq_hz", "a_g") if bifurcation.parameter else
                  any(math.isclose(bifurcation.value, v, rel_tol=1e-12)
                      for v in (bifurcation.freq_hz, bifurcation.a_g)))
    if not on_forcing:
        raise InputError(Problem.BAD_STATE, "bifurcation", bifurcation.kind,
                         why="is on a branch in a number of the " "system, not in the forcing",
                         fix="continue the branch in 'freq_hz' or 'a_g' and pass its " "bifurcation")
    try:
        check_state(bifurcation.state, system)
    except InputError as exc:
        raise InputError(Problem.BAD_STATE, "bifurcation", bifurcation.kind,
                         why=f"is not of this system ({exc})",
                         fix="pass the system the branch was followed on") from None
    if bifurcation.kind == "grazing":
        sides = _Shooter(system, Harmonic(bifurcation.a_g, bifurcation.freq_hz), 1.0 / bifurcation.freq_hz,
                         False).sides()
        if bifurcation.side not in sides:
            raise InputError(Problem.BAD_STATE, "bifurcation.side", bifurcation.side,
                             why=f"names no one contact of this system (its contacts: {', '.join(sides)})",
                             fix="follow one contact's grazing at a time, e.g. "
                                 f"dataclasses.replace(bifurcation, side={sides[0]!r})" if sides else
                                 "a system without contacts has no grazing")
    a_box = _box("a_g", a_g, "g")
    f_box = _box("freqs_hz", freqs_hz, "Hz")
    for name, box, v in (("a_g", a_box, bifurcation.a_g), ("freqs_hz", f_box, bifurcation.freq_hz)):
        if not box[0] <= v <= box[1]:
            raise InputError(Problem.OUT_OF_RANGE, name, box, range=f"a range holding {v:g}",
                             hint=" (the bifurcation's own value)")
    tol, max_step, max_points, exact = _common(system, tol, max_step, max_points, method)
    try:
        return _curve(system, bifurcation, f_box, a_box, tol, max_step, max_points, exact)
    except _NoStart as exc:
        raise InputError(Problem.BAD_STATE, "bifurcation", bifurcation.kind, why=str(exc),
                         fix="locate it again: continue the branch with a smaller max_step") from None


class _NoStart(_Failed):
    """The bifurcation could not be solved as a point of its curve (a fold where the branch turns at
    a grazing has no multiplier 1 to hold): ``bifurcation_curve`` says so as an ``InputError``
    (the caller gave it), ``coexistence_map`` as a note (it found it)."""


def _curve(oscillator: Oscillator, bifurcation: Bifurcation, f_box: tuple, a_box: tuple, tol: float,
           max_step: float, max_points: int, exact: bool) -> BifurcationCurve:
    """The curve through ``bifurcation``, its arguments checked; raises ``_NoStart``."""
    pts: list[CurvePoint] = []
    follower = None
    try:
        with hy.one_blas_thread():
            follower = _follower(oscillator, bifurcation, f_box, a_box, tol, max_step, exact)
            start = _start(follower, bifurcation)
            pts = [start]
            status, message = _follow(follower, start, pts, max_points)
    except (KeyboardInterrupt, Interrupted):
        raise Interrupted(_result(oscillator, bifurcation, follower, pts, f_box, a_box, Status.INTERRUPTED,
                                  "interrupted"), len(pts), None, "points") from None
    return _result(oscillator, bifurcation, follower, pts, f_box, a_box, status, message)


@renamed_keyword("oscillator", "system")
def coexistence_map(
    system: Any,
    *,
    a_g: Any = (0.02, 0.12),
    freqs_hz: Any = (0.5, 5.0),
    levels: Optional[Sequence[float]] = None,
    freq_step_hz: float = 0.1,
    kinds: Sequence[str] = CURVE_KINDS,
    max_step: float = 0.02,
    max_points: int = 500,
    tol: float = 1e-9,
    method: str = "auto",
    sweeps: Any = None,
    basin_sample: int = 4,
    test_freqs_hz: Any = None,
    progress: Any = False,
) -> CoexistenceMap:
    """Where two responses coexist: branches at a_G ``levels``, their folds and grazings followed
    in (a_G, f), and each point of the test matrix judged by its witnesses.

    A branch counts the stable orbits on itself only: it cannot show that a point has one response
    (another branch or an isola is not followed), and says nothing where it did not reach.  Each test
    point is therefore judged by the branch, the ``sweeps`` (two settled steps on different responses
    show two) and a basin sample (:func:`pounding.basins` on a ``basin_sample`` x ``basin_sample``
    grid of initial states); ``verdict`` is "coexist" (some witness shows two or more), "one" (the basin
    sample, every state of it settled, found one response and the branch or the sweeps agree), "one on
    the branch" (no sample taken) or "not assessed", and ``evidence`` says what each witness showed.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system.  A structure's branches, curves and basin samples are those of
        :func:`continuation`, :func:`bifurcation_curve` and :func:`pounding.basins` for it (a response
        read by its largest alpha over every level and its first moving mass's excursion).
    a_g : (float, float)
        The map's range of a_G, g.
    freqs_hz : (float, float)
        The map's range of the frequency, Hz (the branches span it).
    levels : sequence of float, optional
        The a_G of the branches (the test matrix's rows).  Default: the paper's 0.03, 0.05,
        0.075 and 0.1 that lie in ``a_g`` (or four levels spread over it).
    freq_step_hz : float
        The test matrix's frequency step, from ``freqs_hz[0]`` (the paper's 0.1 Hz).
    kinds : sequence of {"fold", "grazing"}
        The bifurcations followed.
    max_step : float
        Largest arclength step, as in :func:`bifurcation_curve`; also the branches'
        (:func:`continuation`).
    max_points : int
        Points at most per curve, as in :func:`bifurcation_curve`.
    tol : float
        Largest scaled residual of each curve's points, as in :func:`bifurcation_curve`.
    method : {"auto", "exact", "finite-difference"}
        The monodromy, as in :func:`periodic_orbit`; also the branches'.
    sweeps : sequence of SweepResult, or CampaignResult, optional
        Sweeps of this system at the levels (up and down): witnesses at their frequencies (a
        structure's: :func:`pounding.sweep` of it).  Each settled period-1 step that the level's
        branch does not pass through starts a short branch of its own (``seeded``), from the step's
        exact state to half way to its neighbouring steps: every settled period-1 step then lies on a
        branch (``steps`` says which, and why a step lies off every one: another period, not settled).
    basin_sample : int
        Points per axis of the basin sample run at each test point (0: none; then a branch's single
        stable orbit is only "one on the branch").
    test_freqs_hz : sequence of float, optional
        The test matrix's frequencies (default: from ``freqs_hz[0]`` by ``freq_step_hz``).
    progress : bool or callable
        True: a progress bar over the basin samples.

    Returns
    -------
    CoexistenceMap
        ``branches``, ``curves``, ``matrix`` (one row per level and frequency: ``stable_orbits`` on
        the branch, NaN where it did not reach, ``sweep_responses``, ``basin_responses``,
        ``responses``, ``verdict``, ``evidence``), ``seeded`` and ``steps`` (with ``sweeps``),
        ``.plot()``, ``.to_dataframe()``.

    Raises
    ------
    Interrupted
        On Ctrl-C; ``.partial`` is the map of the branches and curves finished (and the one under
        way, cut short).

    Examples
    --------
    The damped paper system at a_G = 0.05, from 1.5 to 2.5 Hz by 0.1 Hz: two stable responses
    coexist at four of the test frequencies.

    >>> import pounding
    >>> m = pounding.coexistence_map(pounding.presets.paper_damped(),
    ...                              a_g=(0.04, 0.06), freqs_hz=(1.5, 2.5),
    ...                              levels=[0.05], kinds=["fold"], max_step=0.05)
    >>> int(m.matrix["stable_orbits"].max()), len(m.coexisting())
    (2, 4)
    >>> m.matrix["verdict"].value_counts().to_dict()
    {'one': 7, 'coexist': 4}
    """
    check_system(system)
    a_box = _box("a_g", a_g, "g")
    f_box = _box("freqs_hz", freqs_hz, "Hz")
    if levels is None:
        levels = [v for v in PAPER_YBS_A_G if a_box[0] <= v <= a_box[1]] or list(np.linspace(*a_box, 4))
    levels = _sequence("levels", levels, "a_G values, g")
    levels = [real(f"levels[{i}]", v) for i, v in enumerate(levels)]
    for i, v in enumerate(levels):
        if not a_box[0] <= v <= a_box[1]:
            raise InputError(Problem.OUT_OF_RANGE, f"levels[{i}]", v, range=f"[{a_box[0]:g}, {a_box[1]:g}]",
                             hint=" (the map's a_g range)")
        if v in levels[:i]:
            raise InputError(Problem.DUPLICATE, "levels", levels, repeated=f"{v:g}")
    step = real("freq_step_hz", freq_step_hz)
    width = f_box[1] - f_box[0]
    if not width / MAX_TEST_FREQS <= step <= width:
        raise InputError(Problem.OUT_OF_RANGE, "freq_step_hz", step,
                         range=f"[{width / MAX_TEST_FREQS:g}, {width:g}]",
                         hint=f" (the test matrix's frequency step: at most {MAX_TEST_FREQS} frequencies)")
    kinds = _sequence("kinds", kinds, "'fold' and/or 'grazing'")
    if not all(isinstance(k, str) for k in kinds):
        raise InputError(Problem.WRONG_TYPE, "kinds", kinds, got=type(kinds).__name__,
                         expected="a sequence of 'fold', 'grazing'")
    kinds = tuple(dict.fromkeys(one_of("kinds", k, CURVE_KINDS) for k in kinds))
    tol, max_step, max_points, exact = _common(system, tol, max_step, max_points, method)
    witnesses = check_sweeps(sweeps, system)
    basin_sample = check_basin_sample(basin_sample)
    if test_freqs_hz is None:
        freqs = np.round(np.arange(f_box[0], f_box[1] + 1e-9 * step, step), 10)
    else:
        freqs = np.sort(np.asarray([real(f"test_freqs_hz[{i}]", v) for i, v in
                                    enumerate(_sequence("test_freqs_hz", test_freqs_hz, "frequencies, Hz"))]))
    branches: list[Branch] = []
    seeded: list[Branch] = []
    steps: list[pd.DataFrame] = []
    curves: list[BifurcationCurve] = []
    notes: list[str] = []
    try:
        for level in levels:
            br = _level_branch(system, level, f_box, max_step, method, notes)
            branches.append(br)
            own = [sw for sw in witnesses if math.isclose(sw.a_g, level, rel_tol=1e-9)]
            if own:  # (every settled step of the level's sweeps on a branch, or said to be off)
                more, table = through_sweeps(system, own, [br], f_box, method)
                seeded.extend(more)
                steps.append(table)
            for bif in br.bifurcations:
                if bif.kind in kinds and not any(c.passes(bif) for c in curves):
                    try:
                        curves.append(_curve(system, bif, f_box, a_box, tol, max_step, max_points, exact))
                    except _NoStart as exc:
                        notes.append(f"the {bif.kind} at {bif.freq_hz:.6g} Hz, a_G {bif.a_g:g} was not "
                                     f"followed: {exc}")
    except (Interrupted, KeyboardInterrupt) as exc:
        partial = getattr(exc, "partial", None)
        if isinstance(partial, BifurcationCurve):
            curves.append(partial)
        elif isinstance(partial, Branch):
            branches.append(partial)
        raise Interrupted(CoexistenceMap(system, a_box, f_box, tuple(levels), tuple(branches),
                                         tuple(curves),
                                         judge_matrix(system, branches, freqs, sweeps=witnesses,
                                                      basin_sample=0, seeded=seeded),
                                         tuple(notes), tuple(seeded), _steps(steps)),
                          len(curves), None, "curves") from None
    try:
        matrix = judge_matrix(system, branches, freqs, sweeps=witnesses, basin_sample=basin_sample,
                              progress=progress, seeded=seeded)
    except Interrupted as exc:
        raise Interrupted(CoexistenceMap(system, a_box, f_box, tuple(levels), tuple(branches),
                                         tuple(curves), exc.partial, tuple(notes), tuple(seeded),
                                         _steps(steps)), len(curves), None, "curves") from None
    return CoexistenceMap(system, a_box, f_box, tuple(levels), tuple(branches), tuple(curves), matrix,
                          tuple(notes), tuple(seeded), _steps(steps))


def _steps(tables: list[pd.DataFrame]) -> pd.DataFrame:
    return (pd.concat(tables, ignore_index=True) if tables
            else pd.DataFrame(columns=list(STEP_COLUMNS)))


# ---------------------------------------------------------------------- pieces
def _level_branch(osc: Any, level: float, f_box: tuple, max_step: float, method: str,
                  notes: list[str]) -> Branch:
    """The branch at ``level`` over the map's frequencies, started at the low end, else (no periodic
    response settles there to start from) at the high end, which ``notes`` then says."""
    try:
        return continuation(osc, level, f_box, max_step=max_step, method=method)
    except InputError as low:
        if low.field != "freqs_hz":
            raise
        try:
            branch = continuation(osc, level, f_box[::-1], max_step=max_step, method=method)
            notes.append(f"the branch at a_G {level:g} was started at {f_box[1]:g} Hz: no periodic response "
                         f"settled at {f_box[0]:g} Hz to start it from")
            return branch
        except InputError as high:
            if high.field != "freqs_hz":
                raise
        raise InputError(Problem.BAD_STATE, "levels", level,
                         why=f"has no periodic response to start its branch from at {f_box[0]:g} Hz nor at "
                             f"{f_box[1]:g} Hz (Newton did not converge from the responses settled there)",
                         fix="leave this a_G out of levels, or narrow freqs_hz") from None


def _sequence(field: str, value: Any, what: str) -> list:
    """A non-empty list, or an InputError naming ``field`` (a string, a mapping, a scalar or a 0-d
    array is none)."""
    if isinstance(value, (str, bytes, Mapping)) or np.ndim(value) != 1:
        raise InputError(Problem.WRONG_TYPE, field, value, got=type(value).__name__,
                         expected=f"a sequence of {what}")
    out = list(value)
    if not out:
        raise InputError(Problem.EMPTY, field, value)
    return out


def _box(field: str, value: Any, unit: str) -> tuple[float, float]:
    if isinstance(value, (str, bytes, Mapping)) or np.ndim(value) != 1:
        raise InputError(Problem.WRONG_TYPE, field, value, got=type(value).__name__,
                         expected=f"pair (low, high) in {unit}")
    if len(value) != 2:
        raise InputError(Problem.LENGTH_MISMATCH, field, value, got=len(value), expected=2,
                         hint=f": (low, high) in {unit}")
    lo, hi = sorted(real(f"{field}[{i}]", v) for i, v in enumerate(value))
    if not 0.0 < lo < hi:
        raise InputError(Problem.OUT_OF_RANGE, field, value, range="0 < low < high",
                         hint=f" (a range of positive values, {unit})")
    return lo, hi


def _common(osc: Oscillator, tol: Any, max_step: Any, max_points: Any, method: Any) -> tuple:
    tol = tolerance(tol, 1e-13, 1e-3, 1e-9)
    max_step = step_size(max_step, 1e-4, "the ranges")
    max_points = integer("max_points", max_points, 2, 100_000, "a curve of 2000 points is already dense")
    return tol, max_step, max_points, exact_monodromy(osc, method)


def _follower(osc: Any, bif: Bifurcation, f_box: tuple, a_box: tuple, tol: float, max_step: float,
              exact: bool) -> CurveFollower:
    fam = Family(osc, bif.a_g, bif.freq_hz, "freq_hz", bif.period_multiple, exact, bif.phase_rad,
                 1.0, f_box[1] - f_box[0], 2.0 * math.pi * bif.freq_hz)
    try:
        _, run = fam._ref._image(np.array(bif.state.vector, dtype=float))  # (a period from the bifurcation)
    except _Failed as exc:
        raise _NoStart(f"a period from its state does not run ({exc})") from None
    fam.set_length(length_scale(osc, run))
    return CurveFollower(fam, bif.kind, bif.side, f_box, a_box, tol, max_step)


def _start(cf: CurveFollower, bif: Bifurcation) -> CurvePoint:
    """The bifurcation solved as a point of the curve (a_g held, else f), with its tangent."""
    vec = np.array(bif.state.vector, dtype=float)
    n = cf.fam.n
    for held in (-1, -2):
        normal = np.zeros(n + 2)
        normal[held] = 1.0
        target = np.concatenate((cf.fam.coords(vec) / cf.fam.scales, [bif.freq_hz / cf.fs, bif.a_g / cf.as_]))
        pt = cf.correct(vec, bif.freq_hz, bif.a_g, target, normal, max_iter=30)
        if pt is not None:
            t = np.linalg.svd(pt.ext)[2][-1]
            tau = cf._full(pt, t)
            pt.tau = tau / np.linalg.norm(tau)
            return pt
    raise _NoStart(f"at {bif.freq_hz:.6g} Hz, a_g {bif.a_g:.6g} could not be solved as a point of its "
                   "curve (Newton did not converge)")


def _follow(cf: CurveFollower, start: CurvePoint, pts: list[CurvePoint], max_points: int) -> tuple[Status,
                                                                                                   str]:
    """Both directions from ``start``; ``pts`` filled in the curve's order as they come."""
    ends = []
    for sign in (1.0, -1.0):
        got: list[CurvePoint] = []
        try:
            how, closed = cf.follow(start, sign, max_points - len(pts), got)
        finally:  # (on Ctrl-C too: the points found are kept)
            if sign > 0:
                pts.extend(got)
            else:
                pts[:0] = got[::-1]
        ends.append(how)
        if closed:
            return Status.SUCCESS, "the curve closed on itself"
    if "budget" in ends:
        return Status.BUDGET, f"stopped at max_points = {max_points}"
    failed = [e for e in ends if e not in ("edge", "closed")]
    if failed:
        return Status.STEP_FAILED, "; ".join(failed)
    return Status.SUCCESS, "both ends reached the edge of the box"


def _result(osc: Oscillator, bif: Bifurcation, cf: Optional[CurveFollower], pts: list[CurvePoint],
            f_box: tuple, a_box: tuple, status: Status, message: str) -> BifurcationCurve:
    table, states = curve_table(pts, cf.fam._ref if cf is not None else None)
    if cf is not None and cf.fam.fell_back:
        message += cf.fam.fell_back
    return BifurcationCurve(osc, bif.kind, bif.side, bif.period_multiple, f_box, a_box, table, states, status,
                            message, bif)

