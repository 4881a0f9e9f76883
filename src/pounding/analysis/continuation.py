"""``continuation``: a branch of periodic orbits followed in one parameter by pseudo-arclength,
through its folds, with its bifurcations detected and located.

Each point solves the shooting problem of :func:`periodic_orbit` at a fixed forcing angle (the
state at time 0 under ``Harmonic(a_g, f, phase=phase_rad)``), with the exact monodromy where
the system allows it.  Between two points the detectors watch:

- the tangent's parameter part changing sign: a **fold** (the branch turns back);
- the real multipliers below -1 changing in number: a **period-doubling**;
- the complex multipliers outside the unit circle changing in number: a **Neimark-Sacker** point;
- the orbit's smallest clearance to a bumper (``gap - max D``, negative in contact) changing
  sign: a **grazing**;

and each is located by regula falsi (Illinois) on the arclength step, its test function's zero
to 1e-8, or the step's interval to 1e-9 of the step where the function jumps (a
non-smooth system's multipliers can jump at a grazing).
"""

from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from .._checks import instance_of, integer, positive, real
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from ..engine import State
from ..engine.assembly import check_system
from ..engine.simulate import check_state, short_run
from ..model.dotted import why_unresolved
from . import _hybrid as hy
from ._arclength import Family, system_at
from ._follower import Follower
from .branch import Bifurcation, Branch
from ._args import exact_monodromy, length_scale, section_angle, settled, step_size, tolerance

MAX_POINTS = 100_000


