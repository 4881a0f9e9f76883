"""``simulate``: the validating wrapper around the compiled kernel."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Optional

import numpy as np

from .._checks import instance_of, integer, positive
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from ..excitation import Harmonic, Record
from ..model import Oscillator
from ..model.contact_laws import state_problem, stateless
from ..model.contact_laws import N_LAW_STATE, KelvinVoigt
from .control import (
    DEFAULT_MAX_STEPS,
    check_budget,
    contact_rate,
    isolator_rate,
    new_control,
    run_interruptibly,
    steps_per_second,
)
from .. import _core
from ._system import Forcing, System
from .layout import (DEF_L, DEF_R, IN_L, IN_R, REGION, STATE_BASE, X_A_MAX, X_A_MAX_T, X_D_MAX, X_D_MAX_T,
                      X_D_MIN, X_D_MIN_T, Z_L, Z_R, ZETA, D, T, V)
from .run_args import (DEFAULT_SAMPLE_RATE_HZ, DIRECT_CALL_STEPS, MAX_AUTO_SAMPLES,  # noqa: F401
                        MAX_SAMPLES, check_rtol, history_rate, kernel_forcing)
from .result import EnergyLedger, Run
from .state import MAX_DISPLACEMENT_M, MAX_VELOCITY_M_S, ONE_MASS_DOFS, State

if TYPE_CHECKING:
    from ..model.structure import Structure

_NO_LAW = KelvinVoigt(1.0, 0.0)  # stands in for absent bumpers (never touched)


def check_oscillator(oscillator: Oscillator, field: str = "system") -> None:
    """An InputError naming ``field`` unless ``oscillator`` is one."""
    instance_of(field, oscillator, Oscillator, "pounding.Oscillator")


def check_state(state: Optional[State], oscillator: Oscillator) -> State:
    """``state``, or rest at t = 0 when None; it must belong to a system like ``oscillator``."""
    if state is None:
        return State.at_rest(oscillator)
    instance_of("state", state, State, "pounding.State (e.g. run.final_state)")
    expected = STATE_BASE + 2 * (oscillator.isolator.n_branches - 1)
    if state.layout is not None and not _one_mass_layout(state):
        raise InputError(Problem.BAD_STATE, "state", state,
                         why=f"is the state of a structure of levels {state.dofs}, not of a single mass",
                         fix="start from State.at_rest(oscillator) or a final_state of this system")
    if state.vector.size != expected:
        raise InputError(Problem.BAD_STATE, "state", state,
                         why=f"has {state.vector.size} numbers where this system's states have {expected} "
                             "(it is from a system with another number of isolator branches)",
                         fix="start from State.at_rest(oscillator) or a final_state of this system")
    _check_state_fits(state, oscillator)
    return state


def _one_mass_layout(state: State) -> bool:
    """Whether a state a structure's run made is laid out as a single mass's (a structure of one level with
    one wall, as a single mass's run on its bumpers makes it)."""
    one = State._of(state.vector, ONE_MASS_DOFS, None)._lay
    return state.dofs == ONE_MASS_DOFS and all(state.layout.get(k) == v for k, v in one.items())


def _check_state_fits(state: State, oscillator: Oscillator) -> None:
    """A state the system can be in: contacts, bumper surfaces and isolator springs agree.

    Tolerances are relative (1e-9 of the system's lengths): a run's final state holds the
    rounding of its last event.
    """
    _check_vector_fits(state.vector, oscillator)


def _check_vector_fits(vec: np.ndarray, oscillator: Oscillator) -> None:
    """:func:`_check_state_fits` of a state's raw vector (of the right size, its numbers finite), read
    as Python floats (a solver's runs check one a run: numpy's scalars cost several times more)."""
    x = vec.tolist()
    d = x[D]
    iso = oscillator.isolator
    b = oscillator.bumpers
    lengths = [abs(d), 1e-3, *iso.breakpoints_m] + ([b.gap_left_m, b.gap_right_m] if b else [])
    tol = 1e-9 * max(lengths)
    fix = "start from State.at_rest(oscillator) or a final_state of this system"

    def bad(field: str, value: float, why: str) -> InputError:
        return InputError(Problem.BAD_STATE, f"state.{field}", value, why=why, fix=fix)

    comp = x[DEF_L], x[DEF_R]
    touching = bool(x[IN_L]), bool(x[IN_R])
    if b is None:
        if any(touching) or any(comp):
            raise bad("in_contact", touching, "has a bumper in contact or compressed, but the system has no "
                                              "bumpers")
    else:
        for j, (side, gap, sign) in enumerate((("left", b.gap_left_m, -1.0), ("right", b.gap_right_m, 1.0))):
            depth = sign * d - gap  # how far the mass is beyond this bumper's free surface
            if touching[j] and abs(depth - comp[j]) > tol:
                raise bad(f"bumper_compression_m[{j}]", comp[j],
                          f"differs from the {side} bumper's depth {depth:g} m at the state's displacement "
                          "while in contact")
            if not touching[j] and depth - comp[j] > tol:
                raise bad("displacement_m", d, f"is inside the {side} bumper (its surface is at "
                                               f"{sign * (gap + comp[j]):g} m) while not in contact")
            at = (Z_L, Z_R)[j]
            law = (b.left, b.right)[j]
            if law.STATE_CHECK is stateless and not any(x[at:at + N_LAW_STATE]):
                continue  # (a stateless law's block of zeros: what its check accepts, without numpy)
            found = state_problem(law, vec[at:at + N_LAW_STATE], touching[j], comp[j], tol, side)
            if found is not None:
                q, value, why = found
                raise bad(f"vector[{at + q}]", value, why)
    z = x[ZETA]
    if iso.bouc_wen is None and z != 0.0:
        raise bad(f"vector[{ZETA}]", z,
                  "is an isolator's Bouc-Wen z, but this isolator has no Bouc-Wen spring")
    if iso.bouc_wen is not None and abs(z) > iso.bouc_wen.z_max * (1.0 + 1e-9):
        raise bad(f"vector[{ZETA}]", z,
                  f"is beyond the Bouc-Wen spring's largest |z|, {iso.bouc_wen.z_max:g}")
    n_sp = iso.n_branches - 1
    if iso.hysteresis == "elastic":
        region = int(x[REGION])
        edges = (0.0, *iso.breakpoints_m, np.inf)
        a = abs(region)
        wrong_side = region != 0 and np.sign(region) != np.sign(d)
        if a > n_sp or not edges[a] - tol <= abs(d) <= edges[a + 1] + tol or wrong_side:
            raise bad("isolator_branch", region, f"is not the backbone branch of displacement {d:g} m")
        return
    if x[REGION] != 0.0:
        raise bad("isolator_branch", vec[REGION], "is set, but a kinematic isolator has no branch state")
    for i, brk in enumerate(iso.breakpoints_m):
        strain = d - x[STATE_BASE + i]
        direction = x[STATE_BASE + n_sp + i]
        beyond = abs(strain) > brk + tol if direction == 0.0 else abs(strain - direction * brk) > tol
        if beyond:
            raise bad(f"plastic_slips_m[{i}]", x[STATE_BASE + i],
                      f"leaves spring {i}'s strain {strain:g} m beyond its yield displacement {brk:g} m")


def kernel_system(oscillator: Oscillator) -> System:
    """The oscillator as the core's system: one dof on its isolator, two contact slots (the left bumper,
    sign -1, and the right one, +1, against the ground)."""
    slopes, breaks, rule, bw = oscillator.isolator.kernel_arrays()
    b = oscillator.bumpers
    left = right = _NO_LAW
    gap_l = gap_r = 0.0
    if b is not None:
        left, right, gap_l, gap_r = b.left, b.right, b.gap_left_m, b.gap_right_m
    contacts = [_core.contact_slot(i=0, j=-1, sign=sign, gap_m=gap, law=law.LAW_ID, params=law.params())
                for sign, gap, law in ((-1.0, gap_l, left), (1.0, gap_r, right))]
    isolator = _core.element(i=0, j=-1, c_d=oscillator.isolator.damping_n_s_m, slopes=slopes, breaks=breaks,
                             rule=rule)
    return _core.system([float(oscillator.mass_kg)], np.zeros((1, 1)), np.zeros((1, 1)), [isolator], bw,
                        b is not None, contacts)


@renamed_keyword("oscillator", "system")
def simulate(
    system: "Oscillator | Structure",
    excitation: Harmonic | Record,
    duration: float,
    state: Optional[State] = None,
    *,
    rtol: float = 1e-10,
    sample_rate_hz: Optional[float] = None,
    max_events: int = 10_000_000,
    max_steps: int = DEFAULT_MAX_STEPS,
) -> Run:
    """Simulate the system under a base excitation, exactly at every non-smooth instant.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system: one mass, or a structure of several (then ``state`` is a
        :class:`State` of its own and a :class:`StructureRun` is returned: each level's histories
        and exact extrema, contacts per wall side), or two adjacent structures (an
        :class:`AdjacentRun`: each one's, and the contacts at their links).
    excitation : Harmonic or Record
        Base (table) acceleration.
    duration : float
        Simulated time in s, > 0; the run covers ``[t0, t0 + duration]`` with ``t0`` the
        time of ``state``.
    state : State, optional
        Where to start (default: at rest at ``t = 0``); pass ``run.final_state`` to continue.
    rtol : float
        Relative tolerance of the numerical integration of nonlinear contact laws; phases
        with a linear law are solved in closed form, to rounding.
    sample_rate_hz : float, optional
        Rate of the uniform history samples, Hz; 0: only the start, the events and the
        end.  Default: 1 kHz, lowered for runs over 1000 s so that the history holds at most
        a million samples (``run.sample_rate_hz`` says which).  Extrema, contacts and
        energies are exact whatever the rate.
    max_events : int
        The run stops with ``Status.MAX_EVENTS`` after this many events.
    max_steps : int
        Work budget: the run stops with ``Status.BUDGET`` after this many integration steps
        (sub-intervals: about 8 per period of the fastest motion, plus one per event).  A
        run whose estimate exceeds it is refused before it starts.

    Returns
    -------
    Run
        Histories, exact extrema, contacts, energy ledger, final state, status and message.
        A run that stops early keeps what it computed; ``status`` and ``message`` say why.

    Raises
    ------
    InputError
        A bad argument, or a run estimated to need more than ``max_steps``.
    Interrupted
        On Ctrl-C: ``partial`` is the run up to the stop (status ``INTERRUPTED``).

    Examples
    --------
    The paper's YBs system (with ``C_d = 1 kN s/m``) shaken at 0.1 g and 2 Hz for 5 s, then 5 s
    more from where it stopped:

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> run = pounding.simulate(ybs, pounding.Harmonic(a_g=0.1, freq_hz=2.0),
    ...                         duration=5.0)
    >>> # impacts, mm
    >>> run.status.name, len(run.contacts), round(run.displacement_max * 1e3, 1)
    ('SUCCESS', 19, 18.8)
    >>> later = pounding.simulate(ybs, pounding.Harmonic(a_g=0.1, freq_hz=2.0), 5.0,
    ...                           state=run.final_state)
    >>> float(later.t[0]), float(later.t[-1]), len(later.contacts)  # s, s, impacts
    (5.0, 10.0, 20)
    """
    from ..model.adjacent import Adjacent
    from ..model.structure import Structure

    if isinstance(system, (Structure, Adjacent)):  # (several masses: the same run, a result per level)
        from .structure import simulate_structure

        return simulate_structure(system, excitation, duration, state, rtol=rtol,  # type: ignore[return-value]
                                  sample_rate_hz=sample_rate_hz, max_events=max_events, max_steps=max_steps)
    check_oscillator(system)
    instance_of("excitation", excitation, (Harmonic, Record), "pounding.Harmonic or pounding.Record")
    duration = positive("duration", duration, "s")
    rtol = check_rtol(rtol)
    max_events = integer("max_events", max_events, 1)
    max_steps = integer("max_steps", max_steps, 1)
    state = check_state(state, system)
    rate = history_rate(sample_rate_hz, duration)
    t0 = state.time_s
    omega = excitation.omega_rad_s if isinstance(excitation, Harmonic) else 0.0
    iso_rate, why = isolator_rate(system)
    per_s = float(steps_per_second(iso_rate, omega))
    if omega > iso_rate:
        why = f"the forcing, {omega:.3g} rad/s"
    knots = 0
    if isinstance(excitation, Record):
        knots = int(np.count_nonzero((excitation.t >= t0) & (excitation.t <= t0 + duration)))
        why += f", and {knots} record samples"
    check_budget("duration", duration, per_s * duration + knots, max_steps, why,
                 "shorten the duration, or check the system's numbers (SI units: kg, N/m, N s/m)")

    # at most this many sub-intervals (every phase as fast as the fastest), plus one per event
    most = float(steps_per_second(contact_rate(system), omega)) * duration + knots
    return _run(system, excitation, duration, state, rtol, rate, max_events, max_steps,
                direct=most < DIRECT_CALL_STEPS)


# the work budget of a short run (``short_run``): a forcing period or two of any system fits in it
# many times over, and the kernel returns within about a second when it is spent
SHORT_RUN_STEPS = 1_000_000


class ShortRun:
    """What the periodic-orbit solvers read of a run (:func:`short_run`), without the public
    ``Run``'s histories, energy ledger and checks: ``vector`` (the final state's), the event
    and contact tables (``Run``'s columns), the exact extrema and the status."""

    __slots__ = ("vector", "event_table", "contact_table", "displacement_max", "displacement_min",
                 "abs_acceleration_max", "excitation", "status")

    def __init__(self, out: _core.RunOutput, excitation: Harmonic, status: int) -> None:
        self.vector = out.state
        self.event_table = out.events
        self.contact_table = out.contacts
        extrema = out.per_dof(1)[0]
        self.displacement_max = float(extrema[X_D_MAX])
        self.displacement_min = float(extrema[X_D_MIN])
        self.abs_acceleration_max = float(extrema[X_A_MAX])
        self.excitation = excitation
        self.status = status

    @property
    def success(self) -> bool:
        return self.status == Status.SUCCESS

    @property
    def message(self) -> str:
        return Status(self.status).message

    @property
    def final_state(self) -> State:
        return State._from_kernel(self.vector)


class NotAState(Exception):
    """A state vector a solver made (a Newton step, a finite difference) is none of the system's
    states: the solver's own failure, not the caller's input (``InputError`` is for that)."""


def short_run(oscillator: Oscillator, excitation: Harmonic, duration: float, state: State | np.ndarray,
              system: Optional[System] = None, forcing: Optional[Forcing] = None) -> ShortRun:
    """A run of a period or so, events only, for the periodic-orbit solvers' many runs: the state
    checked, the arguments trusted (the caller checked them), the kernel called in this thread
    (no helper thread: Ctrl-C lands when it returns) within ``SHORT_RUN_STEPS`` sub-intervals
    (status ``BUDGET`` beyond).

    ``state`` may be a raw state vector (the solvers' own: only what ties it to this system is
    checked, and one that is none of its states raises :class:`NotAState`); ``system`` the
    oscillator's :func:`kernel_system` and ``forcing`` the excitation's :func:`kernel_forcing`, when
    the caller keeps them for many runs.  A continuation makes some 15,000 runs of about 12 us in the
    kernel each: the public ``simulate``'s checks and ``Run`` took 90 us a run around them.
    """
    if isinstance(state, np.ndarray):
        # the moves of a solver change the continuous numbers only: those are checked here, and a
        # vector that fails is checked in full (for the message)
        size = STATE_BASE + 2 * (oscillator.isolator.n_branches - 1)
        x = state.tolist()
        fits = (state.size == size and all(map(math.isfinite, x))
                and abs(x[D]) <= MAX_DISPLACEMENT_M and abs(x[V]) <= MAX_VELOCITY_M_S
                and x[DEF_L] >= 0.0 and x[DEF_R] >= 0.0)
        try:
            if fits:  # (no State made: its vector's copy is what the kernel takes)
                _check_vector_fits(state, oscillator)
                vector, t0 = np.array(state, dtype=float), x[T]
            else:
                checked = State(state)
                _check_state_fits(checked, oscillator)
                vector, t0 = np.array(checked.vector), checked.time_s
        except InputError as exc:  # (the public checks' words, as the solver's failure)
            raise NotAState(str(exc)) from None
    else:
        state = check_state(state, oscillator)
        vector, t0 = np.array(state.vector), state.time_s
    if system is None:
        system = kernel_system(oscillator)
    out = _core.run(system, kernel_forcing(excitation) if forcing is None else forcing, vector, t0 + duration,
                    0.0, 1e-10, 10_000_000, False, new_control(SHORT_RUN_STEPS))
    status = out.status
    if status == Status.SUCCESS and not all(map(math.isfinite, out.extrema.tolist())):
        status = int(Status.NONFINITE)
    return ShortRun(out, excitation, status)


def _run(oscillator: Oscillator, excitation: Harmonic | Record, duration: float, state: State, rtol: float,
         rate: float, max_events: int, max_steps: int, direct: bool, system: Optional[System] = None) -> Run:
    """The kernel on checked arguments, its outputs as a ``Run`` (``Interrupted`` on Ctrl-C)."""
    t0 = state.time_s
    if system is None:
        system = kernel_system(oscillator)
    forcing = kernel_forcing(excitation)
    ctl = new_control(max_steps)
    out = run_interruptibly(lambda: _core.run(
        system, forcing, state.vector.copy(),
        t0 + duration, 1.0 / rate if rate > 0 else 0.0, rtol, int(max_events), True, ctl), [ctl],
        direct=direct)
    ledger, extrema = out.ledger, out.per_dof(1)[0]
    status = Status(out.status)
    if status == Status.SUCCESS and not (np.all(np.isfinite(ledger)) and np.all(np.isfinite(extrema))):
        status = Status.NONFINITE

    energy = EnergyLedger.of(ledger)
    cols = out.samples.T
    run = Run(
        t=cols[0], displacement=cols[1], velocity=cols[2], abs_acceleration=cols[3],
        isolator_force=cols[4], bumper_force_left=cols[5], bumper_force_right=cols[6],
        displacement_max=float(extrema[X_D_MAX]), displacement_max_time_s=float(extrema[X_D_MAX_T]),
        displacement_min=float(extrema[X_D_MIN]), displacement_min_time_s=float(extrema[X_D_MIN_T]),
        abs_acceleration_max=float(extrema[X_A_MAX]), abs_acceleration_max_time_s=float(extrema[X_A_MAX_T]),
        contact_table=out.contacts, event_table=out.events, energy=energy,
        final_state=State._from_kernel(out.state),
        status=status, message=status.message, oscillator=oscillator, excitation=excitation,
        sample_rate_hz=rate, chatter_table=out.chatters)
    if status == Status.INTERRUPTED:
        raise Interrupted(run, round(run.final_state.time_s - t0, 6), duration, "simulated seconds")
    return run
