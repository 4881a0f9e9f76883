"""``periodic_orbit`` of a structure of several masses (or two adjacent ones): Newton shooting on the
core's stroboscopic map, with the exact monodromy of the n-dof hybrid system.

The map takes the core's state vector at the section time to the one a period (or ``period_multiple``
periods) later.  Its Jacobian is composed exactly where every phase is linear (multi-linear isolators and
storeys without a Bouc-Wen spring, Kelvin-Voigt contacts): the state-transition matrix of each phase between
the run's events, a saltation matrix at each event (``_hybrid.monodromy``, the same propagation one mass goes
through).  For the other systems it is a central finite difference of the map.

The shooting coordinates are the state's free numbers: every mass's displacement and velocity, the
compression of a Kelvin-Voigt contact not touched (it relaxes), the slip of a storey's or isolator's spring
that sticks and yields over the period.  A contact in progress and a slipping spring follow the masses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from .._errors import InputError, Problem
from ..engine.layout import C_SLOT, C_T_END, C_T_START, C_V_IN, CONTACT_COLS, E_ACTION, E_INDEX
from ..engine.assembly import Assembly, assemble, structures_of
from ..engine.state import State
from ..engine.structure import check_structure_state, simulate_structure
from ..excitation import Harmonic
from ..model.adjacent import Adjacent
from ..model.contact_laws import is_rigid, linear_form
from ..model.structure import Structure
from . import _hybrid as hy
from ._args import exact_monodromy, orbit_arguments, settled
from ._shooting import Floquet, _Failed, _Newton, at_section, finished_contacts, multipliers_of

ACT_YIELD = hy.ACT_YIELD


@dataclass(frozen=True, eq=False)
class StructurePeriodicOrbit(Floquet):
    """A periodic response of a structure (or two adjacent ones) and its stability.

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
        ``delta_wall<w>_<side>`` and ``delta_link<k>`` for a relaxing contact's compression,
        ``u_<spring>`` for a spring's slip.
    residual : float
        Largest difference between the state and its image a period later, each coordinate over its scale
        (lengths over the largest ``|x|`` of any level over the guess's period, velocities over that times
        Omega).
    converged : bool
        Whether ``residual <= tol``.
    iterations : int
        Newton iterations made.
    method : str
        ``"exact"`` (state-transition and saltation matrices) or ``"finite-difference"``.
    run : StructureRun or AdjacentRun
        One period from ``state``, densely sampled.
    message : str
        What happened, for people.

    Examples
    --------
    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=4.0e3)
    >>> stop = pounding.Wall(0, 0.02, 0.02, pounding.KelvinVoigt(1.0e8, 2.0e4))
    >>> b = pounding.Structure(2.0e3, iso,
    ...                        [pounding.Storey(1.0e3, 2.0e6, 2.0e3)], [stop])
    >>> orbit = pounding.periodic_orbit(b, pounding.Harmonic(0.1, 1.5))
    >>> orbit.converged, orbit.method, orbit.coordinates[:4]
    (True, 'exact', ('x_0', 'x_1', 'v_0', 'v_1'))
    >>> orbit.contacts_per_period, orbit.stable
    (2, True)
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
    run: Any = field(repr=False)
    message: str

    def _contact_tables(self) -> list:
        return contact_tables(self.run)

    @property
    def alpha(self) -> np.ndarray:
        """Each level's peak absolute acceleration over the table's peak, shape (levels,) (a pair's: the
        first's levels, then the second's)."""
        peak = abs(self.run.excitation.peak_m_s2)
        acc = np.concatenate([part.abs_acceleration_max for part in run_parts(self.run)])
        return acc / peak if peak > 0.0 else np.full(acc.shape, math.nan)

    @property
    def excursion_m(self) -> np.ndarray:
        """Each level's ``D_max - D_min`` over the period, m, shape (levels,) (a pair's: the first's levels,
        then the second's)."""
        return np.concatenate([part.excursion_m for part in run_parts(self.run)])

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Each level's orbit in its phase plane (x, v), its contacts marked; returns its Figure."""
        from ..plots.periodic import plot_structure_orbit
        from ..plots import figure_of

        return figure_of(plot_structure_orbit(self, ax=ax, **kwargs), ax)


