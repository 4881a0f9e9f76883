"""What a sweep returns, for any system: per step and level, the paper's metrics and the structure's (alpha,
extrema, eta, e, the contacts and their means, drift), with the resonance, the contact range and the jumps."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._checks import integer, positive
from .._errors import InputError, Problem, Status, warn_renamed
from ..engine import State
from ..metrics.impacts import IMPACT_COLUMNS, S_COUNT
from .sweep_features import (DEFAULT_JUMP_RATIO, PAPER_QUANTITIES, jumps_of, paper_quantities_of,
                             structure_quantities_of)
from .sweep_table import contacts_table, dataset, exact_table, measured_table

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ..metrics import HysteresisLoop

# the columns of SweepResult.to_dataframe() after freq_hz, nu, (structure,) level; in order
STEP_COLUMNS = ("freq_hz", "nu", "alpha", "excursion_m", "displacement_max_m", "displacement_min_m",
                "eta", "e", "contact", "contacts_per_cycle", *IMPACT_COLUMNS, "steady",
                "period_multiple", "cycles_run", "events_per_cycle", "sticks_per_cycle")
LEVEL_COLUMNS = ("abs_acceleration_max_m_s2", "drift_peak_m", "drift_ratio_peak")


@dataclass(frozen=True, eq=False)
class SweepResult:
    """Result of :func:`pounding.sweep`, for any system: per frequency step, each level's metrics over the
    step's window (its last cycles), exact (event-located extrema, every contact whole).

    A single mass is the one-level case: one row per step.  Use :meth:`to_dataframe` / :meth:`to_xarray`
    for the table (one row per step and level), :meth:`contacts_dataframe` per contact slot,
    :attr:`nu_r`, :attr:`contact_range_hz` and :meth:`jumps` for the sweep's features,
    :meth:`paper_quantities` for the paper's Tables 2-4, :meth:`hysteresis_loop` for Figs. 7/15 and
    :meth:`plot`.

    Attributes
    ----------
    system : Oscillator, Structure or Adjacent
        The system swept.
    a_g : float
        Peak table acceleration in g (``A_t = a_g g``, :attr:`peak_m_s2`).
    freqs_hz : ndarray, shape (n,)
        Step frequencies in stepping order (increasing "up", decreasing "down").
    direction : {"up", "down"}
        The stepping direction.
    steady_mode : {"adaptive", "fixed"}
        How each step ended (the ``steady`` argument of :func:`pounding.sweep`).
    cycles : int
        Cycles per step (fixed mode), or the most per step (adaptive mode: ``max_cycles``).
    measure_cycles : int
        Cycles measured at the end of each step (the window; adaptive: rounded up to whole periods).
    omega_min_rad_s : float
        ``Omega_min`` of ``D_tmax = A_t / Omega_min^2``, rad/s (normalizes ``e``).
    f_ref_hz : float
        ``f_R`` of ``nu = f / f_R``, Hz.
    g : float
        The acceleration of gravity used, m/s^2 (9.81).
    levels, storeys, contact_slots : tuple of tuple
        What the metrics' columns are: a level ``(structure, level)``; a storey ``(structure, storey)``
        (storey ``s`` carries level ``s``); a contact slot ``(structure, "wall", wall, level, side)`` or
        ``(-1, "link", link, level_first, "")`` (a single mass: level ``(0, 0)``, its bumpers wall 0).
    level_metrics : ndarray, shape (n, n_levels, 3)
        Each level's exact displacement max and min (m, relative to the ground) and absolute acceleration
        peak (m/s^2) over the window (NaN: a step not measured).
    drift_metrics : ndarray, shape (n, n_storeys, 2)
        Each storey's exact drift max and min, m.
    contact_sums : ndarray, shape (n, n_slots, SIDE_SUMS)
        Per contact slot, over the contacts that ended in the window: their number, the number with a
        restitution, and the sums of the ``IMPACT_COLUMNS`` (:mod:`pounding.metrics.impacts`' ``S_*``).
    window_cycles, cycles_run, period_multiple : ndarray of int, shape (n,)
        Each step's window's cycles; the cycles it ran; the period multiple of its steady response (0: not
        periodic).
    window_events : ndarray of int, shape (n, 2)
        The events the engine located in each step's window: all of them (contacts' starts and ends, a
        bearing's yields, reversals, sticks and slips, ...), and the sticks of its friction isolators.
    window_states : ndarray, shape (n, n_state)
        The exact state at the start of each step's window (what loops restart from).
    window_strobes : ndarray, shape (n, cycles, 2, n_levels)
        Each level's displacement (m) and velocity (m/s) at the end of each of the window's cycles (table
        phase 0: the stroboscopic section); NaN past a step's window and where it was not measured.
    step_start_s : ndarray, shape (n,)
        When each step began (table phase 0 there), s.
    steps_done : int
        Steps finished (fewer than n after an early stop or an interruption).
    final_state : State
        State after the last step (continue with ``sweep(..., state=final_state)``).
    status, message : Status, str
        ``Status.SUCCESS`` or why the sweep stopped early, and a summary in words.
    measurement : MeasurementChain or None
        The chain a single mass's metrics were measured through (``sweep(..., measurement=)``), or None:
        the exact metrics.
    measured : DataFrame or None
        With a chain: per step, the metrics of its window as measured (alpha, excursion, eta, e, the
        contacts and their means) and ``window_start_s``; they replace the exact ones in
        :meth:`to_dataframe` and the sweep's features.
    measured_impacts : DataFrame or None
        With a chain: every contact read in the windows (the lab's columns, with ``freq_hz``).

    Examples
    --------
    >>> import pounding
    >>> sw = pounding.sweep(pounding.presets.paper_damped(), 0.05, [1.5, 2.0, 2.5])
    >>> # each step periodic, period 1
    >>> sw.status.name, sw.steps_done, sw.period_multiple.tolist()
    ('SUCCESS', 3, [1, 1, 1])
    >>> # D_tmax in mm
    >>> round(sw.alpha_max, 2), sw.resonance_hz, round(sw.d_tmax_m * 1e3, 1)
    (8.3, 1.5, 34.5)
    >>> sw.to_dataframe()["contact"].tolist()
    [True, False, False]
    >>> sw.jumps()[["freq_from_hz", "freq_to_hz", "kind"]].values.tolist()
    [[1.5, 2.0, 'down'], [2.0, 2.5, 'down']]

    A two-storey building on a linear isolator, a stop at its base 2 cm away, swept at 0.1 g:

    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=4.0e3)
    >>> stop = pounding.Wall(0, 0.02, 0.02, pounding.KelvinVoigt(1.0e8, 1.0e4))
    >>> storeys = [pounding.Storey(1.0e3, 2.0e6, 2.0e3)] * 2
    >>> b = pounding.Structure(2.0e3, iso, storeys, [stop])
    >>> res = pounding.sweep(b, 0.1, [1.0, 1.5, 2.0])
    >>> res.message
    'All 3 steps reached a periodic steady state.'
    >>> res.alpha.shape  # (steps, levels)
    (3, 3)
    >>> df = res.to_dataframe()  # one row per step and level
    >>> list(df.columns[:5])
    ['freq_hz', 'nu', 'level', 'alpha', 'excursion_m']
    """

    system: Any = field(repr=False)
    a_g: float
    freqs_hz: np.ndarray = field(repr=False)
    direction: str
    steady_mode: str
    cycles: int
    measure_cycles: int
    omega_min_rad_s: float
    f_ref_hz: float
    g: float
    levels: tuple = field(repr=False)
    storeys: tuple = field(repr=False)
    contact_slots: tuple = field(repr=False)
    level_metrics: np.ndarray = field(repr=False)
    drift_metrics: np.ndarray = field(repr=False)
    contact_sums: np.ndarray = field(repr=False)
    window_cycles: np.ndarray = field(repr=False)
    window_events: np.ndarray = field(repr=False)
    cycles_run: np.ndarray = field(repr=False)
    period_multiple: np.ndarray = field(repr=False)
    window_states: np.ndarray = field(repr=False)
    window_strobes: np.ndarray = field(repr=False)
    step_start_s: np.ndarray = field(repr=False)
    steps_done: int
    final_state: State = field(repr=False)
    status: Status
    message: str
    measurement: Any = None
    measured: pd.DataFrame | None = field(default=None, repr=False)
    measured_impacts: pd.DataFrame | None = field(default=None, repr=False)

    # ---- names before one result served every system
    @property
    def oscillator(self) -> Any:
        """The system swept (its name before: :attr:`system`)."""
        warn_renamed("SweepResult.oscillator", "SweepResult.system", why="one result for every system")
        return self.system

    @property
    def structure(self) -> Any:
        """The system swept (its name before: :attr:`system`)."""
        warn_renamed("SweepResult.structure", "SweepResult.system", why="one result for every system")
        return self.system

    # ---- derived scalars
    @property
    def peak_m_s2(self) -> float:
        """``A_t = a_g g``, m/s^2."""
        return self.a_g * self.g

    @property
    def d_tmax_m(self) -> float:
        """``D_tmax = A_t / Omega_min^2``, m (normalizes ``e``)."""
        return self.peak_m_s2 / self.omega_min_rad_s**2

    @property
    def total_gap_m(self) -> float:
        """``Delta`` of the lowest level with a wall, the first structure's first (a single mass:
        ``g_L + g_R`` of its bumpers), m; NaN without walls."""
        return float(next((g for g in self.level_gaps_m if not math.isnan(g)), math.nan))

    @property
    def success(self) -> bool:
        """True when every step ran (``status`` ``SUCCESS``); steps may be unsettled (``steady``)."""
        return self.status == Status.SUCCESS and self.steps_done == self.freqs_hz.size

    @property
    def nu(self) -> np.ndarray:
        """``f / f_R`` of each step, shape (n,)."""
        return self.freqs_hz / self.f_ref_hz

    @property
    def alpha(self) -> np.ndarray:
        """Each level's ``max |a_abs| / A_t`` over each step's window, shape (n, n_levels)."""
        return self.level_metrics[:, :, 2] / self.peak_m_s2

    @property
    def alpha_base(self) -> np.ndarray:
        """The (first) structure's base's alpha per step, shape (n,) (a fixed base: 1, the ground's)."""
        return self.alpha[:, 0]

    @property
    def alpha_top(self) -> np.ndarray:
        """The (first) structure's top level's alpha per step, shape (n,) (a single mass: its own)."""
        return self.alpha[:, self._top]

    @property
    def contacts_per_cycle(self) -> np.ndarray:
        """Each contact slot's contacts per cycle over each step's window, shape (n, n_slots)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.contact_sums[:, :, S_COUNT] / self.window_cycles[:, None]

    @property
    def peak_drift(self) -> np.ndarray:
        """Each storey's largest absolute drift per step, m, shape (n, n_storeys)."""
        return np.maximum(np.abs(self.drift_metrics[:, :, 0]), np.abs(self.drift_metrics[:, :, 1]))

    @cached_property
    def _moving(self) -> tuple:
        """The levels that move (counted through :attr:`levels`): all but a fixed base's level 0."""
        return tuple(q for q, (b, lv) in enumerate(self.levels)
                     if not (lv == 0 and self._structures[b].fixed))

    @cached_property
    def _top(self) -> int:
        return max(q for q, (b, _) in enumerate(self.levels) if b == 0)

    def _level(self, level: int) -> int:
        n = len(self.levels)
        return integer("level", level, -n, n - 1) % n

    @cached_property
    def _structures(self) -> tuple:
        from ..engine.assembly import structures_of

        return structures_of(self.system)[0]

    @property
    def level_masses_kg(self) -> np.ndarray:
        """Each level's mass, kg, shape (n_levels,) (NaN for a fixed base's ground)."""
        return np.concatenate([s.masses_kg for s in self._structures])

    @property
    def level_gaps_m(self) -> np.ndarray:
        """Each level's total gap ``Delta`` (its wall's two gaps; a single mass: ``g_L + g_R``), m,
        shape (n_levels,); NaN without a wall at the level."""
        def gap(walls: tuple, lv: int) -> float:  # (a level has one wall at most)
            return next((w.gap_left_m + w.gap_right_m for w in walls if w.level == lv), math.nan)

        return np.array([gap(self._structures[b].walls, lv) for b, lv in self.levels])

    # ---- the table
    @cached_property
    def _table(self) -> pd.DataFrame:
        return measured_table(self, self._exact_table)

    @cached_property
    def _exact_table(self) -> pd.DataFrame:
        return exact_table(self)

    def to_dataframe(self) -> pd.DataFrame:
        """One row per step and level, steps in stepping order (a single mass: one row per step; SI units;
        NaN where a step did not run).

        Columns: ``freq_hz``, ``nu``, (``structure``: ``first`` or ``second`` of a pair), ``level``,
        ``alpha``, ``excursion_m`` (``E``), ``displacement_max_m``, ``displacement_min_m``, ``eta``
        (``E / Delta`` over the level's walls' total gap, NaN without a wall), ``e`` (``E / D_tmax``),
        ``contact``, ``contacts_per_cycle``, the impact means over the window at the level's walls (both
        sides pooled): ``restitution``, ``contact_time_s``, ``impulse_n_s``, ``mean_force_n``,
        ``peak_force_n``, ``dissipated_energy_j`` (``E_d``), ``bumper_dissipation_j``; ``steady``,
        ``period_multiple``, ``cycles_run``, ``events_per_cycle`` (every event the engine located in the
        window, per cycle: the whole system's) and ``sticks_per_cycle`` (its friction isolators' sticks);
        ``abs_acceleration_max_m_s2``, the storey below's
        ``drift_peak_m`` and ``drift_ratio_peak`` (NaN at a base); then the impact columns per side with
        suffixes ``_left`` and ``_right``.
        """
        return self._table.copy()

    def exact_dataframe(self) -> pd.DataFrame:
        """The table of :meth:`to_dataframe` with the exact metrics (event-located), whatever the
        measurement chain; the same as :meth:`to_dataframe` without one."""
        return self._exact_table.copy()

    def contacts_dataframe(self) -> pd.DataFrame:
        """One row per step and contact slot: ``freq_hz``, ``nu``, ``structure`` (-1 a link), ``kind``
        (``wall`` or ``link``), its ``index``, ``level``, ``side``, then ``contacts_per_cycle`` and the impact
        means over the window (``restitution``, ``contact_time_s``, ... as :meth:`to_dataframe`'s)."""
        return contacts_table(self)

    def to_xarray(self) -> "xr.Dataset":
        """The table as a Dataset on ``freq_hz`` (increasing) and ``level`` (its ``nu`` and the step order as
        ``step``), with each contact slot's means along ``slot`` (``wall 0 left``, ...; its ``slot_kind``,
        ``slot_level`` and ``slot_side`` as coordinates; ``contacts_per_cycle_per_contact``, ...) and each
        storey's drift extrema along ``storey`` (``drift_max_m``, ``drift_min_m``), where there are any;
        units in each variable's ``units``; the sweep's settings, status and message as attributes."""
        return dataset(self)

    # ---- the sweep's features (of the first structure's top level: a single mass's own)
    def _rows(self, q: int) -> pd.DataFrame:
        """Level ``q``'s rows of the table over the steps that ran (an InputError if none did)."""
        df = self._table.iloc[q::len(self.levels)].iloc[: self.steps_done]
        if df.empty:
            raise InputError(Problem.NOT_STARTED, "sweep", self.direction, what="its features")
        return df

    def resonance_of(self, level: int = -1) -> float:
        """The step frequency where ``level``'s alpha peaks, Hz (``level`` counts through :attr:`levels`;
        -1 the last: a single structure's top level); NaN where no step measured it."""
        alpha = self._rows(self._level(level))["alpha"].to_numpy()
        if not np.any(np.isfinite(alpha)):
            return math.nan
        return float(self.freqs_hz[int(np.nanargmax(alpha))])

    @property
    def resonance_hz(self) -> float:
        """Frequency of the step with the largest alpha of the (first) structure's top level (a single mass:
        the pseudo-resonance ``f``), Hz; any level's: :meth:`resonance_of`."""
        return self.resonance_of(self._top)

    @property
    def nu_r(self) -> float:
        """The pseudo-resonance ``nu_R = f / f_R`` where :attr:`resonance_hz` is."""
        return self.resonance_hz / self.f_ref_hz

    @property
    def alpha_max(self) -> float:
        """The largest alpha of the (first) structure's top level over the steps that ran."""
        return float(np.nanmax(self._rows(self._top)["alpha"]))

    @property
    def contact_freqs_hz(self) -> np.ndarray:
        """Frequencies of the steps with a contact (at any wall or link), increasing, Hz."""
        n_lev = len(self.levels)
        done = self._table.iloc[: len(self._rows(0)) * n_lev]  # (the table's, measured if it was)
        hit = done["contact"].to_numpy(bool).reshape(-1, n_lev).any(axis=1)
        links = [c for c, slot in enumerate(self.contact_slots) if slot[1] == "link"]
        if links:
            hit |= np.sum(self.contact_sums[: self.steps_done, links, S_COUNT], axis=1) > 0
        return np.sort(self.freqs_hz[: self.steps_done][hit])

    @property
    def contact_range_hz(self) -> tuple[float, float] | None:
        """``(lowest, highest)`` frequency with contact, Hz (None if no contact); the
        paper's contact range ``Delta nu_C`` is this divided by ``f_ref_hz``."""
        f = self.contact_freqs_hz
        return None if f.size == 0 else (float(f[0]), float(f[-1]))

    def jumps(self, ratio: float = DEFAULT_JUMP_RATIO) -> pd.DataFrame:
        """Where the response leaves one branch for another along the sweep.

        A jump is a step-to-step change of the (first) structure's top level's alpha or excursion by a
        factor ``ratio`` or more (default 1.5), in stepping order.

        Returns
        -------
        DataFrame
            ``freq_from_hz``, ``freq_to_hz``, ``alpha_from``, ``alpha_to``,
            ``excursion_from_m``, ``excursion_to_m``, ``contact_from``, ``contact_to``,
            ``kind`` ("up" when the response grows, "down" when it drops).
        """
        return jumps_of(self._rows(self._top), ratio)

    def paper_quantities(self, level: int | None = None) -> dict[str, float]:
        """The paper's per-sweep quantities (Tables 2-4) of one level (counted through :attr:`levels`; default
        the (first) structure's lowest moving level: its base, what a shaking table's rig carries, or the
        first floor of a fixed base; a single mass: itself), by their table names.

        Over the sweep: ``nu_r`` and the largest ``alpha`` of the level, the largest ``eta`` (the level's
        excursion over its walls' total gap; NaN without a wall there) and ``e``, the largest excursion
        ``excursion_max_m`` (m), the contact range in ``nu`` (at the level's walls); at the level's
        resonance step, its walls' impact means: ``contact_time_ms``, ``restitution``,
        ``mean_force_over_mg``, ``peak_force_over_mg`` and ``dissipated_energy_per_mass`` (m^2/s^2; ``m`` the
        level's mass).  NaN where a quantity does not exist (no contact, no wall, no step measured, a fixed
        base's level 0: the ground).
        """
        q = self._moving[0] if level is None else self._level(level)
        if q not in self._moving:  # (a fixed base's ground)
            return dict.fromkeys(PAPER_QUANTITIES, math.nan)
        return paper_quantities_of(self, q)

    def quantities(self) -> dict[str, float]:
        """The sweep in a few numbers (a campaign's Tables 2-4 row, a study point's), by their table names.

        A single mass: its :meth:`paper_quantities`.  A structure (or a pair): ``nu_r_top`` (where the top
        level's alpha peaks), ``alpha_top_max``, ``alpha_base_max``, ``drift_ratio_max`` (over every storey
        and step), ``contact_nu_min`` and ``contact_nu_max`` (the range of ``nu`` with a contact at any wall
        or link; NaN without).  NaN for a sweep with no step done.
        """
        from ..engine.assembly import is_single_mass

        if is_single_mass(self.system):
            return self.paper_quantities()
        return structure_quantities_of(self)

    def step_index(self, freq_hz: float) -> int:
        """Index (stepping order) of the step at ``freq_hz`` (to 1e-9 Hz)."""
        f = positive("freq_hz", freq_hz, "Hz")
        hits = np.flatnonzero(np.abs(self.freqs_hz[: self.steps_done] - f) <= 1e-9 * max(1.0, f))
        if hits.size == 0:
            choices = ", ".join(f"{x:g}" for x in self.freqs_hz[: self.steps_done])
            raise InputError(Problem.NOT_IN_RESULT, "freq_hz", freq_hz, choices=choices or "(none)")
        return int(hits[0])

    def hysteresis_loop(self, freq_hz: float, *, total_gap_m: float | None = None,
                        points_per_cycle: int = 2000) -> "HysteresisLoop":
        """The loop ``r = F_I / (M g)`` against ``d = D / Delta`` of one step of a single mass (Figs. 7, 15).

        The step's window is re-run exactly from its saved state over one period of the
        response (``period_multiple`` cycles, or one cycle if it was not periodic), with
        dense samples and every event instant.

        Parameters
        ----------
        freq_hz : float
            A step of this sweep.
        total_gap_m : float, optional
            ``Delta`` (default: the bumpers' total gap; required without bumpers, e.g.
            0.03 for the paper's NBs loops).
        points_per_cycle : int
            Uniform samples per forcing cycle.
        """
        from ..engine import simulate
        from ..engine.assembly import assemble
        from ..excitation import Harmonic
        from ..metrics import HysteresisLoop

        from ..engine.assembly import is_single_mass

        if not is_single_mass(self.system):  # (the loop reads a single mass's run: its bumpers' force)
            raise InputError(Problem.WRONG_MODE, "hysteresis_loop", freq_hz, mode="a single mass's sweep",
                             fix="plot a structure's contacts from a run of the step: pounding.simulate")
        i = self.step_index(freq_hz)
        if total_gap_m is None:
            if not self.total_gap_m > 0:  # (NaN without bumpers)
                why = "the gaps are zero" if self.contact_slots else "no bumpers here"
                raise InputError(Problem.MISSING_KEY, "total_gap_m", None,
                                 choices=f"a length in m to normalize D ({why}), e.g. 0.03")
            total_gap_m = self.total_gap_m
        total_gap_m = positive("total_gap_m", total_gap_m, "m")
        points = integer("points_per_cycle", points_per_cycle, 8)
        f = float(self.freqs_hz[i])
        asm = assemble(self.system)
        state = State._of(self.window_states[i], asm.dofs, asm.layout)
        omega = 2 * math.pi * f
        n_cyc = max(1, int(self.period_multiple[i]))
        exc = Harmonic(self.a_g, f, phase=-(omega * float(self.step_start_s[i])), g=self.g)
        run = simulate(self.system, exc, n_cyc / f, state, sample_rate_hz=points * f)
        return HysteresisLoop.from_run(run, total_gap_m, f, self.a_g, n_cyc)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """alpha and eta (e without bumpers) against nu (a single mass), or each level's alpha and each
        contact slot's contacts per cycle (several levels); see :func:`pounding.plots.plot_sweep`.  Returns
        its Figure."""
        from ..plots import figure_of, plot_sweep

        return figure_of(plot_sweep(self, ax=ax, **kwargs), ax)
