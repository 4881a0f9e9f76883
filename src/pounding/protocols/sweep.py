"""Stepped-sine sweeps (docs/paper.md): the virtual shaking table, one frequency after another.

:func:`sweep` validates, builds a :class:`SweepPlan` and runs it; the plan is plain data
and :func:`run_plan` needs nothing else, so campaigns hand plans to worker threads.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from .._checks import at_least, at_most, float_array, integer, one_of, plausible, positive
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from ..engine import State
from ..engine.layout import T
from ..engine.control import (DEFAULT_MAX_STEPS, check_budget, fastest_rate, new_control,
                               run_interruptibly, steps_per_second, stop_requested)
from ..engine.simulate import check_rtol, check_state
from ..excitation import MAX_FREQ_HZ, GRAVITY_M_S2, Harmonic
from ..model import MeasurementChain, Oscillator
from ..engine.assembly import assemble, check_system, is_single_mass
from .._runner.progress import Progress, progress_reporter
from ..engine.kernels import W_CYCLES, W_EVENTS, W_STICKS, StepOutput, run_step, run_window
from ..metrics.impacts import SIDE_SUMS
from .sweep_result import SweepResult
from .sweep_window import (check_adaptive_window, check_steady_rtol, from_step, labels_of, measure,
                           slot_masses, step_measures_all, strobes)

if TYPE_CHECKING:  # pragma: no cover
    from ..model import Adjacent, Structure

Direction = Literal["up", "down"]
SteadyMode = Literal["adaptive", "fixed"]

from ..data import PAPER_F_REF_HZ, PAPER_OMEGA_MIN_RAD_S  # noqa: E402  (the paper's conventions)
MAX_STEPS_PER_SWEEP = 100_000
MAX_CYCLES_PER_STEP = 1_000_000


def paper_frequencies_hz() -> np.ndarray:
    """The paper's steps: 0.5 to 5.0 Hz by 0.1 Hz (46 values).

    Returns
    -------
    ndarray, shape (46,)
        The step frequencies in Hz, increasing (what :func:`sweep` and :func:`campaign` step
        through by default).

    Examples
    --------
    >>> import pounding
    >>> freqs = pounding.paper_frequencies_hz()
    >>> len(freqs), float(freqs[0]), float(freqs[-1])
    (46, 0.5, 5.0)
    >>> round(float(freqs[1] - freqs[0]), 3)  # the step, Hz
    0.1
    """
    return np.arange(5, 51) / 10.0


@dataclass(frozen=True, eq=False)
class SweepPlan:
    """Everything a sweep needs, validated (build it with :func:`sweep` or :func:`make_plan`).

    ``freqs_hz`` is in stepping order.  ``cycles`` is the number of cycles per step in the
    fixed mode and the maximum in the adaptive mode.
    """

    oscillator: Oscillator
    a_g: float
    freqs_hz: np.ndarray
    direction: str
    steady: str
    cycles: int
    measure_cycles: int
    steady_rtol: float
    max_period: int
    omega_min_rad_s: float
    f_ref_hz: float
    rtol: float
    max_events_per_cycle: int
    state: State | None
    max_steps: int
    measurement: MeasurementChain | None = None

    def step(self, system: Any, freq_hz: float, start: np.ndarray,
             control: np.ndarray) -> tuple[Harmonic, StepOutput]:
        """One step at ``freq_hz`` from the state ``start``, in the core (``system``: the plan's, as the core
        takes it): its excitation and what the step gave; a single mass's sweep and a structure's run their
        steps alike."""
        exc = Harmonic(self.a_g, freq_hz)
        steady = (self.steady == "adaptive", int(self.cycles), int(self.measure_cycles),
                  float(self.steady_rtol), int(self.max_period))
        return exc, run_step(system, exc.peak_m_s2, exc.omega_rad_s, start, steady, self.rtol,
                             self.max_events_per_cycle, control)

    def steps(self, system: Any, state: np.ndarray, control: np.ndarray,
              advance: Callable[[int], None] | None,
              take: Callable[[int, float, np.ndarray, Harmonic, StepOutput], int],
              ) -> tuple[np.ndarray, int, Status, bool]:
        """Every step of the plan in its order from ``state`` (a single mass's sweep and a structure's
        alike): ``take(i, freq_hz, start, excitation, step)`` keeps step ``i`` and returns its status (a
        structure's measured window may end it); ``advance(1)`` after each. A step that did not finish
        (a stop from ``control``, a KeyboardInterrupt) is dropped, and a status other than success ends
        the sweep. Returns (the state after the last finished step, the steps finished, the status,
        whether it was interrupted)."""
        status, done, interrupted = Status.SUCCESS, 0, False
        try:
            for i, f in enumerate(self.freqs_hz):
                if stop_requested(control):
                    interrupted = True
                    break
                exc, stepped = self.step(system, f, state, control)
                code = stepped.status
                if code != Status.INTERRUPTED:
                    code = take(i, f, state, exc, stepped)
                if code == Status.INTERRUPTED:  # (the step did not finish: dropped)
                    interrupted = True
                    break
                state = stepped.state
                done = i + 1
                if advance is not None:
                    advance(1)
                if code != Status.SUCCESS:
                    status = Status(int(code))
                    break
        except KeyboardInterrupt:
            interrupted = True
        return state, done, status, interrupted


@dataclass(frozen=True)
class SweepOptions:
    """The options of a sweep besides its system, level, frequencies, direction and start: one
    list with one set of defaults, which :func:`sweep`, :func:`make_plan`, :func:`campaign` and
    :func:`identify` take by name (their meaning: :func:`sweep`'s parameters)."""

    steady: SteadyMode = "adaptive"
    cycles: int | None = None
    measure_cycles: int = 5
    max_cycles: int | None = None
    steady_rtol: float = 1e-6
    max_period: int = 8
    omega_min_rad_s: float = PAPER_OMEGA_MIN_RAD_S
    f_ref_hz: float = PAPER_F_REF_HZ
    rtol: float = 1e-10
    max_events_per_cycle: int = 1_000_000
    max_steps: int = DEFAULT_MAX_STEPS
    measurement: MeasurementChain | None = None


# their names, in order (campaign, identify and studies pass them on)
SWEEP_OPTIONS = tuple(f.name for f in fields(SweepOptions))


def check_sweep_options(options: dict[str, Any], also: str = "") -> SweepOptions:
    """``options`` (keyword arguments) as :class:`SweepOptions`; an unknown name is an
    :class:`InputError` listing the known ones (and ``also``: the caller's own, if any)."""
    unknown = sorted(set(options) - set(SWEEP_OPTIONS))
    if unknown:
        raise InputError(Problem.UNKNOWN_KEY, unknown[0], options[unknown[0]],
                         choices=", ".join(SWEEP_OPTIONS) + (f" (sweep options), or {also}" if also else ""))
    return SweepOptions(**options)


def make_plan(oscillator: Oscillator, a_g: float, freqs_hz: np.ndarray | None = None,
              direction: str = "up", state: State | None = None, **options: Any) -> SweepPlan:
    """Validate the arguments of :func:`sweep` into a plan (same parameters; ``options``:
    :class:`SweepOptions`' names)."""
    opts = check_sweep_options(options)
    (steady, cycles, measure_cycles, max_cycles, steady_rtol, max_period, omega_min_rad_s, f_ref_hz,
     rtol, max_events_per_cycle, max_steps, measurement) = (getattr(opts, name) for name in SWEEP_OPTIONS)
    if measurement is not None and not isinstance(measurement, MeasurementChain):
        raise InputError(Problem.WRONG_TYPE, "measurement", measurement, got=type(measurement).__name__,
                         expected="pounding.MeasurementChain or None (the exact metrics)")

    check_system(oscillator)
    several = not is_single_mass(oscillator)
    if several and measurement is not None:
        raise InputError(Problem.WRONG_MODE, "measurement", measurement, mode="a single mass (Oscillator)",
                         fix="leave it None for a Structure: its metrics are the exact ones")
    a_g = Harmonic(positive("a_g", a_g, "g (e.g. 0.05)"), 1.0).a_g  # its magnitude checks
    freqs = paper_frequencies_hz() if freqs_hz is None else float_array("freqs_hz", freqs_hz)
    if freqs.size > MAX_STEPS_PER_SWEEP:
        raise InputError(Problem.TOO_LARGE, "freqs_hz", f"array of {freqs.size}", maximum=MAX_STEPS_PER_SWEEP,
                         what=" frequency steps", fix="give fewer frequencies (a coarser step)")
    bad = np.flatnonzero(~((freqs > 0.0) & (freqs <= 1e3)))  # (vectorised: a sweep may have many)
    for i in bad[:1]:
        f = positive(f"freqs_hz[{i}]", float(freqs[i]), "Hz")
        at_most(f"freqs_hz[{i}]", f, MAX_FREQ_HZ, " Hz", "give it in Hz")
        plausible(f"freqs_hz[{i}]", f, 0.0, 1e3, "the frequencies are in Hz, not rad/s")
    unique, counts = np.unique(freqs, return_counts=True)
    if np.any(counts > 1):
        raise InputError(Problem.DUPLICATE, "freqs_hz", freqs.tolist(),
                         repeated=unique[counts > 1].tolist())
    one_of("direction", direction, ("up", "down"))
    freqs = np.sort(freqs) if direction == "up" else np.sort(freqs)[::-1].copy()
    one_of("steady", steady, ("adaptive", "fixed"))
    measure_cycles = integer("measure_cycles", measure_cycles, 1, MAX_CYCLES_PER_STEP)
    if steady == "fixed":
        if max_cycles is not None:
            raise InputError(Problem.WRONG_MODE, "max_cycles", max_cycles, mode="steady='adaptive'",
                             fix="leave it None with steady='fixed' (the fixed mode runs exactly `cycles`)")
        n_cycles = integer("cycles", 30 if cycles is None else cycles, 1, MAX_CYCLES_PER_STEP)
        if n_cycles < measure_cycles:
            raise InputError(Problem.TOO_SMALL, "cycles", n_cycles, minimum=measure_cycles,
                             hint=" (at least measure_cycles, which are the last of them)")
    else:
        if cycles is not None:
            raise InputError(Problem.WRONG_MODE, "cycles", cycles, mode="steady='fixed'",
                             fix="leave it None with steady='adaptive' (use max_cycles), or give "
                                 "steady='fixed'")
        n_cycles = integer("max_cycles", 500 if max_cycles is None else max_cycles, 1, MAX_CYCLES_PER_STEP)
        check_adaptive_window(n_cycles, measure_cycles)
    steady_rtol = check_steady_rtol(steady_rtol)
    max_period = integer("max_period", max_period, 1, 1000)
    # (each between 1 mHz and the largest frequency, in its unit: beyond, e and nu overflowed or divided by 0)
    omega_min_rad_s = positive("omega_min_rad_s", omega_min_rad_s, "rad/s")
    at_least("omega_min_rad_s", omega_min_rad_s, 2e-3 * math.pi, " rad/s", "it is in rad/s: 0.6 Hz is 3.77")
    at_most("omega_min_rad_s", omega_min_rad_s, 2.0 * math.pi * MAX_FREQ_HZ, " rad/s", "give it in rad/s")
    f_ref_hz = positive("f_ref_hz", f_ref_hz, "Hz")
    at_least("f_ref_hz", f_ref_hz, 1e-3, " Hz", "it is in Hz")
    at_most("f_ref_hz", f_ref_hz, MAX_FREQ_HZ, " Hz", "give it in Hz")
    rtol = check_rtol(rtol)
    max_events_per_cycle = integer("max_events_per_cycle", max_events_per_cycle, 1)
    max_steps = integer("max_steps", max_steps, 1)
    if several or state is not None:
        state = check_state(state, oscillator)
    rate, why = fastest_rate(oscillator)
    # the least work the sweep can take: every step's fewest cycles
    least_cycles = n_cycles if steady == "fixed" else min(n_cycles, 2 * measure_cycles + 1)
    estimate = float(np.sum(steps_per_second(rate, 2.0 * math.pi * freqs) * least_cycles / freqs))
    check_budget("freqs_hz", f"{freqs.size} steps of {least_cycles}+ cycles", estimate, max_steps,
                 f"at least {least_cycles} cycles at each of {freqs.size} frequencies; {why}",
                 "sweep fewer frequencies or cycles, or check the system's numbers (SI units)")
    if measurement is not None:  # (a chain whose windows are too long is refused before the sweep)
        from .measured_sweep import check_window_samples

        longest = measure_cycles + (max_period - 1 if steady == "adaptive" else 0)
        check_window_samples(measurement, freqs, longest)
    return SweepPlan(oscillator, a_g, freqs, direction, steady, n_cycles, measure_cycles, steady_rtol,
                     max_period, omega_min_rad_s, f_ref_hz, rtol, max_events_per_cycle, state, max_steps,
                     measurement)


def with_sweep_options(fn: Callable) -> Callable:
    """``fn`` (which takes ``**options``) shown with :class:`SweepOptions`' names and defaults as
    keyword parameters (``help``, notebooks and the docs read ``__signature__``)."""
    sig = inspect.signature(fn)
    params = list(sig.parameters.values())
    first_keyword = next(i for i, p in enumerate(params) if p.kind is p.KEYWORD_ONLY)
    options = [inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default, annotation=f.type)
               for f in fields(SweepOptions)]
    fn.__signature__ = sig.replace(parameters=params[:first_keyword] + options + [
        p for p in params[first_keyword:] if p.kind is not p.VAR_KEYWORD])
    return fn


@with_sweep_options
@renamed_keyword("oscillator", "system")
def sweep(system: "Oscillator | Structure | Adjacent", a_g: float, freqs_hz: np.ndarray | None = None,
          direction: Direction = "up", *, state: State | None = None, progress: Progress = False,
          **options: Any) -> SweepResult:
    """Stepped-sine sweep: hold each frequency in turn, the state carried over, and measure.

    Every step starts at table phase 0 (``A = 0`` at the step boundary, so the table
    acceleration is continuous) and lasts whole cycles.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system (a single mass with bumpers: YBs; without: NBs; a building, with its walls; two adjacent
        buildings).
    a_g : float
        Peak table acceleration in g (``A_t = a_g * 9.81`` m/s^2), > 0.
    freqs_hz : array_like, shape (n,), optional
        Step frequencies in Hz, any order, no repeats (default: 0.5 to 5.0 by 0.1).
    direction : {"up", "down"}
        Step through them increasing or decreasing.
    steady : {"adaptive", "fixed"}
        ``"adaptive"`` (default): a step ends as soon as the stroboscopic samples (the
        state at every cycle end) repeat with some period multiple ``k <= max_period`` over
        the measurement window, to within ``steady_rtol``, or after ``max_cycles``.
        ``"fixed"``: every step lasts ``cycles`` cycles, as a lab's schedule.
    cycles : int, optional
        Cycles per step in the fixed mode (default 30).
    measure_cycles : int
        Cycles measured at the end of each step (default 5; adaptive: rounded up to a
        multiple of the period multiple).
    max_cycles : int, optional
        Most cycles per step in the adaptive mode (default 500); a step that reaches it
        without becoming periodic has ``steady`` False and is measured on its last
        ``measure_cycles``.
    steady_rtol : float
        Periodicity tolerance, relative to the response amplitude (displacement; velocity
        scaled by Omega), on the estimated distance to the periodic orbit.
    max_period : int
        Largest period multiple (subharmonic order) looked for.
    omega_min_rad_s : float
        ``Omega_min`` of ``e = E / D_tmax`` with ``D_tmax = A_t / Omega_min^2``; default
        ``2 pi 0.6`` rad/s, what the paper's D_tmax values imply.
    f_ref_hz : float
        ``f_R`` of ``nu = f / f_R`` (default 1.0 Hz as the paper).
    state : State, optional
        Start (default: at rest at t = 0), e.g. another sweep's ``final_state``.
    rtol : float
        Tolerance of the numerical integration of nonlinear contact laws (see
        :func:`simulate`).
    max_events_per_cycle : int
        A cycle with more events stops the sweep with ``Status.MAX_EVENTS``.
    max_steps : int
        Work budget of the whole sweep in integration steps (see :func:`simulate`): the
        sweep stops with ``Status.BUDGET`` once it is used; a sweep whose fewest cycles are
        estimated to need more is refused before it starts.
    measurement : MeasurementChain, optional
        The lab's instruments: the metrics of each window (alpha, excursion, eta, e, the contacts
        and their means) are then measured as the lab pipeline measures a recording, from the
        window's histories through the chain (:attr:`SweepResult.measured`, and the table, the
        resonance and the contact range follow them; :meth:`SweepResult.exact_dataframe` keeps
        the exact ones). Default: the exact metrics.
    progress : bool or callable
        True: a progress bar; a callable is called with the number of steps just finished.

    Returns
    -------
    SweepResult
        Per step and level: alpha, excursion, eta, e, contacts and the impact characterization per
        side, drift, steadiness and period multiple; per contact slot its contacts' means; the
        resonance, contact range and jumps.

    Raises
    ------
    InputError
        For a bad argument (names it, the value and the fix).
    Interrupted
        On Ctrl-C; its ``partial`` holds the finished steps.

    Examples
    --------
    Three coarse steps up (the paper steps by 0.1 Hz, :func:`paper_frequencies_hz`) on the damped
    paper system at a_G = 0.05 g; only the 1.5 Hz step pounds:

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> up = pounding.sweep(ybs, 0.05, [1.5, 2.0, 2.5], direction="up")
    >>> up.message
    'All 3 steps reached a periodic steady state.'
    >>> df = up.to_dataframe()
    >>> print(df[["freq_hz", "alpha", "eta",
    ...           "contacts_per_cycle"]].round(2).to_string(index=False))
     freq_hz  alpha  eta  contacts_per_cycle
         1.5   8.30 1.07                 2.0
         2.0   0.93 0.38                 0.0
         2.5   0.47 0.19                 0.0
    >>> up.nu_r, up.contact_range_hz
    (1.5, (1.5, 1.5))

    A lab's schedule instead: every step exactly 10 cycles, the last 5 measured.

    >>> fixed = pounding.sweep(ybs, 0.05, [1.5, 2.0], steady="fixed", cycles=10,
    ...                        measure_cycles=5)
    >>> fixed.cycles_run.tolist(), fixed.status.name
    ([10, 10], 'SUCCESS')
    """
    plan = make_plan(system, a_g, freqs_hz, direction, state, **options)
    ctl = new_control(plan.max_steps)
    with progress_reporter(progress, plan.freqs_hz.size,
                           f"sweep {direction}, a_G = {plan.a_g:g}") as advance:
        # on a helper thread, so that Ctrl-C stops the step kernel at once (engine/control.py)
        return run_interruptibly(lambda: run_plan(plan, advance, ctl), [ctl])


def run_plan(plan: SweepPlan, advance: Callable[[int], None] | None = None,
             control: np.ndarray | None = None) -> SweepResult:
    """Run a validated plan of any system step by step; ``advance(1)`` after each step.

    Each step runs in the core until steady (or for its fixed cycles).  Its own window measures one moving
    level and one wall's two sides (a single mass, a one-level structure); a system with more is measured
    on its window run once more from the window's exact start: every level's extrema, every storey's drift,
    every contact slot's impacts (``sweep_window``).

    ``control`` is the run control the step kernels poll (``engine.control``; default a
    fresh one with the plan's budget): another thread stops the sweep with
    ``request_stop([control])``.  On such a stop (or a KeyboardInterrupt raised by
    ``advance``) the unfinished step is dropped and :class:`~pounding.Interrupted` is
    raised, carrying the finished steps.
    """
    ctl = new_control(plan.max_steps) if control is None else control
    model = plan.oscillator
    asm = assemble(model)
    system = asm.system
    n_steps = plan.freqs_hz.size
    levels, storeys, slots = labels_of(model, asm)
    level_dof = [d for dofs in asm.dofs for d in dofs]
    again = not step_measures_all(asm)
    masses = slot_masses(asm)
    level = np.full((n_steps, len(levels), 3), np.nan)       # d_max, d_min, a_abs_max
    drift = np.full((n_steps, len(storeys), 2), np.nan)      # max, min
    sums = np.full((n_steps, len(slots), SIDE_SUMS), np.nan)
    cycles_run = np.zeros(n_steps, dtype=np.int64)
    period_multiple = np.zeros(n_steps, dtype=np.int64)
    window_cycles = np.zeros(n_steps, dtype=np.int64)
    window_events = np.zeros((n_steps, 2), dtype=np.int64)  # every event located, the sticks
    state = (plan.state if plan.state is not None else State.at_rest(model)).vector.copy()
    window_states = np.full((n_steps, state.size), np.nan)
    # (a window is rounded up to whole periods when adaptive: up to max_period - 1 more cycles)
    strobe_cap = plan.measure_cycles + (plan.max_period - 1 if plan.steady == "adaptive" else 0)
    window_strobes = np.full((n_steps, strobe_cap, 2, len(levels)), np.nan)
    step_start_s = np.full(n_steps, np.nan)

    def take(i: int, f: float, start: np.ndarray, exc: Harmonic, stepped: StepOutput) -> int:
        code, win_state = stepped.status, stepped.window_state
        m = int(stepped.window[W_CYCLES])
        if not again:
            level[i], sums[i] = from_step(stepped.window, len(slots))
            window_strobes[i, :len(stepped.window_strobes), :, 0] = stepped.window_strobes
        elif code == Status.SUCCESS:  # the window once more, from its exact start, every level measured
            t0 = float(win_state[T])
            at = Harmonic(plan.a_g, f, phase=-(exc.omega_rad_s * t0))
            period = 1.0 / float(f)
            out = run_window(system, at.peak_m_s2, at.omega_rad_s, at.phase, win_state, t0 + m * period,
                             period, plan.rtol, plan.max_events_per_cycle * m, ctl)
            code = out.status
            if code == Status.INTERRUPTED:
                return code
            if code == Status.SUCCESS:
                measure(out, level_dof, at.peak_m_s2, masses, level[i], drift[i], sums[i], system.n)
                window_strobes[i, :min(m, strobe_cap)] = strobes(out.samples, level_dof, t0, period, m,
                                                                 system.n)[:strobe_cap]
        step_start_s[i] = start[T]
        cycles_run[i] = stepped.cycles_run
        period_multiple[i] = stepped.period_multiple
        window_cycles[i] = m
        window_events[i] = stepped.window[[W_EVENTS, W_STICKS]]
        window_states[i] = win_state
        return code

    state, done, status, interrupted = plan.steps(system, state, ctl, advance, take)
    measured = measured_impacts = None
    if plan.measurement is not None and not interrupted and done:
        from .measured_sweep import measure_steps

        try:  # (the step that stopped the sweep early is not measured: its window did not finish)
            measured, measured_impacts = measure_steps(
                model, plan.a_g, plan.freqs_hz, window_states, window_cycles.astype(float),
                done if status == Status.SUCCESS else done - 1, plan.measurement,
                omega_min_rad_s=plan.omega_min_rad_s, steady_rtol=plan.steady_rtol, rtol=plan.rtol,
                max_events_per_cycle=plan.max_events_per_cycle, max_steps=plan.max_steps,
                stop=lambda: stop_requested(ctl))
        except KeyboardInterrupt:
            interrupted = True
    result = SweepResult(
        system=model, a_g=plan.a_g, freqs_hz=plan.freqs_hz, direction=plan.direction,
        steady_mode=plan.steady, cycles=plan.cycles, measure_cycles=plan.measure_cycles,
        omega_min_rad_s=plan.omega_min_rad_s, f_ref_hz=plan.f_ref_hz, g=GRAVITY_M_S2,
        levels=levels, storeys=storeys, contact_slots=slots, level_metrics=level, drift_metrics=drift,
        contact_sums=sums, window_cycles=window_cycles, window_events=window_events, cycles_run=cycles_run,
        period_multiple=period_multiple, window_states=window_states, window_strobes=window_strobes,
        step_start_s=step_start_s, steps_done=done, final_state=State._of(state, asm.dofs, asm.layout),
        status=status,
        message=sweep_message(status, done, n_steps, plan, cycles_run, period_multiple, interrupted),
        measurement=plan.measurement if measured is not None else None, measured=measured,
        measured_impacts=measured_impacts)
    if interrupted:
        raise Interrupted(result, done, n_steps)
    return result


def sweep_message(status, done, n_steps, plan, cycles_run, period_multiple, interrupted) -> str:
    """A sweep's ``message``: how it ended, in words."""
    if interrupted and done == n_steps and plan.measurement is not None:
        return (f"Interrupted while measuring the windows through the chain: the {done} steps ran, "
                "and their metrics are the exact ones (no chain).")
    if interrupted:
        return f"Interrupted after {done} of {n_steps} steps; the others are NaN."
    if status != Status.SUCCESS:
        return (f"Stopped at step {done} of {n_steps} ({plan.freqs_hz[done - 1]:g} Hz): "
                f"{status.message}")
    not_steady = int(np.sum(period_multiple[:done] == 0))
    if plan.steady == "adaptive":
        if not_steady:
            return (f"{not_steady} of {n_steps} steps reached max_cycles = {plan.cycles} without "
                    f"a periodic response (steady False); raise max_cycles or add damping.")
        return f"All {n_steps} steps reached a periodic steady state."
    if not_steady:
        return (f"Fixed schedule of {plan.cycles} cycles: {not_steady} of {n_steps} steps were not "
                f"periodic over their last {plan.measure_cycles} cycles (steady False).")
    return f"Fixed schedule of {plan.cycles} cycles: every step was periodic when measured."
