"""What a sweep of a structure returns: per step, every level's alpha and extrema, every storey's drift and
every wall side's (and link's) contacts, measured exactly over the step's window."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from .._checks import integer
from ..data import PAPER_OMEGA_MIN_RAD_S
from .._errors import Status

# the contact statistics of a step, per contact slot
C_COUNT, C_TIME, C_IMPULSE, C_PEAK, C_RESTITUTION = 0, 1, 2, 3, 4
CONTACT_STATS = 5
CONTACT_NAMES = ("contacts_per_cycle", "contact_time_mean_s", "impulse_mean_n_s", "peak_force_max_n",
                 "restitution_mean")
_NAMES = ("first", "second")


def labels_of(model: Any, asm: Any) -> tuple[list, list, list]:
    """(levels, storeys, contact slots) of a structure or a pair, as rows of labels: a level
    ``(structure, level)``, a storey ``(structure, storey)`` (storey ``s`` under level ``s``), a slot
    ``(structure, "wall", wall, level, side)`` or ``(-1, "link", link, level_first, "")``."""
    from ..engine.assembly import structures_of

    structures, links = structures_of(model)
    levels = [(b, q) for b, s in enumerate(structures) for q in range(s.n_levels)]
    storeys = [(b, q + 1) for b, s in enumerate(structures) for q in range(len(s.storeys))]
    slots = []
    for b, wall, side in asm.slots:
        if b >= 0:
            slots.append((b, "wall", wall, structures[b].walls[wall].level, ("left", "right")[side]))
        else:
            slots.append((-1, "link", wall, links[wall].level_first, ""))
    return levels, storeys, slots


@dataclass(frozen=True, eq=False)
class StructureSweepResult:
    """Result of :func:`pounding.sweep` of a :class:`~pounding.Structure` (or :class:`~pounding.Adjacent`):
    per frequency step, each level's alpha and exact extrema, each storey's drift, each contact's
    statistics, over the step's window (its last cycles, run again from the window's exact start).

    Attributes
    ----------
    structure : Structure or Adjacent
        The system swept.
    a_g : float
        Peak table acceleration in g.
    freqs_hz : ndarray, shape (n,)
        Step frequencies in stepping order.
    direction : {"up", "down"}
        The stepping direction.
    steady_mode : {"adaptive", "fixed"}
        How each step ended (``steady`` of :func:`pounding.sweep`).
    cycles : int
        Cycles per step (fixed), or the most per step (adaptive).
    measure_cycles : int
        Cycles measured at the end of each step (the window; adaptive: rounded up to whole periods).
    f_ref_hz : float
        ``f_R`` of ``nu = f / f_R``, Hz.
    g : float
        The acceleration of gravity used, m/s^2.
    levels, storeys, contact_slots : list of tuple
        What the columns of the metrics are: a level ``(structure, level)``; a storey ``(structure,
        storey)`` (storey ``s`` carries level ``s``); a contact slot ``(structure, "wall", wall, level,
        side)`` or ``(-1, "link", link, level_first, "")`` (``structure`` 0, or 0 and 1 for a pair).
    level_metrics : ndarray, shape (n, n_levels, 3)
        Each level's exact displacement max and min (m, relative to the ground) and absolute acceleration
        peak (m/s^2) over the window (NaN: a step not measured).
    drift_metrics : ndarray, shape (n, n_storeys, 2)
        Each storey's exact drift max and min, m.
    contact_metrics : ndarray, shape (n, n_slots, 5)
        Per contact slot: contacts per cycle (those that ended in the window), mean contact time (s),
        mean impulse (N s), largest peak force (N), mean restitution (the pair's relative velocity out over
        in, negated).
    cycles_run, period_multiple, window_cycles : ndarray of int, shape (n,)
        Cycles each step ran; the period multiple of its steady response (0: not periodic); its window's
        cycles.
    window_states : ndarray, shape (n, n_state)
        The exact state at each window's start.
    omega_min_rad_s : float
        ``Omega_min`` of ``D_tmax = A_t / Omega_min^2``, rad/s (normalizes ``e``: ``paper_quantities``).
    window_strobes : ndarray, shape (n, measure_cycles, 2, n_levels)
        Each level's displacement (m) and velocity (m/s) at the end of each of the window's cycles (table
        phase 0: the stroboscopic section); NaN beyond a step's window and where it was not measured.
    step_start_s : ndarray, shape (n,)
        When each step began, s.
    steps_done : int
        Steps finished.
    final_state : State
        Where the sweep ended (``state`` of the next sweep).
    status : Status
        How the sweep ended.
    message : str
        How it ended, in words.

    Examples
    --------
    A two-storey building on a linear isolator, a stop at its base 2 cm away, swept at 0.1 g:

    >>> import pounding
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
    ['freq_hz', 'nu', 'level', 'alpha', 'displacement_max_m']
    """

    structure: Any
    a_g: float
    freqs_hz: np.ndarray
    direction: str
    steady_mode: str
    cycles: int
    measure_cycles: int
    f_ref_hz: float
    g: float
    levels: list
    storeys: list
    contact_slots: list
    level_metrics: np.ndarray
    drift_metrics: np.ndarray
    contact_metrics: np.ndarray
    cycles_run: np.ndarray
    period_multiple: np.ndarray
    window_cycles: np.ndarray
    window_states: np.ndarray
    step_start_s: np.ndarray
    steps_done: int
    final_state: Any
    status: Status
    message: str
    window_strobes: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 2, 0)), repr=False)
    omega_min_rad_s: float = PAPER_OMEGA_MIN_RAD_S

    # ------------------------------------------------------------------ derived
    @property
    def success(self) -> bool:
        return self.status == Status.SUCCESS

    @property
    def peak_m_s2(self) -> float:
        """The table's peak acceleration ``A_t = a_g g``, m/s^2."""
        return self.a_g * self.g

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
        """The (first) structure's top floor's alpha per step, shape (n,)."""
        top = max(q for q, (b, _) in enumerate(self.levels) if b == 0)
        return self.alpha[:, top]

    @property
    def peak_drift(self) -> np.ndarray:
        """Each storey's largest absolute drift per step, m, shape (n, n_storeys)."""
        return np.maximum(np.abs(self.drift_metrics[:, :, 0]), np.abs(self.drift_metrics[:, :, 1]))

    def _level(self, level: int) -> int:
        n = len(self.levels)
        q = integer("level", level, -n, n - 1)
        return q % n

    def resonance_hz(self, level: int = -1) -> float:
        """The step frequency where ``level``'s alpha peaks, Hz (``level`` counts through :attr:`levels`;
        -1 the last: the top floor of a single structure)."""
        alpha = self.alpha[:, self._level(level)]
        if not np.any(np.isfinite(alpha)):
            return float("nan")
        return float(self.freqs_hz[int(np.nanargmax(alpha))])

    def nu_r(self, level: int = -1) -> float:
        """The pseudo-resonance ``nu_R`` of ``level``: where its alpha peaks, over ``f_R``."""
        return self.resonance_hz(level) / self.f_ref_hz

    def paper_quantities(self, level: int = 0) -> dict[str, float]:
        """The paper's per-sweep quantities (Tables 2-4, as ``campaign.sweep_quantities`` gives a single
        mass's) of one level of the (first) structure: by default its base, the mass a shaking table's
        rig carries.  Over the sweep: ``nu_r`` and the largest ``alpha`` of the level, ``eta`` (its
        largest excursion over the total gap of its wall; NaN without a wall at the level), ``e`` (that
        excursion over ``D_tmax = A_t / Omega_min^2``), ``excursion_max_m``, the contact range in ``nu``
        (of the level's walls); at the level's resonance step, its walls' mean ``contact_time_ms`` and
        ``restitution``.  The forces and the dissipated energy (``mean_force_over_mg``,
        ``peak_force_over_mg``, ``dissipated_energy_per_mass``) are not measured here: NaN."""
        q = self._level(level)
        b, lv = self.levels[q]
        done = slice(0, self.steps_done)
        nan = float("nan")
        names = ("nu_r", "alpha", "eta", "e", "excursion_max_m", "contact_nu_min", "contact_nu_max",
                 "mean_force_over_mg", "contact_time_ms", "peak_force_over_mg", "dissipated_energy_per_mass",
                 "restitution")
        out = dict.fromkeys(names, nan)
        alpha = self.alpha[done, q]
        if not np.any(np.isfinite(alpha)):
            return out
        excursion = self.level_metrics[done, q, 0] - self.level_metrics[done, q, 1]
        structure = self.structure.structures[b] if hasattr(self.structure, "structures") else self.structure
        walls = [c for c, slot in enumerate(self.contact_slots)
                 if slot[0] == b and slot[1] == "wall" and slot[3] == lv]
        gap = sum(getattr(structure.walls[self.contact_slots[c][2]], f"gap_{self.contact_slots[c][4]}_m")
                  for c in walls) if walls else nan
        i = int(np.nanargmax(alpha))
        counts = self.contact_metrics[done][:, walls, C_COUNT] if walls else np.zeros((self.steps_done, 0))
        hit = np.nansum(counts, axis=1) > 0
        at = self.contact_metrics[i, walls] if walls else np.zeros((0, CONTACT_STATS))
        weight = np.nan_to_num(at[:, C_COUNT])

        def mean(col: int) -> float:
            ok = (weight > 0) & np.isfinite(at[:, col])
            return float(np.average(at[ok, col], weights=weight[ok])) if ok.any() else nan

        widest = float(np.nanmax(excursion))
        out.update({"nu_r": float(self.freqs_hz[i]) / self.f_ref_hz, "alpha": float(alpha[i]),
                    "eta": widest / gap, "e": widest / (self.peak_m_s2 / self.omega_min_rad_s**2),
                    "excursion_max_m": widest,
                    "contact_nu_min": float(self.nu[done][hit].min()) if hit.any() else nan,
                    "contact_nu_max": float(self.nu[done][hit].max()) if hit.any() else nan,
                    "contact_time_ms": mean(C_TIME) * 1e3, "restitution": mean(C_RESTITUTION)})
        return out

    def quantities(self) -> dict[str, float]:
        """The sweep in a few numbers (a campaign's Table 2 row, a study point's): ``nu_r_top`` (where the
        top floor's alpha peaks), ``alpha_top_max``, ``alpha_base_max``, ``drift_ratio_max`` (over every
        storey and step), ``contact_nu_min`` and ``contact_nu_max`` (the range of ``nu`` with a contact at
        any wall or link; NaN without).  NaN for a sweep with no step done."""
        names = ("nu_r_top", "alpha_top_max", "alpha_base_max", "drift_ratio_max", "contact_nu_min",
                 "contact_nu_max")
        done = slice(0, self.steps_done)
        if self.steps_done == 0:
            return {k: float("nan") for k in names}
        frame = self.to_dataframe()
        frame = frame[frame["freq_hz"].isin(self.freqs_hz[done])]
        hit = np.nansum(self.contact_metrics[done, :, 0], axis=1) > 0 if self.contact_slots else []
        hits = self.nu[done][hit] if len(hit) else np.zeros(0)
        top = max(q for q, (b, _) in enumerate(self.levels) if b == 0)
        nan = float("nan")

        def largest(values: np.ndarray) -> float:  # (NaN where no step measured it: no warning)
            return float(np.nanmax(values)) if np.any(np.isfinite(values)) else nan

        return dict(zip(names, (
            self.nu_r(level=top), largest(self.alpha_top[done]), largest(self.alpha_base[done]),
            largest(frame["drift_ratio_peak"].to_numpy()) if self.storeys else nan,
            float(np.min(hits)) if hits.size else nan, float(np.max(hits)) if hits.size else nan)))

    # ------------------------------------------------------------------ tables
    def _level_columns(self) -> dict[str, Any]:
        pair = len({b for b, _ in self.levels}) > 1
        cols: dict[str, Any] = {}
        if pair:
            cols["structure"] = [_NAMES[b] for b, _ in self.levels]
        cols["level"] = [q for _, q in self.levels]
        return cols

    def to_dataframe(self) -> pd.DataFrame:
        """One row per step and level (steps in stepping order): ``freq_hz``, ``nu``, (``structure``),
        ``level``, ``alpha``, exact displacement extrema and excursion (m), absolute acceleration peak
        (m/s^2), the storey below's peak drift (m) and drift ratio (NaN at a base), ``steady``,
        ``period_multiple``, ``cycles_run``."""
        n, n_lev = len(self.freqs_hz), len(self.levels)
        below = {lv: s for s, lv in enumerate(self.storeys)}
        heights = self._storey_heights()
        drift = np.full((n, n_lev), np.nan)
        ratio = np.full((n, n_lev), np.nan)
        for q, lv in enumerate(self.levels):
            if lv in below:
                drift[:, q] = self.peak_drift[:, below[lv]]
                ratio[:, q] = drift[:, q] / heights[below[lv]]
        m = self.level_metrics
        cols = self._level_columns()
        frame = {"freq_hz": np.repeat(self.freqs_hz, n_lev), "nu": np.repeat(self.nu, n_lev),
                 **{k: np.tile(v, n) for k, v in cols.items()},
                 "alpha": self.alpha.ravel(), "displacement_max_m": m[:, :, 0].ravel(),
                 "displacement_min_m": m[:, :, 1].ravel(), "excursion_m": (m[:, :, 0] - m[:, :, 1]).ravel(),
                 "abs_acceleration_max_m_s2": m[:, :, 2].ravel(), "drift_peak_m": drift.ravel(),
                 "drift_ratio_peak": ratio.ravel(),
                 "steady": np.repeat(self.period_multiple > 0, n_lev),
                 "period_multiple": np.repeat(self.period_multiple, n_lev),
                 "cycles_run": np.repeat(self.cycles_run, n_lev)}
        return pd.DataFrame(frame)

    def _storey_heights(self) -> np.ndarray:
        from ..engine.assembly import structures_of

        structures = structures_of(self.structure)[0]
        return np.array([structures[b].storeys[s - 1].height_m for b, s in self.storeys])

    def contacts_dataframe(self) -> pd.DataFrame:
        """One row per step and contact slot: ``freq_hz``, ``nu``, ``structure`` (-1 a link), ``kind``
        (``wall`` or ``link``), its index, ``level``, ``side``, then contacts per cycle, mean contact time
        (s), mean impulse (N s) and largest peak force (N) over the window."""
        n, n_c = len(self.freqs_hz), len(self.contact_slots)
        labels = list(zip(*self.contact_slots)) if n_c else [()] * 5
        frame = {"freq_hz": np.repeat(self.freqs_hz, n_c), "nu": np.repeat(self.nu, n_c)}
        for name, values in zip(("structure", "kind", "index", "level", "side"), labels):
            frame[name] = np.tile(np.array(values, dtype=object), n)
        for k, name in enumerate(CONTACT_NAMES):
            frame[name] = self.contact_metrics[:, :, k].ravel()
        return pd.DataFrame(frame)

    def to_xarray(self) -> Any:
        """The metrics as a Dataset along ``step``, ``level``, ``storey`` and ``contact`` (units in each
        variable's ``units``; each level's and storey's number and structure, ``first`` or ``second``, as
        coordinates; ``status``, ``message``, ``a_g`` as attributes).  Each variable's name ends with its
        unit, as a single mass's sweep's (``displacement_max_m``, ``abs_acceleration_max_m_s2``,
        ``drift_max_m``)."""
        import xarray as xr

        m = self.level_metrics
        level = self._level_columns()
        ds = xr.Dataset(
            {"alpha": (("step", "level"), self.alpha, {"units": "1"}),
             "displacement_max_m": (("step", "level"), m[:, :, 0], {"units": "m"}),
             "displacement_min_m": (("step", "level"), m[:, :, 1], {"units": "m"}),
             "abs_acceleration_max_m_s2": (("step", "level"), m[:, :, 2], {"units": "m/s^2"}),
             "drift_max_m": (("step", "storey"), self.drift_metrics[:, :, 0], {"units": "m"}),
             "drift_min_m": (("step", "storey"), self.drift_metrics[:, :, 1], {"units": "m"}),
             **{name: (("step", "contact"), self.contact_metrics[:, :, k], {"units": unit})
                for k, (name, unit) in enumerate(zip(CONTACT_NAMES, ("1/cycle", "s", "N s", "N", "1")))},
             "period_multiple": ("step", self.period_multiple),
             "cycles_run": ("step", self.cycles_run)},
            coords={"freq_hz": ("step", self.freqs_hz, {"units": "Hz"}), "nu": ("step", self.nu),
                    "level_number": ("level", np.array(level["level"])),
                    "storey_number": ("storey", np.array([s for _, s in self.storeys], dtype=int)),
                    "level_structure": ("level", np.array([_NAMES[b] for b, _ in self.levels], dtype=str)),
                    "storey_structure": ("storey", np.array([_NAMES[b] for b, _ in self.storeys], dtype=str)),
                    "contact_name": ("contact", np.array([_slot_name(s) for s in self.contact_slots],
                                                         dtype=str))})
        ds.attrs.update({"a_g": self.a_g, "direction": self.direction, "status": self.status.name,
                         "message": self.message})
        return ds

    # ------------------------------------------------------------------ plot
    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Each level's alpha against ``nu`` (and, with contacts, each slot's contacts per cycle);
        see :func:`pounding.plots.plot_structure_sweep`.

        Returns its Figure.
        """
        from ..plots import plot_structure_sweep, figure_of

        return figure_of(plot_structure_sweep(self, ax=ax, **kwargs), ax)


def _slot_name(slot: tuple) -> str:
    b, kind, index, level, side = slot
    if kind == "link":
        return f"link {index}"
    who = f"{_NAMES[b]} " if b > 0 else ""
    return f"{who}wall {index} {side}".strip()


def level_name(levels: list, q: int) -> str:
    """A level's name in a legend: ``"level 2"``, ``"second level 2"`` for a pair's second structure."""
    b, level = levels[q]
    pair = len({s for s, _ in levels}) > 1
    return f"{_NAMES[b]} level {level}" if pair else f"level {level}"


def slot_name(slots: list, c: int) -> str:
    """A contact slot's name in a legend."""
    return _slot_name(slots[c])