@renamed_keyword("oscillator", "system")
def continuation(
    system: Any,
    a_g: Any,
    freqs_hz: Any,
    *,
    parameter: str = "freq_hz",
    values: Optional[tuple[float, float]] = None,
    period_multiple: int = 1,
    guess: "State | Bifurcation | None" = None,
    tol: float = 1e-10,
    max_step: float = 0.02,
    max_points: int = 5000,
    phase_rad: float = 0.0,
    method: str = "auto",
    settle_cycles: int = 100,
    f_ref_hz: float = 1.0,
) -> Branch:
    """Follow a branch of periodic orbits through its folds, with its bifurcations.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system: a single mass, a structure or two adjacent ones.
    a_g : float or (float, float)
        The table's peak acceleration, g; ``(start, end)`` with ``parameter="a_g"``.
    freqs_hz : (float, float) or float
        The forcing frequency's range ``(start, end)``, Hz, with ``parameter="freq_hz"``
        (either order: the branch starts at ``start``); one frequency otherwise.
    parameter : str
        What varies: ``"freq_hz"``, ``"a_g"`` or a dotted name of a number of the system
        (``"bumpers.gap_left_m"``, ``"isolator.damping_n_s_m"``, ``"bumpers.law.stiffness"``), whose
        range is then ``values``.
    values : (float, float), optional
        The range of a system number continued (``parameter`` a dotted name).
    period_multiple : int
        The orbits' period in forcing periods.
    guess : State or Bifurcation, optional
        Where to start: an orbit's state at the start value under ``Harmonic(a_g, f,
        phase=phase_rad)`` at the state's time (e.g. a run's ``final_state``; the section is moved
        to time 0 with the forcing's angle there), or a ``"period-doubling"`` or
        ``"branch-point"`` :class:`Bifurcation` of another branch, whose other branch (of twice
        the period, for a period-doubling) is followed from there (``period_multiple`` and the
        range's start are then the bifurcation's).  Default: the state after ``settle_cycles`` periods from
        rest at the
        start value (the response a sweep would settle on).
    tol : float
        Largest scaled residual accepted at each point (lengths over the scale of the
        branch: half the narrowest total gap, or the first orbit's largest ``|x|`` if larger).
    max_step : float
        Largest arclength step, in units where the parameter's range is 1 (0.02: at least 50
        points over the range).
    max_points : int
        Points at most (the branch stops there with status ``BUDGET``).
    phase_rad : float
        The forcing's angle at the section, rad.
    method : {"auto", "exact", "finite-difference"}
        The monodromy, as in :func:`periodic_orbit`.
    settle_cycles : int
        Forcing periods run from rest for the default guess.
    f_ref_hz : float
        The frequency ``nu`` is relative to in the table (the paper's 1 Hz).

    Returns
    -------
    Branch
        ``status`` ``SUCCESS`` when the branch reached an end of the range (the start's, after
        a fold, or the end's), ``STEP_FAILED`` when the corrector failed at the smallest step
        (``message`` says where), ``BUDGET`` at ``max_points``.

    Raises
    ------
    Interrupted
        On Ctrl-C; ``.partial`` is the branch followed so far.

    Examples
    --------
    The damped paper system at a_G = 0.05 from 1 to 3 Hz: the asymmetric orbits fold at 1.237 Hz
    (next to the branch point where they meet the symmetric branch), and the impacting branch
    folds at 2.014 Hz and back at 1.605 Hz, the folds that bracket the sweeps' jumps.

    >>> import pounding
    >>> branch = pounding.continuation(pounding.presets.paper_damped(), 0.05,
    ...                                (1.0, 3.0))
    >>> branch.status.name
    'SUCCESS'
    >>> [round(b.freq_hz, 3) for b in branch.folds()]
    [1.237, 2.014, 1.605]
    """
    check_system(system)
    parameter, values, a_g, freq_hz = _check_range(system, parameter, a_g, freqs_hz, values)
    period_multiple = integer("period_multiple", period_multiple, 1, 64,
                              "give the orbits' period in forcing periods")
    tol = tolerance(tol, 1e-14, 1e-3, 1e-10)
    max_step = step_size(max_step, 1e-5, "the parameter's range")
    max_points = integer("max_points", max_points, 2, MAX_POINTS, "a branch of 5000 points is already dense")
    phase_rad = section_angle(phase_rad)
    settle_cycles = integer("settle_cycles", settle_cycles, 1, 100_000, "give a guess instead")
    f_ref_hz = positive("f_ref_hz", f_ref_hz, "Hz")
    exact = exact_monodromy(system, method)
    if isinstance(guess, Bifurcation):
        if guess.kind not in ("period-doubling", "branch-point"):
            raise InputError(Problem.BAD_STATE, "guess", guess,
                             why=f"is a {guess.kind}; only a period-doubling or "
                             "a branch point starts another branch", fix="pass a Bifurcation of kind "
                             "'period-doubling' or 'branch-point', or a State")
        held = {"freq_hz": ("a_g", guess.a_g, a_g), "a_g": ("freqs_hz", guess.freq_hz,
                                                            freq_hz)}.get(parameter)
        if held is not None and not math.isclose(held[1], held[2], rel_tol=1e-12):
            raise InputError(Problem.BAD_STATE, "guess", guess,
                             why=f"is a bifurcation at {held[0]} = {held[1]:g}, "
                             f"not the {held[2]:g} given",
                             fix=f"give {held[0]} = {held[1]:g} (the bifurcation's)")
        if not min(values) <= guess.value <= max(values):
            raise InputError(Problem.OUT_OF_RANGE, "guess", guess,
                             range=f"[{min(values):g}, {max(values):g}]",
                             hint=f" (the range of {parameter} given: the bifurcation is at {guess.value:g})")
        gap = float(np.min(np.abs(guess.multipliers + 1.0))) if guess.multipliers.size else math.inf
        if guess.kind == "period-doubling" and gap > 1e-3:
            raise InputError(Problem.BAD_STATE, "guess", guess,
                             why="is a period-doubling where the multipliers jump across -1 (the nearest is "
                                 f"{gap:.2g} from it): a discontinuity of the map (a contact appearing or a "
                                 "mode changing there), from which no doubled branch starts smoothly",
                             fix="look for the doubled response with a sweep (its period_multiple) or a "
                             "periodic_orbit of period_multiple=2 from a sweep's state")
        period_multiple = guess.period_multiple * (2 if guess.kind == "period-doubling" else 1)
        phase_rad = guess.phase_rad
    elif guess is not None and not isinstance(guess, State):
        raise InputError(Problem.WRONG_TYPE, "guess", guess, got=type(guess).__name__,
                         expected="pounding.State, or a period-doubling or branch-point Bifurcation")
    p0, p1 = values
    p_start = guess.value if isinstance(guess, Bifurcation) else p0
    start_osc = system_at(system, parameter, p_start)
    fam_a_g = p_start if parameter == "a_g" else a_g
    fam_f = p_start if parameter == "freq_hz" else freq_hz
    f_mid = math.sqrt(p0 * p1) if parameter == "freq_hz" else freq_hz
    if isinstance(guess, State):  # (its section: the forcing's angle at its time)
        phase_rad = section_angle((phase_rad + 2.0 * math.pi * fam_f * guess.time_s) % (2.0 * math.pi))
    fam = Family(start_osc, fam_a_g, fam_f, parameter, period_multiple, exact,
                 phase_rad, 1.0, abs(p1 - p0), 2.0 * math.pi * f_mid)
    vec = _start_vector(start_osc, fam._ref, fam_a_g, fam_f, phase_rad, guess, settle_cycles)
    fam.set_length(length_scale(start_osc, _first_run(fam._ref, fam_a_g, fam_f, phase_rad, vec,
                                                      period_multiple)))
    follower = Follower(fam, p0, p1, tol, max_step, max_points, f_ref_hz)
    follower.doubled = isinstance(guess, Bifurcation) and guess.kind == "period-doubling"
    try:
        with hy.one_blas_thread():
            try:
                follower.start(vec, p_start, guess if isinstance(guess, Bifurcation) else None)
            except InputError as exc:
                if guess is not None:
                    raise
                field_name = {"freq_hz": "freqs_hz", "a_g": "a_g"}.get(parameter, "values")
                raise InputError(Problem.BAD_STATE, field_name, values,
                                 why=f"gives no periodic orbit of {period_multiple} period(s) to start "
                                     f"from at {p_start:g}: Newton did not converge from the response "
                                     f"settled over {settle_cycles} periods from rest there",
                                 fix="start the branch at the range's other end (give it reversed), raise "
                                     "settle_cycles, or give a guess (a sweep's window state)") from exc
            follower.follow()
    except KeyboardInterrupt:
        raise Interrupted(follower.branch(system, values, Status.INTERRUPTED, "interrupted"),
                          len(follower.points), None, "points") from None
    return follower.branch(system, values, follower.status, follower.message)


