"""``simulate``: the validating wrapper around the compiled kernel, one for every system (a single mass, a
structure, two adjacent ones), and what the periodic-orbit solvers run (``short_run``)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Optional

import numpy as np

from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from ..excitation import Harmonic, Record
from ..model import Oscillator
from .control import (DEFAULT_MAX_STEPS, check_budget, model_rates, new_control, run_interruptibly,
                      steps_per_second, why_rate)
from .. import _core
from ._system import Forcing, System
from .layout import CONTACT_COLUMNS
from .run_args import (DEFAULT_SAMPLE_RATE_HZ, DIRECT_CALL_STEPS, MAX_AUTO_SAMPLES,  # noqa: F401
                        MAX_SAMPLES, check_rtol, checked_run_args, history_rate, kernel_forcing)
from .adjacent_result import AdjacentRun
from .result import EnergyLedger, Run
from .assembly import Assembly, assemble, check_system, clearances, is_plan, is_single_mass, structures_of
from .run_quantities import PartPeaks, run_peaks
from .structure_result import StructureRun
from .state import MAX_DISPLACEMENT_M, MAX_VELOCITY_M_S, State, one_mass_layout
from .state_check import _FIX, check_fits, check_layout, check_state, contact_name  # noqa: F401  (check_state: here too)

if TYPE_CHECKING:
    from ..excitation import RecordPair
    from ..model.adjacent import Adjacent
    from ..model.plan import PlanBuilding
    from ..model.structure import Structure
    from .plan_result import PlanRun

def kernel_system(oscillator: Oscillator) -> System:
    """The oscillator as the core's system: the one-level structure it is, assembled (:func:`assemble`: its
    bumpers the wall at its base, contact slot 0 the left, sign -1, and 1 the right)."""
    return assemble(oscillator).system


@renamed_keyword("oscillator", "system")
def simulate(
    system: "Oscillator | Structure | Adjacent | PlanBuilding",
    excitation: "Harmonic | Record | RecordPair",
    duration: float,
    state: Optional[State] = None,
    *,
    rtol: float = 1e-10,
    sample_rate_hz: Optional[float] = None,
    max_events: int = 10_000_000,
    max_steps: int = DEFAULT_MAX_STEPS,
) -> "Run | StructureRun | AdjacentRun | PlanRun":
    """Simulate the system under a base excitation, exactly at every non-smooth instant.

    Parameters
    ----------
    system : Oscillator, Structure, Adjacent or PlanBuilding
        The system: one mass, or a structure of several (then ``state`` is a
        :class:`State` of its own and a :class:`StructureRun` is returned: each level's histories
        and exact extrema, contacts per wall side), or two adjacent structures (an
        :class:`AdjacentRun`: each one's, and the contacts at their links), or a building in plan (a
        :class:`PlanRun`: each floor's x, y and rotation, each bearing's exact largest displacement in
        plan, the contacts at its moat).
    excitation : Harmonic, Record or RecordPair
        Base (table) acceleration; a building in plan takes a :class:`RecordPair` (its two components
        along the plan's x and y; :meth:`RecordPair.of_direction`: one along any direction), or one
        component along x.
    duration : float
        Simulated time in s, > 0; the run covers ``[t0, t0 + duration]`` with ``t0`` the
        time of ``state``.
    state : State, optional
        Where to start (default: at rest at ``t = 0``); pass ``run.final_state`` to continue.
    rtol : float
        Relative tolerance of the numerical integration of nonlinear contact laws; phases
        with a linear law are solved in closed form, to rounding.
    sample_rate_hz : float, optional
        Rate of the uniform history samples, Hz; 0: only the start, the events and the
        end.  Default: 1 kHz, lowered for runs over 1000 s so that the history holds at most
        a million samples (``run.sample_rate_hz`` says which).  Extrema, contacts and
        energies are exact whatever the rate.
    max_events : int
        The run stops with ``Status.MAX_EVENTS`` after this many events.
    max_steps : int
        Work budget: the run stops with ``Status.BUDGET`` after this many integration steps
        (sub-intervals: about 8 per period of the system's fastest motion, plus one per event).  A
        run whose estimate exceeds it is refused before it starts.

    Returns
    -------
    Run, StructureRun, AdjacentRun or PlanRun
        Histories, exact extrema, contacts, energy ledger, final state, status and message (a
        single mass's, each level's, each structure's and their links'). A run that stops early
        keeps what it computed; ``status`` and ``message`` say why.

    Raises
    ------
    InputError
        A bad argument, or a run estimated to need more than ``max_steps``.
    Interrupted
        On Ctrl-C: ``partial`` is the run up to the stop (status ``INTERRUPTED``).

    Examples
    --------
    The paper's YBs system (with ``C_d = 1 kN s/m``) shaken at 0.1 g and 2 Hz for 5 s, then 5 s
    more from where it stopped:

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> run = pounding.simulate(ybs, pounding.Harmonic(a_g=0.1, freq_hz=2.0),
    ...                         duration=5.0)
    >>> # impacts, mm
    >>> run.status.name, len(run.contacts), round(run.displacement_max * 1e3, 1)
    ('SUCCESS', 19, 18.8)
    >>> later = pounding.simulate(ybs, pounding.Harmonic(a_g=0.1, freq_hz=2.0), 5.0,
    ...                           state=run.final_state)
    >>> float(later.t[0]), float(later.t[-1]), len(later.contacts)  # s, s, impacts
    (5.0, 10.0, 20)
    """
    if is_plan(system):
        from .plan_run import simulate_plan

        return simulate_plan(system, excitation, duration, state, rtol, sample_rate_hz, max_events, max_steps)
    return _run(system, excitation, duration, state, rtol, sample_rate_hz, max_events, max_steps, True)


def peaks(system: "Oscillator | Structure | Adjacent", excitation: Harmonic | Record, duration: float,
          state: Optional[State] = None, *, max_steps: int = DEFAULT_MAX_STEPS) -> dict[str, float]:
    """``simulate(system, excitation, duration, state, sample_rate_hz=0, max_steps=max_steps).quantities()``,
    number for number, without the energy integrals, which no peak reads (a tenth to a quarter of a record
    sample's work): what a study's point, a pounding spectrum's run and an orientation's run are read for.
    Checks, raises and interrupts as :func:`simulate` does (a building in plan: its run's, energy
    included)."""
    if is_plan(system):
        from .plan_run import simulate_plan

        run = simulate_plan(system, excitation, duration, state, 1e-10, 0.0, 10_000_000, max_steps)
        return run.quantities()
    return _run(system, excitation, duration, state, 1e-10, 0.0, 10_000_000, max_steps, False,
                peaks_only=True)


def _run(system: "Oscillator | Structure | Adjacent", excitation: Harmonic | Record, duration: float,
         state: Optional[State], rtol: float, sample_rate_hz: Optional[float], max_events: int,
         max_steps: int, with_energy: bool,
         peaks_only: bool = False) -> "Run | StructureRun | AdjacentRun | dict[str, float]":
    """:func:`simulate` (``with_energy`` False: the energy ledger left NaN, not computed; ``peaks_only``: the
    run's :meth:`~StructureRun.quantities` alone, read off the core's run without the result's histories
    and tables, the same numbers)."""
    check_system(system)
    asm, state, duration, rtol, rate, max_events, max_steps, omega, knots = checked_run_args(
        system, excitation, duration, state, rtol, sample_rate_hz, max_events, max_steps)
    free, touching = model_rates(system, asm)
    why = f"the forcing, {omega:.3g} rad/s" if omega > free else why_rate(asm, free)
    if isinstance(excitation, Record):
        why += f", and {knots} record samples"
    least = float(steps_per_second(free, omega)) * duration + knots
    check_budget("duration", duration, least, max_steps, why,
                 "shorten the duration, or check the system's numbers (SI units: kg, N/m, N s/m)")
    # at most this many sub-intervals (every phase as fast as the fastest), plus one per event
    most = float(steps_per_second(touching, omega)) * duration + knots
    t0 = state.time_s
    forcing = kernel_forcing(excitation)
    ctl = new_control(max_steps)
    out = run_interruptibly(lambda: _core.run(
        asm.system, forcing, state.vector.copy(), t0 + duration, 1.0 / rate if rate > 0 else 0.0, rtol,
        int(max_events), with_energy, ctl), [ctl], direct=most < DIRECT_CALL_STEPS)
    if peaks_only and out.status != Status.INTERRUPTED:
        return peaks_of_output(system, asm, excitation, out, t0, with_energy)
    run = run_of(system, asm, excitation, rate, out, t0, with_energy)
    if run.status == Status.INTERRUPTED:
        raise Interrupted(run, round(run.final_state.time_s - t0, 6), duration, "simulated seconds")
    return run


# the work budget of a short run (``short_run``): a forcing period or two of any system fits in it
# many times over, and the kernel returns within about a second when it is spent
SHORT_RUN_STEPS = 1_000_000


class ShortRun:
    """What the periodic-orbit solvers read of a run (:func:`short_run`), of any system, without the
    public run's histories, energy ledger and checks: ``vector`` (the final state's), the core's event
    and contact tables (a contact's slot its number in the assembly), the exact extrema of each dof
    (``extrema``, shape (n, DOF_EXTREMA)), the start time and the status."""

    __slots__ = ("vector", "event_table", "contact_table", "extrema", "excitation", "status", "asm",
                 "t_start_s", "_out")

    def __init__(self, out: _core.RunOutput, excitation: Harmonic, status: int, asm: Assembly,
                 t_start_s: float) -> None:
        self.asm = asm
        self._out = out
        self.vector = out.state
        self.event_table = out.events
        self.contact_table = out.contacts
        self.extrema = out.per_dof(asm.system.n)
        self.excitation = excitation
        self.status = status
        self.t_start_s = t_start_s

    @property
    def clearance_m(self) -> np.ndarray:
        """Each contact slot's smallest clearance over the run, m (negative: it touched)."""
        return clearances(self.asm, self._out)

    @property
    def success(self) -> bool:
        return self.status == Status.SUCCESS

    @property
    def message(self) -> str:
        return Status(self.status).message

    @property
    def final_state(self) -> State:
        return State._of(self.vector, self.asm.dofs, self.asm.layout)


class NotAState(Exception):
    """A state vector a solver made (a Newton step, a finite difference) is none of the system's
    states: the solver's own failure, not the caller's input (``InputError`` is for that)."""


def short_run(model: "Oscillator | Structure | Adjacent", excitation: Harmonic, duration: float,
              state: State | np.ndarray, asm: Optional[Assembly] = None,
              forcing: Optional[Forcing] = None, checked: bool = False) -> ShortRun:
    """A run of a period or so, events only, for the periodic-orbit solvers' many runs: the state
    checked, the arguments trusted (the caller checked them), the kernel called in this thread
    (no helper thread: Ctrl-C lands when it returns) within ``SHORT_RUN_STEPS`` sub-intervals
    (status ``BUDGET`` beyond).

    ``model`` is any system (a single mass, a structure, a pair).  ``state`` may be a raw state vector
    (the solvers' own: only what ties it to this system is checked, and one that is none of its states
    raises :class:`NotAState`); ``asm`` the model's :func:`assemble` and ``forcing`` the excitation's
    :func:`kernel_forcing`, when the caller keeps them for many runs; ``checked`` True: ``state`` is a
    vector an earlier short run of this system took (a solver's same state under another forcing), not
    checked again.  A continuation makes some 15,000
    runs of about 12 us in the kernel each: the public ``simulate``'s checks and ``Run`` took 90 us a run
    around them.
    """
    if asm is None:
        asm = assemble(model)
    lay = asm.layout
    n = int(asm.system.n)
    if checked and isinstance(state, np.ndarray):
        vector, t0 = np.array(state, dtype=float), float(state[0])
    elif isinstance(state, np.ndarray):
        # the moves of a solver change the continuous numbers only: those are checked here (a vector that
        # fails: in full, for the message)
        x = state.tolist()
        try:
            if not (state.size == lay["size"] and all(map(math.isfinite, x))):
                check_layout(State(state, asm.dofs, one_mass_layout(lay)), asm, _FIX)  # (it says why)
            d = max(map(abs, x[lay["x"]:lay["x"] + n]))
            v = max(map(abs, x[lay["v"]:lay["v"] + n]))
            if d > MAX_DISPLACEMENT_M or v > MAX_VELOCITY_M_S:
                raise InputError(Problem.BAD_STATE, "state", (d, v),
                                 why=f"has a displacement or a velocity beyond {MAX_DISPLACEMENT_M:g} m or "
                                     f"{MAX_VELOCITY_M_S:g} m/s", fix=_FIX)
            check_fits(state, asm, _FIX)
        except InputError as exc:  # (the public checks' words, as the solver's failure)
            raise NotAState(str(exc)) from None
        vector, t0 = np.array(state, dtype=float), x[0]
    else:
        state = check_state(state, model, asm)
        vector, t0 = np.array(state.vector), state.time_s
    out = _core.run(asm.system, kernel_forcing(excitation) if forcing is None else forcing, vector,
                    t0 + duration, 0.0, 1e-10, 10_000_000, False, new_control(SHORT_RUN_STEPS))
    status = out.status
    if status == Status.SUCCESS and not all(map(math.isfinite, out.extrema.tolist())):
        status = int(Status.NONFINITE)
    return ShortRun(out, excitation, status, asm, t0)


def run_of(system: "Oscillator | Structure | Adjacent", asm: Assembly, excitation: Harmonic | Record,
           rate: float, out: _core.RunOutput, t0: float,
           with_energy: bool = True) -> "Run | StructureRun | AdjacentRun":
    """The result of the core's run of any system: a single mass's :class:`Run`, a structure's
    :class:`StructureRun`, a pair's :class:`AdjacentRun` (its status ``NONFINITE`` where a successful
    run's extrema or ledger are not finite; ``t0``: when it started, s; ``with_energy`` False: a run made
    without its ledger, NaN, which then says nothing of the run)."""
    energy = EnergyLedger.of(out.ledger)
    status = _status_of(out, with_energy)
    final = State._of(out.state, asm.dofs, asm.layout)
    levels = _structures_run(system, asm, excitation, rate, out, status, energy, final, t0)
    if is_single_mass(system):  # (its Run: the one-level structure's run, read as one mass's)
        return Run._of_levels(levels, system, out.chatters)
    return levels


def _status_of(out: _core.RunOutput, with_energy: bool) -> Status:
    """A run's status: the core's, ``NONFINITE`` where a successful run's extrema or ledger (``with_energy``)
    are not finite."""
    status = Status(out.status)
    finite_ledger = not with_energy or np.isfinite(out.ledger).all()
    if status == Status.SUCCESS and not (finite_ledger and np.isfinite(out.extrema).all()):
        status = Status.NONFINITE
    return status


def peaks_of_output(system: "Oscillator | Structure | Adjacent", asm: Assembly, excitation: Harmonic | Record,
                    out: _core.RunOutput, t0: float, with_energy: bool = False) -> dict[str, float]:
    """``run_of(...).quantities()`` of the core's run ``out`` of any system, read off its extrema and
    contact rows alone (:func:`~pounding.engine.run_quantities.run_peaks`): what a study's point, a pounding
    spectrum's run and a stripe's run are read for, without the result's histories, events and energy."""
    structures = structures_of(system)[0]
    parts = [PartPeaks.of(s, b, asm, structures, excitation, out, t0) for b, s in enumerate(structures)]
    status = _status_of(out, with_energy)
    if len(structures) == 1:
        return run_peaks(parts, None, (), status, excitation.g)
    return run_peaks(parts, _link_rows(asm, out.contacts)[1], system.links, status, excitation.g)


def _link_rows(asm: Assembly, contacts: np.ndarray) -> tuple[list, np.ndarray]:
    """A pair's links (their contact slots) and their contact rows, each numbered as its link."""
    links = [c for c, (owner, _, _) in enumerate(asm.slots) if owner == -1]
    slot = CONTACT_COLUMNS["contact"]
    link_rows = contacts[np.isin(contacts[:, slot], links)].copy()
    link_rows[:, slot] -= links[0]
    return links, link_rows


def structure_runs(run: "Run | StructureRun | AdjacentRun") -> tuple:
    """Every structure's run within a run, each a :class:`StructureRun`: a single mass's the one-level
    structure's it is read off (``Run.levels``), a structure's its own, a pair's first and second."""
    if isinstance(run, AdjacentRun):
        return run.first, run.second
    return (run.levels,) if isinstance(run, Run) else (run,)


def _isolator_switches(events: np.ndarray, element: int, surfaces: range = range(0)) -> np.ndarray:
    """A pair's event rows of one structure's isolator's sticks, slips and reversals (a rubber bearing's
    reversals too), its element numbered 0 as the structure's own isolator, and a triple friction
    pendulum's surface slips, rings and rings left (``surfaces``: its surfaces' indices among the pair's
    springs), numbered from 0 as its own: what one structure of a pair reads of the pair's events (none for
    a fixed base)."""
    if element < 0:
        return events[:0].copy()
    kinds = [_core.ACTIONS[k] for k in ("stick", "slip", "reversal")]
    own = np.isin(events[:, 1], [_core.ACTIONS[k] for k in ("surface_slip", "ring", "ring_off")]) & np.isin(
        events[:, 2], list(surfaces))
    mine = (events[:, 2] == element) & np.isin(events[:, 1], kinds)
    rows = events[mine | own].copy()
    rows[mine[mine | own], 2] = 0.0
    if surfaces:
        rows[own[mine | own], 2] -= surfaces.start
    return rows


def _structures_run(model: "Structure | Adjacent", asm: Assembly, excitation: Harmonic | Record, rate: float,
                    out: _core.RunOutput, status: Status, energy: EnergyLedger,
                    final: State, t0: float) -> "StructureRun | AdjacentRun":
    samples, contacts = out.samples, out.contacts
    structures = structures_of(model)[0]
    clear = clearances(asm, out)
    names = tuple(contact_name(slot, len(structures) > 1) for slot in asm.slots)
    if len(structures) == 1:
        return StructureRun._part(structures[0], 0, asm, structures, excitation, rate, out, status, t0,
                                  event_table=out.events, energy=energy, final_state=final, clearance_m=clear,
                                  chatter_table=out.chatters, contact_names=names)
    firsts = np.cumsum([0] + [len(el[3]) for el in asm.elements])  # (each element's first spring)

    def surfaces(e: int) -> range:  # (a triple friction pendulum's surfaces among the pair's springs)
        el = asm.elements[e] if e >= 0 else None
        return range(int(firsts[e]), int(firsts[e + 1])) if el is not None and el[4] == 2 else range(0)

    parts = [StructureRun._part(s, b, asm, structures, excitation, rate, out, status, t0,
                                event_table=_isolator_switches(out.events, asm.isolator[b],
                                                               surfaces(asm.isolator[b])))
             for b, s in enumerate(structures)]
    links, link_rows = _link_rows(asm, contacts)
    n, nh = asm.system.n, asm.system.n_elements
    return AdjacentRun(model, excitation, rate, parts[0], parts[1], samples[:, 0],
                       samples[:, [1 + 3 * n + nh + c for c in links]], link_rows, out.events, energy, final,
                       status, clear, out.chatters, names)
