"""Where a single mass is: :class:`State`, the core's state vector with its fields named, and the bounds a
state's numbers are checked against."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._checks import at_most, instance_of, real
from .._errors import InputError, Problem
from .layout import DEF_L, DEF_R, IN_L, IN_R, REGION, STATE_BASE, Z_L, Z_R, ZETA
from .layout import D as I_D
from .layout import T as I_T
from .layout import V as I_V

if TYPE_CHECKING:  # pragma: no cover
    from ..model import Oscillator


@dataclass(frozen=True, eq=False)
class State:
    """Complete state of the system at one instant, from which a run continues exactly.

    Build one at rest with :meth:`at_rest`; every :class:`Run` has its ``final_state``.
    The raw vector (``vector``) also holds the isolator's internal variables and the
    running totals of a contact in progress, so that a continued run reports that contact
    whole.

    Attributes
    ----------
    vector : ndarray, shape (37 + 2 (n - 1),)
        The raw state, read-only, for an isolator of ``n`` branches: time, displacement,
        velocity, the bumpers' compressions and contact flags, the isolator's branch, the
        running totals of a contact in progress, the bumper laws' states, the Bouc-Wen ``z``,
        then the slips and slip directions of the isolator's ``n - 1`` springs.  Read it
        through the properties (``time_s``, ``displacement_m``, ``in_contact``, ...).

    Examples
    --------
    Start the paper's YBs system at rest with a push of 0.6 m/s, run it 0.5 s and continue:

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> start = pounding.State.at_rest(ybs, velocity_m_s=0.6)
    >>> run = pounding.simulate(ybs, pounding.Harmonic(a_g=0.05, freq_hz=2.2),
    ...                         duration=0.5, state=start)
    >>> end = run.final_state
    >>> end.time_s, round(end.displacement_m * 1e3, 1), end.in_contact  # s, mm
    (0.5, -12.0, (False, False))
    >>> # mm, the isolator's two slipping springs
    >>> (end.plastic_slips_m * 1e3).round(2).tolist()
    [-3.36, 0.0]
    >>> pounding.simulate(ybs, pounding.Harmonic(a_g=0.05, freq_hz=2.2), 0.5,
    ...                   state=end).final_state.time_s
    1.0
    """

    vector: np.ndarray = field(repr=False)

    def __post_init__(self) -> None:
        vec = _state_vector(self.vector)
        vec.setflags(write=False)
        object.__setattr__(self, "vector", vec)

    @classmethod
    def _from_kernel(cls, vector: np.ndarray) -> "State":
        """A state the engine itself produced: not checked again (a kernel's final state)."""
        state = object.__new__(cls)
        vec = np.array(vector, dtype=float)
        vec.setflags(write=False)
        object.__setattr__(state, "vector", vec)
        return state

    @classmethod
    def at_rest(cls, oscillator: "Oscillator", time_s: float = 0.0, displacement_m: float = 0.0,
                velocity_m_s: float = 0.0) -> "State":
        """Relaxed bumpers and an isolator on its backbone, with the given time and motion.

        Parameters
        ----------
        oscillator : Oscillator
            The system the state is for.
        time_s : float
            Time, s.
        displacement_m : float
            Displacement relative to the table, m, between the bumpers' surfaces
            (``-gap_left_m <= D <= gap_right_m``).  The isolator is where a slow push from 0
            would leave it (on the backbone; a Bouc-Wen spring's z at 0).
        velocity_m_s : float
            Velocity relative to the table, m/s.
        """
        from ..model import Oscillator

        instance_of("oscillator", oscillator, Oscillator, "pounding.Oscillator")
        time_s = at_most("time_s", real("time_s", time_s), MAX_TIME_S, " s", "give the time in s")
        d = at_most("displacement_m", real("displacement_m", displacement_m), MAX_DISPLACEMENT_M, " m",
                    "give the displacement in m")
        v = at_most("velocity_m_s", real("velocity_m_s", velocity_m_s), MAX_VELOCITY_M_S, " m/s",
                    "give the velocity in m/s")
        b = oscillator.bumpers
        if b is not None and not -b.gap_left_m <= d <= b.gap_right_m:
            side, surface = ("left", -b.gap_left_m) if d < 0 else ("right", b.gap_right_m)
            raise InputError(Problem.BAD_STATE, "displacement_m", d,
                             why=f"is inside the {side} bumper, whose surface is at {surface:g} m",
                             fix=f"give a displacement between {-b.gap_left_m:g} and {b.gap_right_m:g} m "
                                 "(a state in contact comes from a run's final_state)")
        iso = oscillator.isolator
        n_sp = iso.n_branches - 1
        vec = np.zeros(STATE_BASE + 2 * n_sp)
        vec[I_T], vec[I_D], vec[I_V] = time_s, d, v
        breaks = np.asarray(iso.breakpoints_m)
        if iso.hysteresis == "elastic":
            vec[REGION] = np.sign(d) * np.searchsorted(breaks, abs(d), side="right")
        else:  # the springs that a monotonic push to d made slip keep that slip
            vec[STATE_BASE:STATE_BASE + n_sp] = d - np.clip(d, -breaks, breaks)
        return cls(vec)

    @property
    def time_s(self) -> float:
        """Time, s."""
        return float(self.vector[I_T])

    @property
    def displacement_m(self) -> float:
        """Displacement ``D`` of the mass relative to the table, m."""
        return float(self.vector[I_D])

    @property
    def velocity_m_s(self) -> float:
        """Velocity of the mass relative to the table, m/s."""
        return float(self.vector[I_V])

    @property
    def bumper_compression_m(self) -> tuple[float, float]:
        """Compression of the (left, right) bumper, m."""
        return float(self.vector[DEF_L]), float(self.vector[DEF_R])

    @property
    def in_contact(self) -> tuple[bool, bool]:
        """Whether the mass touches the (left, right) bumper."""
        return bool(self.vector[IN_L]), bool(self.vector[IN_R])

    @property
    def bumper_law_state(self) -> tuple[float, float]:
        """The (left, right) bumper law's own state: an elastic-plastic law's plastic offset (m,
        >= 0) or its line (-1 the yield line, -2 the unloading line); Hertzdamp's damping of the
        last contact (N s/m^(n+1)); 0 for the other laws (a kinematic multi-linear law's springs:
        :attr:`bumper_slips_m`)."""
        return float(self.vector[Z_L]), float(self.vector[Z_R])

    @property
    def bouc_wen_z(self) -> float:
        """The isolator's Bouc-Wen variable ``z`` (0 without a Bouc-Wen spring)."""
        return float(self.vector[ZETA])

    @property
    def bumper_slips_m(self) -> np.ndarray:
        """Slips (m) of a kinematic multi-linear bumper's springs, shape (2, 3): (left, right) by
        breakpoint (0 for a breakpoint that is no softening, and for the other laws)."""
        return np.array([self.vector[Z_L + 1:Z_L + 4], self.vector[Z_R + 1:Z_R + 4]])

    @property
    def bumper_slip_directions(self) -> np.ndarray:
        """Slip directions (-1, 0, +1) of those springs, shape (2, 3)."""
        return np.array([self.vector[Z_L + 4:Z_L + 7], self.vector[Z_R + 4:Z_R + 7]])

    @property
    def isolator_branch(self) -> int:
        """Backbone branch of an ``elastic`` isolator (0: centre, +-j: j-th outer branch)."""
        return int(self.vector[REGION])

    @property
    def plastic_slips_m(self) -> np.ndarray:
        """Slip ``u_i`` of each elastic-perfectly-plastic spring of a ``kinematic`` isolator, m."""
        n_sp = (self.vector.size - STATE_BASE) // 2
        return self.vector[STATE_BASE:STATE_BASE + n_sp].copy()

    def __repr__(self) -> str:
        return (f"State(time_s={self.time_s:.6g}, displacement_m={self.displacement_m:.6g}, "
                f"velocity_m_s={self.velocity_m_s:.6g}, in_contact={self.in_contact})")


MAX_TIME_S = 1e12
MAX_DISPLACEMENT_M = 1e6
MAX_VELOCITY_M_S = 1e6


def _bad_state(field: str, value: Any, why: str, fix: str) -> InputError:
    return InputError(Problem.BAD_STATE, f"state.{field}", value, why=why, fix=fix)


_FROM_A_RUN = "start from State.at_rest(...) or a run's final_state"


def _state_vector(vector: Any) -> np.ndarray:
    """The raw state vector, checked for what holds whatever the system (see ``layout``)."""
    try:
        vec = np.array(vector, dtype=float)
    except (TypeError, ValueError):
        raise InputError(Problem.NOT_A_NUMBER, "state.vector", vector) from None
    if vec.ndim != 1 or vec.size < STATE_BASE or (vec.size - STATE_BASE) % 2:
        raise _bad_state("vector", f"array of shape {vec.shape}",
                         f"is no state vector (length {STATE_BASE} + 2 x (isolator branches - 1))",
                         _FROM_A_RUN)
    bad = np.flatnonzero(~np.isfinite(vec))
    if bad.size:
        raise InputError(Problem.NOT_FINITE, f"state.vector[{bad[0]}]", float(vec[bad[0]]))
    for i, name, limit in ((I_T, "time_s", MAX_TIME_S), (I_D, "displacement_m", MAX_DISPLACEMENT_M),
                           (I_V, "velocity_m_s", MAX_VELOCITY_M_S)):
        at_most(f"state.{name}", float(vec[i]), limit, "", _FROM_A_RUN)
    for i, name in ((DEF_L, "bumper_compression_m[0]"), (DEF_R, "bumper_compression_m[1]")):
        if vec[i] < 0.0:
            raise _bad_state(name, float(vec[i]), "is negative (a compression is >= 0)", _FROM_A_RUN)
    for i, name in ((IN_L, "in_contact[0]"), (IN_R, "in_contact[1]")):
        if vec[i] not in (0.0, 1.0):
            raise _bad_state(name, float(vec[i]), "is not a contact flag (0 or 1)", _FROM_A_RUN)
    if not float(vec[REGION]).is_integer():
        raise _bad_state("isolator_branch", float(vec[REGION]), "is not a whole number", _FROM_A_RUN)
    n_sp = (vec.size - STATE_BASE) // 2
    dirs = vec[STATE_BASE + n_sp:]
    bad = np.flatnonzero((dirs != -1.0) & (dirs != 0.0) & (dirs != 1.0))
    if bad.size:
        raise _bad_state(f"vector[{STATE_BASE + n_sp + bad[0]}]", float(dirs[bad[0]]),
                         "is not a slip direction (-1, 0 or 1)", _FROM_A_RUN)
    return vec
