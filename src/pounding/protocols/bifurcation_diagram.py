"""Brute-force bifurcation diagrams: the shaking table's stepped sine, each frequency held until
the transient has passed, then the state at table phase 0 (the stroboscopic section) recorded
cycle after cycle.

A period-1 response leaves one point per frequency, a period-k response k points, a response that
never repeats a cloud; going up and then down shows where two responses coexist (the jumps fall
at different frequencies).  It is the experiment's view of what :func:`pounding.continuation`
computes as branches of periodic orbits, and is drawn over them.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, Optional, Sequence

import numpy as np
import pandas as pd

from .._checks import integer, one_of
from .._control import DEFAULT_MAX_STEPS, new_control, run_interruptibly
from .._errors import InputError, Interrupted, Problem, Status, renamed_keyword
from .._runner.progress import Progress, progress_reporter
from ..metrics.impacts import S_COUNT
from .sweep import MAX_CYCLES_PER_STEP, make_plan, run_plan
from .sweep_result import SweepResult
from .sweep_window import NAMES

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

DiagramDirection = Literal["up", "down", "both"]
MAX_RECORD_CYCLES = 10_000
# what the diagram keeps per step besides its strobes (SweepResult.to_dataframe's columns)
STEP_QUANTITIES = ("alpha", "excursion_m", "contacts_per_cycle")


@renamed_keyword("oscillator", "system")
def bifurcation_diagram(system: Any, a_g: float, freqs_hz: Any, *,
                        direction: DiagramDirection = "both", transient_cycles: int = 100,
                        record_cycles: int = 20, max_period: int = 8, steady_rtol: float = 1e-6,
                        rtol: float = 1e-10, max_steps: int = DEFAULT_MAX_STEPS,
                        progress: Progress = False) -> "BifurcationDiagram":
    """The stroboscopic samples of a stepped-sine sweep, frequency by frequency: a bifurcation
    diagram as the shaking table would draw it.

    Each frequency is held for ``transient_cycles + record_cycles`` whole cycles, the state
    carried over from the frequency before (as on the table); the state at the end of each of
    the last ``record_cycles`` (table phase 0) is kept, with the period found in them.

    Parameters
    ----------
    system : Oscillator, Structure or Adjacent
        The system: one mass, or a structure of several (or two adjacent ones), whose diagram
        then holds every level's samples (a ``level`` dimension) and each level's alpha and
        excursion; its period is that of every level's samples (x, v).
    a_g : float
        Peak table acceleration, g.
    freqs_hz : array_like, shape (n,)
        The frequencies, Hz (any order, no repeats; stepped in increasing order up, decreasing
        down).
    direction : {"both", "up", "down"}
        ``"both"`` (default): up, then down from where the up sweep ended.
    transient_cycles : int
        Cycles held at each frequency before recording (default 100).
    record_cycles : int
        Cycles recorded at each frequency (default 20), more than ``max_period``.
    max_period : int
        Largest period multiple looked for (default 8): the smallest ``k`` with which every
        recorded sample repeats ``k`` cycles later, to within ``steady_rtol``; a response that
        does not (chaotic, quasi-periodic, or still settling) has period 0.
    steady_rtol : float
        Tolerance of the period's test, relative to the response amplitude (the velocity's
        scaled by the forcing's angular frequency).
    rtol : float
        Tolerance of the numerical integration of nonlinear contact laws.
    max_steps : int
        Work budget of the whole diagram, in integration steps (it stops with
        ``Status.BUDGET``, keeping what it finished).
    progress : bool or callable
        True: a progress bar; a callable is called with the number of steps just finished.

    Returns
    -------
    BifurcationDiagram
        The strobes (displacement and velocity), period, alpha, excursion and contacts per
        cycle at each frequency and direction; ``.plot()``, ``.to_xarray()``.

    Raises
    ------
    InputError
        For a bad argument (names it, the value and the fix).
    Interrupted
        On Ctrl-C; its ``partial`` is the diagram of the steps finished.

    Examples
    --------
    The damped paper system at a_G = 0.05 g: going up it stays in contact with the bumpers (alpha
    above 9) to 2.0 Hz, then falls off; going down it is free from 1.7 Hz, until it meets the
    contact response again at 1.6 Hz.  Where the two differ, two responses coexist.

    >>> import numpy as np, pounding
    >>> osc = pounding.presets.paper_damped()
    >>> freqs = np.arange(1.6, 2.15, 0.1)
    >>> diagram = pounding.bifurcation_diagram(osc, 0.05, freqs,
    ...     transient_cycles=30, record_cycles=10)
    >>> print(diagram.message)
    Both directions ran all 6 frequencies; of its 12 steps (2 directions x 6
    frequencies): 1 not periodic, 11 of period 1.
    >>> df = diagram.to_dataframe(cycles=False)
    >>> alpha = df.pivot(index="freq_hz", columns="direction", values="alpha")
    >>> print(alpha.round(2).to_string())
    direction  down     up
    freq_hz
    1.6        9.39   9.39
    1.7        1.81  10.42
    1.8        1.40  11.39
    1.9        1.13  12.27
    2.0        0.93  12.79
    2.1        0.79   0.79

    (30 cycles do not settle the response just after the up sweep's jump: period 0 at 2.1 Hz.)
    """
    one_of("direction", direction, ("both", "up", "down"))
    max_period = integer("max_period", max_period, 1, 1000)
    record = integer("record_cycles", record_cycles, 1, MAX_RECORD_CYCLES)
    if record <= max_period:
        raise InputError(Problem.TOO_SMALL, "record_cycles", record, minimum=max_period + 1,
                         hint=" (more than max_period: a period is seen repeating in the recorded cycles)")
    transient = integer("transient_cycles", transient_cycles, 0, MAX_CYCLES_PER_STEP - record)
    dirs = ("up", "down") if direction == "both" else (direction,)
    options = dict(steady="fixed", cycles=transient + record, measure_cycles=record, max_period=max_period,
                   steady_rtol=steady_rtol, rtol=rtol, max_steps=max_steps)
    plans = [make_plan(system, a_g, freqs_hz, d, **options) for d in dirs]  # (all checked first)
    n_total = sum(p.freqs_hz.size for p in plans)
    ctl = new_control(plans[0].max_steps)
    sweeps: list[SweepResult] = []
    state: Optional[Any] = None
    with progress_reporter(progress, n_total, f"bifurcation diagram, a_G = {plans[0].a_g:g}") as advance:
        for plan in plans:
            if state is not None:  # (down from where up ended)
                plan = make_plan(system, a_g, freqs_hz, plan.direction, state, **options)
            try:
                sw = run_interruptibly(lambda: run_plan(plan, advance, ctl), [ctl])
            except Interrupted as stop:
                sweeps.append(stop.partial)
                done = sum(s.steps_done for s in sweeps)
                raise Interrupted(_diagram(system, sweeps, dirs, transient, record, max_period,
                                           steady_rtol, True), done,
                                  n_total, "steps") from None
            sweeps.append(sw)
            state = sw.final_state
            if sw.status != Status.SUCCESS:
                break
    return _diagram(system, sweeps, dirs, transient, record, max_period, steady_rtol, False)


def periods(strobes: np.ndarray, amplitude_m: np.ndarray, omega_rad_s: np.ndarray, max_period: int,
            rtol: float) -> np.ndarray:
    """The smallest ``k <= max_period`` with which every stroboscopic sample repeats ``k`` cycles
    later, to within ``rtol`` of the amplitude (velocities over ``omega``); 0 where none does.

    ``strobes`` shape (steps, cycles, 2): displacement (m), velocity (m/s), or (steps, cycles, 2, m)
    for m masses at once; ``amplitude_m`` and ``omega_rad_s`` shape (steps,).  Returns int, shape
    (steps,).
    """
    steps = strobes.shape[0]
    tol = rtol * np.maximum(amplitude_m, 1e-12)
    om = np.reshape(omega_rad_s, (-1, 1) + (1,) * (strobes.ndim - 3))
    scaled = np.stack([strobes[:, :, 0], strobes[:, :, 1] / om], axis=2)
    out = np.zeros(steps, dtype=np.int64)
    for k in range(max_period, 0, -1):  # (the smallest that holds wins)
        diff = np.abs(scaled[:, k:] - scaled[:, :-k]).reshape(steps, -1).max(axis=1)
        out[diff <= tol] = k
    return out


@dataclass(frozen=True, eq=False)
class BifurcationDiagram:
    """What :func:`bifurcation_diagram` found: per direction and frequency, the recorded
    stroboscopic samples and the response's period, alpha, excursion and contacts per cycle.

    Attributes
    ----------
    oscillator : Oscillator, Structure or Adjacent
        The system.
    a_g : float
        Peak table acceleration, g.
    data : xarray.Dataset
        Dimensions ``direction`` ("up", "down"), ``freq_hz`` (increasing) and ``cycle``
        (the recorded cycles): ``strobe_displacement_m`` and ``strobe_velocity_m_s``
        (direction, freq_hz, cycle); ``period`` (0: not periodic, -1: not run), ``alpha``,
        ``excursion_m`` and ``contacts_per_cycle`` (direction, freq_hz).  NaN where a step did
        not run.  A structure's adds the dimension ``level`` to the strobes, ``alpha`` and
        ``excursion_m`` (its coordinates ``level_number`` and ``level_structure``), and its
        ``contacts_per_cycle`` counts every wall side and link.
    sweeps : tuple of SweepResult
        The sweeps it was drawn from, in the order run.
    status : Status
        ``SUCCESS``, or why a sweep stopped early (``INTERRUPTED`` on Ctrl-C).
    message : str
        What happened, for people.

    Examples
    --------
    The samples of each direction at one frequency, and the period found there:

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> diagram = pounding.bifurcation_diagram(osc, 0.05, [1.8, 2.5],
    ...     transient_cycles=40, record_cycles=10)
    >>> ds = diagram.to_xarray()
    >>> ds["period"].sel(freq_hz=2.5).values.tolist()  # up, down
    [1, 1]
    >>> d = ds["strobe_displacement_m"].sel(direction="up", freq_hz=2.5)
    >>> round(float(d[0]) * 1e3, 3)  # mm, the first recorded cycle
    0.511
    """

    oscillator: Any
    a_g: float
    data: "xr.Dataset"
    sweeps: tuple
    status: Status
    message: str

    @property
    def success(self) -> bool:
        """Every direction ran every frequency."""
        return self.status == Status.SUCCESS

    def to_xarray(self) -> "xr.Dataset":
        """The labelled data (``data``)."""
        return self.data

    def to_dataframe(self, cycles: bool = True) -> pd.DataFrame:
        """A long table: one row per direction, frequency and recorded cycle (``cycles`` True:
        ``displacement_m`` and ``velocity_m_s`` at the section), or per direction and frequency
        (``cycles`` False), with ``period``, ``alpha``, ``excursion_m``, ``contacts_per_cycle`` (and
        ``largest_exponent``, 1/s, once :func:`pounding.largest_exponents` added it); steps not run
        left out."""
        ds = self.data
        extra = ["largest_exponent"] if "largest_exponent" in ds else []  # (pounding.largest_exponents)
        steps = ds[["period", *STEP_QUANTITIES, *extra]].to_dataframe().reset_index()
        steps = steps[steps["period"] >= 0].reset_index(drop=True)
        if not cycles:
            return steps
        strobes = ds[["strobe_displacement_m", "strobe_velocity_m_s"]].to_dataframe().reset_index()
        strobes = strobes.rename(columns={"strobe_displacement_m": "displacement_m",
                                          "strobe_velocity_m_s": "velocity_m_s"})
        keys = ["direction", "freq_hz"] + (["level"] if "level" in ds.dims else [])
        steps = steps.drop(columns=["level_number", "level_structure"], errors="ignore")  # (in strobes too)
        return strobes.dropna(subset=["displacement_m"]).merge(steps, on=keys)

    def to_netcdf(self, path: str | Path) -> Path:
        """Write the dataset to a netCDF file (atomically); returns its path."""
        from .._io import atomic_write, output_file

        return atomic_write(output_file("path", path), self.data.to_netcdf)

    def plot(self, ax: Any = None, *, branches: Any = None, y: str = "displacement", level: int = -1,
             **kwargs: Any) -> Any:
        """The diagram: the section's ``y`` ("displacement", mm, or "velocity", m/s) against the
        frequency, up and down in two colours; ``branches`` (from :func:`pounding.continuation`)
        drawn under it at the same section, stable solid, unstable dashed; a structure's ``level``
        (its place along ``level``, the top by default); returns its Figure."""
        from ..plots.diagram import plot_bifurcation_diagram
        from ..plots import figure_of

        drawn = plot_bifurcation_diagram(self, ax=ax, branches=branches, y=y, level=level, **kwargs)
        return figure_of(drawn, ax)

    def __repr__(self) -> str:
        n = self.data.sizes
        return (f"BifurcationDiagram(a_G {self.a_g:g}, {n['freq_hz']} frequencies x "
                f"{', '.join(self.data['direction'].values.tolist())}, {n['cycle']} cycles recorded; "
                f"{self.status.name}: {self.message})")


def _diagram(osc: Any, sweeps: list, dirs: Sequence[str], transient: int, record: int,
             max_period: int, rtol: float, interrupted: bool) -> BifurcationDiagram:
    import xarray as xr

    freqs = np.sort(sweeps[0].freqs_hz)
    shape = (len(dirs), freqs.size)
    levels = sweeps[0].levels
    n_levels = len(levels)
    strobes = np.full(shape + (record, 2, n_levels), np.nan)
    period = np.full(shape, -1, dtype=np.int64)
    steps = {q: np.full(shape + ((n_levels,) if q != "contacts_per_cycle" else ()), np.nan)
             for q in STEP_QUANTITIES}
    for sw in sweeps:
        i = dirs.index(sw.direction)
        done = sw.steps_done
        cols = np.searchsorted(freqs, sw.freqs_hz[:done])
        strobes[i, cols] = sw.window_strobes[:done, :record]
        m = sw.level_metrics[:done]
        excursion = m[:, :, 0] - m[:, :, 1]
        with np.errstate(invalid="ignore", divide="ignore"):  # (every wall side and link)
            per_cycle = np.sum(sw.contact_sums[:done, :, S_COUNT], axis=1) / sw.window_cycles[:done]
        values = {"alpha": sw.alpha[:done], "excursion_m": excursion, "contacts_per_cycle": per_cycle}
        amplitude = 0.5 * np.nanmax(excursion, axis=1, initial=0.0)
        period[i, cols] = periods(strobes[i, cols], amplitude, 2.0 * np.pi * sw.freqs_hz[:done], max_period,
                                  rtol)
        for q in STEP_QUANTITIES:
            steps[q][i, cols] = values[q]
    dims = ("direction", "freq_hz")
    coords: dict[str, Any] = {"direction": list(dirs), "freq_hz": freqs, "cycle": np.arange(record),
                              "level": np.arange(n_levels),
                              "level_number": ("level", np.array([q for _, q in levels], dtype=int)),
                              "level_structure": ("level", np.array([NAMES[b] for b, _ in levels],
                                                                    dtype=str))}
    ds = xr.Dataset(
        {"strobe_displacement_m": (dims + ("cycle", "level"), strobes[:, :, :, 0]),
         "strobe_velocity_m_s": (dims + ("cycle", "level"), strobes[:, :, :, 1]),
         "period": (dims, period),
         **{q: (dims + (("level",) if q != "contacts_per_cycle" else ()), v) for q, v in steps.items()}},
        coords=coords)
    if n_levels == 1:  # (a single mass: no level axis)
        ds = ds.isel(level=0, drop=True)  # (its coordinates along level go with it)
    ds["freq_hz"].attrs["units"] = "Hz"
    a_g = sweeps[0].a_g
    ds.attrs.update({"a_g": a_g, "transient_cycles": transient, "record_cycles": record,
                     "max_period": max_period, "steady_rtol": rtol, "system": osc.to_toml_text()})
    status = Status.INTERRUPTED if interrupted else next(
        (s.status for s in sweeps if s.status != Status.SUCCESS), Status.SUCCESS)
    return BifurcationDiagram(osc, a_g, ds, tuple(sweeps), status, _message(sweeps, dirs, period, status))


def _message(sweeps: list, dirs: Sequence[str], period: np.ndarray, status: Status) -> str:
    n = sweeps[0].freqs_hz.size
    ran = period >= 0
    if status == Status.INTERRUPTED:
        return f"Interrupted after {int(ran.sum())} of {n * len(dirs)} steps; the others are NaN."
    if status != Status.SUCCESS:
        return next(s.message for s in sweeps if s.status != Status.SUCCESS)
    which = "Both directions" if len(dirs) == 2 else f"The {dirs[0]} sweep"
    kinds = sorted(set(period[ran].tolist()))
    if kinds == [1]:
        how = "every response is periodic (period 1)"
    else:
        counts = [f"{int((period == k).sum())} {'not periodic' if k == 0 else f'of period {k}'}"
                  for k in kinds]
        how = (f"of its {int(ran.sum())} steps ({len(dirs)} direction{'s' if len(dirs) > 1 else ''} x {n} "
               "frequencies): " + ", ".join(counts))
    return f"{which} ran all {n} frequencies; {how}."