# ---------------------------------------------------------------------- arguments
def _pair(field: str, value: Any, unit: str) -> tuple[float, float]:
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
        raise InputError(Problem.WRONG_TYPE, field, value, got=type(value).__name__,
                         expected=f"pair (start, end) in {unit}")
    pair = (real(f"{field}[0]", value[0]), real(f"{field}[1]", value[1]))
    if pair[0] == pair[1]:
        raise InputError(Problem.BAD_STATE, field, value, why="starts where it ends",
                         fix="give two different values (start, end)")
    return pair


def _check_range(osc: Any, parameter: Any, a_g: Any, freqs_hz: Any, values: Any) -> tuple:
    instance_of("parameter", parameter, str,
                "str ('freq_hz', 'a_g' or a dotted name such as 'bumpers.gap_left_m')")
    if parameter == "freq_hz":
        pair = _pair("freqs_hz", freqs_hz, "Hz")
        for i, f in enumerate(pair):
            positive(f"freqs_hz[{i}]", f, "Hz")
        return parameter, pair, positive("a_g", a_g, "g"), math.nan
    if parameter == "a_g":
        pair = _pair("a_g", a_g, "g")
        for i, v in enumerate(pair):
            positive(f"a_g[{i}]", v, "g")
        return parameter, pair, math.nan, positive("freqs_hz", freqs_hz, "Hz")
    why = why_unresolved(osc.to_dict(), parameter)
    if why is not None:
        raise InputError(Problem.BAD_STATE, "parameter", parameter,
                         why=f"names no number of the system: {why}",
                         fix="give 'freq_hz', 'a_g' or a dotted name such as 'bumpers.gap_left_m'")
    if values is None:
        raise InputError(Problem.MISSING_INPUT, "values", None, what=f"the range (start, end) of {parameter}")
    pair = _pair("values", values, "the parameter's unit")
    for i, v in enumerate(pair):
        try:
            system_at(osc, parameter, v)
        except InputError as exc:
            raise InputError(Problem.BAD_STATE, f"values[{i}]", v, why=f"makes no system ({exc})",
                             fix=f"give values of {parameter} the system can have") from None
    return parameter, pair, positive("a_g", a_g, "g"), positive("freqs_hz", freqs_hz, "Hz")


def _start_vector(osc: Any, sh: Any, a_g: float, freq_hz: float, phase: float, guess: Any,
                  settle_cycles: int) -> np.ndarray:
    """The first orbit's guess at the section (``sh``: the family's shooter, for the system's layout)."""
    from ..excitation import Harmonic

    if isinstance(guess, Bifurcation):
        return np.array(guess.state.vector, dtype=float)
    if isinstance(guess, State):
        try:
            guess = check_state(guess, osc)
        except InputError as exc:
            raise InputError(Problem.BAD_STATE, "guess", guess, why=f"is not a state of this system ({exc})",
                             fix="give a state of this system, e.g. a run's final_state") from None
        return sh.at_section(guess.vector)
    return sh.at_section(settled(osc, Harmonic(a_g, freq_hz, phase=phase), settle_cycles).final_state.vector)


def _first_run(sh: Any, a_g: float, freq_hz: float, phase: float, vec: np.ndarray, k: int) -> Any:
    from ..excitation import Harmonic

    state = sh._state(vec)
    run = short_run(sh.model, Harmonic(a_g, freq_hz, phase=phase), k / freq_hz, state, sh.asm)
    if not run.success:
        raise InputError(Problem.BAD_STATE, "guess", state, why=f"cannot be shot from: {run.message}",
                         fix="start from another state, or a smaller a_g")
    return run
