"""What every run of the engine checks and builds alike, a single mass's or a structure's: the integration
tolerance, the history's sample rate, the forcing as the core takes it."""

from __future__ import annotations

from typing import Any, NamedTuple, Optional

import numpy as np

from .._checks import instance_of, integer, non_negative, positive
from .._errors import InputError, Problem
from ..excitation import Harmonic, Record, RecordPair
from ._system import Forcing
from .assembly import Assembly, assemble
from .state import State
from .state_check import check_state


def check_rtol(rtol: float) -> float:
    """The integration tolerance of nonlinear contact laws, in (0, 1e-3]."""
    rtol = positive("rtol", rtol, "(relative)")
    if not 1e-14 <= rtol <= 1e-3:
        raise InputError(Problem.OUT_OF_RANGE, "rtol", rtol, range="[1e-14, 1e-3]",
                         hint=" (below 1e-14 the steps cannot meet it in double precision)")
    return rtol


def kernel_forcing(excitation: Harmonic | Record | RecordPair) -> Forcing:
    """The excitation as the kernels' forcing record (a pair's: its x component first, its y second)."""
    if isinstance(excitation, RecordPair):
        kind, p, rec_t, rec_a = excitation.x.kernel_arrays()
        return Forcing(kind=int(kind), p=p, rec_t=rec_t, rec_a=rec_a,
                       rec_b=np.array(excitation.y.accel, dtype=float))
    kind, p, rec_t, rec_a = excitation.kernel_arrays()
    return Forcing(kind=int(kind), p=p, rec_t=rec_t, rec_a=rec_a)


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


class RunArgs(NamedTuple):
    """A run's arguments, checked (:func:`checked_run_args`), with what its work estimate counts from."""

    asm: Assembly        # the system, assembled
    state: State         # the state to run from
    duration: float      # s
    rtol: float
    rate: float          # samples per second (0: none)
    max_events: int
    max_steps: int
    omega: float         # the forcing's angular frequency, rad/s (0 for a record)
    knots: int           # a record's samples within the run (0 for a harmonic)


def checked_run_args(system: Any, excitation: Any, duration: Any, state: Any, rtol: Any, sample_rate_hz: Any,
                     max_events: Any, max_steps: Any) -> RunArgs:
    """``simulate``'s arguments of any system checked, in their order (the system's own type checked
    before), its state the one to run from."""
    instance_of("excitation", excitation, (Harmonic, Record), "pounding.Harmonic or pounding.Record")
    duration = positive("duration", duration, "s")
    rtol = check_rtol(rtol)
    max_events = integer("max_events", max_events, 1)
    max_steps = integer("max_steps", max_steps, 1)
    asm = assemble(system)
    state = check_state(state, system, asm)
    rate = history_rate(sample_rate_hz, duration)
    t0 = state.time_s
    omega = excitation.omega_rad_s if isinstance(excitation, Harmonic) else 0.0
    knots = 0
    if isinstance(excitation, Record):
        knots = int(np.count_nonzero((excitation.t >= t0) & (excitation.t <= t0 + duration)))
    return RunArgs(asm, state, duration, rtol, rate, max_events, max_steps, omega, knots)
