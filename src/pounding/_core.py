"""The one door into the compiled core (``pounding._pounding_core``, C++17 built with the package).

The core takes plain structures (a system, a forcing, options) and returns arrays; every argument is
checked before it gets here (the core trusts its inputs).  Nothing else in the package imports the
compiled module, and only the engine calls its runs (the protocols and analyses through
``engine.kernels``).

* :class:`System` - a system as the core takes it (:func:`system`, from :class:`ContactSlot` and
  :class:`Element`, each built by keyword: :func:`contact_slot`, :func:`element`, and the pairs whose
  extrema it tracks, :class:`TrackedPair`); picklable by name, so it travels to worker processes.
* :class:`Forcing` - the excitation as the core takes it.
* :func:`run` - the event-driven run (``engine.simulate``'s kernel).
* :func:`step` - one frequency step of a sweep, cycles until steady (``engine.kernels.run_step``).
* :func:`spectrum` - exact elastic response peaks under a record; :func:`spectrum_pair` - in each direction
  under a pair of components (RotD spectra).
* :func:`monodromy` - the exact monodromy of a hybrid system of linear modes.
* :func:`impact_row`, :func:`law_force_many`, :func:`periodicity`, :func:`expm` - the smaller kernels.
* :func:`held_force_probe` - the held rigid stops' forces and their rates in a state (for the tests).

Each run releases the GIL, and polls its run control (``pounding._control``: Ctrl-C and the work budget).
What comes back is named, never positional: :class:`RunOutput`, :class:`StepOutput`, :class:`Monodromy`.
Every index is the core's own, by name: ``LAYOUT`` the state vector's offsets and the outputs' sizes,
``CONTACT_COLUMNS`` a contact table's columns, ``EVENT_COLUMNS`` an event table's, ``LEDGER`` the energy
ledger's slots, ``DOF_EXTREMA`` and ``PAIR_EXTREMA`` a run's extrema per dof and per tracked pair,
``NORM_EXTREMA`` a tracked vector's (its length's largest), ``EXCITATION`` the forcing's kinds,
``LAW_IDS`` each contact law's id, ``STATUS`` the codes a run ends with, ``ACTIONS`` the events' codes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Optional

import math

import numpy as np

from ._core_checks import check_contacts, check_elements, check_levers, check_pair

try:
    from . import _pounding_core as _c
except ImportError as exc:  # pragma: no cover  (a source tree never built)
    raise ImportError(
        "pounding's compiled core is not built: install the package (pip install -e . in a checkout, which "
        "compiles it with CMake; see docs/building.md)") from exc

System = _c.System
TrackedPair = _c.TrackedPair  # (by keyword: i, j; levers as below; tracked_pair checks them)
ContactSlot = _c.ContactSlot  # (built by keyword: i, j, sign, gap_m, law, params; levers as below)
Element = _c.Element  # (by keyword: i, j, c_d, slopes, breaks, rule, friction_n, friction_fast_n,
#                        friction_rate_s_m, surface_friction_n, surface_ring_n_m, bw; levers as below)
# Either acts on a pair: dof i, plus arm_i_m times dof lever_i (a lever: a point of a floor in plan moves
# as x - y_c theta, so arm_i_m = -y_c on the rotation's dof), against dof j (plus arm_j_m times dof lever_j)
# or the ground; lever -1: none.  Its relative displacement is w . x (w: 1 on i, arm_i_m on lever_i, -1 on
# j, -arm_j_m on lever_j), and its force f enters the dofs' restoring forces as f w (a pair's +f on i, -f
# on j).
LAYOUT: dict[str, int] = dict(_c.LAYOUT)
LAW_IDS: dict[str, int] = dict(_c.LAW_IDS)
STATUS: dict[str, int] = dict(_c.STATUS)
ACTIONS: dict[str, int] = dict(_c.ACTIONS)
CONTACT_COLUMNS: dict[str, int] = dict(_c.CONTACT_COLUMNS)
EVENT_COLUMNS: dict[str, int] = dict(_c.EVENT_COLUMNS)
LEDGER: dict[str, int] = dict(_c.LEDGER)
DOF_EXTREMA: dict[str, int] = dict(_c.DOF_EXTREMA)
PAIR_EXTREMA: dict[str, int] = dict(_c.PAIR_EXTREMA)
NORM_EXTREMA: dict[str, int] = dict(_c.NORM_EXTREMA)
EXCITATION: dict[str, int] = dict(_c.EXCITATION)


@dataclass(frozen=True, slots=True)
class Forcing:
    """The excitation as the core takes it (``engine.run_args.kernel_forcing`` makes it).

    Attributes
    ----------
    kind : int
        :data:`EXCITATION`'s ``harmonic`` or ``record``.
    p : ndarray, shape (3,) or (5,)
        Harmonic: amplitude m/s^2, omega rad/s, phase rad, then the second component's amplitude m/s^2 and
        phase rad (the same omega; none: no second component); a record: its uniform step s (0 if none),
        0, 0.
    rec_t, rec_a : ndarray, shape (k,)
        A record's times (s) and accelerations (m/s^2); one-element zeros for a harmonic.
    rec_b : ndarray, shape (k,) or (0,)
        A record's second component (m/s^2) on the same times; empty: none.

    The table acceleration on dof ``i`` is ``influence[i, 0] a + influence[i, 1] b`` (:func:`system`'s
    ``influence``; by default every dof moves with the first component alone).  Its sizes are checked and
    its arrays made contiguous float64 once, here (a ValueError for a caller's bug), for the many runs
    that take it.
    """

    kind: int
    p: np.ndarray
    rec_t: np.ndarray
    rec_a: np.ndarray
    rec_b: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def __post_init__(self) -> None:
        for name in ("p", "rec_t", "rec_a", "rec_b"):
            object.__setattr__(self, name, _f64(getattr(self, name)))
        object.__setattr__(self, "kind", int(self.kind))
        harmonic = self.kind == EXCITATION["harmonic"]
        if self.kind not in EXCITATION.values() or self.rec_b.size not in ((0,) if harmonic else (
                0, self.rec_t.size)) or self.p.size not in ((3, 5) if harmonic else (3,)):
            raise ValueError(f"a Forcing's kind is one of {EXCITATION}; a harmonic's p holds 3 or 5 numbers "
                             f"and no rec_b; a record's p 3 and rec_b none or as many values as rec_t "
                             f"({self.rec_t.size}): got kind {self.kind}, p {self.p.size}, rec_b "
                             f"{self.rec_b.size}")


@dataclass(frozen=True, slots=True)
class RunOutput:
    """What a run returns (:func:`run`).

    Attributes
    ----------
    state : ndarray, shape (size,)
        The state vector at the run's end.
    samples : ndarray, shape (k, sample columns)
        The history (``System.layout``'s sample columns), empty when not asked for.
    contacts : ndarray, shape (c, CONTACT_COLS)
        One row per contact, columns :data:`CONTACT_COLUMNS`.
    events : ndarray, shape (e, EVENT_COLS)
        t, action (:data:`ACTIONS`), index.
    ledger : ndarray, shape (LEDGER_LEN,)
        The energy ledger, J, slots :data:`LEDGER` (NaN without the energy integrals).
    extrema : ndarray, shape (DOF_EXTREMA n + PAIR_EXTREMA p,)
        The exact extrema: per dof (:data:`DOF_EXTREMA`), then per tracked pair (:data:`PAIR_EXTREMA`);
        :meth:`per_dof` and :meth:`per_pair` give them as tables.
    status : int
        How the run ended (:data:`STATUS`).
    chatters : ndarray, shape (q, 5)
        The rigid stops' chatter sequences: contact, first impact s, accumulation or last impact s,
        impacts, accumulated 1/0.
    norms : ndarray, shape (v, NORM_EXTREMA)
        Each tracked vector's (:func:`system`'s ``vectors``) exact largest length (m), its time (s) and its
        two components there (m), columns :data:`NORM_EXTREMA`.

    ``state``, ``ledger``, ``extrema`` and ``norms`` are views of one array (the core returns them so): each
    its own numbers, but keeping one keeps the others' memory, and none can be resized in place.
    """

    state: np.ndarray
    samples: np.ndarray
    contacts: np.ndarray
    events: np.ndarray
    ledger: np.ndarray
    extrema: np.ndarray
    status: int
    chatters: np.ndarray
    norms: np.ndarray

    def per_dof(self, n: int) -> np.ndarray:
        """The extrema of each of the ``n`` dofs, shape (n, DOF_EXTREMA), columns :data:`DOF_EXTREMA`."""
        return self.extrema[:_N_DOF_EXTREMA * n].reshape(n, _N_DOF_EXTREMA)

    def per_pair(self, n: int) -> np.ndarray:
        """The extrema of each tracked pair of a system of ``n`` dofs, shape (p, PAIR_EXTREMA), columns
        :data:`PAIR_EXTREMA`."""
        return self.extrema[_N_DOF_EXTREMA * n:].reshape(-1, _N_PAIR_EXTREMA)


@dataclass(frozen=True, slots=True)
class StepOutput:
    """What one frequency step returns (:func:`step`).

    Attributes
    ----------
    state : ndarray, shape (size,)
        The state at the step's end.
    cycles_run : int
    period_multiple : int
        The period multiple the step settled with (0: not settled).
    window : ndarray, shape (WINDOW_COLS,)
        The measurement window's metrics (``_step_kernel``'s ``W_*`` columns).
    window_state : ndarray, shape (size,)
        The state at the window's start.
    window_strobes : ndarray, shape (k, 2)
        The first dof's displacement and velocity at each of the window's cycle ends.
    status : int
        :data:`STATUS`.
    """

    state: np.ndarray
    cycles_run: int
    period_multiple: int
    window: np.ndarray
    window_state: np.ndarray
    window_strobes: np.ndarray
    status: int


@dataclass(frozen=True, slots=True)
class Monodromy:
    """The exact Jacobian of a run's map of the coordinates (:func:`monodromy`).

    Attributes
    ----------
    jacobian : ndarray, shape (m, m)
        Of the coordinates (displacements, velocities, compressions, slips).
    x_end : ndarray, shape (m,)
        Those coordinates at the end.
    code : int
        -1, or the row of an event met tangentially, or ``-2 - row`` for an event of a phase that is not
        linear.
    """

    jacobian: np.ndarray
    x_end: np.ndarray
    code: int


_N_DOF_EXTREMA, _N_PAIR_EXTREMA = LAYOUT["DOF_EXTREMA"], LAYOUT["PAIR_EXTREMA"]
_N_NORM_EXTREMA, _LEDGER_LEN = len(NORM_EXTREMA), LAYOUT["LEDGER_LEN"]
_CONTACT_COLS, _EVENT_COLS = LAYOUT["CONTACT_COLS"], LAYOUT["EVENT_COLS"]
_CHATTER_COLS = LAYOUT["CHATTER_COLS"]
_INT64, _CTL_SHAPE = np.dtype(np.int64), (LAYOUT["CTL_LEN"],)


def system(mass: np.ndarray, k0: np.ndarray, c0: np.ndarray, elements: list[Element], has_b: bool,
           contacts: list[ContactSlot], tracked: tuple[tuple[int, int] | TrackedPair, ...] = (),
           influence: np.ndarray | None = None, vectors: tuple[tuple[int, int], ...] = (),
           vector_offsets_m: np.ndarray | None = None) -> System:
    """A system as the core takes it: ``mass`` (kg, shape (n,)), the linear springs and dashpots ``k0``,
    ``c0`` (N/m, N s/m, shape (n, n)), the hysteretic elements (:class:`Element`: dof ``i`` against dof ``j``,
    -1 the ground; its dashpot ``c_d`` N s/m, backbone ``slopes`` N/m and ``breaks`` m, ``rule`` 0 kinematic,
    1 elastic or 2 Coulomb friction (one slope, its force ``friction_n`` N); a Bouc-Wen spring in parallel
    by its numbers ``bw``, none for none; the isolator first; no element at all: a structure fixed at its
    base), and the contact slots (:class:`ContactSlot`: dof ``i`` against dof
    ``j``, -1 the ground, compressed by ``sign (x_i - x_j) - gap_m``; its ``law`` id of :data:`LAW_IDS` and
    ``params``); ``has_b`` makes them active.  ``tracked``: pairs ``(i, j)``, or :class:`TrackedPair` (on
    levers: a bearing's displacement along an axis), whose relative displacement's exact extrema a run adds
    after the dofs' (:data:`PAIR_EXTREMA`; a storey's drift).  ``influence``
    (shape (n, 2), finite): how the ground's two components move each dof (dof ``i`` feels
    ``-m_i (influence[i, 0] a + influence[i, 1] b)``); None: every dof with the first alone, ``(1, 0)``.
    ``vectors``: pairs ``(p, q)`` of indices into ``tracked``, each a vector of those two components (a
    bearing's displacement in plan: its x and y) whose length's exact largest a run finds (``norms``);
    ``vector_offsets_m`` (shape (len(vectors), 2), finite; None: zeros): each vector's offset, m, added to
    it before its length is taken (a floor's corner's place from a ring's centre: its distance from it).

    The core trusts what it is given: the sizes and indices are checked here (a ``ValueError`` is a
    caller's bug; the public functions check what users give before)."""
    m = np.atleast_1d(np.asarray(mass, dtype=float))
    n = m.size
    k0, c0 = np.asarray(k0, dtype=float), np.asarray(c0, dtype=float)
    if m.ndim != 1 or n < 1 or k0.shape != (n, n) or c0.shape != (n, n):
        raise ValueError(f"mass (n,) and k0, c0 (n, n): got {m.shape}, {k0.shape}, {c0.shape}")

    check_elements(elements, n, Element)
    check_contacts(contacts, n, ContactSlot, LAW_IDS)
    pairs_tracked = [p if isinstance(p, TrackedPair) else TrackedPair(i=int(p[0]), j=int(p[1]))
                     for p in tracked]
    for q, p in enumerate(pairs_tracked):
        check_pair(p.i, p.j, n, f"tracked pair {q}")
        check_levers(p, n, f"tracked pair {q}")
    for v, pq in enumerate(vectors):
        ok = all(isinstance(k, (int, np.integer)) and 0 <= k < len(pairs_tracked) for k in pq)
        if len(pq) != 2 or not ok or pq[0] == pq[1]:
            raise ValueError(f"vector {v}: two different indices of the {len(pairs_tracked)} tracked pairs, "
                             f"got {pq!r}")
    at: list[float] = []
    if vector_offsets_m is not None:
        o = np.asarray(vector_offsets_m, dtype=float)
        if o.shape != (len(vectors), 2) or not np.all(np.isfinite(o)):
            raise ValueError(f"vector_offsets_m: finite, shape ({len(vectors)}, 2), got {o.shape}")
        at = o.reshape(-1).tolist()
    infl: list[float] = []
    if influence is not None:
        r = np.asarray(influence, dtype=float)
        if r.shape != (n, 2) or not np.all(np.isfinite(r)):
            raise ValueError(f"influence: finite, shape ({n}, 2), got {r.shape}")
        infl = r.reshape(2 * n).tolist()
    return _c.System(n=n, mass=m.tolist(), k0=k0.reshape(n * n).tolist(), c0=c0.reshape(n * n).tolist(),
                     elements=list(elements), has_b=bool(has_b),
                     contacts=list(contacts),
                     tracked=pairs_tracked, infl=infl, norm_p=[int(p) for p, _ in vectors],
                     norm_q=[int(q) for _, q in vectors], norm_at=at)


def _lever_args(lever_i: int, arm_i_m: float, lever_j: int, arm_j_m: float) -> dict:
    """A pair's levers as the core's classes take them; a ValueError for an arm without its lever (the core
    would drop it) or one that is not finite."""
    for end, lever, arm in (("i", lever_i, arm_i_m), ("j", lever_j, arm_j_m)):
        if not math.isfinite(float(arm)) or (int(lever) == -1 and float(arm) != 0.0):
            raise ValueError(f"the arm of end {end} ({arm}): finite, and 0 without a lever (lever_{end} "
                             f"{lever})")
    return dict(lever_i=int(lever_i), arm_i_m=float(arm_i_m), lever_j=int(lever_j), arm_j_m=float(arm_j_m))


def tracked_pair(*, i: int, j: int, lever_i: int = -1, arm_i_m: float = 0.0, lever_j: int = -1,
                 arm_j_m: float = 0.0) -> TrackedPair:
    """A tracked pair (:class:`TrackedPair`): dof ``i`` against dof ``j`` (-1: the ground), with levers as
    :func:`contact_slot`'s; :func:`system` checks it against the system's dofs."""
    return TrackedPair(i=int(i), j=int(j), **_lever_args(lever_i, arm_i_m, lever_j, arm_j_m))


def contact_slot(*, i: int, j: int, sign: float, gap_m: float, law: int, params: Any, lever_i: int = -1,
                 arm_i_m: float = 0.0, lever_j: int = -1, arm_j_m: float = 0.0,
                 ring_y: Optional[TrackedPair] = None, ring_at_m: tuple[float, float] = (0.0, 0.0),
                 ring_radius_m: float = 0.0) -> ContactSlot:
    """A contact slot (:class:`ContactSlot`) from numbers as the model gives them: ``params`` at most
    ``N_LAW_PARAMS`` numbers (the rest 0); its pair's levers (-1: none) and arms (m per unit of the lever's
    dof: a rotation's, m/rad).  ``ring_y`` (a :class:`TrackedPair`): the slot is a ring's wall (a circular
    moat) struck by a point at ``ring_at_m`` (m, from the ring's centre at rest) that moves by its pair
    (``i``, ``j`` and levers) along x and by ``ring_y`` along y; compressed by its distance from the centre
    less ``ring_radius_m`` (m), pushed back along the ring's normal; ``sign`` +1 and ``gap_m`` its clearance
    at rest (any law: a rigid stop's held point slides along the ring)."""
    params = [float(x) for x in params]
    if len(params) > LAYOUT["N_LAW_PARAMS"]:
        raise ValueError(f"a contact law's parameters: at most {LAYOUT['N_LAW_PARAMS']}, got {len(params)}")
    ring = {} if ring_y is None else dict(ring_y=ring_y, ring_px_m=float(ring_at_m[0]),
                                          ring_py_m=float(ring_at_m[1]), ring_radius_m=float(ring_radius_m))
    return ContactSlot(i=int(i), j=int(j), sign=float(sign), gap_m=float(gap_m), law=int(law), params=params,
                       **_lever_args(lever_i, arm_i_m, lever_j, arm_j_m), **ring)


def element(*, i: int, j: int, c_d: float, slopes: Any, breaks: Any, rule: int, friction_n: float = 0.0,
            friction_fast_n: float = 0.0, friction_rate_s_m: float = 0.0,
            surface_friction_n: Any = (), surface_ring_n_m: Any = (), bw: Any = (), bw_mate: int = -1,
            bw_plastic: bool = False, lever_i: int = -1, arm_i_m: float = 0.0, lever_j: int = -1,
            arm_j_m: float = 0.0) -> Element:
    """A hysteretic element (:class:`Element`) from numbers as the model gives them (``friction_n``: the
    friction of rule 2 at rest, N; with ``friction_rate_s_m`` > 0, s/m, a slip's friction is
    ``friction_fast_n - (friction_fast_n - friction_n) exp(-friction_rate_s_m |u'|)``, on rule 2, on rule 0
    of two slopes (a pre-slip: ``friction_n`` its yield force) while its spring slips, or on a bidirectional
    Bouc-Wen spring (a friction circle: ``friction_n`` 0, its force at rest ``bw[0]`` scaled so at the
    slip's rate); ``surface_friction_n``:
    rule 2's surfaces in series, each surface's friction N, its stiffness in ``slopes`` N/m and its travel to
    its ring in ``breaks`` m; ``surface_ring_n_m``: each ring's stiffness, N/m, 0 or none given: rigid;
    ``bw``: a Bouc-Wen spring in parallel, its ``BW_PARAMS`` numbers (force per unit z N, yield displacement
    m, a, beta, gamma, n), none or zeros for none; ``bw_mate``: the element whose Bouc-Wen spring makes one
    bidirectional spring with this one's (a bearing's other axis: the same numbers; :func:`system` checks
    them), -1 none; ``bw_plastic``: that bidirectional spring elastic-perfectly-plastic (both mates;
    ``a = 1`` and ``beta + gamma = 1``, its ``n`` unused): elastic inside the circle ``|z| = 1``,
    slipping on it, its switches located as events (the friction circle); its pair's levers and arms as
    :func:`contact_slot`'s)."""
    bw = [float(x) for x in bw]
    if bw and (len(bw) != LAYOUT["BW_PARAMS"] or (bw[0] != 0.0 and not (
            bw[1] > 0.0 and bw[2] > 0.0 and bw[3] + bw[4] > 0.0 and bw[5] > 0.0))):
        raise ValueError(f"bw: none, or {LAYOUT['BW_PARAMS']} numbers (force per unit z, u_y > 0, a > 0, "
                         f"beta + gamma > 0, n > 0; the first 0: none), got {bw}")
    return Element(i=int(i), j=int(j), c_d=float(c_d), slopes=[float(x) for x in slopes],
                   breaks=[float(x) for x in breaks], rule=int(rule), friction_n=float(friction_n),
                   friction_fast_n=float(friction_fast_n), friction_rate_s_m=float(friction_rate_s_m),
                   surface_friction_n=[float(x) for x in surface_friction_n],
                   surface_ring_n_m=[float(x) for x in surface_ring_n_m], bw=bw, bw_mate=int(bw_mate),
                   bw_plastic=bool(bw_plastic),
                   **_lever_args(lever_i, arm_i_m, lever_j, arm_j_m))


def _one_component(sy: System, what: str) -> None:
    """A ValueError unless no dof of ``sy`` moves with the ground's second component: ``what`` takes a
    harmonic of one."""
    if any(sy.infl[1::2]):
        raise ValueError(f"{what}: a harmonic of one component; this system's dofs move with a second "
                         "(its influence's second column), which it would leave out")


def _f64(a: Any) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64)


def _ctl(ctl: np.ndarray) -> np.ndarray:
    """``ctl`` as the kernels write it: the run control's int64 array of ``LAYOUT["CTL_LEN"]``
    (``pounding._control.new_control``); a ValueError otherwise (they write to each slot)."""
    flags = getattr(ctl, "flags", None)
    if not (isinstance(ctl, np.ndarray) and (ctl.dtype is _INT64 or ctl.dtype == _INT64)
            and ctl.shape == _CTL_SHAPE and flags.c_contiguous and flags.writeable):
        raise ValueError(f"ctl: the run control, a writable int64 array of {LAYOUT['CTL_LEN']} "
                         f"(pounding._control.new_control); got {getattr(ctl, 'dtype', type(ctl))!s} "
                         f"{getattr(ctl, 'shape', '')}")
    return ctl


def run(sy: System, forcing: Forcing, state0: np.ndarray, t_end: float, sample_dt: float, rtol: float,
        max_events: int, with_energy: bool, ctl: np.ndarray, screen_extrema: bool = True,
        audit_screen: bool = False, whole_steps: bool = True, own_samples: bool = True) -> RunOutput:
    """Simulate ``sy`` under ``forcing`` (:class:`Forcing`) from ``state0`` to ``t_end``.

    ``sample_dt`` is the history's step (0: events only; -1: not even those); ``with_energy`` False
    skips the energy integrals outside contacts (the ledger is then NaN); ``screen_extrema`` False
    finds every extremum inside a record's sub-interval rather than screening them from its ends
    (the same numbers: for the tests that show it); ``audit_screen`` True finds each one the screen
    clears all the same and counts it in ``ctl[CTL_AUDITED]``, and in ``ctl[CTL_ESCAPES]`` where it
    lies outside the range the screen's bound gives (for the tests); ``whole_steps`` False takes a record's
    step in the parts a phase faster than it is cut into, even where the screen clears the step of every
    event and extremum (the results then differ from the default's by rounding: for the tests);
    ``own_samples`` False takes every sample of a record at its own step through the general loop's steps,
    even in a run without history where most need none of their cases (the same numbers: for the tests that
    show it)."""
    small, size, norms_at, status, samples, contacts, events, chatters = _c.run(
        sy, forcing.kind, forcing.p, forcing.rec_t, forcing.rec_a, forcing.rec_b, _f64(state0),
        float(t_end), float(sample_dt), float(rtol), int(max_events), bool(with_energy), _ctl(ctl),
        bool(screen_extrema), bool(audit_screen), bool(whole_steps), bool(own_samples))
    # (the fixed-size outputs come as one array, read here by views: the state's size, then the ledger, the
    # extrema up to norms_at, the norms; a table without rows as None)
    at = size + _LEDGER_LEN
    return RunOutput(state=small[:size],
                     samples=np.empty((0, sy.sample_cols)) if samples is None else samples,
                     contacts=np.empty((0, _CONTACT_COLS)) if contacts is None else contacts,
                     events=np.empty((0, _EVENT_COLS)) if events is None else events,
                     ledger=small[size:at], extrema=small[at:norms_at], status=status,
                     chatters=np.empty((0, _CHATTER_COLS)) if chatters is None else chatters,
                     norms=small[norms_at:].reshape(-1, _N_NORM_EXTREMA))


def held_force_probe(sy: System, forcing: Forcing, state: np.ndarray) -> np.ndarray:
    """The held rigid stops' forces and their rates in time in ``state`` under ``forcing``, as a run's
    held-release events take them: shape (held stops, 3), each ``(contact, force N, rate N/s)`` (for the
    tests: a rate against its force's differences along a run)."""
    return _c.held_force_probe(sy, forcing.kind, forcing.p, forcing.rec_t, forcing.rec_a, forcing.rec_b,
                               _f64(state))


def step(sy: System, amp: float, omega: float, state0: np.ndarray, steady: tuple, rtol: float,
         max_events: int, ctl: np.ndarray) -> StepOutput:
    """Hold ``amp sin(omega (t - t0))`` (m/s^2, rad/s) from ``state0`` (time ``t0``) cycle by cycle until
    steady; ``steady`` is ``(adaptive, n_cycles, measure_cycles, steady_rtol, max_period)``."""
    _one_component(sy, "step")
    adaptive, n_cycles, measure_cycles, steady_rtol, max_period = steady
    state, cycles_run, period_multiple, window, window_state, window_strobes, status = _c.step(
        sy, float(amp), float(omega), _f64(state0), bool(adaptive), int(n_cycles), int(measure_cycles),
        float(steady_rtol), int(max_period), float(rtol), int(max_events), _ctl(ctl))
    return StepOutput(state=state, cycles_run=int(cycles_run), period_multiple=int(period_multiple),
                      window=window, window_state=window_state, window_strobes=window_strobes,
                      status=int(status))


def periodicity(strobe: np.ndarray, cyc: np.ndarray, n: int, window: int, max_period: int,
                steady_rtol: float, omega: float, round_window: bool) -> tuple[int, int]:
    """The smallest period multiple with which the last cycles repeat, and the window (the step's test)."""
    return _c.periodicity(_f64(strobe), _f64(cyc), int(n), int(window), int(max_period), float(steady_rtol),
                          float(omega), bool(round_window))


def impact_row(contact: np.ndarray, mass: float, out: np.ndarray) -> None:
    """The paper's per-impact quantities of one contact row into ``out``."""
    _c.impact_row(_f64(contact), float(mass), out)


def law_force_many(law: int, p: np.ndarray, d: np.ndarray, dd: np.ndarray, out: np.ndarray) -> None:
    """A law's force at each (compression, rate) into ``out``, a hysteretic law's along the path."""
    _c.law_force_many(int(law), _f64(p), _f64(d), _f64(dd), out)


def spectrum(t: np.ndarray, acc: np.ndarray, omegas: np.ndarray, zeta: float, out: np.ndarray,
             ctl: np.ndarray) -> int:
    """Exact peaks (max |u|, |u'|, |a_abs|) of each oscillator under the record into ``out``; the status."""
    return _c.spectrum(_f64(t), _f64(acc), _f64(omegas), float(zeta), out, _ctl(ctl))


def spectrum_pair(t: np.ndarray, ax: np.ndarray, ay: np.ndarray, omegas: np.ndarray, zeta: float,
                  angles_rad: np.ndarray, out: np.ndarray, ctl: np.ndarray) -> int:
    """Exact peak ``max |cos(a) u_x + sin(a) u_y|`` of each oscillator (rows of ``out``) in each direction
    ``a`` (its columns) under a pair of components; the status."""
    angles = _f64(angles_rad)
    return _c.spectrum_pair(_f64(t), _f64(ax), _f64(ay), _f64(omegas), float(zeta), np.cos(angles),
                            np.sin(angles), out, _ctl(ctl))


def monodromy(sy: System, state0: np.ndarray, events: np.ndarray, t_end: float, omega: float, amp: float,
              phase: float) -> Monodromy:
    """The exact Jacobian of ``sy``'s map from the state vector ``state0`` to ``t_end`` along ``events``
    (rows of t, action, index) under ``amp sin(omega t + phase)``."""
    _one_component(sy, "monodromy")
    if sy.levered:
        raise ValueError("monodromy: a system with levers (a contact or an element on a point of a floor in "
                         "plan) has no exact monodromy yet")
    jac, x_end, code = _c.monodromy(sy, _f64(state0), _f64(events).reshape(-1, 3), float(t_end), float(omega),
                                    float(amp), float(phase))
    return Monodromy(jacobian=jac, x_end=x_end, code=int(code))


def root_guess(fa: float, fb: float, sa: float, sb: float) -> float:
    """The event locator's first guess in (0, 1) at the root of a function with values ``fa``, ``fb`` and
    slopes (per unit of the interval) ``sa``, ``sb`` at 0 and 1: inverse cubic Hermite interpolation, the
    secant's root where the slopes do not allow it."""
    return _c.root_guess(float(fa), float(fb), float(sa), float(sb))


def value_at_root(root: float, x: float, value: float, f: float, fp: float) -> float:
    """A value stationary at a root, from its ``value`` at the last point ``x`` evaluated where the rate
    was ``f`` and its derivative ``fp`` (second-order Taylor)."""
    return _c.value_at_root(float(root), float(x), float(value), float(f), float(fp))


def expm(a: np.ndarray) -> np.ndarray:
    """``exp(a)`` of a small square matrix (balanced, then Higham's scaling and squaring)."""
    return _c.expm(_f64(a))
