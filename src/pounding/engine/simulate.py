"""``simulate``: the validating wrapper around the compiled kernel."""

from __future__ import annotations

from typing import Optional

from .._checks import integer, non_negative, positive
from .._errors import InputError, Problem, Status
from ..excitation import Harmonic, Record
from ..model import Oscillator
from ..model.contact_laws import KelvinVoigt
from ._kernel import run_kernel
from .result import EnergyLedger, Run, State

_NO_LAW = KelvinVoigt(1.0, 0.0)  # stands in for absent bumpers (never touched)


def check_oscillator(oscillator: Oscillator) -> None:
    if not isinstance(oscillator, Oscillator):
        raise InputError(Problem.WRONG_TYPE, "oscillator", oscillator,
                         got=type(oscillator).__name__, expected="pounding.Oscillator")


def check_rtol(rtol: float) -> float:
    """The integration tolerance of nonlinear contact laws, in (0, 1e-3]."""
    rtol = positive("rtol", rtol, "(relative)")
    if rtol > 1e-3:
        raise InputError(Problem.NOT_ONE_OF, "rtol", rtol, choices="values in (0, 1e-3]")
    return rtol


def check_state(state: Optional[State], oscillator: Oscillator) -> State:
    """``state``, or rest at t = 0 when None; it must belong to a system like ``oscillator``."""
    if state is None:
        return State.at_rest(oscillator)
    if not isinstance(state, State):
        raise InputError(Problem.WRONG_TYPE, "state", state, got=type(state).__name__,
                         expected="pounding.State (e.g. run.final_state)")
    expected = State.at_rest(oscillator).vector.size
    if state.vector.size != expected:
        raise InputError(Problem.LENGTH_MISMATCH, "state", state, got=state.vector.size, expected=expected)
    return state


def kernel_system(oscillator: Oscillator) -> tuple:
    """The oscillator as the kernel's leading arguments (arrays and scalars only)."""
    slopes, breaks, rule = oscillator.isolator.kernel_arrays()
    b = oscillator.bumpers
    left = right = _NO_LAW
    gap_l = gap_r = 0.0
    if b is not None:
        left, right, gap_l, gap_r = b.left, b.right, b.gap_left, b.gap_right
    return (oscillator.mass, oscillator.isolator.damping, slopes, breaks, rule, b is not None,
            gap_l, gap_r, left.LAW_ID, left.params(), right.LAW_ID, right.params())


def simulate(
    oscillator: Oscillator,
    excitation: Harmonic | Record,
    duration: float,
    state: Optional[State] = None,
    *,
    rtol: float = 1e-10,
    sample_rate_hz: float = 1000.0,
    max_events: int = 10_000_000,
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
    sample_rate_hz : float
        Rate of the uniform history samples, Hz (0: only the start, the events and the end).
        Extrema, contacts and energies are exact whatever the rate.
    max_events : int
        The run stops with ``Status.MAX_EVENTS`` after this many events.

    Returns
    -------
    Run
        Histories, exact extrema, contacts, energy ledger, final state, status and message.
    """
    check_oscillator(oscillator)
    if not isinstance(excitation, (Harmonic, Record)):
        raise InputError(Problem.WRONG_TYPE, "excitation", excitation,
                         got=type(excitation).__name__, expected="pounding.Harmonic or pounding.Record")
    duration = positive("duration", duration, "s")
    rate = non_negative("sample_rate_hz", sample_rate_hz, "Hz")
    rtol = check_rtol(rtol)
    max_events = integer("max_events", max_events, 1)
    state = check_state(state, oscillator)

    exc_kind, exc_p, rec_t, rec_a = excitation.kernel_arrays()
    t0 = state.time_s
    st, samples, contacts, events, ledger, extrema, status = run_kernel(
        *kernel_system(oscillator), exc_kind, exc_p, rec_t, rec_a, state.vector.copy(),
        t0 + duration, 1.0 / rate if rate > 0 else 0.0, rtol, int(max_events), True)
    status = Status(int(status))

    energy = EnergyLedger(
        input_work=ledger[0], kinetic=ledger[4], isolator_elastic=ledger[5],
        bumper_elastic=ledger[6], viscous=ledger[1], hysteretic=ledger[2],
        bumper_dissipation=ledger[3])
    cols = samples.T
    return Run(
        t=cols[0], displacement=cols[1], velocity=cols[2], abs_acceleration=cols[3],
        isolator_force=cols[4], bumper_force_left=cols[5], bumper_force_right=cols[6],
        displacement_max=float(extrema[0]), displacement_max_time_s=float(extrema[1]),
        displacement_min=float(extrema[2]), displacement_min_time_s=float(extrema[3]),
        abs_acceleration_max=float(extrema[4]), abs_acceleration_max_time_s=float(extrema[5]),
        contact_table=contacts, event_table=events, energy=energy, final_state=State(st),
        status=status, message=status.message, oscillator=oscillator, excitation=excitation)
