"""The stroboscopic map of any system (a single mass, a structure, a pair) in its shooting coordinates:
what ``periodic_orbit``, ``continuation`` and ``lyapunov`` shoot with (the Newton loop: ``_shooting``).

The map takes the core's state vector at the section time to the one a period (or ``period_multiple``
periods) later, by the core's short runs (``engine.simulate.short_run``).  Its coordinates are the core's
monodromy coordinates: every dof's displacement and velocity, each contact's compression, each hysteretic
element's slips (then a Bouc-Wen z, where there is one). The free ones are the shooting coordinates: the
displacements and velocities, the compression of a damped Kelvin-Voigt or elastic multi-linear contact not
touched (it relaxes), the slip of a spring that sticks and yields over the period, the displacement of a
friction surface held in series with others (a triple friction pendulum's) that moves over the period. A
contact in progress, a slipping spring, the slipping surfaces of a series (where the force puts them) and,
while the series sticks, its surface that slips first (the base's displacement less the others') follow the
masses.
"""

from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from .._errors import InputError, Problem
from ..engine.assembly import Assembly, assemble, structures_of
from ..engine.layout import C_SLOT, C_T_END, C_T_START, C_V_IN, X_A_MAX, X_D_MAX, X_D_MIN
from ..engine.run_args import kernel_forcing
from ..engine.simulate import NotAState, ShortRun, short_run
from ..engine.state import State
from ..excitation import Harmonic
from ..excitation.peak import ground_peak
from ..model.contact_laws import is_rigid
from . import _hybrid as hy
from ._shooting import _Failed, _Newton, at_section, finished_contacts


