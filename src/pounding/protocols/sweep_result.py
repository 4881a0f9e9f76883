"""What a sweep returns: per-step metrics, with the resonance, contact range and jumps."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._checks import integer, positive
from .._errors import InputError, Problem, Status
from ..engine import State
from ..metrics.impacts import IMPACT_COLUMNS, S_COUNT, S_N_RESTITUTION, S_SUMS, SIDE_SUMS
from ..engine.kernels import W_AMAX, W_CYCLES, W_DMAX, W_DMIN, W_SUMS
from .measured_sweep import MEASURED_COLUMNS

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from ..metrics import HysteresisLoop
    from ..model import Oscillator

# the columns of SweepResult.to_dataframe(), in order
STEP_COLUMNS = ("freq_hz", "nu", "alpha", "excursion_m", "displacement_max_m", "displacement_min_m",
                "eta", "e", "contact", "contacts_per_cycle", *IMPACT_COLUMNS, "steady",
                "period_multiple", "cycles_run")
SIDE_COLUMNS = ("contacts_per_cycle", *IMPACT_COLUMNS)
SIDES = ("left", "right")
DEFAULT_JUMP_RATIO = 1.5


# a sweep's quantities (``SweepResult.quantities``): the paper's Table 2, 3 and 4 rows
PAPER_QUANTITIES = ("nu_r", "alpha", "eta", "e", "contact_nu_min", "contact_nu_max", "excursion_max_m",
                    "mean_force_over_mg", "contact_time_ms", "peak_force_over_mg",
                    "dissipated_energy_per_mass", "restitution")


@dataclass(frozen=True, eq=False)
class SweepResult:
    """Result of :func:`pounding.sweep`: one row of metrics per frequency step.

    The metrics are measured over each step's last cycles (the window) and are exact
    (event-located extrema, every contact whole).  Use :meth:`to_dataframe` /
    :meth:`to_xarray` for the table, :attr:`nu_r`, :attr:`contact_range_hz` and
    :meth:`jumps` for the sweep's features, :meth:`hysteresis_loop` for Figs. 7/15 and
    :meth:`plot` for alpha and eta against nu.

    Attributes
    ----------
    oscillator : Oscillator
        The system swept.
    a_g : float
        Peak table acceleration in g (``A_t = a_g g``, :attr:`peak_m_s2`).
    direction : {"up", "down"}
        The stepping direction.
    steady_mode : {"adaptive", "fixed"}
        How each step ended (the ``steady`` argument of :func:`pounding.sweep`).
    cycles : int
        Cycles per step (fixed mode), or the most per step (adaptive mode: ``max_cycles``).
    measure_cycles : int
        Cycles measured at the end of each step (the window).
    omega_min_rad_s : float
        ``Omega_min`` of ``D_tmax = A_t / Omega_min^2``, rad/s (normalizes ``e``).
    f_ref_hz : float
        ``f_R`` of ``nu = f / f_R``, Hz.
    g : float
        The acceleration of gravity used, m/s^2 (9.81).
    freqs_hz : ndarray, shape (n,)
        Step frequencies in stepping order (increasing "up", decreasing "down").
    window : ndarray, shape (n, WINDOW_COLS)
        Raw window measurements (NaN for steps not run); see ``engine.kernels``.
    cycles_run, period_multiple : ndarray of int, shape (n,)
        Cycles each step ran; period multiple of its steady response (0: not periodic).
    window_states : ndarray, shape (n, n_state)
        The exact state at the start of each step's window (what loops restart from).
    window_strobes : ndarray, shape (n, cycles, 2)
        Each step's stroboscopic samples over its window: displacement (m) and velocity (m/s)
        at the end of each of its cycles (table phase 0); NaN past the window's length.
    step_start_s : ndarray, shape (n,)
        When each step began (table phase 0 there), s.
    steps_done : int
        Steps finished (fewer than n after an early stop or an interruption).
    final_state : State
        State after the last step (continue with ``sweep(..., state=final_state)``).
    status, message : Status, str
        ``Status.SUCCESS`` or why the sweep stopped early, and a summary in words.
    measurement : MeasurementChain or None
        The chain the metrics were measured through (``sweep(..., measurement=)``), or None:
        the exact metrics.
    measured : DataFrame or None
        With a chain: per step, the metrics of its window as measured (alpha, excursion, eta,
        e, the contacts and their means) and ``window_start_s``; they replace the exact ones in
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
    """

    oscillator: "Oscillator" = field(repr=False)
    a_g: float
    freqs_hz: np.ndarray = field(repr=False)
    direction: str
    steady_mode: str
    cycles: int
    measure_cycles: int
    omega_min_rad_s: float
    f_ref_hz: float
    g: float
    window: np.ndarray = field(repr=False)
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
        """``Delta = g_L + g_R`` (NaN without bumpers), m."""
        b = self.oscillator.bumpers
        return math.nan if b is None else b.total_gap

    @property
    def success(self) -> bool:
        """True when every step ran (``status`` ``SUCCESS``); steps may be unsettled (``steady``)."""
        return self.status == Status.SUCCESS and self.steps_done == self.freqs_hz.size

    # ---- the table
    @cached_property
    def _table(self) -> pd.DataFrame:
        exact = self._exact_table
        if self.measured is None:
            return exact
        table = exact.copy()
        ran = np.arange(len(table)) < self.steps_done
        for q in MEASURED_COLUMNS:
            table[q] = self.measured[q].to_numpy()
        table["contact"] = np.where(ran, self.measured["contact"].eq(True).to_numpy(), False)  # (NaN: unread)
        table["bumper_dissipation_j"] = np.nan  # (not measurable from the accelerations)
        per_side = _measured_sides(self.measured_impacts, self.freqs_hz, self.window[:, W_CYCLES])
        for side in ("_left", "_right"):
            for k in SIDE_COLUMNS:
                table[k + side] = per_side.get(k + side, np.full(len(table), np.nan))
        return table

    @cached_property
    def _exact_table(self) -> pd.DataFrame:
        w = self.window
        excursion = w[:, W_DMAX] - w[:, W_DMIN]
        cols: dict[str, Any] = {
            "freq_hz": self.freqs_hz,
            "nu": self.freqs_hz / self.f_ref_hz,
            "alpha": w[:, W_AMAX] / self.peak_m_s2,
            "excursion_m": excursion,
            "displacement_max_m": w[:, W_DMAX],
            "displacement_min_m": w[:, W_DMIN],
            # (undefined at zero gap, as without bumpers)
            "eta": excursion / self.total_gap_m if self.total_gap_m > 0 else np.full_like(excursion, np.nan),
            "e": excursion / self.d_tmax_m,
        }
        sides = [w[:, W_SUMS + j * SIDE_SUMS: W_SUMS + (j + 1) * SIDE_SUMS] for j in range(2)]
        both = sides[0] + sides[1]
        count = both[:, S_COUNT]
        ran = np.arange(w.shape[0]) < self.steps_done
        cols["contact"] = np.where(ran, count > 0, False)
        per_side: dict[str, np.ndarray] = {}
        for name, sums in (("", both), ("_left", sides[0]), ("_right", sides[1])):
            for key, value in _impact_means(sums, w[:, W_CYCLES]).items():
                per_side[key + name] = value
        cols.update({k: per_side[k] for k in SIDE_COLUMNS})
        cols["steady"] = np.where(ran, self.period_multiple > 0, False)
        cols["period_multiple"] = self.period_multiple
        cols["cycles_run"] = self.cycles_run
        for side in ("_left", "_right"):
            cols.update({k + side: per_side[k + side] for k in SIDE_COLUMNS})
        return pd.DataFrame(cols)

    def to_dataframe(self) -> pd.DataFrame:
        """One row per step in stepping order (SI units; NaN where a step did not run).

        Columns: ``freq_hz``, ``nu``, ``alpha``, ``excursion_m`` (``E``),
        ``displacement_max_m``, ``displacement_min_m``, ``eta`` (``E / Delta``, NaN
        without bumpers), ``e`` (``E / D_tmax``), ``contact``, ``contacts_per_cycle``,
        the impact means over the window (both sides pooled): ``restitution``,
        ``contact_time_s``, ``impulse_n_s``, ``mean_force_n``, ``peak_force_n``,
        ``dissipated_energy_j`` (``E_d``), ``bumper_dissipation_j``; ``steady``,
        ``period_multiple``, ``cycles_run``; then the impact columns per side with
        suffixes ``_left`` and ``_right``.
        """
        return self._table.copy()

    def exact_dataframe(self) -> pd.DataFrame:
        """The table of :meth:`to_dataframe` with the exact metrics (event-located), whatever the
        measurement chain; the same as :meth:`to_dataframe` without one."""
        return self._exact_table.copy()

    def to_xarray(self) -> "xr.Dataset":
        """The table as a Dataset on ``freq_hz`` (increasing), with ``nu`` and the step order."""
        import xarray as xr

        df = self._table.copy()
        df["step"] = np.arange(len(df))
        df = df.sort_values("freq_hz").set_index("freq_hz")
        ds = xr.Dataset.from_dataframe(df.drop(columns=["nu"]))
        ds = ds.assign_coords(nu=("freq_hz", df["nu"].to_numpy()))
        for name in ("contact", "steady"):
            ds[name] = ds[name].astype(bool)
        ds["freq_hz"].attrs["units"] = "Hz"
        ds.attrs.update(self._attrs())
        return ds

    def _attrs(self) -> dict[str, Any]:
        return {"a_g": self.a_g, "direction": self.direction, "steady_mode": self.steady_mode,
                "cycles": self.cycles, "measure_cycles": self.measure_cycles,
                "omega_min_rad_s": self.omega_min_rad_s, "f_ref_hz": self.f_ref_hz,
                "total_gap_m": self.total_gap_m, "d_tmax_m": self.d_tmax_m,
                "status": str(self.status), "message": self.message,
                "measurement": "exact" if self.measurement is None else self.measurement.describe(),
                "system": self.oscillator.to_toml_text()}

    # ---- the sweep's features
    def _done(self) -> pd.DataFrame:
        df = self._table.iloc[: self.steps_done]
        if df.empty:
            raise InputError(Problem.NOT_STARTED, "sweep", self.direction, what="its features")
        return df

    @property
    def resonance_hz(self) -> float:
        """Frequency of the step with the largest alpha (the pseudo-resonance ``f``), Hz."""
        df = self._done()
        return float(df["freq_hz"].iloc[int(np.nanargmax(df["alpha"].to_numpy()))])

    @property
    def nu_r(self) -> float:
        """The pseudo-resonance ``nu_R = f / f_R`` where alpha peaks."""
        return self.resonance_hz / self.f_ref_hz

    @property
    def alpha_max(self) -> float:
        """The largest alpha over the steps that ran."""
        return float(np.nanmax(self._done()["alpha"]))

    @property
    def contact_freqs_hz(self) -> np.ndarray:
        """Frequencies of the steps with contact, increasing, Hz."""
        df = self._done()
        return np.sort(df.loc[df["contact"], "freq_hz"].to_numpy())

    @property
    def contact_range_hz(self) -> tuple[float, float] | None:
        """``(lowest, highest)`` frequency with contact, Hz (None if no contact); the
        paper's contact range ``Delta nu_C`` is this divided by ``f_ref_hz``."""
        f = self.contact_freqs_hz
        return None if f.size == 0 else (float(f[0]), float(f[-1]))

    def jumps(self, ratio: float = DEFAULT_JUMP_RATIO) -> pd.DataFrame:
        """Where the response leaves one branch for another along the sweep.

        A jump is a step-to-step change of alpha or of the excursion by a factor
        ``ratio`` or more (default 1.5), in stepping order.

        Returns
        -------
        DataFrame
            ``freq_from_hz``, ``freq_to_hz``, ``alpha_from``, ``alpha_to``,
            ``excursion_from_m``, ``excursion_to_m``, ``contact_from``, ``contact_to``,
            ``kind`` ("up" when the response grows, "down" when it drops).
        """
        ratio = positive("ratio", ratio, "(a factor > 1)")
        if ratio <= 1.0:
            raise InputError(Problem.TOO_SMALL, "ratio", ratio, minimum="1 (exclusive)", hint="")
        df = self._done()
        a = df["alpha"].to_numpy()
        e = df["excursion_m"].to_numpy()
        rows = []
        for i in range(len(df) - 1):
            ra = a[i + 1] / a[i]
            re = e[i + 1] / e[i]
            if max(ra, 1 / ra, re, 1 / re) >= ratio:
                rows.append({
                    "freq_from_hz": df["freq_hz"].iloc[i], "freq_to_hz": df["freq_hz"].iloc[i + 1],
                    "alpha_from": a[i], "alpha_to": a[i + 1],
                    "excursion_from_m": e[i], "excursion_to_m": e[i + 1],
                    "contact_from": bool(df["contact"].iloc[i]),
                    "contact_to": bool(df["contact"].iloc[i + 1]),
                    "kind": "up" if max(ra, re) >= max(1 / ra, 1 / re) else "down"})
        columns = ["freq_from_hz", "freq_to_hz", "alpha_from", "alpha_to", "excursion_from_m",
                   "excursion_to_m", "contact_from", "contact_to", "kind"]
        return pd.DataFrame(rows, columns=columns)

    def quantities(self) -> dict[str, float]:
        """The sweep in a few numbers (a campaign's Tables 2-4 row, a study point's), by their table names.

        Table 2's are over the sweep (``nu_r``, max ``alpha``, ``eta``, ``e``, the contact range in ``nu``;
        and the largest excursion ``excursion_max_m``, m); Tables 3 and 4's are the impact means at the
        resonance step (``contact_time_ms``, ``restitution``, ``mean_force_over_mg``, ``peak_force_over_mg``,
        ``dissipated_energy_per_mass`` in m^2/s^2).  NaN where a quantity does not exist (no contact, no
        bumpers, no step done).
        """
        if self.steps_done == 0:
            return {k: math.nan for k in PAPER_QUANTITIES}
        df = self.to_dataframe().iloc[: self.steps_done]
        rng = self.contact_range_hz
        step = df.iloc[self.step_index(self.resonance_hz)]
        mg = self.oscillator.mass_kg * self.g
        return {
            "nu_r": self.nu_r, "alpha": self.alpha_max, "eta": df["eta"].max(), "e": df["e"].max(),
            "excursion_max_m": df["excursion_m"].max(),
            "contact_nu_min": np.nan if rng is None else rng[0] / self.f_ref_hz,
            "contact_nu_max": np.nan if rng is None else rng[1] / self.f_ref_hz,
            "mean_force_over_mg": step["mean_force_n"] / mg,
            "contact_time_ms": step["contact_time_s"] * 1e3,
            "peak_force_over_mg": step["peak_force_n"] / mg,
            "dissipated_energy_per_mass": step["dissipated_energy_j"] / self.oscillator.mass_kg,
            "restitution": step["restitution"],
        }

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
        """The loop ``r = F_I / (M g)`` against ``d = D / Delta`` of one step (Figs. 7, 15).

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
        from ..excitation import Harmonic
        from ..metrics import HysteresisLoop

        i = self.step_index(freq_hz)
        if total_gap_m is None:
            if not self.total_gap_m > 0:  # (NaN without bumpers)
                why = "no bumpers here" if self.oscillator.bumpers is None else "the gaps are zero"
                raise InputError(Problem.MISSING_KEY, "total_gap_m", None,
                                 choices=f"a length in m to normalize D ({why}), e.g. 0.03")
            total_gap_m = self.total_gap_m
        total_gap_m = positive("total_gap_m", total_gap_m, "m")
        points = integer("points_per_cycle", points_per_cycle, 8)
        f = float(self.freqs_hz[i])
        from ..engine.simulate import kernel_system

        state = State._from_kernel(self.window_states[i], kernel_system(self.oscillator).layout)
        omega = 2 * math.pi * f
        n_cyc = max(1, int(self.period_multiple[i]))
        exc = Harmonic(self.a_g, f, phase=-(omega * float(self.step_start_s[i])), g=self.g)
        run = simulate(self.oscillator, exc, n_cyc / f, state, sample_rate_hz=points * f)
        return HysteresisLoop.from_run(run, total_gap_m, f, self.a_g, n_cyc)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """alpha and eta (e without bumpers) against nu; see :func:`pounding.plots.plot_sweep`.
        Returns its Figure."""
        from ..plots import plot_sweep, figure_of

        return figure_of(plot_sweep(self, ax=ax, **kwargs), ax)


def _measured_sides(impacts: pd.DataFrame | None, freqs_hz: np.ndarray,
                    window_cycles: np.ndarray) -> dict[str, np.ndarray]:
    """Per side, the measured contacts' means per step (``contacts_per_cycle`` and the impact
    columns the lab measures; NaN where it cannot)."""
    out: dict[str, np.ndarray] = {}
    for side in SIDES:
        for k in SIDE_COLUMNS:
            out[f"{k}_{side}"] = np.full(freqs_hz.size, np.nan)
        out[f"contacts_per_cycle_{side}"] = np.where(window_cycles > 0, 0.0, np.nan)
        if impacts is None or not len(impacts):
            continue
        mine = impacts[impacts["side"] == side]
        for i, f in enumerate(freqs_hz):
            at = mine[mine["freq_hz"] == f]
            if not len(at) or not window_cycles[i] > 0:
                continue
            out[f"contacts_per_cycle_{side}"][i] = len(at) / window_cycles[i]
            for k in SIDE_COLUMNS:
                if k in at.columns:
                    out[f"{k}_{side}"][i] = float(at[k].mean())
    return out


def _impact_means(sums: np.ndarray, window_cycles: np.ndarray) -> dict[str, np.ndarray]:
    """Window means of the impact quantities from per-side sums (NaN without contact)."""
    count = sums[:, S_COUNT]
    with np.errstate(invalid="ignore", divide="ignore"):
        out = {"contacts_per_cycle": count / window_cycles}
        for j, name in enumerate(IMPACT_COLUMNS):
            n = sums[:, S_N_RESTITUTION] if j == 0 else count
            out[name] = np.where(n > 0, sums[:, S_SUMS + j] / np.where(n > 0, n, 1.0), np.nan)
    return out


def sweep_message(status, done, n_steps, plan, cycles_run, period_multiple, interrupted) -> str:
    """A sweep's ``message``: how it ended, in words (a single mass's or a structure's)."""
    if interrupted and done == n_steps and plan.measurement is not None:
        return (f"Interrupted while measuring the windows through the chain: the {done} steps ran, "
                "and their metrics are the exact ones (no chain).")
    if interrupted:
        return f"Interrupted after {done} of {n_steps} steps; the others are NaN."
    if status != Status.SUCCESS:
        return (f"Stopped at step {done} of {n_steps} ({plan.freqs_hz[done - 1]:g} Hz): "
                f"{status.message}")
    not_steady = int(np.sum(period_multiple[:done] == 0))
    if plan.steady == "adaptive":
        if not_steady:
            return (f"{not_steady} of {n_steps} steps reached max_cycles = {plan.cycles} without "
                    f"a periodic response (steady False); raise max_cycles or add damping.")
        return f"All {n_steps} steps reached a periodic steady state."
    if not_steady:
        return (f"Fixed schedule of {plan.cycles} cycles: {not_steady} of {n_steps} steps were not "
                f"periodic over their last {plan.measure_cycles} cycles (steady False).")
    return f"Fixed schedule of {plan.cycles} cycles: every step was periodic when measured."
