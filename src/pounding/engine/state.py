"""Where a system is: :class:`State`, the core's state vector with its fields named (a single mass's, a
structure's or a pair's), and the bounds a state's numbers are checked against."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from .._checks import at_most, real
from .._errors import InputError, Problem, renamed_keyword
from .layout import ACC_L, ACC_R, DEF_L, DEF_R, IN_L, IN_R, N_LAW_STATE, REGION, STATE_BASE, Z_L, ZETA
from .layout import D as I_D
from .layout import T as I_T
from .layout import V as I_V

if TYPE_CHECKING:  # pragma: no cover
    from ..model import Adjacent, Oscillator, Structure
    from .assembly import Assembly


ONE_MASS_DOFS = ((0,),)  # a single mass: one structure, one level, the one moving mass


@dataclass(frozen=True, eq=False)
class State:
    """Complete state of a system at one instant, from which a run continues exactly: one mass, a
    structure or two adjacent ones.

    Build one at rest with :meth:`at_rest`; every run has its ``final_state``.  The raw vector
    (``vector``) also holds the isolators' internal variables and the running totals of a contact in
    progress, so that a continued run reports that contact whole.

    Attributes
    ----------
    vector : ndarray
        The core's state vector, read-only: time, each moving mass's displacement and velocity, each
        contact's compression and flag, each hysteretic element's branch, each contact's running totals
        and law state, the Bouc-Wen ``z``, then the springs' slips and slip directions.  Read it through
        the properties (``time_s``, ``displacements_m``, ``in_contact``, ...).  A single mass's is the
        one-level structure's it is: with bumpers, ``37 + 2 (n - 1)`` numbers for an isolator of ``n``
        branches, its two contact slots its bumpers (left, right); without, no contact slots
        (``5 + 2 (n - 1)`` numbers; 0.1's vector of a mass without bumpers, its two slots unused, is
        still taken).
    dofs : tuple of tuple of int
        Each structure's levels' places among the moving masses (-1: the ground of a fixed base); a
        single mass: ``((0,),)``.
    layout : dict or None
        Where each block starts in ``vector`` (the core system's ``layout``); None for the core's one-mass
        layout (one level and two contact slots: a single mass with its bumpers, or a one-level
        structure with one wall).

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

    A building's state, each level's numbers:

    >>> iso = pounding.Isolator(slopes_n_m=[1.0e5], breakpoints_m=[])
    >>> b = pounding.Structure(1.0e3, iso, [pounding.Storey(1.0e3, 1.0e6)])
    >>> state = pounding.simulate(b, pounding.Harmonic(0.1, 1.0), 2.0).final_state
    >>> state.time_s, state.displacements_m.shape
    (2.0, (2,))
    >>> later = pounding.simulate(b, pounding.Harmonic(0.1, 1.0), 2.0, state)
    >>> float(later.t[0]), float(later.t[-1])
    (2.0, 4.0)
    """

    vector: np.ndarray = field(repr=False)
    dofs: tuple = ONE_MASS_DOFS
    layout: Optional[dict] = field(default=None, repr=False)

    def __post_init__(self) -> None:
        if self.layout is None:
            if self.dofs != ONE_MASS_DOFS:
                raise _bad_state("dofs", self.dofs, "are levels of a structure, but no layout is given (a "
                                 "single mass's state has dofs ((0,),))", _FROM_A_RUN)
            vec = _state_vector(self.vector)
        else:
            layout = _layout(self.layout)
            vec = _structure_vector(self.vector, layout)
            object.__setattr__(self, "dofs", _dofs(self.dofs, layout["v"] - layout["x"]))
            object.__setattr__(self, "layout", layout)
        vec.setflags(write=False)
        object.__setattr__(self, "vector", vec)

    def __setstate__(self, saved: dict) -> None:
        """Unpickled (or deep-copied): the vector read-only again."""
        for name, value in saved.items():
            object.__setattr__(self, name, value)
        self.vector.setflags(write=False)

    @classmethod
    def _from_kernel(cls, vector: np.ndarray, layout: Optional[dict] = None) -> "State":
        """A single mass's state the engine itself produced (a kernel's final state), not checked again:
        ``layout`` its core system's (one with bumpers, or None: the core's one-mass layout, kept as None)."""
        return cls._of(vector, ONE_MASS_DOFS, layout)

    @classmethod
    def _of(cls, vector: np.ndarray, dofs: tuple, layout: Optional[dict]) -> "State":
        """A state the engine made (of the system whose core ``layout`` it is), not checked again.  The
        core's one-mass layout (one level, two contact slots: a single mass with its bumpers, or a one-level
        structure with one wall) is kept as None."""
        state = object.__new__(cls)
        vec = np.array(vector, dtype=float)
        vec.setflags(write=False)
        object.__setattr__(state, "vector", vec)
        dofs = tuple(tuple(d) for d in dofs)
        if dofs == ONE_MASS_DOFS:
            layout = one_mass_layout(layout)
        object.__setattr__(state, "dofs", dofs)
        object.__setattr__(state, "layout", None if layout is None else dict(layout))  # (its own copy)
        return state

    @classmethod
    @renamed_keyword("oscillator", "system")
    @renamed_keyword("structure", "system")
    def at_rest(cls, system: "Oscillator | Structure | Adjacent", time_s: float = 0.0,
                displacement_m: float = 0.0, velocity_m_s: float = 0.0) -> "State":
        """Relaxed contacts and isolators on their backbones, with the given time and motion.

        Parameters
        ----------
        system : Oscillator, Structure or Adjacent
            The system the state is for.
        time_s : float
            Time, s.
        displacement_m : float
            Displacement relative to the ground, m, of the single mass, or of every moving level of a
            structure (the first of a pair), shifted as one body; each isolator where a slow push from 0
            would leave it (on its backbone; a Bouc-Wen spring's z at 0), a fixed base's first storey
            deformed by the shift, stands and a pair's second structure at rest.  It must leave every
            bumper, wall and link open (a single mass: ``-gap_left_m <= D <= gap_right_m``).
        velocity_m_s : float
            Velocity relative to the ground, m/s, of the same masses.
        """
        from .assembly import check_system, is_single_mass

        check_system(system)
        time_s = at_most("time_s", real("time_s", time_s), MAX_TIME_S, " s", "give the time in s")
        d = at_most("displacement_m", real("displacement_m", displacement_m), MAX_DISPLACEMENT_M, " m",
                    "give the displacement in m")
        v = at_most("velocity_m_s", real("velocity_m_s", velocity_m_s), MAX_VELOCITY_M_S, " m/s",
                    "give the velocity in m/s")
        if not is_single_mass(system):  # (a structure, or a pair: through its assembly)
            from .assembly import assemble

            at_most("displacement_m", d, MAX_SHIFT_M, " m", "give the shift in m")
            at_most("velocity_m_s", v, MAX_SHIFT_VELOCITY_M_S, " m/s", "give the velocity in m/s")
            return shifted(assemble(system), time_s, d, v)
        b = system.bumpers
        if b is not None and not -b.gap_left_m <= d <= b.gap_right_m:
            side, surface = ("left", -b.gap_left_m) if d < 0 else ("right", b.gap_right_m)
            raise InputError(Problem.BAD_STATE, "displacement_m", d,
                             why=f"is inside the {side} bumper, whose surface is at {surface:g} m",
                             fix=f"give a displacement between {-b.gap_left_m:g} and {b.gap_right_m:g} m "
                                 "(a state in contact comes from a run's final_state)")
        from .assembly import assemble

        rest = shifted(assemble(system), time_s, d, v)  # (the one-level structure the mass is)
        return cls._from_kernel(rest.vector, rest.layout)

    # ------------------------------------------------------------------ where each block is
    @property
    def _lay(self) -> dict:
        """The layout: the system's, or a single mass's for this vector's isolator."""
        if self.layout is not None:
            return self.layout
        return {"x": I_D, "v": I_V, "def": DEF_L, "in": IN_L, "region": REGION, "acc": ACC_L, "z": Z_L,
                "zeta": ZETA, "base": STATE_BASE, "n_springs": (self.vector.size - STATE_BASE) // 2,
                "size": self.vector.size}

    @property
    def n_dof(self) -> int:
        """The moving masses: the levels, then the walls' stands (a single mass: 1)."""
        lay = self._lay
        return lay["v"] - lay["x"]

    @property
    def n_contacts(self) -> int:
        """The contact slots: a single mass's two bumpers; a structure's walls' sides (wall ``w``'s left
        ``2 w``, its right ``2 w + 1``), then a pair's links."""
        lay = self._lay
        return lay["in"] - lay["def"]

    def _per_level(self, start: int) -> np.ndarray:
        values = self.vector[start:start + self.n_dof]
        return np.array([values[d] if d >= 0 else 0.0 for levels in self.dofs for d in levels])

    # ------------------------------------------------------------------ its numbers
    @property
    def time_s(self) -> float:
        """Time, s."""
        return float(self.vector[I_T])

    @property
    def displacements_m(self) -> np.ndarray:
        """Each level's displacement relative to the ground, m, shape (levels,) (the first structure's
        levels, then the second's; 0 for a fixed base's ground; a single mass: its one)."""
        return self._per_level(self._lay["x"])

    @property
    def velocities_m_s(self) -> np.ndarray:
        """Each level's velocity relative to the ground, m/s, shape (levels,)."""
        return self._per_level(self._lay["v"])

    @property
    def displacement_m(self) -> float:
        """Displacement ``D`` of a single mass relative to the table, m (a structure's:
        :attr:`displacements_m`)."""
        return float(self.vector[self._one("displacement_m", "displacements_m", "x")])

    @property
    def velocity_m_s(self) -> float:
        """Velocity of a single mass relative to the table, m/s (a structure's: :attr:`velocities_m_s`)."""
        return float(self.vector[self._one("velocity_m_s", "velocities_m_s", "v")])

    def _one(self, name: str, instead: str, block: str) -> int:
        if self.n_dof != 1:
            raise InputError(Problem.WRONG_MODE, f"state.{name}", f"a state of {self.n_dof} masses",
                             mode="the state of a single mass", fix=f"read state.{instead}, one per level")
        return self._lay[block]

    @property
    def bumper_compression_m(self) -> tuple[float, ...]:
        """Compression of each contact slot's law, m: a single mass's (left, right) bumper."""
        at = self._lay["def"]
        return tuple(float(self.vector[at + c]) for c in range(self.n_contacts))

    @property
    def in_contact(self) -> tuple[bool, ...]:
        """Whether each contact slot touches: a single mass's (left, right) bumper."""
        at = self._lay["in"]
        return tuple(bool(self.vector[at + c]) for c in range(self.n_contacts))

    @property
    def bumper_law_state(self) -> tuple[float, ...]:
        """Each contact slot's law's own state (a single mass's (left, right) bumper): an elastic-plastic
        law's plastic offset (m, >= 0) or its line (-1 the yield line, -2 the unloading line); Hertzdamp's
        damping of the last contact (N s/m^(n+1)); 0 for the other laws (a kinematic multi-linear law's
        springs: :attr:`bumper_slips_m`)."""
        at = self._lay["z"]
        return tuple(float(self.vector[at + c * N_LAW_STATE]) for c in range(self.n_contacts))

    @property
    def bumper_slips_m(self) -> np.ndarray:
        """Slips (m) of a kinematic multi-linear law's springs, shape (contacts, 3): by contact slot (a
        single mass's left, right) and breakpoint (0 for a breakpoint that is no softening, and for the
        other laws)."""
        return self._law_block(1)

    @property
    def bumper_slip_directions(self) -> np.ndarray:
        """Slip directions (-1, 0, +1) of those springs, shape (contacts, 3)."""
        return self._law_block(4)

    def _law_block(self, first: int) -> np.ndarray:
        at = self._lay["z"]
        return np.array([self.vector[at + c * N_LAW_STATE + first:at + c * N_LAW_STATE + first + 3]
                         for c in range(self.n_contacts)]).reshape(self.n_contacts, 3)

    @property
    def bouc_wen_z(self) -> float:
        """The Bouc-Wen variable ``z`` of the first element that has a Bouc-Wen spring (the isolator's; 0
        without any); :attr:`bouc_wen_zs` has every spring's."""
        return float(self.vector[self._lay["zeta"]])

    @property
    def bouc_wen_zs(self) -> np.ndarray:
        """Every Bouc-Wen spring's ``z``, in the order of the elements that have one (two isolators'; a
        building in plan's bearings, each axis's), shape (b,); one 0 without any."""
        lay = self._lay
        return self.vector[lay["zeta"]:lay["base"]].copy()

    @property
    def isolator_branch(self) -> int:
        """Backbone branch of the first hysteretic element (a single mass's isolator) under the
        ``elastic`` rule (0: centre, +-j: j-th outer branch)."""
        lay = self._lay
        return int(self.vector[lay["region"]]) if lay["acc"] > lay["region"] else 0

    @property
    def plastic_slips_m(self) -> np.ndarray:
        """Slip ``u_i`` of each elastic-perfectly-plastic spring of the hysteretic elements (a single mass's
        isolator's), m, shape (springs,): every element's springs in turn (those of an element of the
        ``elastic`` rule, which has no slips, stay 0)."""
        lay = self._lay
        return self.vector[lay["base"]:lay["base"] + lay["n_springs"]].copy()

    def __repr__(self) -> str:
        if self.dofs == ONE_MASS_DOFS and self.n_dof == 1:
            return (f"State(time_s={self.time_s:.6g}, displacement_m={self.displacement_m:.6g}, "
                    f"velocity_m_s={self.velocity_m_s:.6g}, in_contact={self.in_contact})")
        return (f"State(time_s={self.time_s:.6g}, displacements_m={self.displacements_m.round(9).tolist()}, "
                f"dofs={self.dofs})")



def one_mass_layout(layout: Optional[dict]) -> Optional[dict]:
    """A single mass's state's ``layout``: None for the core's one-mass layout (a mass with its two bumpers'
    contact slots), the core system's for one without bumpers."""
    if layout is None or (layout["v"] - layout["x"] == 1 and layout["in"] - layout["def"] == 2):
        return None
    return layout


def shifted(asm: "Assembly", time_s: float, d: float, v: float) -> State:
    """A structure's (or a pair's) state at rest, its first structure shifted as one body (``at_rest``),
    from its assembly; an InputError where the shift closes a wall or a link."""
    lay = asm.layout
    vec = np.zeros(lay["size"])
    vec[0] = time_s
    moved = [dof for dof in asm.dofs[0] if dof >= 0]
    vec[[lay["x"] + q for q in moved]] = d
    vec[[lay["v"] + q for q in moved]] = v
    x = vec[lay["x"]:lay["x"] + asm.system.n]
    for c, (i, j, sign, gap, _) in enumerate(asm.pairs):
        depth = sign * (x[i] - (x[j] if j >= 0 else 0.0)) - gap
        if depth > 0.0:
            slot = asm.slots[c]
            what = (f"link {slot[1]}" if slot[0] < 0 else
                    f"wall {slot[1]}'s {('left', 'right')[slot[2]]} side")
            raise InputError(Problem.BAD_STATE, "displacement_m", d,
                             why=f"puts {what} {depth:g} m past its gap",
                             fix="give a shift that leaves every wall and link open (a state in contact "
                                 "comes from a run's final_state)")
    first = 0
    for e, (i, j, slopes, breaks, rule, rings, frictions) in enumerate(asm.elements):  # (on its backbone)
        u = x[i] - (x[j] if j >= 0 else 0.0)
        b = np.asarray(breaks, dtype=float)
        if rule == 1:
            vec[lay["region"] + e] = np.sign(u) * np.searchsorted(b, abs(u), side="right")
        elif rule == 2 and b.size:  # (a triple friction pendulum: its surfaces where a slow push leaves them)
            from ..model.triple_friction import slide

            ring = float(rings[0]) if rings else 0.0
            *_, u_g, held = slide(slopes, frictions, b, ring, u)
            if abs(u_g.sum() - u) > 1e-9 * max(abs(u), 1e-3):  # (rigid rings: its travel ends short of u)
                raise InputError(Problem.BAD_STATE, "displacement_m", d,
                                 why=f"is beyond the triple friction pendulum's travel, {b.sum():g} m, "
                                     "where its rigid rings stop it",
                                 fix="give a displacement within the travel (or stiff rings: "
                                     "ring_stiffness_n_m)")
            vec[lay["base"] + first:lay["base"] + first + b.size] = u_g
            vec[lay["base"] + lay["n_springs"] + first:lay["base"] + lay["n_springs"] + first + b.size] = held
        else:
            vec[lay["base"] + first:lay["base"] + first + b.size] = u - np.clip(u, -b, b)
        first += b.size
    return State._of(vec, asm.dofs, lay)


MAX_TIME_S = 1e12
MAX_SHIFT_M = 100.0  # a structure shifted as one body (at_rest): beyond any gap
MAX_SHIFT_VELOCITY_M_S = 1000.0
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
                         f"is no state vector of a single mass with bumpers (length {STATE_BASE} + 2 x "
                         "(isolator branches - 1)); another system's state needs its layout: "
                         "State(vector, dofs, layout) with a run's final_state's dofs and layout",
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
    bad = np.flatnonzero((dirs != np.round(dirs)) | (np.abs(dirs) > 3.0))
    if bad.size:
        raise _bad_state(f"vector[{STATE_BASE + n_sp + bad[0]}]", float(dirs[bad[0]]),
                         "is not a slip direction (-1, 0 or 1; a friction surface's +-2: at its rigid ring, "
                         "+-3: slipping on its stiff ring)",
                         _FROM_A_RUN)
    return vec


def _structure_vector(vector: Any, layout: dict) -> np.ndarray:
    """A structure's raw state vector, checked for what holds whatever the structure: its length, its
    numbers finite (what ties it to its structure is checked where it is used)."""
    try:
        vec = np.array(vector, dtype=float)
    except (TypeError, ValueError):
        raise InputError(Problem.NOT_A_NUMBER, "state.vector", vector) from None
    if vec.ndim != 1 or vec.size != layout.get("size"):
        raise _bad_state("vector", f"array of shape {vec.shape}",
                         f"is no state vector of this layout (length {layout.get('size')})", _FROM_A_RUN)
    bad = np.flatnonzero(~np.isfinite(vec))
    if bad.size:
        raise InputError(Problem.NOT_FINITE, f"state.vector[{bad[0]}]", float(vec[bad[0]]))
    return vec


LAYOUT_KEYS = ("x", "v", "def", "in", "region", "acc", "z", "zeta", "base", "n_springs", "size")


def _layout(layout: Any) -> dict:
    """A state's layout, checked: the core system's (``system.layout``), each block after the one before."""
    if not isinstance(layout, dict):
        raise _bad_state("layout", layout, "is not a core system's layout (a dict; 0.1's StructureState took "
                         "n_dof here)", "start from State.at_rest(system) or a run's final_state")
    missing = [k for k in LAYOUT_KEYS if k not in layout]
    if missing:
        raise _bad_state("layout", layout, f"lacks {', '.join(missing)}", _FROM_A_RUN)
    try:
        at = [int(layout[k]) for k in LAYOUT_KEYS]
    except (TypeError, ValueError):
        raise _bad_state("layout", layout, "holds a place that is not a whole number",
                         _FROM_A_RUN) from None
    x, v, d, i, region, acc, z, zeta, base, n_springs, size = at
    n, nc = v - x, i - d
    if not (x == I_D and n >= 1 and d == v + n and region == i + nc and acc >= region
            and z == acc + nc * (ACC_R - ACC_L) and zeta == z + nc * N_LAW_STATE and base > zeta
            and n_springs >= 0 and size == base + 2 * n_springs):
        raise _bad_state("layout", layout, "is no layout the core makes (its blocks out of order)",
                         _FROM_A_RUN)
    return dict(zip(LAYOUT_KEYS, at)) | {k: v for k, v in layout.items() if k not in LAYOUT_KEYS}


def _dofs(dofs: Any, n_dof: int) -> tuple:
    """A state's levels' places, checked: a tuple per structure of its levels' dofs, each -1 (a fixed
    base's ground) or one of the ``n_dof`` moving masses."""
    try:
        out = tuple(tuple(int(q) for q in levels) for levels in dofs)
    except (TypeError, ValueError):
        raise _bad_state("dofs", dofs, "are not a tuple of levels' places per structure",
                         _FROM_A_RUN) from None
    if not out or any(not -1 <= q < n_dof for levels in out for q in levels):
        raise _bad_state("dofs", dofs, f"name a place outside the layout's {n_dof} moving masses",
                         _FROM_A_RUN)
    return out