def run_parts(run: Any) -> tuple:
    """The structures' runs of a run: a structure's itself, a pair's first and second."""
    return (run.first, run.second) if hasattr(run, "first") else (run,)


def contact_tables(run: Any) -> list:
    """A run's contact tables (the core's columns): each structure's walls', then a pair's links'."""
    parts = run_parts(run)
    return [p.contact_table for p in parts] + ([run.link_table] if len(parts) > 1 else [])


def structure_periodic_orbit(model: Structure | Adjacent, excitation: Harmonic, *,
                             guess: Optional[State] = None, period_multiple: int = 1,
                             tol: float = 1e-10, max_iter: int = 40, settle_cycles: int = 100,
                             method: str = "auto", samples_per_period: int = 400) -> StructurePeriodicOrbit:
    """:func:`pounding.periodic_orbit` of a structure or an adjacent pair (the same arguments; ``guess`` a
    :class:`~pounding.State`)."""
    period_multiple, tol, max_iter, settle_cycles, samples_per_period = orbit_arguments(
        excitation, period_multiple, tol, max_iter, settle_cycles, samples_per_period)
    exact = exact_monodromy(model, method)
    period = period_multiple / excitation.freq_hz
    if guess is None:
        guess = settled(model, excitation, settle_cycles).final_state
    elif not isinstance(guess, State):
        raise InputError(Problem.WRONG_TYPE, "guess", guess, got=type(guess).__name__,
                         expected="pounding.State (e.g. run.final_state)")
    else:
        guess = check_structure_state(guess, model)
    shooter = _StructureShooter(model, excitation, period, exact)
    with hy.one_blas_thread():
        vec, res, jac, frozen, it, message = shooter.solve(np.array(guess.vector, dtype=float), tol, max_iter)
    state = simulate_structure(model, excitation, period, shooter._state(vec), sample_rate_hz=0).final_state
    run = simulate_structure(model, excitation, period, state, sample_rate_hz=samples_per_period / period)
    mult = multipliers_of(jac)
    method = "exact" if shooter.exact else "finite-difference"
    return StructurePeriodicOrbit(state, period, mult, jac, tuple(shooter.names(vec, frozen)), res,
                                  res <= tol, it, method, run, message)


