"""``periodic_orbit``: a periodic response found by Newton shooting on the engine's
stroboscopic map, with its Floquet multipliers.

The map takes the state of any system (a single mass, a structure, a pair) at a time ``t0`` to the
state one forcing period (or ``period_multiple`` periods) later, by the engine (exact at every event;
the map: ``_shooter``).  Its Jacobian, the monodromy matrix, is composed exactly for systems whose
phases are all linear (multi-linear isolators and storeys without a Bouc-Wen spring; Kelvin-Voigt,
multi-linear, elastic-plastic or rigid contacts): the closed-form state-transition matrices of the phases
between the engine's events, and a saltation matrix at every event (``_hybrid``).  For the other systems
it is a central finite difference of the map (``PeriodicOrbit.method`` says which).

The shooting coordinates are the state's free numbers at ``t0``: every level's displacement and velocity,
the compression of a damped Kelvin-Voigt or elastic multi-linear contact not touched (it relaxes), the slip
of a spring that does not slip; a contact in progress and a slipping spring follow the masses. The contacts
of other laws (and of laws with memory: a kinematic multi-linear bumper, an elastic-plastic one) are no
coordinates: their compressions and their own states follow the motion (a stiff contact's relaxation is over
long before the period ends).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from .._errors import InputError, Problem, old_names, renamed_keyword
from ..engine import Run, State, simulate, structure_runs
from ..engine.assembly import check_system
from ..engine.simulate import check_state
from ..excitation import Harmonic
from ..model import Oscillator
from ..model.adjacent import Adjacent
from ..model.structure import Structure  # noqa: F401  (the annotations')
from . import _hybrid as hy
from ._args import exact_monodromy, orbit_arguments, settled
from ._shooter import _Shooter
from ._shooting import Floquet, _Failed, multipliers_of  # noqa: F401  (_Failed: the solvers' failure, here)


@dataclass(frozen=True, eq=False)
class _Orbit(Floquet):
    """What every periodic orbit holds (its attributes: :class:`PeriodicOrbit`'s)."""

    state: State
    period_s: float
    multipliers: np.ndarray = field(repr=False)
    monodromy: np.ndarray = field(repr=False)
    coordinates: tuple[str, ...]
    residual: float
    converged: bool
    iterations: int
    method: str
    run: Any = field(repr=False)
    message: str


@dataclass(frozen=True, eq=False)
class PeriodicOrbit(_Orbit):
    """A periodic response and its stability (what :func:`periodic_orbit` returns), of any system.

    Attributes
    ----------
    state : State
        The orbit's state at the section time (``state.time_s``).
    period_s : float
        Its period, s: ``period_multiple`` periods of the forcing.
    multipliers : ndarray of complex, shape (r,)
        Floquet multipliers: the eigenvalues of ``monodromy``, largest modulus first.
    max_abs_multiplier : float
        The largest ``|multiplier|`` (NaN without a monodromy: a search that stopped early).
    stable : bool
        Whether every multiplier lies inside the unit circle.
    monodromy : ndarray, shape (r, r)
        Jacobian of the stroboscopic map in the shooting coordinates ``coordinates``.
    coordinates : tuple of str
        Names of the shooting coordinates: ``x_<level>`` and ``v_<level>`` for each moving level
        (``first.``/``second.`` for a pair; ``stand_<wall>_<side>`` for a wall's stand),
        ``delta_wall<w>_<side>`` and ``delta_link<k>`` for a relaxing contact's compression, ``u_<spring>``
        for a spring's slip, ``z`` for a Bouc-Wen spring's; a single mass's are its one level's
        (``x_0``, ``v_0``, ``delta_wall0_left``, ...).
    residual : float
        Largest difference between the state and its image one period later, each coordinate
        over its scale (lengths over the largest ``|x|`` of any level over the guess's first period,
        velocities over that times Omega, the Bouc-Wen z over 1).
    converged : bool
        Whether ``residual <= tol``.
    iterations : int
        Newton iterations made.
    method : str
        How ``monodromy`` was computed: ``"exact"`` (state-transition and saltation matrices)
        or ``"finite-difference"``.
    run : Run, StructureRun or AdjacentRun
        One period from ``state``, densely sampled.
    message : str
        What happened, for people.
    alpha, excursion_m, eta : float, or ndarray of shape (levels,)
        A single mass's, or each level's of a system of several (a pair's: the first's levels, then the
        second's): see the properties.

    Examples
    --------
    >>> import pounding
    >>> orbit = pounding.periodic_orbit(pounding.presets.paper_damped(),
    ...                                 pounding.Harmonic(0.05, 1.5))
    >>> orbit.method, orbit.coordinates
    ('exact', ('x_0', 'v_0', 'delta_wall0_left', 'delta_wall0_right', 'u_0'))
    >>> round(orbit.period_s, 4), orbit.contacts_per_period, orbit.stable
    (0.6667, 2, True)
    >>> print(f"alpha {orbit.alpha:.2f}, eta {orbit.eta:.3f}, max |mu| "
    ...       f"{orbit.max_abs_multiplier:.3f}")
    alpha 8.30, eta 1.066, max |mu| 0.368

    A two-level building against a stop at its base:

    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=4.0e3)
    >>> stop = pounding.Wall(0, 0.02, 0.02, pounding.KelvinVoigt(1.0e8, 2.0e4))
    >>> b = pounding.Structure(2.0e3, iso,
    ...                        [pounding.Storey(1.0e3, 2.0e6, 2.0e3)], [stop])
    >>> orbit = pounding.periodic_orbit(b, pounding.Harmonic(0.1, 1.5))
    >>> orbit.converged, orbit.method, orbit.coordinates[:4]
    (True, 'exact', ('x_0', 'x_1', 'v_0', 'v_1'))
    >>> orbit.contacts_per_period, orbit.stable, orbit.alpha.shape
    (2, True, (2,))
    """

    def _levels(self, values: list) -> "float | np.ndarray":
        """Per-level numbers as this orbit gives them: a single mass's its one float, else an array over
        the levels (a pair's: the first's, then the second's)."""
        out = np.concatenate(values)
        return float(out[0]) if isinstance(self.run, Run) else out

    @property
    def alpha(self) -> "float | np.ndarray":
        """Peak absolute acceleration over the table's peak, ``max|a_abs| / A_t``: a single mass's, or each
        level's, shape (levels,)."""
        peak = abs(self.run.excitation.peak_m_s2)
        acc = [part.abs_acceleration_max for part in structure_runs(self.run)]
        return self._levels([a / peak if peak > 0.0 else np.full(a.shape, math.nan) for a in acc])

    @property
    def excursion_m(self) -> "float | np.ndarray":
        """``D_max - D_min`` over the period, m: a single mass's, or each level's, shape (levels,)."""
        return self._levels([part.excursion_m for part in structure_runs(self.run)])

    @property
    def eta(self) -> "float | np.ndarray":
        """Excursion over the total gap of the wall at its level (``gap_left_m + gap_right_m``; a single
        mass's bumpers), NaN without one: a single mass's, or each level's, shape (levels,)."""
        return self._levels([part.excursion_m / _total_gaps(part.structure)
                             for part in structure_runs(self.run)])

    def _contact_tables(self) -> list:
        parts = structure_runs(self.run)
        return [p.contact_table for p in parts] + ([self.run.link_table] if len(parts) > 1 else [])

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The orbit in the phase plane (x, v), each level's, its contacts marked; see
        :func:`pounding.plots.plot_orbit`.  Returns its Figure."""
        from ..plots.periodic import plot_orbit
        from ..plots import figure_of

        return figure_of(plot_orbit(self, ax=ax, **kwargs), ax)


def _total_gaps(structure: "Structure") -> np.ndarray:
    """Each level's total gap: its first wall's ``gap_left_m + gap_right_m``, m (NaN without a wall)."""
    gaps = np.full(structure.n_levels, math.nan)
    for wall in reversed(structure.walls):
        gaps[wall.level] = wall.gap_left_m + wall.gap_right_m
    return gaps


@renamed_keyword("oscillator", "system")
def periodic_orbit(
    system: "Oscillator | Structure | Adjacent",
    excitation: Harmonic,
    *,
    guess: Optional[State] = None,
    period_multiple: int = 1,
    tol: float = 1e-10,
    max_iter: int = 40,
    settle_cycles: int = 100,
    method: str = "auto",
    samples_per_period: int = 400,
) -> PeriodicOrbit:
    """Find a periodic response by Newton shooting, with its exact Floquet multipliers.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system: one mass, or a structure of several (or two adjacent ones): ``guess`` is then a
        structure's :class:`State` (its
        shooting coordinates every mass's displacement and velocity, the relaxing contacts'
        compressions and the sticking springs' slips; the monodromy exact, saltation at each
        contact, for Kelvin-Voigt, multi-linear, elastic-plastic and rigid contacts and multi-linear
        isolators and storeys).
    excitation : Harmonic
        The table's harmonic acceleration.
    guess : State, optional
        Where to start the search (its time is the section time).  Default: the state after
        ``settle_cycles`` periods from rest, which finds the response a sweep would settle on.
    period_multiple : int
        The orbit's period in periods of the forcing (2 for a period-doubled response).
    tol : float
        Largest residual accepted, relative to the orbit's size (see ``PeriodicOrbit.residual``).
    max_iter : int
        Newton iterations at most.
    settle_cycles : int
        Forcing periods run from rest for the default guess.
    method : {"auto", "exact", "finite-difference"}
        The monodromy: composed exactly (systems with linear phases only: ``"auto"`` takes it
        where it can) or by central finite differences of the map.
    samples_per_period : int
        Samples of the returned ``run``.

    Returns
    -------
    PeriodicOrbit
        ``converged`` False when Newton did not reach ``tol`` (``message`` says why); the
        orbit is then the best iterate.

    Examples
    --------
    The damped paper system at a_G = 0.05 and 1.5 Hz: a stable response that hits both bumpers
    once per cycle.

    >>> import pounding
    >>> orbit = pounding.periodic_orbit(pounding.presets.paper_damped(),
    ...                                 pounding.Harmonic(0.05, 1.5))
    >>> orbit.converged, orbit.stable, orbit.contacts_per_period
    (True, True, 2)
    >>> [round(float(v), 3) for v in orbit.impact_velocities_m_s]
    [-0.068, 0.068]
    """
    check_system(system)
    period_multiple, tol, max_iter, settle_cycles, samples_per_period = orbit_arguments(
        excitation, period_multiple, tol, max_iter, settle_cycles, samples_per_period)
    exact = exact_monodromy(system, method)
    period = period_multiple / excitation.freq_hz
    if guess is None:
        guess = settled(system, excitation, settle_cycles).final_state
    elif not isinstance(guess, State):
        raise InputError(Problem.WRONG_TYPE, "guess", guess, got=type(guess).__name__,
                         expected="pounding.State (e.g. run.final_state)")
    else:
        try:
            guess = check_state(guess, system)
        except InputError as exc:
            raise InputError(Problem.BAD_STATE, "guess", guess, why=f"is not a state of this system ({exc})",
                             fix="give a state of this system, e.g. a run's final_state") from None
    shooter = _Shooter(system, excitation, period, exact)
    with hy.one_blas_thread():
        vec, res, jac, frozen, it, message = shooter.solve(np.array(guess.vector, dtype=float), tol, max_iter)
    # the state one period on: the same point of the orbit, with the running totals of a contact in
    # progress its own (the guess's otherwise)
    state = simulate(system, excitation, period, shooter._state(vec), sample_rate_hz=0).final_state
    run = simulate(system, excitation, period, state, sample_rate_hz=samples_per_period / period)
    return PeriodicOrbit(state, period, multipliers_of(jac), jac, tuple(shooter.names(vec, frozen)), res,
                         res <= tol, it, "exact" if shooter.exact else "finite-difference", run, message)


# its name before one orbit served every system, for one release
__getattr__ = old_names(__name__, {
    "StructurePeriodicOrbit": ("pounding.PeriodicOrbit", lambda: PeriodicOrbit,
                               "one class for every system")})
