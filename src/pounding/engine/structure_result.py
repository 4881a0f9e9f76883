"""What a structure's run returns: :class:`StructureRun` (histories per level, exact extrema per level,
contacts per wall side, the energy ledger over every element) and :class:`StructureEnergy`."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._errors import Interrupted, Status
from ._layout import (EVENT_NAMES, L_BUMPER, L_BUMPER_LOSS, L_HYSTERETIC, L_INPUT, L_ISOLATOR, L_KINETIC,
                      L_VISCOUS)

if TYPE_CHECKING:
    from ..excitation import Harmonic, Record
    from ..model.structure import Structure
    from .structure import StructureState

CONTACT_COLUMNS = ("wall", "level", "side", "t_start", "t_end", "v_in", "v_out", "impulse", "peak_force",
                   "max_compression", "work")


@dataclass(frozen=True)
class StructureEnergy:
    """The energy ledger of a structure's run, J: the input's work equals what the dashpots (storeys' and
    isolator's), the isolator's hysteresis and the walls' laws dissipated plus the change of the kinetic
    and elastic energies (``residual``: the difference, rounding).

    Attributes
    ----------
    input_work : float
        The work of the ground's motion on the structure.
    viscous : float
        Dissipated by the storeys' and the isolator's dashpots.
    hysteretic : float
        Dissipated by the isolator's hysteresis.
    contact_dissipation : float
        Dissipated by the walls' laws.
    kinetic : float
        Change of the kinetic energy.
    elastic : float
        Change of the isolator's and the storeys' elastic energy.
    contact_elastic : float
        Change of the walls' laws' elastic energy.

    Examples
    --------
    >>> import pounding
    >>> iso = pounding.Isolator(slopes=[1.0e5, 2.0e4], breakpoints=[0.01])
    >>> b = pounding.Structure(1.0e3, iso, [pounding.Storey(1.0e3, 1.0e6, 1.0e3)])
    >>> e = pounding.simulate(b, pounding.Harmonic(0.2, 1.5), 5.0).energy
    >>> abs(e.residual) < 1e-9 * e.input_work
    True
    """

    input_work: float
    viscous: float
    hysteretic: float
    contact_dissipation: float
    kinetic: float
    elastic: float            # the isolator's and the storeys' springs
    contact_elastic: float    # the walls' laws

    @classmethod
    def of(cls, ledger: np.ndarray) -> "StructureEnergy":
        return cls(*(float(ledger[k]) for k in (L_INPUT, L_VISCOUS, L_HYSTERETIC, L_BUMPER_LOSS, L_KINETIC,
                                                L_ISOLATOR, L_BUMPER)))

    @property
    def residual(self) -> float:
        """The input's work less every other term, J (rounding)."""
        return self.input_work - (self.viscous + self.hysteretic + self.contact_dissipation + self.kinetic
                                  + self.elastic + self.contact_elastic)


@dataclass(frozen=True)
class StructureRun:
    """A structure's run.

    Attributes
    ----------
    t : ndarray, shape (k,)
        Sample times, s (the uniform samples, and one after each event).
    displacement, velocity, abs_acceleration : ndarray, shape (k, n_levels)
        Each level relative to the ground (m, m/s) and its absolute acceleration (m/s^2).
    isolator_force : ndarray, shape (k,)
        The isolator's force on the base, N.
    contact_force : ndarray, shape (k, 2 n_walls)
        Each wall side's force, N (>= 0): wall ``w``'s left side in column ``2 w``, its right in ``2 w + 1``.
    displacement_max, displacement_min, abs_acceleration_max : ndarray, shape (n_levels,)
        Exact extrema of each level over the run (m, m/s^2: not from the samples); their times in
        ``*_time_s``.
    contacts : pandas.DataFrame
        One row per contact: wall, level, side, times (s), the pair's velocities in and out (m/s), impulse
        (N s), peak force (N), largest compression (m), the work of the contact force (J).
    energy : StructureEnergy
        The energy ledger.
    final_state : StructureState
        Pass as ``state`` to continue.
    status : Status
        How the run ended (``message`` says it in words).
    structure : Structure
        The structure run.
    excitation : Harmonic or Record
        The base motion.
    sample_rate_hz : float
        The uniform samples' rate, Hz (0: events only).
    contact_table, event_table : ndarray
        The core's rows behind ``contacts`` and ``events``.
    displacement_max_time_s, displacement_min_time_s, abs_acceleration_max_time_s : ndarray
        When each level's extrema were reached, s, shape (n_levels,).

    Examples
    --------
    A two-storey building whose top floor hits a stop 5 cm away:

    >>> import pounding
    >>> iso = pounding.Isolator(slopes=[2.0e5], breakpoints=[], damping=2.0e3)
    >>> stop = pounding.Wall(2, 0.05, 0.05, pounding.KelvinVoigt(1.0e8, 1.0e4))
    >>> b = pounding.Structure(2.0e3, iso, [pounding.Storey(1.0e3, 2.0e6)] * 2,
    ...                        [stop])
    >>> run = pounding.simulate(b, pounding.Harmonic(0.3, 1.5), 5.0)
    >>> run.displacement.shape[1], run.drift.shape[1], len(run.contacts) > 0
    (3, 2, True)
    >>> peaks = run.peaks()  # a row per level
    >>> list(peaks.columns)[:3]
    ['displacement_max_m', 'displacement_min_m', 'abs_acceleration_max_m_s2']
    """

    structure: "Structure"
    excitation: "Harmonic | Record"
    sample_rate_hz: float
    t: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    abs_acceleration: np.ndarray
    isolator_force: np.ndarray
    contact_force: np.ndarray
    displacement_max: np.ndarray
    displacement_max_time_s: np.ndarray
    displacement_min: np.ndarray
    displacement_min_time_s: np.ndarray
    abs_acceleration_max: np.ndarray
    abs_acceleration_max_time_s: np.ndarray
    contact_table: np.ndarray = field(repr=False)
    event_table: np.ndarray = field(repr=False)
    energy: StructureEnergy = field(repr=False)
    final_state: "StructureState" = field(repr=False)
    status: Status = Status.SUCCESS

    @classmethod
    def _of(cls, structure: "Structure", excitation: Any, rate: float, final_state: "StructureState",
            samples: np.ndarray, contacts: np.ndarray, events: np.ndarray, energy: StructureEnergy,
            extrema: np.ndarray, status: int, t0: float, duration: float) -> "StructureRun":
        n = structure.n_levels
        status = Status(status)
        if status == Status.SUCCESS and not (np.all(np.isfinite(extrema)) and np.isfinite(energy.residual)):
            status = Status.NONFINITE
        ex = extrema.reshape(n, 7)
        run = cls(structure, excitation, rate, samples[:, 0], samples[:, 1:1 + n],
                  samples[:, 1 + n:1 + 2 * n], samples[:, 1 + 2 * n:1 + 3 * n], samples[:, 1 + 3 * n],
                  samples[:, 2 + 3 * n:],
                  ex[:, 0].copy(), ex[:, 1].copy(), ex[:, 2].copy(), ex[:, 3].copy(), ex[:, 4].copy(),
                  ex[:, 5].copy(), contacts, events, energy, final_state, status)
        if status == Status.INTERRUPTED:
            raise Interrupted(run, round(final_state.time_s - t0, 6), duration, "simulated seconds")
        return run

    # ------------------------------------------------------------------ derived
    @property
    def success(self) -> bool:
        return self.status == Status.SUCCESS

    @property
    def message(self) -> str:
        return self.status.message

    @property
    def drift(self) -> np.ndarray:
        """Each storey's drift (the floor's displacement less the one below), m, shape (k, n_levels - 1),
        at the samples."""
        return np.diff(self.displacement, axis=1)

    @property
    def drift_ratio(self) -> np.ndarray:
        """Each storey's drift over its height, shape (k, n_levels - 1), at the samples."""
        heights = np.array([s.height_m for s in self.structure.storeys])
        return self.drift / heights

    @property
    def peak_drift_sampled(self) -> np.ndarray:
        """Each storey's largest |drift| among the samples, m, shape (n_levels - 1,): as fine as the samples
        (not an exact extremum; raise ``sample_rate_hz`` to refine it)."""
        d = self.drift
        return np.abs(d).max(axis=0) if d.shape[0] else np.full(d.shape[1], np.nan)

    @property
    def contacts(self) -> pd.DataFrame:
        c = self.contact_table
        slot = c[:, 0].astype(int)
        walls = self.structure.walls
        return pd.DataFrame({
            "wall": slot // 2,
            "level": [walls[s // 2].level for s in slot],
            "side": np.where(slot % 2 == 0, "left", "right"),
            **{name: c[:, k] for k, name in enumerate(CONTACT_COLUMNS[3:], start=1)},
        })

    @property
    def events(self) -> pd.DataFrame:
        """Every event: time (s), what happened and the element's index (a contact slot, an isolator
        spring)."""
        e = self.event_table
        return pd.DataFrame({"t": e[:, 0], "event": [EVENT_NAMES[int(a)] for a in e[:, 1]],
                             "index": e[:, 2].astype(int)})

    def peaks(self) -> pd.DataFrame:
        """One row per level: exact peak displacements (m) and absolute acceleration (m/s^2), with the
        storey below's sampled peak drift and drift ratio."""
        n = self.structure.n_levels
        drift = np.concatenate([[np.nan], self.peak_drift_sampled])
        heights = np.array([np.nan] + [s.height_m for s in self.structure.storeys])
        return pd.DataFrame({
            "level": np.arange(n),
            "displacement_max_m": self.displacement_max,
            "displacement_min_m": self.displacement_min,
            "abs_acceleration_max_m_s2": self.abs_acceleration_max,
            "drift_peak_sampled_m": drift,
            "drift_ratio_peak_sampled": drift / heights,
        }).set_index("level")

    # ------------------------------------------------------------------ tables
    def to_xarray(self) -> Any:
        """The histories as a Dataset along ``sample`` and ``level`` (``contact``: the wall sides), units in
        each variable's ``units``; ``status`` and ``message`` as attributes."""
        import xarray as xr

        n = self.structure.n_levels
        nc = self.contact_force.shape[1]
        ds = xr.Dataset(
            {"t": ("sample", self.t, {"units": "s"}),
             "displacement": (("sample", "level"), self.displacement, {"units": "m"}),
             "velocity": (("sample", "level"), self.velocity, {"units": "m/s"}),
             "abs_acceleration": (("sample", "level"), self.abs_acceleration, {"units": "m/s^2"}),
             "isolator_force": ("sample", self.isolator_force, {"units": "N"}),
             "contact_force": (("sample", "contact"), self.contact_force, {"units": "N"}),
             "displacement_max": ("level", self.displacement_max, {"units": "m"}),
             "displacement_min": ("level", self.displacement_min, {"units": "m"}),
             "abs_acceleration_max": ("level", self.abs_acceleration_max, {"units": "m/s^2"})},
            coords={"level": np.arange(n), "contact": np.arange(nc)},
            attrs={"status": self.status.name, "message": self.message})
        return ds

    def to_dataframe(self) -> pd.DataFrame:
        """The histories, one row per sample, a column per quantity and level (``displacement_m[2]``...),
        SI units in the names."""
        cols: dict[str, np.ndarray] = {"t_s": self.t}
        for name, unit, data in (("displacement", "m", self.displacement), ("velocity", "m_s", self.velocity),
                                 ("abs_acceleration", "m_s2", self.abs_acceleration)):
            for i in range(data.shape[1]):
                cols[f"{name}_{unit}[{i}]"] = data[:, i]
        cols["isolator_force_n"] = self.isolator_force
        for c in range(self.contact_force.shape[1]):
            cols[f"contact_force_n[{c}]"] = self.contact_force[:, c]
        return pd.DataFrame(cols)

    def plot(self, **kwargs: Any) -> Any:
        """Each level's displacement and absolute acceleration against time, and the peak envelopes over
        the height; see :func:`pounding.plots.plot_structure_run`."""
        from ..plots import plot_structure_run

        return plot_structure_run(self, **kwargs)