class _StructureShooter(_Newton):
    """The map of a structure's core state vector, its residual and Jacobian in the shooting coordinates.

    ``coords`` are the core's monodromy coordinates: the n displacements, the n velocities, the nc
    contacts' compressions, the n_sp springs' slips (then a Bouc-Wen z, where there is one)."""

    def __init__(self, model: Structure | Adjacent, excitation: Harmonic, period: float, exact: bool,
                 like: Optional["_StructureShooter"] = None) -> None:
        self.model, self.exc, self.period, self.exact = model, excitation, period, exact
        self.osc = model  # (the name the one-mass shooter gives its system)
        self.fell_back = ""
        self.asm: Assembly = like.asm if like is not None and like.model is model else assemble(model)
        self.system = self.asm.system
        lay = self.system.layout
        self.lay = lay
        self.n = int(self.system.n)
        self.nc = len(self.asm.pairs)
        self.n_sp = int(lay["n_springs"])
        self.size = 2 * self.n + self.nc + self.n_sp
        bw_iso = [s.isolator.bouc_wen for s in structures_of(model)[0]
                  if s.isolator is not None and s.isolator.bouc_wen is not None]
        self.z_max = bw_iso[0].z_max if bw_iso else 0.0
        # each contact slot: (i, j, sign, gap, relaxes: a Kelvin-Voigt law with damping, free when apart)
        self.slots = [(i, j, sign, gap, bool((linear_form(law) or (0.0, 0.0))[1] > 0.0))
                      for i, j, sign, gap, law in self.asm.pairs]
        self.springs = []  # each kinematic spring: (global index, i, j, break)
        self.elastic = []  # each element of the elastic rule: (element, i, j, breaks)
        first = 0
        for e, (i, j, slopes, breaks, rule) in enumerate(self.asm.elements):
            if rule == 0:
                self.springs += [(first + s, i, j, float(breaks[s])) for s in range(len(breaks))]
            elif breaks:
                self.elastic.append((e, i, j, np.array(breaks, dtype=float)))
            first += len(slopes) - 1

    # the core's numbers of a state vector
    def _rel(self, vec: np.ndarray, i: int, j: int) -> float:
        x = self.lay["x"]
        return float(vec[x + i] - (vec[x + j] if j >= 0 else 0.0))

    def coords(self, vec: np.ndarray) -> np.ndarray:
        lay, n = self.lay, self.n
        parts = [vec[lay["x"]:lay["x"] + n], vec[lay["v"]:lay["v"] + n], vec[lay["def"]:lay["def"] + self.nc],
                 vec[lay["base"]:lay["base"] + self.n_sp]]
        if self.z_max > 0.0:
            parts.append([vec[lay["zeta"]]])
        return np.concatenate(parts)

    def _slip_dir(self, vec: np.ndarray, g: int) -> float:
        return float(vec[self.lay["base"] + self.n_sp + g])

    def _layout(self, vec: np.ndarray, frozen: tuple = ()) -> tuple[np.ndarray, np.ndarray]:
        n, lay = self.n, self.lay
        total = self.size + (self.z_max > 0.0)
        follows = np.zeros((total, n))  # d coords = follows dx for the entries that are not free
        free = list(range(2 * n))
        for c, (i, j, sign, _, relaxes) in enumerate(self.slots):
            row = 2 * n + c
            if self.system.has_b and vec[lay["in"] + c]:
                follows[row, i] += sign
                if j >= 0:
                    follows[row, j] -= sign
            elif self.system.has_b and relaxes:
                free.append(row)
        for g, i, j, _ in self.springs:
            row = 2 * n + self.nc + g
            if self._slip_dir(vec, g) != 0.0:
                follows[row, i] += 1.0
                if j >= 0:
                    follows[row, j] -= 1.0
            elif g not in frozen:
                free.append(row)
        if self.z_max > 0.0:
            free.append(self.size)
        free_idx = np.array(sorted(free))
        emb = np.zeros((total, free_idx.size))
        emb[free_idx, np.arange(free_idx.size)] = 1.0
        emb[:, :n] += follows  # (the displacements are the first n free coordinates)
        return free_idx, emb

    def frozen(self, vec: np.ndarray, run: Any) -> tuple:
        """The springs that stick at the section and do not yield over the period: their slips are
        constants of the motion (multipliers 1 that say nothing of stability), not coordinates."""
        ev = run.event_table
        yielded = set(ev[ev[:, E_ACTION] == ACT_YIELD, E_INDEX].astype(int).tolist())
        return tuple(g for g, *_ in self.springs if self._slip_dir(vec, g) == 0.0 and g not in yielded)

    def labels(self) -> list[str]:
        """The names of ``coords``' entries."""
        structures, _ = structures_of(self.model)
        dof = [""] * self.n
        for b, levels in enumerate(self.asm.dofs):
            prefix = "" if len(structures) == 1 else ("first." if b == 0 else "second.")
            for level, d in enumerate(levels):
                if d >= 0:
                    dof[d] = f"{prefix}{level}"
            for w, side, d in self.asm.stands[b]:
                dof[d] = f"{prefix}stand_{w}_{('left', 'right')[side]}"
        contact = []
        for b, w, side in self.asm.slots:
            if b < 0:
                contact.append(f"delta_link{w}")
            else:
                prefix = "" if len(structures) == 1 else ("first." if b == 0 else "second.")
                contact.append(f"{prefix}delta_wall{w}_{('left', 'right')[side]}")
        return ([f"x_{d}" for d in dof] + [f"v_{d}" for d in dof] + contact
                + [f"u_{g}" for g in range(self.n_sp)] + (["z"] if self.z_max > 0.0 else []))

    def names(self, vec: np.ndarray, frozen: tuple = ()) -> list[str]:
        labels = self.labels()
        return [labels[i] for i in self._layout(vec, frozen)[0]]

    def spectrum_coordinates(self, slips: set) -> np.ndarray:
        """Indices (in ``coords``) of a Lyapunov spectrum's coordinates: every displacement and velocity,
        a relaxing contact's compression, the slips of ``slips`` (the springs that slip during the run), z."""
        keep = list(range(2 * self.n))
        if self.system.has_b:
            keep += [2 * self.n + c for c, slot in enumerate(self.slots) if slot[4]]
        keep += [2 * self.n + self.nc + g for g in sorted(slips)]
        if self.z_max > 0.0:
            keep.append(self.size)
        return np.array(keep)

    def section(self, vec: np.ndarray) -> np.ndarray:
        """Every mass's (x, v) of a state vector, shape (2, n)."""
        lay = self.lay
        return np.stack([vec[lay["x"]:lay["x"] + self.n], vec[lay["v"]:lay["v"] + self.n]])

    # what a branch of orbits reads of each (analysis._follower, _detect)
    def extent(self, run: Any) -> tuple[float, float]:
        """The first moving mass's largest and smallest displacement over the run, m (the base of an
        isolated building)."""
        first = run_parts(run)[0]
        q = next(q for q, d in enumerate(self.asm.dofs[0]) if d >= 0)
        return float(first.displacement_max[q]), float(first.displacement_min[q])

    def clearances(self, run: Any) -> dict[str, float]:
        """Each wall side's and link's smallest clearance over the run, m (negative: touched).  A rigid stop
        that the orbit impacts has no clearance but an impact speed: minus the slowest impact's speed over
        the forcing's angular frequency, m (0 at a grazing, as the clearance)."""
        labels = self.labels()[2 * self.n:2 * self.n + self.nc]
        out = [float(c) for c in run.clearance_m]
        parts = run_parts(run)
        tables, offset = [], 0  # (each part's rows, in the core's slot numbers: walls in order, then links)
        for part in parts:
            t = part.contact_table.copy()
            t[:, C_SLOT] += offset
            tables.append(t)
            offset += 2 * len(part.structure.walls)
        if len(parts) > 1:
            t = run.link_table.copy()
            t[:, C_SLOT] += offset
            tables.append(t)
        rows = np.vstack(tables) if tables else np.zeros((0, CONTACT_COLS))
        for c, law in enumerate(pair.law for pair in self.asm.pairs):
            rigid_hits = (rows[:, C_SLOT] == c) & (rows[:, C_T_END] == rows[:, C_T_START])
            hits = rows[rigid_hits] if is_rigid(law) else rows[:0]
            if len(hits):
                out[c] = -float(np.abs(hits[:, C_V_IN]).min()) / self.exc.omega_rad_s
        return {name.replace("delta_", ""): c for name, c in zip(labels, out)}

    def rigid_sides(self) -> set[str]:
        """The sides of :meth:`clearances` that are rigid stops."""
        labels = self.labels()[2 * self.n:2 * self.n + self.nc]
        pairs = zip(labels, self.asm.pairs)
        return {name.replace("delta_", "") for name, pair in pairs if is_rigid(pair.law)}

    def summary(self, run: Any, exc: Harmonic) -> dict[str, float]:
        """A branch's row of the orbit run over its period: the largest alpha over every level, the first
        moving mass's excursion and extrema (eta against its wall's total gap, when it has one at its
        level), the contacts at every wall side and link."""
        parts = run_parts(run)
        done = finished_contacts(contact_tables(run))
        peak = abs(exc.peak_m_s2)
        amax = max(float(np.max(p.abs_acceleration_max)) for p in parts)
        dmax, dmin = self.extent(run)
        first = structures_of(self.model)[0][0]
        level = next(q for q, d in enumerate(self.asm.dofs[0]) if d >= 0)
        walls = [w for w in first.walls if w.level == level]
        gap = walls[0].gap_left_m + walls[0].gap_right_m if walls else math.nan
        return {"alpha": amax / peak if peak > 0 else math.nan, "excursion_m": dmax - dmin,
                "displacement_max_m": dmax, "displacement_min_m": dmin,
                "eta": (dmax - dmin) / gap if gap > 0 else math.nan,
                "contacts_per_period": int(done.shape[0]),
                "impact_velocity_max_m_s": float(np.abs(done[:, C_V_IN]).max()) if done.shape[0] else 0.0}

    def advance(self, exc: Harmonic, duration: float, vec: np.ndarray) -> Optional[np.ndarray]:
        """The state vector ``duration`` s on under ``exc`` (None where the engine stopped)."""
        try:
            run = simulate_structure(self.model, exc, duration, self._state(vec), sample_rate_hz=0)
        except InputError:
            return None
        return np.array(run.final_state.vector) if run.success else None

    def at_section(self, vec: np.ndarray) -> np.ndarray:
        """The state vector moved to time 0 (a whole number of forcing periods back): a contact in
        progress keeps its start relative to the section."""
        return at_section(vec, self.lay, self.nc)

    def free_state_matrix(self) -> np.ndarray:
        """The state matrix (2n, 2n) of the masses' free motion, no contact, every element on its stiffest
        slope (a linear structure's own)."""
        n, m = self.n, self.asm.masses
        return np.block([[np.zeros((n, n)), np.eye(n)],
                         [-self.asm.k_fast / m[:, None], -self.asm.c_all / m[:, None]]])

    def _scales(self, free_idx: np.ndarray) -> np.ndarray:
        s = np.full(free_idx.size, self.scale_d)
        s[(free_idx >= self.n) & (free_idx < 2 * self.n)] = self.scale_d * self.exc.omega_rad_s
        if self.z_max > 0.0:
            s[free_idx == self.size] = 1.0
        return s

    def _image(self, vec: np.ndarray) -> tuple[np.ndarray, Any]:
        try:
            run = simulate_structure(self.model, self.exc, self.period, self._state(vec), sample_rate_hz=0)
        except InputError as exc:
            raise _Failed(f"a trial state left the system's states ({exc})") from None
        if not run.success:
            raise _Failed(f"the engine stopped over a period: {run.message}")
        return np.array(run.final_state.vector), run

    def _size_of(self, run: Any) -> float:
        parts = run_parts(run)
        return max([1e-6] + [float(np.max(np.abs(np.concatenate((p.displacement_max, p.displacement_min)))))
                             for p in parts])

    def _propagate(self, vec: np.ndarray, run: Any) -> tuple[np.ndarray, np.ndarray]:
        return hy.monodromy(self.system, vec, run.event_table, vec[0] + self.period, self.exc.omega_rad_s,
                            self.exc.peak_m_s2, self.exc.phase)

    def _state(self, vec: np.ndarray) -> State:
        return State._of(vec, self.asm.dofs, self.lay)

    def _inwards(self, vec: np.ndarray, idx: int, step: float) -> float:
        if 2 * self.n <= idx < 2 * self.n + self.nc:
            return 1.0
        if self.z_max > 0.0 and idx == self.size and abs(vec[self.lay["zeta"]]) + step > self.z_max:
            return 1.0 if vec[self.lay["zeta"]] < 0.0 else -1.0
        return 0.0

    def _moved(self, vec: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """The state vector moved by ``dx`` (in ``coords``), its followers kept on their constraints and the
        elastic rule's branches the ones of the new deformations."""
        lay, n, nc, out = self.lay, self.n, self.nc, vec.copy()
        out[lay["x"]:lay["x"] + n] += dx[:n]
        out[lay["v"]:lay["v"] + n] += dx[n:2 * n]
        d0 = lay["def"]
        out[d0:d0 + nc] = np.maximum(0.0, vec[d0:d0 + nc] + dx[2 * n:2 * n + nc])
        out[lay["base"]:lay["base"] + self.n_sp] += dx[2 * n + nc:self.size]
        if self.z_max > 0.0:
            out[lay["zeta"]] = min(max(vec[lay["zeta"]] + dx[self.size], -self.z_max), self.z_max)
        for c, (i, j, sign, gap, _) in enumerate(self.slots):
            if self.system.has_b and vec[lay["in"] + c]:
                out[lay["def"] + c] = max(0.0, sign * self._rel(out, i, j) - gap)
        for g, i, j, brk in self.springs:
            s = self._slip_dir(vec, g)
            if s != 0.0:
                out[lay["base"] + g] = self._rel(out, i, j) - s * brk
        for e, i, j, breaks in self.elastic:
            u = self._rel(out, i, j)
            out[lay["region"] + e] = np.sign(u) * np.searchsorted(breaks, abs(u), side="right")
        return out
