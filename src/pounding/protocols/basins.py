"""Basins of attraction: which response each initial state ends on.

Every initial state of a grid (or of a random sample of a box) at table phase 0 is run cycle after
cycle by the step kernel until its stroboscopic samples repeat (a periodic response of period
``k <= max_period``) or ``max_cycles`` pass.  The settled responses are then matched into
attractors by what they are (period, alpha, excursion, contacts per cycle), not given: two
responses within ``match_rtol`` of each other in those are one attractor.  A kinematic isolator
that does not yield keeps the set its transient left, a family of orbits shifted from each other:
they are one attractor, as their period, alpha and excursion say.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np
import pandas as pd

from .._checks import instance_of, integer, one_of, positive, real
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from .._runner import Context, run_tasks
from .._runner.progress import Progress
from ..engine import State
from ..engine.layout import T
from ..engine.simulate import check_rtol
from ..engine.assembly import assemble, check_system
from ..excitation import Harmonic
from ..metrics.impacts import S_COUNT, SIDE_SUMS
from .sweep_window import check_adaptive_window, check_steady_rtol, step_measures_all
from ..model import Oscillator
from ..engine.kernels import (CONTACT_COLUMNS, DOF_EXTREMA, W_AMAX, W_CYCLES, W_DMAX, W_DMIN, W_SUMS,
                              run_step, run_window)

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

MAX_STATES = 4_000_000
ROWS_PER_TASK = 64
NOT_SETTLED = -1  # the label of a state that did not settle within max_cycles (or the engine stopped)
NOT_RUN = -2      # the label of a state a Ctrl-C left unrun
# a state's row: its period (0: not settled), alpha, excursion (m), contacts per cycle on the left and
# on the right (over its last cycles), D (m) and V (m/s) at the section, cycles run
R_PERIOD, R_ALPHA, R_EXCURSION, R_LEFT, R_RIGHT, R_D, R_V, R_CYCLES = range(8)
N_ROW = 8
SIGNATURE = slice(R_ALPHA, R_RIGHT + 1)  # (what two settled responses must share to be one attractor)


def run_states(task: tuple, ctx: Context) -> np.ndarray:
    """Run each initial state of the task until it settles: per state, a row of the ``R_*`` columns
    (period, alpha, excursion, contacts per cycle with the left and with the right bumper, D and V
    at the section, cycles run).  ``task``: (system, amplitude,
    omega, states (n, state length), steady options, rtol, view), ``view`` for a structure (its
    ``core_view``; None for one mass): its settled window is run once more, for its largest alpha over
    every level and its contacts at every wall side and link (``_window_row``)."""
    system, amp, omega, states, steady, rtol, view = task
    out = np.full((len(states), N_ROW), np.nan)
    try:
        for i, start in enumerate(states):
            if ctx.stopped():
                raise Interrupted(out, i, len(states), "states")
            step = run_step(system, amp, omega, start.copy(), steady, rtol, 1_000_000, ctx.control)
            win, code = step.window, step.status
            if code == Status.INTERRUPTED:  # (stopped: Ctrl-C; the state is left NaN)
                raise Interrupted(out, i, len(states), "states")
            per_cycle = 1.0 / max(win[W_CYCLES], 1.0)
            # (the engine stopped early: not settled)
            out[i] = (step.period_multiple if code == Status.SUCCESS else 0,
                      win[W_AMAX] / amp, win[W_DMAX] - win[W_DMIN],  # (the excursion: D_max - D_min)
                      win[W_SUMS + S_COUNT] * per_cycle, win[W_SUMS + SIDE_SUMS + S_COUNT] * per_cycle,
                      step.window_strobes[-1, 0], step.window_strobes[-1, 1], step.cycles_run)
            if view is not None and code == Status.SUCCESS:
                out[i, [R_ALPHA, R_LEFT, R_RIGHT]] = _window_row(system, view, amp, omega, step.window_state,
                                                                 int(win[W_CYCLES]), rtol, ctx)
            ctx.advance(1)
    except KeyboardInterrupt as stop:  # (a progress callback's Ctrl-C: keep the states finished)
        if isinstance(stop, Interrupted):
            raise
        raise Interrupted(out, 0, len(states), "states") from None
    return out


def core_view(model: Any) -> tuple[Any, tuple[np.ndarray, list[int]] | None]:
    """Any system's core system, and what a basin's window reads of it: None where the step kernel's own
    window measures it all (a single mass, a one-level structure with one wall), else its contact slots'
    signs and its levels' dofs (the stands' left out of alpha: a floor's acceleration, not a bumper's)."""
    asm = assemble(model)
    if step_measures_all(asm):
        return asm.system, None
    levels = [d for dofs in asm.dofs for d in dofs if d >= 0]
    return asm.system, (np.array([pair.sign for pair in asm.pairs], dtype=float), levels)


def _window_row(system: Any, view: tuple, amp: float, omega: float, win_state: np.ndarray, m: int,
                rtol: float, ctx: Context) -> tuple[float, float, float]:
    """A structure's settled window run once more from its exact start: (its largest alpha over every
    level, contacts per cycle at the wall sides and links that stop negative motion, at those that stop
    positive motion)."""
    signs, levels = view
    t0 = float(win_state[T])
    period = 2.0 * math.pi / omega
    out = run_window(system, amp, omega, -(omega * t0), win_state, t0 + m * period, -1.0, rtol, 1_000_000,
                     ctx.control)
    amax = float(np.max(out.per_dof(system.n)[levels, DOF_EXTREMA["a_abs_max"]]))
    ended = out.contacts[np.isfinite(out.contacts[:, CONTACT_COLUMNS["t_end_s"]])]
    slot_sign = signs[ended[:, CONTACT_COLUMNS["contact"]].astype(int)]
    return amax / amp, float(np.sum(slot_sign < 0)) / m, float(np.sum(slot_sign > 0)) / m


@renamed_keyword("oscillator", "system")
def basins(system: Any, excitation: Harmonic, *, displacement_m: Any = None,
           velocity_m_s: Any = None, n: Any = None, sampling: str = "grid", seed: int = 0,
           max_cycles: int = 500, measure_cycles: int = 5, max_period: int = 8, steady_rtol: float = 1e-8,
           match_rtol: float = 1e-4, rtol: float = 1e-10, scheduler: Any = None, workers: Any = None,
           progress: Progress = False) -> "Basins":
    """Which response each initial state ends on, and how likely each response is.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system.  A structure's initial states shift it (the first of a pair) as one body:
        each of its moving levels at the state's displacement and velocity, its isolator on its
        backbone (``State.at_rest``); its attractors are matched by their largest alpha
        over every level and their contacts per cycle at every wall side and link, and their
        ``excursion_m``, ``displacement_m`` and ``velocity_m_s`` are its first moving mass's.
    excitation : Harmonic
        The shaking (its phase is ignored: every state starts at table phase 0).
    displacement_m, velocity_m_s : (float, float), optional
        The box of initial displacements (m, between the bumpers' surfaces; a structure's: the
        shifts that leave its walls and links open) and velocities (m/s); default: the gaps (or
        +-50 mm without bumpers) and +-1 m/s.
    n : (int, int) or int, optional
        Grid points in displacement and velocity (``sampling="grid"``, default 50 x 50), or the
        number of random states (``sampling="random"``, default 2500).
    sampling : {"grid", "random"}
        A regular grid, or states drawn uniformly in the box (with ``seed``): basin stability.
    seed : int
        The random states' seed.
    max_cycles : int
        Most cycles a state runs before it is called not settled (label -1).
    measure_cycles, max_period, steady_rtol : int, int, float
        When a response is settled: its stroboscopic samples repeat with a period ``k <=
        max_period`` over ``measure_cycles`` cycles, to within ``steady_rtol`` of its amplitude.
    match_rtol : float
        Two settled responses are one attractor when they have the same period and their alpha,
        excursion and contacts per cycle agree to ``match_rtol`` (relative).
    rtol : float
        Tolerance of the numerical integration of nonlinear contact laws.
    scheduler : str or dask.distributed.Client, optional
        How the states run: ``"threads"`` (default), ``"serial"``, ``"processes"``, ``"local"``
        (a Dask ``LocalCluster``), a Dask scheduler's address or a ``Client``.
    workers : int, optional
        Threads or processes (default: the machine's cores).
    progress : bool or callable
        True: a progress bar over the states.

    Returns
    -------
    Basins
        The label of every state, the attractors and their basins' fractions with their standard
        errors; ``.plot()``, ``.to_xarray()``.

    Raises
    ------
    InputError
        For a bad argument (names it, the value and the fix).
    Interrupted
        On Ctrl-C; its ``partial`` holds the states finished (the others -1).

    Examples
    --------
    The damped paper system at a_G = 0.05 g, 1.8 Hz, where a response in contact with the bumpers
    and a free one coexist:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> b = pounding.basins(osc, pounding.Harmonic(0.05, 1.8), n=(12, 12))
    >>> table = b.attractors[["period", "alpha", "impacts"]].round(2)
    >>> print(table.to_string(index=False))
     period  alpha  impacts
          1   1.40    False
          1  11.39     True
    >>> b.fractions.round(2).tolist()
    [0.51, 0.49]
    """
    check_system(system)
    instance_of("excitation", excitation, Harmonic, "pounding.Harmonic (basins are of a periodic forcing)")
    one_of("sampling", sampling, ("grid", "random"))
    d_box, v_box = state_box(system, displacement_m, velocity_m_s)
    if sampling == "grid":
        shape = _grid_shape((50, 50) if n is None else n)
        d = np.linspace(*d_box, shape[0])
        v = np.linspace(*v_box, shape[1])
        dd, vv = (a.ravel() for a in np.meshgrid(d, v, indexing="ij"))
    else:
        count = integer("n", 2500 if n is None else n, 1, MAX_STATES)
        rng = np.random.default_rng(integer("seed", seed, 0))
        dd, vv = rng.uniform(*d_box, count), rng.uniform(*v_box, count)
        shape = (count,)
    steady = steady_options(max_cycles, measure_cycles, max_period, steady_rtol)
    match_rtol = positive("match_rtol", match_rtol, "(relative)")
    rtol = check_rtol(rtol)
    starts = initial_states(system, dd, vv)
    core_system, view = core_view(system)
    amp, omega = excitation.peak_m_s2, excitation.omega_rad_s
    chunks = [starts[i:i + ROWS_PER_TASK] for i in range(0, len(starts), ROWS_PER_TASK)]
    tasks = [(core_system, amp, omega, c, steady, float(rtol), view) for c in chunks]
    ran = run_tasks(run_states, tasks, scheduler=scheduler, workers=workers, progress=progress,
                    label=f"basins at {excitation.freq_hz:g} Hz", total=len(starts), on_error="stop")
    ran.raise_first_error(lambda i: f"the states {i * ROWS_PER_TASK} to {(i + 1) * ROWS_PER_TASK - 1}")
    rows = np.vstack([v if v is not None else np.full((len(c), N_ROW), np.nan)
                      for v, c in zip(ran.values, chunks)])
    result = _basins(system, excitation, sampling, shape, dd, vv, rows, match_rtol, not ran.complete)
    if ran.interrupted:
        raise Interrupted(result, int(np.isfinite(rows[:, R_PERIOD]).sum()), len(rows), "states")
    return result


@dataclass(frozen=True, eq=False)
class Basins:
    """What :func:`basins` found.

    Attributes
    ----------
    oscillator : Oscillator
    excitation : Harmonic
    sampling : str
        "grid" or "random".
    displacement_m, velocity_m_s : ndarray, shape (states,)
        The initial states (table phase 0, the isolator on its backbone).
    labels : ndarray of int
        The attractor each state ends on (its row of ``attractors``), -1 where it did not settle,
        -2 where a Ctrl-C left it unrun; shape (nx, ny) for a grid, (states,) for random states.
    attractors : DataFrame
        One row per attractor: ``period``, ``alpha``, ``excursion_m``, ``contacts_per_cycle``,
        ``impacts`` (whether it touches the bumpers), ``displacement_m`` and ``velocity_m_s`` (a
        sample of it at the section), ``states`` (how many ended on it), ``fraction`` and
        ``standard_error`` (of the fraction, as a sampling estimate: sqrt(p (1 - p) / N)).
    cycles_run : ndarray of int
        Cycles each state ran, the shape of ``labels``.
    complete : bool
        Every state ran (False after Ctrl-C).

    Examples
    --------
    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> b = pounding.basins(osc, pounding.Harmonic(0.05, 2.5), n=(6, 6))
    >>> # one response, reached from everywhere
    >>> len(b.attractors), b.fractions.tolist()
    (1, [1.0])
    """

    oscillator: Oscillator
    excitation: Harmonic
    sampling: str
    displacement_m: np.ndarray
    velocity_m_s: np.ndarray
    labels: np.ndarray
    attractors: pd.DataFrame
    cycles_run: np.ndarray
    complete: bool

    @property
    def fractions(self) -> pd.Series:
        """Each attractor's share of the states (those not settled count in the total)."""
        return self.attractors["fraction"]

    @property
    def not_settled(self) -> float:
        """The share of the states that ran which did not settle within ``max_cycles`` (or whose
        run the engine stopped)."""
        ran = self.labels != NOT_RUN
        return float(np.sum(self.labels == NOT_SETTLED) / max(int(ran.sum()), 1))

    def to_dataframe(self) -> pd.DataFrame:
        """One row per initial state: ``displacement_m``, ``velocity_m_s``, ``label`` (its row of
        :attr:`attractors`; -1 not settled, -2 not run) and ``cycles_run``."""
        return pd.DataFrame({"displacement_m": np.ravel(self.displacement_m),
                             "velocity_m_s": np.ravel(self.velocity_m_s), "label": np.ravel(self.labels),
                             "cycles_run": np.ravel(self.cycles_run)})

    def to_xarray(self) -> "xr.Dataset":
        """Labels and cycles per initial state (a grid: dimensions ``displacement_m`` and
        ``velocity_m_s``; random states: ``state``), the attractors as variables over ``attractor``."""
        import xarray as xr

        if self.sampling == "grid":
            nx, ny = self.labels.shape
            coords = {"displacement_m": self.displacement_m.reshape(nx, ny)[:, 0],
                      "velocity_m_s": self.velocity_m_s.reshape(nx, ny)[0]}
            dims: tuple = ("displacement_m", "velocity_m_s")
        else:
            coords = {"state": np.arange(self.labels.size)}
            dims = ("state",)
        ds = xr.Dataset({"label": (dims, self.labels), "cycles_run": (dims, self.cycles_run)}, coords=coords)
        if self.sampling != "grid":
            ds["initial_displacement_m"] = (dims, self.displacement_m)
            ds["initial_velocity_m_s"] = (dims, self.velocity_m_s)
        for col in self.attractors.columns:
            ds[f"attractor_{col}"] = ("attractor", self.attractors[col].to_numpy())
        ds.attrs.update({"a_g": self.excitation.a_g, "freq_hz": self.excitation.freq_hz,
                         "complete": int(self.complete), "system": self.oscillator.to_toml_text()})
        return ds

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The basins in the plane of initial displacement (mm) and velocity, coloured by attractor,
        the attractors' samples at the section marked.

        Returns its Figure.
        """
        from ..plots.basins import plot_basins
        from ..plots import figure_of

        return figure_of(plot_basins(self, ax=ax, **kwargs), ax)

    def __repr__(self) -> str:
        shares = ", ".join(f"{r.fraction:.3f}" for r in self.attractors.itertuples())
        exc = self.excitation
        return (f"Basins({self.labels.size} states at a_G {exc.a_g:g}, {exc.freq_hz:g} Hz: "
                f"{len(self.attractors)} attractors, fractions {shares}; not settled {self.not_settled:.3f})")


def state_box(osc: Any, displacement_m: Any, velocity_m_s: Any) -> tuple[tuple, tuple]:
    """The box of initial displacements (between the bumpers' surfaces; default the gaps, or +-50 mm
    without bumpers; a structure's: the shifts that leave its walls and links open) and velocities
    (default +-1 m/s), checked."""
    lo, hi = open_range(osc)
    bounded = np.isfinite(lo) or np.isfinite(hi)
    d_box = _box("displacement_m", displacement_m,
                 (lo if np.isfinite(lo) else -0.05, hi if np.isfinite(hi) else 0.05), "m")
    if bounded and (d_box[0] < lo or d_box[1] > hi):
        raise InputError(Problem.OUT_OF_RANGE, "displacement_m", d_box, range=f"[{lo:g}, {hi:g}]",
                         hint=" (the shifts of the mass, or of the structure as one body, that leave its "
                              "bumpers, walls and links open, m)")
    return d_box, _box("velocity_m_s", velocity_m_s, (-1.0, 1.0), "m/s")


def open_range(osc: Any) -> tuple[float, float]:
    """The displacements (m) the mass, or a structure shifted as one body (its first's moving levels),
    can start at with every contact open: (-inf, inf) without any."""
    asm = assemble(osc)
    moved = {dof for dof in asm.dofs[0] if dof >= 0}
    lo, hi = -math.inf, math.inf
    for i, j, sign, gap, _ in asm.pairs:  # (open while sign (x_i - x_j) <= gap)
        side = (i in moved) - (j in moved)  # (+1: x_i - x_j is the shift; -1: minus it; 0: it does not move)
        if side * sign > 0:
            hi = min(hi, gap)
        elif side * sign < 0:
            lo = max(lo, -gap)
    return lo, hi


def steady_options(max_cycles: Any, measure_cycles: Any, max_period: Any, steady_rtol: Any) -> tuple:
    """The step kernel's adaptive options ``(True, max_cycles, measure_cycles, steady_rtol,
    max_period)``, checked."""
    max_cycles = integer("max_cycles", max_cycles, 1, 1_000_000)
    measure_cycles = integer("measure_cycles", measure_cycles, 1, 10_000)
    max_period = integer("max_period", max_period, 1, 1000)
    check_adaptive_window(max_cycles, measure_cycles)
    return (True, max_cycles, measure_cycles, check_steady_rtol(steady_rtol), max_period)


def initial_states(osc: Any, dd: np.ndarray, vv: np.ndarray) -> np.ndarray:
    """State vectors at time 0 (table phase 0), the bumpers relaxed and the isolator on its
    backbone, at displacements ``dd`` (m) and velocities ``vv`` (m/s) (a structure's: its first's
    moving levels shifted as one body, ``State.at_rest``); shape (states, length)."""
    starts = np.array([State.at_rest(osc, 0.0, float(x), float(y)).vector for x, y in zip(dd, vv)])
    starts[:, T] = 0.0
    return starts


def _box(field: str, value: Any, default: tuple, unit: str) -> tuple[float, float]:
    if value is None:
        return (float(default[0]), float(default[1]))
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) or len(value) != 2:
        raise InputError(Problem.WRONG_TYPE, field, value, got=type(value).__name__,
                         expected=f"(low, high) in {unit}")
    lo, hi = real(f"{field}[0]", value[0]), real(f"{field}[1]", value[1])
    if not lo < hi:
        raise InputError(Problem.OUT_OF_RANGE, field, value, range="low < high", hint=f" ({unit})")
    return lo, hi


def _grid_shape(n: Any) -> tuple[int, int]:
    if isinstance(n, (int, np.integer)) and not isinstance(n, bool):
        n = (n, n)
    if isinstance(n, (str, bytes)) or not isinstance(n, Sequence) or len(n) != 2:
        raise InputError(Problem.WRONG_TYPE, "n", n, got=type(n).__name__, expected="(nx, ny) or an int")
    nx, ny = integer("n[0]", n[0], 1), integer("n[1]", n[1], 1)
    if nx * ny > MAX_STATES:
        raise InputError(Problem.TOO_LARGE, "n", n, maximum=MAX_STATES, what=" states",
                         fix="give a coarser grid")
    return nx, ny


def _basins(osc: Oscillator, exc: Harmonic, sampling: str, shape: tuple, dd: np.ndarray, vv: np.ndarray,
            rows: np.ndarray, match_rtol: float, interrupted: bool) -> Basins:
    """The attractors matched from the settled states' rows, and each state's label."""
    ran = np.isfinite(rows[:, R_PERIOD])
    labels = np.where(ran, NOT_SETTLED, NOT_RUN).astype(np.int64)
    found: list[np.ndarray] = []  # one row per attractor: the first state's
    members: list[list[int]] = []
    for i, row in enumerate(rows):
        if not (ran[i] and row[R_PERIOD] > 0):
            continue
        for j, att in enumerate(found):
            if att[R_PERIOD] == row[R_PERIOD] and all(
                    math.isclose(a, b, rel_tol=match_rtol, abs_tol=1e-12) for a, b in zip(att[SIGNATURE],
                                                                                       row[SIGNATURE])):
                labels[i] = j
                members[j].append(i)
                break
        else:
            labels[i] = len(found)
            found.append(row)
            members.append([i])
    order = np.argsort([att[R_ALPHA] for att in found], kind="stable")  # (by alpha, lowest first)
    relabel = np.empty(len(found), dtype=np.int64)
    relabel[order] = np.arange(len(found))
    labels[labels >= 0] = relabel[labels[labels >= 0]]
    total = max(int(ran.sum()), 1)  # (the states that ran: a Ctrl-C's partial result)
    table = []
    for j in order:
        att = found[j]
        p = len(members[j]) / total
        contacts = att[R_LEFT] + att[R_RIGHT]
        table.append({"period": int(att[R_PERIOD]), "alpha": att[R_ALPHA], "excursion_m": att[R_EXCURSION],
                      "contacts_per_cycle": contacts, "impacts": bool(contacts > 0.0),
                      "displacement_m": att[R_D], "velocity_m_s": att[R_V],
                      "states": len(members[j]), "fraction": p,
                      "standard_error": math.sqrt(p * (1.0 - p) / total)})
    columns = ["period", "alpha", "excursion_m", "contacts_per_cycle", "impacts", "displacement_m",
               "velocity_m_s", "states", "fraction", "standard_error"]
    cycles = np.nan_to_num(rows[:, R_CYCLES], nan=0.0).astype(np.int64)
    return Basins(osc, exc, sampling, dd, vv, labels.reshape(shape), pd.DataFrame(table, columns=columns),
                  cycles.reshape(shape), not interrupted)

