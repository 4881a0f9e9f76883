"""``Branch`` and ``Bifurcation``: what :func:`pounding.continuation` returns."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Optional, Sequence

import numpy as np
import pandas as pd

from .._errors import InputError, Problem, Status
from ..engine import State

if TYPE_CHECKING:  # pragma: no cover
    from ..model import Oscillator
    from ..protocols.sweep_result import SweepResult
    from .periodic import PeriodicOrbit

KINDS = ("fold", "branch-point", "period-doubling", "neimark-sacker", "grazing")

# the table's columns, in order (the parameter's own column comes first when it is a system number)
COLUMNS = ("freq_hz", "nu", "a_g", "alpha", "excursion_m", "displacement_max_m", "displacement_min_m", "eta",
           "stable", "max_abs_multiplier", "contacts_per_period", "impact_velocity_max_m_s",
           "period_multiple", "residual", "arclength", "phase_rad")


def _first_mass(state: Any) -> tuple[float, float]:
    """(displacement m, velocity m/s) of the mass, or of a structure's first moving mass (its base)."""
    q = next(q for q, d in enumerate(state.dofs[0]) if d >= 0)
    return float(state.displacements_m[q]), float(state.velocities_m_s[q])


@dataclass(frozen=True, eq=False)
class Bifurcation:
    """A special point of a branch, located between two of its points.

    Attributes
    ----------
    kind : {"fold", "branch-point", "period-doubling", "neimark-sacker", "grazing"}
        ``fold``: the branch turns back (a multiplier crosses +1; a saddle-node); the response
        jumps there in a sweep.  ``branch-point``: another branch crosses this one (a symmetric
        orbit's pitchfork; pass this object as ``guess`` to :func:`pounding.continuation` to
        follow the branch left there).  ``period-doubling``: a multiplier crosses -1 (a branch of twice
        the period starts: pass this object as ``guess`` to :func:`pounding.continuation`).
        ``neimark-sacker``: a complex pair crosses the unit circle.  ``grazing``: the orbit
        touches a bumper with zero velocity (a contact appears or vanishes; ``side`` says which).
    value : float
        The continued parameter's value there.
    freq_hz, a_g : float
        The forcing there (Hz, g).
    multipliers : ndarray of complex
        The orbit's Floquet multipliers there, largest modulus first.
    state : State
        The orbit's state at the section (time 0).
    index : int
        The branch's rows before it: it lies between rows ``index - 1`` and ``index``.
    side : str
        The contact of a grazing (``"wall0_left"``, ``"wall0_right"``: a single mass's bumpers; a
        structure's ``"wall<w>_<side>"``, ``"link<k>"``), else ``""``.
    direction : ndarray
        For a period-doubling, the critical eigenvector in every coordinate of the system's state (every
        level's ``x_<level>``, then ``v_<level>``, every contact's compression, every hysteretic element's
        slips ``u_<i>``, zero for one of the elastic rule, then ``z``; unscaled); for a branch point, the
        other branch's tangent (those coordinates, then the parameter); else the branch's tangent's
        coordinate parts.
    period_multiple : int
        The branch's period, in forcing periods.
    alpha : float
        Peak absolute acceleration over the table's peak there.
    located : bool
        Whether the location met its tolerance (the test function's zero to 1e-8, or the
        step's interval to 1e-9 of the step).
    phase_rad : float
        The forcing's angle at the section where ``state`` is, rad.
    tangent : ndarray
        The branch's tangent there: the coordinates' parts (unscaled), then the parameter's.
    parameter : str
        The parameter of the branch it is on (``"freq_hz"``, ``"a_g"`` or a dotted name).
    scaling_exponent : float
        For a located grazing, the measured exponent ``gamma`` of the Poincare map's singular part
        against the depth ``delta`` the free orbit would reach past the contact: ``P(x) = P_0(x) + c
        delta^gamma + O(delta^(gamma + 1/2))``.  1/2 at a rigid stop (the square-root singularity); at a
        deformable bumper 1 where its force jumps at the touch (a dashpot's), 3/2 where it starts from
        zero (a spring's).  Measured with the engine from the map's second difference across the
        grazing, at would-be depths of 1e-8 and 1e-10 of the orbit's size.  NaN otherwise.
    scaling_term : ndarray
        For a located grazing, ``c``: the map's singular part over ``delta ** gamma`` (``gamma`` 1/2 at
        a rigid stop, else the measured one to the nearest half), in the state coordinates of
        ``direction`` (their units per m^gamma); empty otherwise.  At a rigid stop it is the impact's
        velocity jump over ``sqrt(delta)``, ``-(1 + e) sqrt(2 a_n)`` (``a_n`` the acceleration away from
        the stop at the touch), carried to the section by the flow.

    Examples
    --------
    The first fold of the damped paper system's branch at a_G = 0.05: there a stable and an
    unstable orbit meet (a multiplier is 1) and an up sweep jumps off the impacting response.

    >>> import pounding
    >>> branch = pounding.continuation(pounding.presets.paper_damped(), 0.05,
    ...                                (1.5, 2.5))
    >>> fold = branch.folds()[0]
    >>> fold.kind, round(fold.freq_hz, 4), fold.a_g, fold.located
    ('fold', 2.0144, 0.05, True)
    >>> round(float(fold.multipliers[0].real), 6), round(fold.alpha, 1)
    (1.0, 12.5)
    """

    kind: str
    value: float
    freq_hz: float
    a_g: float
    multipliers: np.ndarray = field(repr=False)
    state: State = field(repr=False)
    index: int
    side: str = ""
    direction: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    period_multiple: int = 1
    alpha: float = math.nan
    located: bool = True
    phase_rad: float = 0.0
    tangent: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    parameter: str = ""
    scaling_exponent: float = math.nan
    scaling_term: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)

    def to_series(self) -> pd.Series:
        """The bifurcation as one row: kind, side, parameter value, ``freq_hz``, ``a_g``, alpha,
        max ``|mu|``, index, located, and a grazing's ``scaling_exponent``."""
        return pd.Series({"kind": self.kind, "side": self.side, "value": self.value, "freq_hz": self.freq_hz,
                          "a_g": self.a_g, "alpha": self.alpha, "max_abs_multiplier":
                          float(np.abs(self.multipliers).max()) if self.multipliers.size else math.nan,
                          "index": self.index, "located": self.located,
                          "scaling_exponent": self.scaling_exponent})