class _Shooter(_Newton):
    """The map of a system's core state vector, its residual and Jacobian in the shooting coordinates.

    ``coords`` are the core's monodromy coordinates: the n displacements, the n velocities, the nc
    contacts' compressions, the n_sp springs' slips (then a Bouc-Wen z, where there is one).  ``like``: a
    shooter of the same system, whose assembly and layouts this one shares."""

    def __init__(self, model: Any, excitation: Harmonic, period: float, exact: bool,
                 like: Optional["_Shooter"] = None) -> None:
        self.osc = self.model = model
        self.exc, self.period, self.exact = excitation, period, exact
        self.fell_back = ""  # why the exact monodromy gave way to finite differences, if it did
        self._forcing: Any = None  # (the excitation as the kernel takes it: made at the first run)
        if like is not None and like.model is model:
            self.__dict__.update(like._shared)
            return
        self.asm: Assembly = assemble(model)
        self.system = self.asm.system
        lay = self.lay = self.asm.layout
        self.n = int(self.system.n)
        self.nc = len(self.asm.pairs)
        self.n_sp = int(lay["n_springs"])
        self.size = 2 * self.n + self.nc + self.n_sp
        structures = structures_of(model)[0]
        bw_iso = [s.isolator.bouc_wen for s in structures if s.isolator is not None
                  and s.isolator.bouc_wen is not None]
        if len(bw_iso) > 1:
            raise InputError(Problem.WRONG_CONFIGURATION, "system", type(model).__name__,
                             got="with two isolators' Bouc-Wen springs (an orbit's coordinates hold one z)",
                             fix="give a Bouc-Wen spring to one of the two isolators at most, or simulate "
                                 "the pair without orbits")
        self.z_max = bw_iso[0].z_max if bw_iso else 0.0
        # each contact slot: (i, j, sign, gap, relaxes: a piecewise linear law with damping and no memory, its
        # compression free when apart: it recovers over time; a kinematic bumper's is held with its springs')
        self.slots = [(i, j, sign, gap, bool(law.PIECEWISE and getattr(law, "damping", 0.0) > 0.0
                                             and not getattr(law, "has_memory", False)))
                      for i, j, sign, gap, law in self.asm.pairs]
        self.springs = []  # each kinematic spring: (global index, i, j, break)
        self.elastic = []  # each element of the elastic rule: (element, i, j, breaks)
        self.series = []  # each series of friction surfaces: (element, i, first, k, f, d, ring), numpy arrays
        first = 0
        for e, (i, j, slopes, breaks, rule, rings, frictions) in enumerate(self.asm.elements):
            if rule == 2 and breaks:  # (its surfaces: held ones free, slipping ones following, _series_rows)
                self.series.append((e, i, first, np.array(slopes, float), np.array(frictions, float),
                                    np.array(breaks, float), float(rings[0]) if rings else 0.0))
            elif rule == 0:
                self.springs += [(first + s, i, j, float(breaks[s])) for s in range(len(breaks))]
            elif breaks:
                self.elastic.append((e, i, j, np.array(breaks, dtype=float)))
            first += len(breaks)
        n = self.n
        # where ``coords`` reads a state vector, and where its mode (contacts touching, springs slipping)
        self._at = np.array([*range(lay["x"], lay["x"] + n), *range(lay["v"], lay["v"] + n),
                             *range(lay["def"], lay["def"] + self.nc),
                             *range(lay["base"], lay["base"] + self.n_sp)]
                            + ([lay["zeta"]] if self.z_max > 0.0 else []))
        touching = [lay["in"] + c for c in range(self.nc)] if self.system.has_b else []
        self._mode_at = touching + [lay["base"] + self.n_sp + g for g, *_ in self.springs]
        for e, _, first, k, *_ in self.series:  # (its slip direction and its surfaces' states)
            states = lay["base"] + self.n_sp + first
            self._mode_at += [lay["region"] + e] + [states + g for g in range(k.size)]
        self._layouts: dict = {}  # (the layouts met so far, by mode: asked for several times a run)
        # the levels' dofs (a fixed base's ground has none), the first moving level's, whether any is fixed
        levels = [d for dofs in self.asm.dofs for d in dofs]
        self._levels = [d for d in levels if d >= 0]
        self._fixed = any(d < 0 for d in levels)
        self._first = next(d for d in self.asm.dofs[0] if d >= 0)
        self._names = self._labels(structures)
        level = self.asm.dofs[0].index(self._first)  # (its wall's total gap, for eta: NaN without one)
        walls = [w for w in structures[0].walls if w.level == level]
        self._gap = walls[0].gap_left_m + walls[0].gap_right_m if walls else math.nan
        self._shared = {k: self.__dict__[k] for k in _SHARED}
        self._shared["_shared"] = self._shared

    # the core's numbers of a state vector
    def _rel(self, vec: Any, i: int, j: int) -> float:
        x = self.lay["x"]
        return float(vec[x + i] - (vec[x + j] if j >= 0 else 0.0))

    def coords(self, vec: np.ndarray) -> np.ndarray:
        return vec[self._at]

    def _slip_dir(self, vec: np.ndarray, g: int) -> float:
        return float(vec[self.lay["base"] + self.n_sp + g])

    def _layout(self, vec: np.ndarray, frozen: tuple = ()) -> tuple[np.ndarray, np.ndarray]:
        """(indices of ``coords`` that are free, embedding E: shape (size, r), dx = E dz).  ``frozen``:
        springs that stick over the period, whose slips are left out.  (Both read-only: one pair for every
        state of the same mode.)"""
        key = (tuple(vec[self._mode_at].tolist()), tuple(frozen),
               tuple(self._first_to_slip(vec, s) for s in self.series))  # (a stuck series's follower)
        got = self._layouts.get(key)
        if got is None:
            if len(self._layouts) >= 256:
                self._layouts.clear()
            got = self._layouts[key] = self._new_layout(vec, frozen)
            for a in got:
                a.setflags(write=False)
        return got

    def _new_layout(self, vec: np.ndarray, frozen: tuple) -> tuple[np.ndarray, np.ndarray]:
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
        followers = [self._series_rows(vec, s, frozen) for s in self.series]
        for rows, held, _ in followers:
            free += [r for r in held if -(r + 1) not in frozen]
        if self.z_max > 0.0:
            free.append(self.size)
        free_idx = np.array(sorted(free))
        emb = np.zeros((total, free_idx.size))
        emb[free_idx, np.arange(free_idx.size)] = 1.0
        emb[:, :n] += follows  # (the displacements are the first n free coordinates)
        column = {int(r): c for c, r in enumerate(free_idx)}
        for rows, held, (i, weights) in followers:  # (a follower: weights on the base's x and the held ones)
            for row, w in zip(rows, weights):
                emb[row, i] += w
                for h in held:
                    if h in column:
                        emb[row, column[h]] -= w
        return free_idx, emb

    def _series_rows(self, vec: np.ndarray, series: tuple, frozen: tuple) -> tuple:
        """A series of friction surfaces in ``coords``: (its following surfaces' rows, its held surfaces'
        rows, (its dof, each follower's weight w: d u_g = w (d x_i - sum of the held ones' d u_h))).
        Slipping, the slipping surfaces follow the force (w = k / K_g, k the series' stiffness); held, the
        surface held within its travel of the lowest threshold (the first to slip: ``k_g u_g + F_g``, the
        first of a tie) follows the base (w = 1); a surface at its rigid ring is neither (a constant)."""
        e, i, first, k, f, d, ring = series
        base = 2 * self.n + self.nc + first
        states = vec[self.lay["base"] + self.n_sp + first:self.lay["base"] + self.n_sp + first + k.size]
        s = vec[self.lay["region"] + e]
        if s != 0.0:
            on = (states == s) | (states == 3.0 * s)
            stiff = np.where(states == 3.0 * s, k + ring, k)
            k_series = 1.0 / float(np.sum(1.0 / stiff[on]))
            rows = [base + g for g in range(k.size) if on[g]]
            weights = [k_series / stiff[g] for g in range(k.size) if on[g]]
        else:
            g0 = self._first_to_slip(vec, series)
            rows, weights = ([base + g0], [1.0]) if g0 is not None else ([], [])
        held = [base + g for g in range(k.size) if states[g] == 0.0 and base + g not in rows]
        return rows, held, (i, weights)

    def _first_to_slip(self, vec: Any, series: tuple) -> Optional[int]:
        """A stuck series's surface held within its travel (state 0) of the lowest threshold up, its spring's
        force (a stiff ring's past its travel) plus its friction: the first to slip, which follows the base
        (the first of a tie); None while the series slips, or with every surface at a rigid ring."""
        e, _, first, k, f, d, ring = series
        lay = self.lay
        if vec[lay["region"] + e] != 0.0:
            return None
        u = [vec[lay["base"] + first + g] for g in range(k.size)]
        inside = [g for g in range(k.size) if vec[lay["base"] + self.n_sp + first + g] == 0.0]
        return min(inside, default=None, key=lambda g: k[g] * u[g] + f[g]
                   + math.copysign(ring * max(abs(u[g]) - d[g], 0.0), u[g]))

    def frozen(self, vec: np.ndarray, run: ShortRun) -> tuple:
        """The springs that stick at the section and do not yield over the period: their slips are
        constants of the motion (multipliers 1 that say nothing of stability), not coordinates.  (Friction
        surfaces in series: -(row + 1) for the row in ``coords`` of each one held at the section that the
        period leaves exactly where it was.)"""
        out: tuple = ()
        if self.springs:
            yielded = {int(i) for _, action, i in run.event_table.tolist() if action == hy.ACT_YIELD}
            out = tuple(g for g, *_ in self.springs if self._slip_dir(vec, g) == 0.0 and g not in yielded)
        if not self.series:
            return out
        end = self.coords(np.asarray(run.vector))
        here = self.coords(vec)
        for e, _, first, k, *_ in self.series:
            base, states = 2 * self.n + self.nc + first, self.lay["base"] + self.n_sp + first
            out += tuple(-(base + g + 1) for g in range(k.size)
                         if vec[states + g] == 0.0 and end[base + g] == here[base + g])
        return out

    def _labels(self, structures: tuple) -> list[str]:
        named = len(structures) > 1
        dof = [""] * self.n
        for b, levels in enumerate(self.asm.dofs):
            prefix = ("first." if b == 0 else "second.") if named else ""
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
                prefix = ("first." if b == 0 else "second.") if named else ""
                contact.append(f"{prefix}delta_wall{w}_{('left', 'right')[side]}")
        return ([f"x_{d}" for d in dof] + [f"v_{d}" for d in dof] + contact
                + [f"u_{g}" for g in range(self.n_sp)] + (["z"] if self.z_max > 0.0 else []))

    def labels(self) -> list[str]:
        """The names of ``coords``' entries: ``x_<level>`` and ``v_<level>`` of each moving level
        (``first.``/``second.`` for a pair; ``stand_<wall>_<side>`` for a wall's stand),
        ``delta_wall<w>_<side>`` and ``delta_link<k>`` of each contact, ``u_<spring>``, ``z``."""
        return list(self._names)

    def names(self, vec: np.ndarray, frozen: tuple = ()) -> list[str]:
        return [self._names[i] for i in self._layout(vec, frozen)[0]]

    def moved_surfaces(self, vec: np.ndarray, end: np.ndarray) -> set:
        """The springs (their indices among the system's) of friction surfaces in series that moved between
        the state vectors ``vec`` and ``end``: coordinates of a Lyapunov spectrum, as a spring's slip that
        yields."""
        lay = self.lay
        return {first + g for _, _, first, k, *_ in self.series for g in range(k.size)
                if end[lay["base"] + first + g] != vec[lay["base"] + first + g]}

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
        """Every dof's (x, v) of a state vector, shape (2, n)."""
        lay = self.lay
        return np.stack([vec[lay["x"]:lay["x"] + self.n], vec[lay["v"]:lay["v"] + self.n]])

    # what a branch of orbits reads of each (analysis._follower, _detect)
    def extent(self, run: ShortRun) -> tuple[float, float]:
        """The first moving level's largest and smallest displacement over the run, m (a single mass's; the
        base of an isolated building)."""
        ex = run.extrema[self._first]
        return float(ex[X_D_MAX]), float(ex[X_D_MIN])

    def clearances(self, run: ShortRun) -> dict[str, float]:
        """Each wall side's and link's smallest clearance over the run, m (negative: touched).  A rigid stop
        that the orbit impacts has no clearance but an impact speed: minus the slowest impact's speed over
        the forcing's angular frequency, m (0 at a grazing, as the clearance)."""
        out = run.clearance_m.tolist()
        rows = run.contact_table
        for c, pair in enumerate(self.asm.pairs):
            if is_rigid(pair.law):
                hits = rows[(rows[:, C_SLOT] == c) & (rows[:, C_T_END] == rows[:, C_T_START])]
                if len(hits):
                    out[c] = -float(np.abs(hits[:, C_V_IN]).min()) / self.exc.omega_rad_s
        return dict(zip(self.sides(), out))

    @property
    def _contact_names(self) -> list[str]:
        return self._names[2 * self.n:2 * self.n + self.nc]

    def sides(self) -> list[str]:
        """The keys of :meth:`clearances`: each contact's name (``wall0_left``, ``first.wall0_right``,
        ``link0``), what a grazing's ``side`` is."""
        return [name.replace("delta_", "") for name in self._contact_names]

    def rigid_sides(self) -> set[str]:
        """The sides of :meth:`clearances` that are rigid stops."""
        return {side for side, pair in zip(self.sides(), self.asm.pairs) if is_rigid(pair.law)}

    def summary(self, run: ShortRun, exc: Harmonic) -> dict[str, float]:
        """A branch's row of the orbit run over its period: the largest alpha over every level, the first
        moving level's excursion and extrema (eta against its wall's total gap, when it has one at its
        level), the contacts at every wall side and link."""
        done = finished_contacts([run.contact_table])
        peak = abs(exc.peak_m_s2)
        amax = float(run.extrema[self._levels, X_A_MAX].max())
        if self._fixed:  # (a fixed base's level: shaken by the table)
            amax = max(amax, ground_peak(exc, run.t_start_s, float(run.vector[0]))[0])
        dmax, dmin = self.extent(run)
        gap = self._gap
        return {"alpha": amax / peak if peak > 0 else math.nan, "excursion_m": dmax - dmin,
                "displacement_max_m": dmax, "displacement_min_m": dmin,
                "eta": (dmax - dmin) / gap if gap > 0 else math.nan,
                "contacts_per_period": int(done.shape[0]),
                "impact_velocity_max_m_s": float(np.abs(done[:, C_V_IN]).max()) if done.shape[0] else 0.0}

    def advance(self, exc: Harmonic, duration: float, vec: np.ndarray) -> Optional[np.ndarray]:
        """The state vector ``duration`` s on under ``exc`` (None where the engine stopped)."""
        try:
            run = short_run(self.model, exc, duration, vec, self.asm)
        except (InputError, NotAState):
            return None
        return np.array(run.vector) if run.success else None

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
            s[free_idx == self.size] = 1.0  # (z is dimensionless, |z| <= z_max about 1)
        return s

    def _image(self, vec: np.ndarray, checked: bool = False) -> tuple[np.ndarray, ShortRun]:
        """(the state vector a period from ``vec``, the run); ``checked``: ``vec`` ran from before, on this
        shooter's system (not checked again)."""
        try:
            if self._forcing is None:
                self._forcing = kernel_forcing(self.exc)
            run = short_run(self.model, self.exc, self.period, vec, self.asm, self._forcing, checked)
        except NotAState as exc:
            raise _Failed(f"a trial state left the system's states ({exc})") from None
        if not run.success:
            raise _Failed(f"the engine stopped over a period: {run.message}")
        return np.array(run.vector), run

    def _size_of(self, run: ShortRun) -> float:
        """The orbit's size, m: its largest |x| of any level (1e-6 m at least)."""
        ex = run.extrema[self._levels]
        return max(1e-6, float(np.abs(ex[:, X_D_MAX]).max()), float(np.abs(ex[:, X_D_MIN]).max()))

    def _propagate(self, vec: np.ndarray, run: ShortRun) -> tuple[np.ndarray, np.ndarray]:
        return hy.monodromy(self.system, vec, run.event_table, vec[0] + self.period, self.exc.omega_rad_s,
                            self.exc.peak_m_s2, self.exc.phase)

    def _state(self, vec: np.ndarray) -> State:
        return State._of(vec, self.asm.dofs, self.lay)

    def _inwards(self, vec: np.ndarray, idx: int, step: float) -> float:
        """0 for a central difference along coordinate ``idx``, else the direction of a one-sided one: a
        compression (>= 0) inwards, z near ``z_max`` towards 0."""
        if 2 * self.n <= idx < 2 * self.n + self.nc:
            return 1.0
        if self.z_max > 0.0 and idx == self.size and abs(vec[self.lay["zeta"]]) + step > self.z_max:
            return 1.0 if vec[self.lay["zeta"]] < 0.0 else -1.0
        return 0.0

    def _moved(self, vec: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """The state vector moved by ``dx`` (in ``coords``), its followers kept on their constraints and the
        elastic rule's branches the ones of the new deformations.  (Its numbers as Python's floats: the same
        arithmetic as numpy's, at a fraction of its cost for the few numbers of a state.)"""
        lay, n, nc, n_sp = self.lay, self.n, self.nc, self.n_sp
        y, step = vec.tolist(), dx.tolist()
        at_x, at_v, d0, base = lay["x"], lay["v"], lay["def"], lay["base"]
        for k in range(n):
            y[at_x + k] += step[k]
            y[at_v + k] += step[n + k]
        for c in range(nc):
            y[d0 + c] = max(0.0, y[d0 + c] + step[2 * n + c])
        for g in range(n_sp):
            y[base + g] += step[2 * n + nc + g]
        if self.z_max > 0.0:
            y[lay["zeta"]] = min(max(y[lay["zeta"]] + step[self.size], -self.z_max), self.z_max)
        if self.system.has_b:
            for c, (i, j, sign, gap, _) in enumerate(self.slots):
                if y[lay["in"] + c]:
                    y[d0 + c] = max(0.0, sign * self._rel(y, i, j) - gap)
        for g, i, j, brk in self.springs:
            s = y[base + n_sp + g]
            if s != 0.0:
                y[base + g] = self._rel(y, i, j) - s * brk
        for e, i, j, breaks in self.elastic:
            u = self._rel(y, i, j)
            y[lay["region"] + e] = float(np.sign(u) * np.searchsorted(breaks, abs(u), side="right"))
        for e, i, first, k, f, d, ring in self.series:  # (followers where the base and held ones put them)
            at, st = base + first, base + n_sp + first
            s = y[lay["region"] + e]
            u = y[at_x + i]
            if s != 0.0:
                on = [g for g in range(k.size) if y[st + g] in (s, 3.0 * s)]
                held = sum(y[at + g] for g in range(k.size) if g not in on)
                stiff = [k[g] + ring if y[st + g] == 3.0 * s else k[g] for g in range(k.size)]
                side = [math.copysign(ring * d[g], y[at + g]) if y[st + g] == 3.0 * s else 0.0
                        for g in range(k.size)]
                compliance = sum(1.0 / stiff[g] for g in on)
                force = (u - held + sum((s * f[g] - side[g]) / stiff[g] for g in on)) / compliance
                for g in on:
                    y[at + g] = (force - s * f[g] + side[g]) / stiff[g]
            else:  # (stuck: the first to slip, as the layout has it, where the base and the others leave it)
                g0 = self._first_to_slip(vec, (e, i, first, k, f, d, ring))
                if g0 is not None:
                    y[at + g0] = u - sum(y[at + g] for g in range(k.size) if g != g0)
        return np.array(y)


# what a shooter of the same system shares (``like``)
_SHARED = ("asm", "system", "lay", "n", "nc", "n_sp", "size", "z_max", "slots", "springs", "elastic",
           "series", "_at", "_mode_at", "_layouts", "_levels", "_fixed", "_first", "_names", "_gap")
