"""``periodic_orbit``: a periodic response found by Newton shooting on the engine's
stroboscopic map, with its Floquet multipliers.

The map takes the state at a time ``t0`` to the state one forcing period (or ``period_multiple``
periods) later, by the engine (``pounding.simulate``, exact at every event).  Its Jacobian, the
monodromy matrix, is composed exactly for systems whose phases are all linear (a multi-linear
isolator without Bouc-Wen spring, Kelvin-Voigt bumpers): the closed-form state-transition
matrices of the phases between the engine's events, and a saltation matrix at every event
(``_hybrid``).  For the other systems it is a central finite difference of the map
(``PeriodicOrbit.method`` says which).

The shooting coordinates are the state's free numbers at ``t0``: the displacement and velocity,
the compression of a Kelvin-Voigt bumper not touched (it relaxes), the slip of an isolator spring
that does not slip; a bumper in contact and a slipping spring follow the mass.  The bumpers of
other laws are no coordinates: their compressions and their own states follow the motion (a
stiff bumper's relaxation is over long before the period ends).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from .._errors import InputError, Problem, renamed_keyword
from ..engine import Run, State, simulate
from ..engine.layout import C_SLOT, C_T_END, C_T_START, C_V_IN
from ..engine.assembly import assemble
from ..engine.run_args import kernel_forcing
from ..engine.state import ONE_MASS_DOFS, one_mass_layout
from ..engine.simulate import NotAState, check_oscillator, check_state, short_run
from ..excitation import Harmonic
from ..model import Oscillator
from ..model.adjacent import Adjacent
from ..model.structure import Structure
from ..model.contact_laws import is_rigid
from . import _hybrid as hy
from ._args import exact_monodromy, orbit_arguments, settled
from ._shooting import Floquet, _Failed, _Newton, at_section, multipliers_of



@dataclass(frozen=True, eq=False)
class PeriodicOrbit(Floquet):
    """A periodic response and its stability (what :func:`periodic_orbit` returns).

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
        Names of the shooting coordinates (``D``, ``V``, ``delta_L``, ``delta_R``, ``u_i``).
    residual : float
        Largest difference between the state and its image one period later, each coordinate
        over its scale (lengths over the largest ``|D|`` over the guess's first period, velocities
        over that times Omega, the Bouc-Wen z over 1).
    converged : bool
        Whether ``residual <= tol``.
    iterations : int
        Newton iterations made.
    method : str
        How ``monodromy`` was computed: ``"exact"`` (state-transition and saltation matrices)
        or ``"finite-difference"``.
    run : Run
        One period from ``state``, densely sampled.
    message : str
        What happened, for people.

    Examples
    --------
    >>> import pounding
    >>> orbit = pounding.periodic_orbit(pounding.presets.paper_damped(),
    ...                                 pounding.Harmonic(0.05, 1.5))
    >>> orbit.method, orbit.coordinates
    ('exact', ('D', 'V', 'delta_L', 'delta_R', 'u_0'))
    >>> round(orbit.period_s, 4), orbit.contacts_per_period, orbit.stable
    (0.6667, 2, True)
    >>> print(f"alpha {orbit.alpha:.2f}, eta {orbit.eta:.3f}, max |mu| "
    ...       f"{orbit.max_abs_multiplier:.3f}")
    alpha 8.30, eta 1.066, max |mu| 0.368
    """

    state: State
    period_s: float
    multipliers: np.ndarray = field(repr=False)
    monodromy: np.ndarray = field(repr=False)
    coordinates: tuple[str, ...]
    residual: float
    converged: bool
    iterations: int
    method: str
    run: Run = field(repr=False)
    message: str

    @property
    def alpha(self) -> float:
        """Peak absolute acceleration over the table's peak, ``max|a_abs| / A_t``."""
        peak = abs(self.run.excitation.peak_m_s2)
        return float(self.run.abs_acceleration_max / peak) if peak > 0.0 else math.nan

    @property
    def excursion_m(self) -> float:
        """``D_max - D_min`` over the period, m."""
        return float(self.run.displacement_max - self.run.displacement_min)

    @property
    def eta(self) -> float:
        """Excursion over the total gap (NaN without bumpers)."""
        b = self.run.oscillator.bumpers
        return self.excursion_m / b.total_gap if b is not None else math.nan

    def _contact_tables(self) -> list:
        return [self.run.contact_table]

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The orbit in the phase plane (D, V), its contacts marked; returns its Figure."""
        from ..plots.periodic import plot_orbit
        from ..plots import figure_of

        return figure_of(plot_orbit(self, ax=ax, **kwargs), ax)


@renamed_keyword("oscillator", "system")
def periodic_orbit(
    system: Oscillator,
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
        The system: one mass, or a structure of several (or two adjacent ones), whose orbit is
        then a :class:`StructurePeriodicOrbit` (``guess`` a structure's :class:`State`; its
        shooting coordinates every mass's displacement and velocity, the relaxing contacts'
        compressions and the sticking springs' slips; the monodromy exact, saltation at each
        contact, for Kelvin-Voigt contacts and multi-linear isolators and storeys).
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
    PeriodicOrbit or StructurePeriodicOrbit
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
    if isinstance(system, (Structure, Adjacent)):
        from .structure_periodic import structure_periodic_orbit

        return structure_periodic_orbit(system, excitation, guess=guess, period_multiple=period_multiple,
                                        tol=tol, max_iter=max_iter, settle_cycles=settle_cycles,
                                        method=method, samples_per_period=samples_per_period)
    check_oscillator(system)
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
    mult = multipliers_of(jac)
    names = tuple(shooter.names(vec, frozen))
    return PeriodicOrbit(state, period, mult, jac, names, res, res <= tol, it,
                         "exact" if shooter.exact else "finite-difference", run, message)


class _Shooter(_Newton):
    """The map, its residual and Jacobian in the shooting coordinates of a state vector."""

    def __init__(self, oscillator: Oscillator, excitation: Harmonic, period: float, exact: bool,
                 like: Optional["_Shooter"] = None) -> None:
        self.osc = oscillator
        self.exc = excitation
        self.period = period
        self.exact = exact
        self.fell_back = ""  # why the exact monodromy gave way to finite differences, if it did
        # what depends on the oscillator alone: from ``like``, a shooter of the same oscillator
        same = like is not None and like.osc is oscillator
        self.asm = like.asm if same else assemble(oscillator)  # (the kernel's arguments)
        self.system = self.asm.system
        self.h = like.h if same else hy.Hybrid.of(oscillator, self.system.layout)
        self.lay = self.h.lay
        self._forcing: Any = None  # (the excitation as the kernel takes it: made at the first run)
        bw = oscillator.isolator.bouc_wen
        self.z_max = bw.z_max if bw is not None else 0.0
        self.scale_d = 1e-3
        # where ``coords`` reads the state vector, and the layouts met so far by mode (a solver asks
        # for one several times a run)
        self._at = like._at if same else np.array(hy.coordinate_places(self.h) + (
            [self.lay["zeta"]] if self.z_max > 0.0 else []))
        self._layouts: dict = like._layouts if same else {}

    def coords(self, vec: np.ndarray) -> np.ndarray:
        """``x`` (``_hybrid``), then the isolator's Bouc-Wen z for a system with one."""
        return vec[self._at]

    # the shooting coordinates: which entries of x are free, and how the others follow D
    def _layout(self, vec: np.ndarray, frozen: tuple = ()) -> tuple[np.ndarray, np.ndarray]:
        """(indices of ``coords`` that are free, embedding E: shape (n, r), dx = E dz).  ``frozen``:
        isolator springs that stay elastic over the period, whose slips are left out.  (Both read-only:
        one pair for every state of the same mode.)"""
        mode = hy.mode_of(self.h, vec)
        key = (mode, tuple(frozen))
        got = self._layouts.get(key)
        if got is None:
            if len(self._layouts) >= 256:
                self._layouts.clear()
            got = self._layouts[key] = self._new_layout(*mode, frozen)
            for a in got:
                a.setflags(write=False)
        return got

    def _new_layout(self, in_l: bool, in_r: bool, iso: Any, frozen: tuple) -> tuple[np.ndarray, np.ndarray]:
        h = self.h
        n = h.size + (self.z_max > 0.0)
        follows = np.zeros(n)  # dx_i = follows_i dD for the entries that are not free
        free = [0, 1]
        for touching, row, sign, side in zip((in_l, in_r), h.compressions, (-1.0, 1.0), (0, 1)):
            if touching:
                follows[row] = sign
            elif h.damping[side] > 0.0:
                free.append(row)
        if h.kinematic:
            for i, s in enumerate(iso):
                if s != 0.0:
                    follows[h.first_slip + i] = 1.0
                elif i not in frozen:
                    free.append(h.first_slip + i)
        if self.z_max > 0.0:
            free.append(n - 1)
        free_idx = np.array(sorted(free))
        emb = np.zeros((n, free_idx.size))
        emb[free_idx, np.arange(free_idx.size)] = 1.0
        emb[:, 0] += follows  # (D is the first free coordinate)
        return free_idx, emb

    def frozen(self, vec: np.ndarray, run: Run) -> tuple:
        """The isolator springs elastic at the section that do not yield over the period: their
        slips are constants of the motion (the set the isolator keeps), each a multiplier 1 that
        says nothing of the orbit's stability; they are the orbit's parameters, not coordinates."""
        if not self.h.kinematic:
            return ()
        iso = hy.mode_of(self.h, vec)[2]
        yielded = {int(i) for _, action, i in run.event_table.tolist() if action == hy.ACT_YIELD}
        return tuple(i for i, s in enumerate(iso) if s == 0.0 and i not in yielded)

    def labels(self) -> list[str]:
        """The names of ``coords``' entries."""
        bumpers = ["delta_L", "delta_R"][:self.h.n_contacts]
        return (["D", "V", *bumpers] + [f"u_{i}" for i in range(self.h.n_slips)]
                + (["z"] if self.z_max > 0.0 else []))

    def names(self, vec: np.ndarray, frozen: tuple = ()) -> list[str]:
        labels = self.labels()
        return [labels[i] for i in self._layout(vec, frozen)[0]]

    def spectrum_coordinates(self, slips: set) -> np.ndarray:
        """Indices (in ``coords``) of a Lyapunov spectrum's coordinates: D, V, a relaxing bumper's
        compression, the slips of ``slips`` (the springs that slip during the run), z."""
        keep = [0, 1]
        keep += [row for side, row in enumerate(self.h.compressions) if self.h.damping[side] > 0.0]
        keep += [self.h.first_slip + i for i in sorted(slips)]
        if self.z_max > 0.0:
            keep.append(self.h.size)
        return np.array(keep)

    def section(self, vec: np.ndarray) -> np.ndarray:
        """(D, V) of a state vector, shape (2,)."""
        return vec[[self.lay["x"], self.lay["v"]]]

    # what a branch of orbits reads of each (analysis._follower, _detect)
    def extent(self, run: Run) -> tuple[float, float]:
        """The mass's largest and smallest displacement over the run, m."""
        return float(run.displacement_max), float(run.displacement_min)

    def clearances(self, run: Run) -> dict[str, float]:
        """Each bumper's smallest clearance over the run, m (negative: touched), by side.  A rigid stop's
        orbit that impacts it has no clearance but an impact speed: its test is minus the slowest impact's
        speed over the forcing's angular frequency (m), which falls to 0 at a grazing as the clearance
        rises from it."""
        gaps = self.h.gaps
        if not np.isfinite(gaps[0]):
            return {}
        out = {"left": float(run.displacement_min) + gaps[0], "right": gaps[1] - float(run.displacement_max)}
        table = run.contact_table
        for code, side, law in ((0.0, "left", self.osc.bumpers.left), (1.0, "right", self.osc.bumpers.right)):
            rigid_hits = (table[:, C_SLOT] == code) & (table[:, C_T_END] == table[:, C_T_START])
            hits = table[rigid_hits] if is_rigid(law) else table[:0]
            if len(hits):
                out[side] = -float(np.abs(hits[:, C_V_IN]).min()) / self.exc.omega_rad_s
        return out

    def rigid_sides(self) -> set[str]:
        """The sides of :meth:`clearances` that are rigid stops."""
        b = self.osc.bumpers
        return {side for side, law in (("left", b.left), ("right", b.right)) if is_rigid(law)} if b else set()

    def summary(self, run: Run, exc: Harmonic) -> dict[str, float]:
        """A branch's row of the orbit run over its period: alpha, excursion, extrema, eta, contacts."""
        table = run.contact_table
        done = table[np.isfinite(table[:, C_T_END])]
        peak = abs(exc.peak_m_s2)
        b = self.osc.bumpers
        gap = b.total_gap if b is not None else math.nan
        exc_m = run.displacement_max - run.displacement_min
        return {"alpha": run.abs_acceleration_max / peak if peak > 0 else math.nan, "excursion_m": exc_m,
                "displacement_max_m": run.displacement_max, "displacement_min_m": run.displacement_min,
                "eta": exc_m / gap if gap > 0 else math.nan, "contacts_per_period": int(done.shape[0]),
                "impact_velocity_max_m_s": float(np.abs(done[:, C_V_IN]).max()) if done.shape[0] else 0.0}

    def advance(self, exc: Harmonic, duration: float, vec: np.ndarray) -> Optional[np.ndarray]:
        """The state vector ``duration`` s on under ``exc`` (None where the engine stopped)."""
        run = short_run(self.osc, exc, duration, vec, self.asm)
        return np.array(run.vector) if run.success else None

    def at_section(self, vec: np.ndarray) -> np.ndarray:
        """The state vector moved to time 0 (a whole number of forcing periods back): a contact in
        progress keeps its start relative to the section."""
        return at_section(vec, self.lay, self.h.n_contacts)

    def _scales(self, free_idx: np.ndarray) -> np.ndarray:
        s = np.full(free_idx.size, self.scale_d)
        s[free_idx == 1] = self.scale_d * self.exc.omega_rad_s
        if self.z_max > 0.0:
            s[free_idx == self.h.size] = 1.0  # (z is dimensionless, |z| <= z_max about 1)
        return s

    def _image(self, vec: np.ndarray) -> tuple[np.ndarray, Run]:
        try:
            if self._forcing is None:
                self._forcing = kernel_forcing(self.exc)
            run = short_run(self.osc, self.exc, self.period, vec, self.asm, self._forcing)
        except NotAState as exc:
            raise _Failed(f"a trial state left the system's states ({exc})") from None
        if not run.success:
            raise _Failed(f"the engine stopped over a period: {run.message}")
        return np.array(run.vector), run

    def _propagate(self, vec: np.ndarray, run: Run) -> tuple[np.ndarray, np.ndarray]:
        return hy.oscillator_monodromy(self.h, self.system, vec, run.event_table, vec[0] + self.period,
                                       self.exc.omega_rad_s, self.exc.peak_m_s2, self.exc.phase)

    def _state(self, vec: np.ndarray) -> State:
        return State(vec, ONE_MASS_DOFS, one_mass_layout(self.lay))

    def _size_of(self, run: Run) -> float:
        """The orbit's size, m: its largest |D| (1e-6 m at least)."""
        return max(abs(run.displacement_max), abs(run.displacement_min), 1e-6)

    def _inwards(self, vec: np.ndarray, idx: int, step: float) -> float:
        """0 for a central difference along coordinate ``idx``, else the direction of a one-sided
        one: a compression (>= 0) inwards, z near ``z_max`` towards 0."""
        zeta = self.lay["zeta"]
        if idx in self.h.compressions:
            return 1.0
        if self.z_max > 0.0 and idx == self.h.size and abs(vec[zeta]) + step > self.z_max:
            return 1.0 if vec[zeta] < 0.0 else -1.0
        return 0.0

    def _moved(self, vec: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """The state vector moved by ``dx`` (in ``coords``), its followers kept on their
        constraints and the elastic rule's branch the one of the new D.  (Its numbers as Python's
        floats: the same arithmetic as numpy's scalars, at a fraction of their cost.)"""
        out = vec.copy()
        h, lay = self.h, self.lay
        x, step = vec.tolist(), dx.tolist()
        at_d, at_v, base = lay["x"], lay["v"], lay["base"]
        d = x[at_d] + step[0]
        out[at_d] = d
        out[at_v] = x[at_v] + step[1]
        for c, row in enumerate(h.compressions):
            out[lay["def"] + c] = max(0.0, x[lay["def"] + c] + step[row])
        n = h.n_slips
        if n:
            out[base:base + n] += dx[h.first_slip:h.first_slip + n]
        if self.z_max > 0.0:
            out[lay["zeta"]] = min(max(x[lay["zeta"]] + step[h.size], -self.z_max), self.z_max)
        in_l, in_r, iso = hy.mode_of(h, vec)
        if in_l:
            out[lay["def"]] = max(0.0, -d - h.gaps[0])
        if in_r:
            out[lay["def"] + 1] = max(0.0, d - h.gaps[1])
        if h.kinematic:
            for i, s in enumerate(iso):
                if s != 0.0:
                    out[base + i] = d - s * float(h.breaks[i])
        elif h.breaks.size:
            out[lay["region"]] = np.sign(d) * np.searchsorted(h.breaks, abs(d), side="right")
        return out