class FollowedTable:
    """What a followed branch or curve (a dataclass with ``status`` and a table ``data``, a row per point)
    says of itself: ``success`` and its length."""

    @property
    def success(self) -> bool:
        """True when it was followed to its end (``status`` is ``SUCCESS``; the class's ``status``
        says what that end is)."""
        return self.status == Status.SUCCESS  # type: ignore[attr-defined]

    def __len__(self) -> int:
        return int(self.data.shape[0])  # type: ignore[attr-defined]


@dataclass(frozen=True, eq=False)
class Branch(FollowedTable):
    """A branch of periodic orbits followed in one parameter.

    Attributes
    ----------
    oscillator : Oscillator, Structure or Adjacent
        The system at the start (the parameter's value set as ``values[0]`` when it is a
        number of the system).  A structure's rows give its largest alpha over every level,
        its first moving mass's (its base's) extrema and excursion (``eta`` over its wall there),
        and its contacts at every wall side and link; its grazings name the wall side or link
        (``side``: ``wall0_left``, ``link0``).
    parameter : str
        ``"freq_hz"``, ``"a_g"`` or a dotted name of the system (``"bumpers.gap_left_m"``).
    values : tuple of float
        The range asked for, ``(start, end)``.
    period_multiple : int
        The orbits' period in forcing periods.
    f_ref_hz : float
        The frequency ``nu`` is relative to (1 Hz: the paper's).
    data : DataFrame
        One row per point in the order followed (see :meth:`to_dataframe`).
    states : ndarray, shape (points, state length)
        The engine's state vector of each orbit at its section (time 0, the forcing's angle
        the table's ``phase_rad``: the section moves along the branch, to the middle of an
        orbit's longest stretch without events, when an event comes near it).
    multipliers : ndarray of complex, shape (points, r)
        Each orbit's Floquet multipliers, largest modulus first (NaN-padded: the number of
        shooting coordinates can change along the branch).
    bifurcations : tuple of Bifurcation
        In the order met.
    status : Status
        ``SUCCESS`` when the branch reached an end of the range, ``STEP_FAILED`` when the
        corrector failed at the smallest step, ``BUDGET`` at ``max_points``, ``INTERRUPTED``
        on Ctrl-C.
    message : str
        What happened, for people.
    a_g, freq_hz : float
        The forcing held fixed: the table's peak acceleration, g, and the frequency, Hz (NaN for
        the one continued).

    Examples
    --------
    The damped paper system's branch at a_G = 0.05 from 1.5 to 2.5 Hz: it folds twice, and just
    past the second fold it grazes both bumpers.

    >>> import pounding
    >>> branch = pounding.continuation(pounding.presets.paper_damped(), 0.05,
    ...                                (1.5, 2.5))
    >>> branch.status.name, branch.parameter, branch.a_g
    ('SUCCESS', 'freq_hz', 0.05)
    >>> [(b.kind, b.side, round(b.freq_hz, 3)) for b in branch.bifurcations]
    [('fold', '', 2.014), ('fold', '', 1.605), ('grazing', 'wall0_left', 1.605),
     ('grazing', 'wall0_right', 1.605)]
    >>> df = branch.to_dataframe()
    >>> round(float(df["alpha"].max()), 1), bool(df["stable"].iloc[0])
    (12.8, True)
    """

    oscillator: "Oscillator" = field(repr=False)
    parameter: str
    values: tuple[float, float]
    period_multiple: int
    f_ref_hz: float
    data: pd.DataFrame = field(repr=False)
    states: np.ndarray = field(repr=False)
    multipliers: np.ndarray = field(repr=False)
    bifurcations: tuple[Bifurcation, ...]
    status: Status
    message: str
    a_g: float = math.nan          # the forcing held fixed (NaN for the one continued)
    freq_hz: float = math.nan

    def to_xarray(self) -> Any:
        """The table of :meth:`to_dataframe` as a Dataset along ``orbit`` (the branch's order)."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "orbit",
                               {"parameter": self.parameter, "status": self.status.name,
                                "message": self.message})

    def to_dataframe(self) -> pd.DataFrame:
        """One row per orbit, in the order followed (SI units).

        Columns: the parameter (when it is a system number), ``freq_hz``, ``nu``, ``a_g``,
        ``alpha``, ``excursion_m``, ``displacement_max_m``, ``displacement_min_m``, ``eta``,
        ``stable``, ``max_abs_multiplier``, ``contacts_per_period``, ``impact_velocity_max_m_s``,
        ``period_multiple``, ``residual`` (scaled, see ``PeriodicOrbit.residual``), ``arclength``
        (scaled: the parameter's range is 1), ``phase_rad`` (the forcing's angle at the section).
        """
        return self.data.copy()

    def bifurcation_table(self) -> pd.DataFrame:
        """The bifurcations, one row each (``kind``, ``side``, ``value``, ``freq_hz``, ``a_g``,
        ``alpha``, ``max_abs_multiplier``, ``index``, ``located``, a grazing's ``scaling_exponent``)."""
        cols = ["kind", "side", "value", "freq_hz", "a_g", "alpha", "max_abs_multiplier", "index", "located",
                "scaling_exponent"]
        return pd.DataFrame([b.to_series() for b in self.bifurcations], columns=cols)

    def folds(self) -> tuple[Bifurcation, ...]:
        """The branch's folds (where sweeps jump), in the order they were met."""
        return tuple(b for b in self.bifurcations if b.kind == "fold")

    def section(self, phase_rad: float = 0.0) -> pd.DataFrame:
        """Each orbit where the forcing's angle is ``phase_rad`` (0: table phase 0, the section a
        sweep's strobes and :func:`pounding.bifurcation_diagram` use): ``freq_hz``, ``a_g``,
        ``displacement_m``, ``velocity_m_s``, ``stable``, and ``point`` (the row of the branch's
        table); a period-k orbit crosses it k times, one row each (a structure's: its first moving
        mass's, its base's).  For branches in ``freq_hz`` or ``a_g``."""
        from .._checks import real
        from ..engine.simulate import simulate
        from ..excitation import Harmonic

        if self.parameter not in ("freq_hz", "a_g"):
            raise InputError(Problem.BAD_STATE, "branch", self.parameter, why="is a number of the system",
                             fix="take the section of a branch in 'freq_hz' or 'a_g'")
        target = real("phase_rad", phase_rad)
        rows = []
        for i, row in enumerate(self.data.itertuples(index=False)):
            exc = Harmonic(float(row.a_g), float(row.freq_hz), phase=float(row.phase_rad))
            period = 2.0 * math.pi / exc.omega_rad_s
            state = self._state(i)
            wait = ((target - float(row.phase_rad)) % (2.0 * math.pi)) / exc.omega_rad_s
            for _ in range(self.period_multiple):
                if wait > 1e-12 * period:
                    state = simulate(self.oscillator, exc, duration=wait, state=state,
                                     sample_rate_hz=0.0).final_state
                rows.append((float(row.freq_hz), float(row.a_g), *_first_mass(state), bool(row.stable), i))
                wait = period
        return pd.DataFrame(rows, columns=["freq_hz", "a_g", "displacement_m", "velocity_m_s", "stable",
                                           "point"])

    def orbit(self, index: int, **kwargs: Any) -> "PeriodicOrbit":
        """The ``index``-th orbit as a :class:`PeriodicOrbit` (densely sampled run, ``plot``);
        ``kwargs`` go to :func:`pounding.periodic_orbit`."""
        from ..excitation import Harmonic
        from .periodic import periodic_orbit

        import inspect

        allowed = set(inspect.signature(periodic_orbit).parameters) - {"oscillator", "excitation", "guess"}
        for key in kwargs:
            if key not in allowed:
                raise InputError(Problem.UNKNOWN_KEY, key, kwargs[key], choices=", ".join(sorted(allowed)))
        n = len(self)
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)):
            raise InputError(Problem.WRONG_TYPE, "index", index, got=type(index).__name__, expected="int")
        if not -n <= index < n:
            raise InputError(Problem.OUT_OF_RANGE, "index", index, range=f"[{-n}, {n - 1}]",
                             hint=" (a row of the branch's table)")
        row = self.data.iloc[int(index)]
        osc = self.oscillator
        if self.parameter not in ("freq_hz", "a_g"):
            from ..model.dotted import set_value

            d = osc.to_dict()
            set_value(d, self.parameter, float(row[self.parameter]))
            osc = type(osc).from_dict(d)
        exc = Harmonic(float(row["a_g"]), float(row["freq_hz"]), phase=float(row["phase_rad"]))
        kwargs.setdefault("period_multiple", self.period_multiple)
        return periodic_orbit(osc, exc, guess=self._state(int(index)), **kwargs)

    def _state(self, index: int) -> Any:
        """Orbit ``index``'s state at its section."""
        from ..engine.assembly import assemble

        asm = assemble(self.oscillator)
        return State._of(self.states[index], asm.dofs, asm.layout)

    def plot(self, ax: Any = None, *, y: str = "alpha", x: Optional[str] = None,
             sweeps: "SweepResult | Sequence[SweepResult] | None" = None, **kwargs: Any) -> Any:
        """The branch: ``y`` against the parameter (``nu`` for the frequency), stable orbits
        solid, unstable dashed, bifurcations marked; ``sweeps`` drawn over it as markers.

        Returns its Figure.
        """
        from ..plots.branch import plot_branch
        from ..plots import figure_of

        return figure_of(plot_branch(self, ax=ax, y=y, x=x, sweeps=sweeps, **kwargs), ax)

    def __repr__(self) -> str:
        kinds = ", ".join(f"{b.kind} at {b.value:.6g}" for b in self.bifurcations) or "none"
        return (f"Branch({self.parameter} from {self.values[0]:.10g} to {self.values[1]:.10g}, {len(self)} "
                f"orbits, period {self.period_multiple}, bifurcations: {kinds}; {self.status.name}: "
                f"{self.message})")
