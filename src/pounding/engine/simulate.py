"""``simulate``: the validating wrapper around the compiled kernel."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from .._checks import integer, non_negative, positive
from .._errors import InputError, Interrupted, Problem, Status
from ..excitation import Harmonic, Record
from ..model import Oscillator
from ..model._elastic_plastic import EP_UNLOAD, EP_YIELD
from ..model.contact_laws import N_LAW_STATE, ElasticPlastic, Hertzdamp, KelvinVoigt, MultilinearBumper
from ._control import (
    DEFAULT_MAX_STEPS,
    check_budget,
    contact_rate,
    isolator_rate,
    new_control,
    run_interruptibly,
    steps_per_second,
)
from ._kernel import run_kernel
from ._layout import REGION, STATE_BASE, Z_L, Z_R, ZETA
from .result import EnergyLedger, Run, State

_NO_LAW = KelvinVoigt(1.0, 0.0)  # stands in for absent bumpers (never touched)


def check_oscillator(oscillator: Oscillator) -> None:
    if not isinstance(oscillator, Oscillator):
        raise InputError(Problem.WRONG_TYPE, "oscillator", oscillator,
                         got=type(oscillator).__name__, expected="pounding.Oscillator")


def check_rtol(rtol: float) -> float:
    """The integration tolerance of nonlinear contact laws, in (0, 1e-3]."""
    rtol = positive("rtol", rtol, "(relative)")
    if not 1e-14 <= rtol <= 1e-3:
        raise InputError(Problem.OUT_OF_RANGE, "rtol", rtol, range="[1e-14, 1e-3]",
                         hint=" (below 1e-14 the steps cannot meet it in double precision)")
    return rtol


def check_state(state: Optional[State], oscillator: Oscillator) -> State:
    """``state``, or rest at t = 0 when None; it must belong to a system like ``oscillator``."""
    if state is None:
        return State.at_rest(oscillator)
    if not isinstance(state, State):
        raise InputError(Problem.WRONG_TYPE, "state", state, got=type(state).__name__,
                         expected="pounding.State (e.g. run.final_state)")
    expected = STATE_BASE + 2 * (oscillator.isolator.n_branches - 1)
    if state.vector.size != expected:
        raise InputError(Problem.BAD_STATE, "state", state,
                         why=f"has {state.vector.size} numbers where this system's states have {expected} "
                             "(it is from a system with another number of isolator branches)",
                         fix="start from State.at_rest(oscillator) or a final_state of this system")
    _check_state_fits(state, oscillator)
    return state


def _check_state_fits(state: State, oscillator: Oscillator) -> None:
    """A state the system can be in: contacts, bumper surfaces and isolator springs agree.

    Tolerances are relative (1e-9 of the system's lengths): a run's final state holds the
    rounding of its last event.
    """
    vec = state.vector
    d = state.displacement_m
    iso = oscillator.isolator
    b = oscillator.bumpers
    lengths = [abs(d), 1e-3, *iso.breakpoints] + ([b.gap_left, b.gap_right] if b else [])
    tol = 1e-9 * max(lengths)
    fix = "start from State.at_rest(oscillator) or a final_state of this system"

    def bad(field: str, value: float, why: str) -> InputError:
        return InputError(Problem.BAD_STATE, f"state.{field}", value, why=why, fix=fix)

    comp = state.bumper_compression_m
    touching = state.in_contact
    if b is None:
        if any(touching) or any(comp):
            raise bad("in_contact", touching, "has a bumper in contact or compressed, but the system has no "
                                              "bumpers")
    else:
        for j, (side, gap, sign) in enumerate((("left", b.gap_left, -1.0), ("right", b.gap_right, 1.0))):
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
            if isinstance(law, MultilinearBumper) and law.hysteresis == "kinematic":
                _check_kinematic_state(vec[at:at + N_LAW_STATE], law, comp[j], touching[j], tol, at, bad)
            else:
                for q in range(1, N_LAW_STATE):
                    if vec[at + q] != 0.0:
                        raise bad(f"vector[{at + q}]", float(vec[at + q]),
                                  "is a kinematic multi-linear bumper's slip, but that bumper has "
                                  "another law")
                _check_law_state(vec[at], law, touching[j], comp[j], tol, j, bad)
    z = float(vec[ZETA])
    if iso.bouc_wen is None and z != 0.0:
        raise bad(f"vector[{ZETA}]", z,
                  "is an isolator's Bouc-Wen z, but this isolator has no Bouc-Wen spring")
    if iso.bouc_wen is not None and abs(z) > iso.bouc_wen.z_max * (1.0 + 1e-9):
        raise bad(f"vector[{ZETA}]", z,
                  f"is beyond the Bouc-Wen spring's largest |z|, {iso.bouc_wen.z_max:g}")
    n_sp = iso.n_branches - 1
    if iso.hysteresis == "elastic":
        region = int(vec[REGION])
        edges = (0.0, *iso.breakpoints, np.inf)
        a = abs(region)
        wrong_side = region != 0 and np.sign(region) != np.sign(d)
        if a > n_sp or not edges[a] - tol <= abs(d) <= edges[a + 1] + tol or wrong_side:
            raise bad("isolator_branch", region, f"is not the backbone branch of displacement {d:g} m")
        return
    if vec[REGION] != 0.0:
        raise bad("isolator_branch", vec[REGION], "is set, but a kinematic isolator has no branch state")
    for i, brk in enumerate(iso.breakpoints):
        strain = d - vec[STATE_BASE + i]
        direction = vec[STATE_BASE + n_sp + i]
        beyond = abs(strain) > brk + tol if direction == 0.0 else abs(strain - direction * brk) > tol
        if beyond:
            raise bad(f"plastic_slips_m[{i}]", float(vec[STATE_BASE + i]),
                      f"leaves spring {i}'s strain {strain:g} m beyond its yield displacement {brk:g} m")


def _check_law_state(z: float, law: Any, touching: bool, comp: float, tol: float, j: int, bad: Any) -> None:
    """A bumper law's own state (``_layout.Z_L``): 0 for a stateless law; Hertzdamp's damping,
    >= 0; for an elastic-plastic law 0 out of contact, in contact a line's code or a plastic
    offset whose elastic branch holds the compression."""
    field = f"vector[{(Z_L, Z_R)[j]}]"
    if isinstance(law, Hertzdamp):
        if z < 0.0:
            raise bad(field, z, "is a Hertzdamp bumper's damping, which is >= 0")
        return
    if not touching or not isinstance(law, ElasticPlastic):
        if z != 0.0:
            raise bad(field, z, "is a bumper law's state, but that bumper has none (a stateless law, or "
                                "out of contact)")
        return
    k1, k2, dy = law.stiffness, law.post_yield_stiffness, law.yield_compression
    if z == EP_UNLOAD:
        return
    if z == EP_YIELD:  # (the yield line starts at the yield compression)
        if comp < dy - tol:
            raise bad(field, z,
                      f"puts the {('left', 'right')[j]} bumper on its yield line at compression {comp:g} m, "
                                f"below its yield compression {dy:g} m")
        return
    low = k1 * z / (k1 - k2)
    if z < 0.0 or not low - tol <= comp <= low + dy + tol:
        raise bad(field, z,
                  f"is no plastic offset of the {('left', 'right')[j]} bumper at compression {comp:g} m "
                            "(its elastic branch would not hold it)")


def _check_kinematic_state(block: np.ndarray, law: Any, comp: float, touching: bool, tol: float, at: int,
                           bad: Any) -> None:
    """A kinematic multi-linear bumper's springs: each softening's slip direction -1, 0 or +1, its
    strain within its breakpoint (at it while slipping); the other places 0.  Out of contact (the
    bumper recovering) no spring slips in compression, and the springs do not pull."""
    slopes, breaks = law.slopes, law.breakpoints
    soft = {i for i in range(len(breaks)) if slopes[i] > slopes[i + 1]}
    for q in range(N_LAW_STATE):
        i = (q - 1) % 3
        if q == 0 or i not in soft:
            if block[q] != 0.0:
                raise bad(f"vector[{at + q}]", float(block[q]),
                          "is no state of this kinematic multi-linear bumper "
                                                              "(a place for a softening it has not): 0")
    for i in sorted(soft):
        u, s = block[1 + i], block[4 + i]
        if s not in (-1.0, 0.0, 1.0):
            raise bad(f"vector[{at + 4 + i}]", float(s), "is a slip direction: -1, 0 or +1")
        strain = comp - u
        if (abs(strain) > breaks[i] + tol) if s == 0.0 else abs(strain - s * breaks[i]) > tol:
            raise bad(f"vector[{at + 1 + i}]", float(u),
                      f"leaves the bumper spring {i}'s strain {strain:g} m beyond "
                                                         f"its breakpoint {breaks[i]:g} m")
        if s > 0.0 and not touching:
            raise bad(f"vector[{at + 4 + i}]", float(s),
                      "slips the bumper spring in compression while out of "
                                                         "contact (it holds once the contact ends)")
    if not touching and comp > 0.0:
        k_lin = slopes[0] - sum(slopes[i] - slopes[i + 1] for i in soft)
        force = max(k_lin, 0.0) * comp + sum((slopes[i] - slopes[i + 1]) * (comp - block[1 + i])
                                             if block[4 + i] == 0.0
                                             else (slopes[i] - slopes[i + 1]) * block[4 + i] * breaks[i]
                                             for i in soft)
        force += sum((slopes[i + 1] - slopes[i]) * max(comp - breaks[i], 0.0)
                     for i in range(len(breaks)) if slopes[i + 1] > slopes[i])
        if force < -tol * max(slopes) - 1e-9:
            raise bad(f"vector[{at + 1}]", float(block[1]),
                      f"makes the recovering bumper pull ({force:g} N at its "
                                                            f"compression {comp:g} m)")


def kernel_system(oscillator: Oscillator) -> tuple:
    """The oscillator as the kernel's leading arguments (arrays and scalars only)."""
    slopes, breaks, rule, bw = oscillator.isolator.kernel_arrays()
    b = oscillator.bumpers
    left = right = _NO_LAW
    gap_l = gap_r = 0.0
    if b is not None:
        left, right, gap_l, gap_r = b.left, b.right, b.gap_left, b.gap_right
    return (oscillator.mass, oscillator.isolator.damping, slopes, breaks, rule, bw, b is not None,
            gap_l, gap_r, left.LAW_ID, left.params(), right.LAW_ID, right.params())


# a run whose every sub-interval (and event) fits in this many returns within about 0.1 s: it
# runs in the caller's thread (Ctrl-C then lands when it returns)
DIRECT_CALL_STEPS = 50_000
MAX_AUTO_SAMPLES = 1_000_000     # the default history's length at most (56 MB)
MAX_SAMPLES = 50_000_000         # refused beyond (2.8 GB of history)
DEFAULT_SAMPLE_RATE_HZ = 1000.0


def history_rate(sample_rate_hz: Optional[float], duration: float) -> float:
    """The history's sample rate: as asked (checked against memory), or the default.

    The default (``None``) is 1 kHz, lowered for long runs so that the history holds at
    most ``MAX_AUTO_SAMPLES`` uniform samples: memory grows with what was asked for.
    """
    if sample_rate_hz is None:
        return min(DEFAULT_SAMPLE_RATE_HZ, MAX_AUTO_SAMPLES / duration)
    rate = non_negative("sample_rate_hz", sample_rate_hz, "Hz")
    if duration * rate > MAX_SAMPLES:
        raise InputError(Problem.TOO_LARGE, "sample_rate_hz", sample_rate_hz, maximum=MAX_SAMPLES / duration,
                         what=f" Hz for {duration:g} s: {duration * rate:.3g} samples, "
                              f"{56 * duration * rate / 1e9:.3g} GB of history",
                         fix="lower it or shorten the duration (extrema, contacts and energies are exact "
                             "without samples: sample_rate_hz=0 keeps the events only)")
    return rate


def simulate(
    oscillator: Oscillator,
    excitation: Harmonic | Record,
    duration: float,
    state: Optional[State] = None,
    *,
    rtol: float = 1e-10,
    sample_rate_hz: Optional[float] = None,
    max_events: int = 10_000_000,
    max_steps: int = DEFAULT_MAX_STEPS,
) -> Run:
    """Simulate the oscillator under a base excitation, exactly at every non-smooth instant.

    Parameters
    ----------
    oscillator : Oscillator
        The system.
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
    check_oscillator(oscillator)
    if not isinstance(excitation, (Harmonic, Record)):
        raise InputError(Problem.WRONG_TYPE, "excitation", excitation,
                         got=type(excitation).__name__, expected="pounding.Harmonic or pounding.Record")
    duration = positive("duration", duration, "s")
    rtol = check_rtol(rtol)
    max_events = integer("max_events", max_events, 1)
    max_steps = integer("max_steps", max_steps, 1)
    state = check_state(state, oscillator)
    rate = history_rate(sample_rate_hz, duration)
    t0 = state.time_s
    omega = excitation.omega_rad_s if isinstance(excitation, Harmonic) else 0.0
    iso_rate, why = isolator_rate(oscillator)
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
    most = float(steps_per_second(contact_rate(oscillator), omega)) * duration + knots
    return _run(oscillator, excitation, duration, state, rtol, rate, max_events, max_steps,
                direct=most < DIRECT_CALL_STEPS)


# the work budget of a short run (``short_run``): a forcing period or two of any system fits in it
# many times over, and the kernel returns within about a second when it is spent
SHORT_RUN_STEPS = 1_000_000


def short_run(oscillator: Oscillator, excitation: Harmonic, duration: float, state: State) -> Run:
    """A run of a period or so, events only, for the periodic-orbit solvers' many runs: the state
    checked, the arguments trusted (the caller checked them), the kernel called in this thread
    (no helper thread: Ctrl-C lands when it returns) within ``SHORT_RUN_STEPS`` sub-intervals
    (status ``BUDGET`` beyond)."""
    state = check_state(state, oscillator)
    return _run(oscillator, excitation, duration, state, 1e-10, 0.0, 10_000_000, SHORT_RUN_STEPS, direct=True)


def _run(oscillator: Oscillator, excitation: Harmonic | Record, duration: float, state: State, rtol: float,
         rate: float, max_events: int, max_steps: int, direct: bool) -> Run:
    """The kernel on checked arguments, its outputs as a ``Run`` (``Interrupted`` on Ctrl-C)."""
    t0 = state.time_s
    exc_kind, exc_p, rec_t, rec_a = excitation.kernel_arrays()
    ctl = new_control(max_steps)
    st, samples, contacts, events, ledger, extrema, status = run_interruptibly(lambda: run_kernel(
        *kernel_system(oscillator), exc_kind, exc_p, rec_t, rec_a, state.vector.copy(),
        t0 + duration, 1.0 / rate if rate > 0 else 0.0, rtol, int(max_events), True, ctl), [ctl],
        direct=direct)
    status = Status(int(status))
    if status == Status.SUCCESS and not (np.all(np.isfinite(ledger)) and np.all(np.isfinite(extrema))):
        status = Status.NONFINITE

    energy = EnergyLedger(
        input_work=float(ledger[0]), kinetic=float(ledger[4]), isolator_elastic=float(ledger[5]),
        bumper_elastic=float(ledger[6]), viscous=float(ledger[1]), hysteretic=float(ledger[2]),
        bumper_dissipation=float(ledger[3]))
    cols = samples.T
    run = Run(
        t=cols[0], displacement=cols[1], velocity=cols[2], abs_acceleration=cols[3],
        isolator_force=cols[4], bumper_force_left=cols[5], bumper_force_right=cols[6],
        displacement_max=float(extrema[0]), displacement_max_time_s=float(extrema[1]),
        displacement_min=float(extrema[2]), displacement_min_time_s=float(extrema[3]),
        abs_acceleration_max=float(extrema[4]), abs_acceleration_max_time_s=float(extrema[5]),
        contact_table=contacts, event_table=events, energy=energy, final_state=State._from_kernel(st),
        status=status, message=status.message, oscillator=oscillator, excitation=excitation,
        sample_rate_hz=rate)
    if status == Status.INTERRUPTED:
        raise Interrupted(run, round(run.final_state.time_s - t0, 6), duration, "simulated seconds")
    return run
