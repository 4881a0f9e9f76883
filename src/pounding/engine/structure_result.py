"""What a structure's run returns: :class:`StructureRun` (histories per level, exact extrema per level,
contacts per wall side, the energy ledger over every element)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Optional

import numpy as np
import pandas as pd

from .._errors import Status
from .layout import impulses
from .layout import (C_SLOT, P_MAX, P_MAX_T, P_MIN, P_MIN_T,
                     X_A_MAX, X_A_MAX_T, X_D_MAX, X_D_MAX_T, X_D_MIN, X_D_MIN_T)
from ._chatter import NamedChatters
from .run_quantities import part_extrema, peaks_of
from .run_parts import EXTREMA_FIELDS, EnergyLedger, Outcome, events_frame, impact_frame, wall_contacts

if TYPE_CHECKING:
    from ..excitation import Harmonic, Record
    from ..model.structure import Structure
    from .state import State





# a run's fields read off the core's extrema: each level's (per dof), each storey's drift (per tracked pair)
_LEVEL_EXTREMA = tuple(zip(EXTREMA_FIELDS, (X_D_MAX, X_D_MAX_T, X_D_MIN, X_D_MIN_T, X_A_MAX, X_A_MAX_T)))
_DRIFT_EXTREMA = (("drift_max", P_MAX), ("drift_max_time_s", P_MAX_T), ("drift_min", P_MIN),
                  ("drift_min_time_s", P_MIN_T))


@dataclass(frozen=True)
class StructureRun(NamedChatters, Outcome):
    """A structure's run.

    Attributes
    ----------
    t : ndarray, shape (k,)
        Sample times, s (the uniform samples, and one after each event).
    displacement, velocity, abs_acceleration : ndarray, shape (k, n_levels)
        Each level relative to the ground (m, m/s) and its absolute acceleration (m/s^2).
    isolator_force : ndarray, shape (k,)
        The isolator's force on the base, N (NaN: a fixed base).
    contact_force : ndarray, shape (k, 2 n_walls)
        Each wall side's force, N (>= 0): wall ``w``'s left side in column ``2 w``, its right in ``2 w + 1``.
    displacement_max, displacement_min, abs_acceleration_max : ndarray, shape (n_levels,)
        Exact extrema of each level over the run (m, m/s^2: not from the samples); their times in
        ``*_time_s``.
    contacts : pandas.DataFrame
        One row per contact: ``wall``, ``level``, ``side``, ``t_start_s``, ``t_end_s``, the pair's velocities
        in and out ``v_in_m_s``, ``v_out_m_s``, ``impulse_n_s``, ``peak_force_n``, the largest compression
        ``max_compression_m``, the energy the contact took from the motion ``bumper_dissipation_j``
        (dissipated, or kept in a kinematic bumper's set).
    energy : EnergyLedger or None
        The energy ledger (None for one of two adjacent structures: the pair's is ``AdjacentRun.energy``).
    final_state : State or None
        Pass as ``state`` to continue (None for one of two adjacent structures: ``AdjacentRun``'s).
    status : Status
        How the run ended (``message`` says it in words).
    structure : Structure
        The structure run.
    excitation : Harmonic or Record
        The base motion.
    sample_rate_hz : float
        The uniform samples' rate, Hz (0: events only).
    contact_table, event_table : ndarray
        The core's rows behind ``contacts`` and ``events`` (no events for one of two adjacent structures:
        the pair's are ``AdjacentRun.events``).  A fixed base's level 0 is the ground: displacement 0, its
        absolute acceleration the ground's (its peak exact too).
    displacement_max_time_s, displacement_min_time_s, abs_acceleration_max_time_s : ndarray
        When each level's extrema were reached, s, shape (n_levels,).
    drift_max, drift_min : ndarray, shape (n_levels - 1,)
        Each storey's exact extrema of drift (its floor's displacement less the level below's), m; their
        times in ``drift_max_time_s``, ``drift_min_time_s``.
    drift_max_time_s, drift_min_time_s : ndarray, shape (n_levels - 1,)
        When they were reached, s.
    stand_displacement : ndarray, shape (k, n_stands)
        The walls' stands' displacements relative to the ground, m (each wall with a stand: its left side's,
        then its right's; ``stands`` names them).
    stand_displacement_max, stand_displacement_min : ndarray, shape (n_stands,)
        Their exact extrema, m.
    clearance_m : ndarray, shape (2 n_walls,)
        Each wall side's smallest clearance over the run (its gap less the largest approach, exact;
        negative: it touched), m; empty for one of two adjacent structures (``AdjacentRun.clearance_m``).
    chatters : pandas.DataFrame
        Rigid stops' (:class:`~pounding.RigidStop`) chatter sequences: ``contact`` (``wall 0 left``),
        ``t_first_s``, ``t_end_s`` (its accumulation, or last impact), ``impacts`` followed one by one,
        ``accumulated``; see :attr:`pounding.Run.chatters` (empty for one of two adjacent structures: the
        pair's ``AdjacentRun.chatters``); built on first use.
    chatter_table : ndarray, shape (n_sequences, 5)
        The core's rows behind ``chatters``.
    contact_names : tuple of str
        Each contact slot's name, as ``chatters`` gives it (``wall 0 left``).

    Examples
    --------
    A two-storey building whose top floor hits a stop 5 cm away:

    >>> import pounding
    >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
    ...                         damping_n_s_m=2.0e3)
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
    energy: Optional[EnergyLedger] = field(repr=False)
    final_state: Optional["State"] = field(repr=False)
    status: Status = Status.SUCCESS
    drift_max: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    drift_max_time_s: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    drift_min: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    drift_min_time_s: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    stand_displacement: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)
    stand_displacement_max: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    stand_displacement_min: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    clearance_m: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    chatter_table: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)), repr=False)
    contact_names: tuple = field(default=(), repr=False)

    @classmethod
    def _part(cls, structure: "Structure", b: int, asm: Any, asm_structures: tuple, excitation: Any,
              rate: float, out: Any, status: Status, t0: float, **whole: Any) -> "StructureRun":
        """Structure ``b``'s columns of a joint run (``out``: the core's ``RunOutput``; ``asm``: the
        assembly, engine.assembly; ``whole``: the fields of the run as a whole, where ``b`` is all of it)."""
        n, nh = asm.system.n, asm.system.n_elements
        samples = out.samples
        dofs = asm.dofs[b]
        t = samples[:, 0]
        k = t.size

        fixed = min(dofs, default=0) < 0  # (a fixed base: its level 0 the ground)

        def columns(first: int, ground: Any) -> np.ndarray:
            if not fixed:
                return _columns(samples, [first + d for d in dofs])
            return np.column_stack([samples[:, first + d] if d >= 0 else ground() for d in dofs])

        displacement = columns(1, lambda: np.zeros(k))
        velocity = columns(1 + n, lambda: np.zeros(k))
        abs_acceleration = columns(1 + 2 * n, lambda: excitation.acceleration(t) if k else np.zeros(k))
        e = asm.isolator[b]
        isolator_force = samples[:, 1 + 3 * n + e].copy() if e >= 0 else np.full(k, np.nan)
        mine = [c for c, (owner, _, _) in enumerate(asm.slots) if owner == b]
        contact_force = _columns(samples, [1 + 3 * n + nh + c for c in mine])
        ex, drifts, table = part_extrema(structure, b, asm, asm_structures, excitation, out, t0)
        per_dof = out.per_dof(n)
        on = [dof for _, _, dof in asm.stands[b]]
        stand_ex = per_dof[on]
        parts = {"event_table": np.zeros((0, 3)), "energy": None, "final_state": None, **whole}
        return cls(structure=structure, excitation=excitation, sample_rate_hz=rate, t=t,
                   displacement=displacement, velocity=velocity, abs_acceleration=abs_acceleration,
                   isolator_force=isolator_force, contact_force=contact_force,
                   **{name: ex[:, q].copy() for name, q in _LEVEL_EXTREMA}, contact_table=table, **parts,
                   status=status, **{name: drifts[:, q].copy() for name, q in _DRIFT_EXTREMA},
                   stand_displacement=_columns(samples, [1 + d for d in on]),
                   stand_displacement_max=stand_ex[:, X_D_MAX].copy(),
                   stand_displacement_min=stand_ex[:, X_D_MIN].copy())

    # ------------------------------------------------------------------ derived
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
    def peak_drift(self) -> np.ndarray:
        """Each storey's largest absolute drift over the run, m, shape (n_levels - 1,): exact."""
        return np.maximum(np.abs(self.drift_max), np.abs(self.drift_min))

    @property
    def contacts(self) -> pd.DataFrame:
        return wall_contacts(self.contact_table, [w.level for w in self.structure.walls])

    @property
    def impacts(self) -> pd.DataFrame:
        """The paper's per-impact quantities (Sect. 3.5), one row per contact at a wall: ``wall``,
        ``level``, ``side``, ``t_start_s``, then ``restitution``, ``contact_time_s``, ``impulse_n_s``,
        ``mean_force_n``, ``peak_force_n``, ``dissipated_energy_j`` (the kinetic energy the impact took
        from the pair's relative motion, ``mu (v_in^2 - v_out^2) / 2`` with ``mu`` the level's mass, or
        with a wall on a stand the pair's effective mass ``m m_s / (m + m_s)``) and
        ``bumper_dissipation_j`` (what the wall's law itself dissipated).  A one-level structure's is its
        oscillator's ``Run.impacts``, column for column and row for row."""
        walls, masses = self.structure.walls, self.structure.masses_kg
        mass = []
        for s in self.contact_table[:, C_SLOT].astype(int):
            wall = walls[s // 2]
            m = float(masses[wall.level])
            mass.append(m if wall.stand is None else m * wall.stand.mass_kg / (m + wall.stand.mass_kg))
        return impact_frame(self.contacts, ("wall", "level", "side"), self.contact_table, mass)

    @property
    def excursion_m(self) -> np.ndarray:
        """Each level's ``D_max - D_min`` over the run, m, shape (levels,)."""
        return self.displacement_max - self.displacement_min

    @property
    def stands(self) -> pd.DataFrame:
        """One row per stand (walls with a :class:`~pounding.Stand`, each side's): wall, level, side, exact
        extrema of its displacement (m)."""
        rows = [(w, wall.level, side) for w, wall in enumerate(self.structure.walls) if wall.stand is not None
                for side in ("left", "right")]
        return pd.DataFrame({"wall": [r[0] for r in rows], "level": [r[1] for r in rows],
                             "side": [r[2] for r in rows], "displacement_max_m": self.stand_displacement_max,
                             "displacement_min_m": self.stand_displacement_min})

    @property
    def events(self) -> pd.DataFrame:
        """Every event: ``t_s``, what happened (``kind``) and the element's ``index``: a contact slot for a
        contact's start or end (wall ``w``'s left side ``2 w``, right ``2 w + 1``), a spring for a yield
        (numbered through the isolator's springs, then each multi-linear storey's), an element for a reversal
        or a branch change (0 the isolator, then the multi-linear storeys)."""
        return events_frame(self.event_table)

    def peaks(self) -> pd.DataFrame:
        """One row per level: exact peak displacements (m) and absolute acceleration (m/s^2), with the
        storey below's exact peak drift (m) and drift ratio."""
        n = self.structure.n_levels
        drift = np.concatenate([[np.nan], self.peak_drift])
        heights = np.array([np.nan] + [s.height_m for s in self.structure.storeys])
        return pd.DataFrame({
            "level": np.arange(n),
            "displacement_max_m": self.displacement_max,
            "displacement_min_m": self.displacement_min,
            "abs_acceleration_max_m_s2": self.abs_acceleration_max,
            "drift_peak_m": drift,
            "drift_ratio_peak": drift / heights,
        }).set_index("level")

    def summary(self) -> pd.Series:
        """The run in a few numbers, each name with its unit, as every run's (what ``pounding simulate``
        prints; a single mass's ``Run.summary()`` is its one-level structure's, this).

        Returns
        -------
        pandas.Series
            ``t_end_s``; the base's (level 0's) exact ``displacement_max_m`` and ``displacement_min_m`` (each
            level's: :meth:`peaks`) and ``displacement_end_m`` at the run's end (a yielding or sliding
            isolator's residual displacement, once the shaking is over); ``sticks`` and ``slips``, a friction
            isolator's (its slips from a stick; 0 with any other isolator); ``surface_slips`` and ``rings``, a
            triple friction pendulum's surfaces' slips and rings reached; the exact
            ``abs_acceleration_max_m_s2`` over every level (between a rigid stop's impacts, which are
            impulses) and ``alpha``, that over the table's peak (a sine's amplitude, a record's PGA; NaN
            without shaking); ``contacts`` at every wall, ``contacts_left``
            (at their left sides), and with more than one level ``contacts_level_<k>`` at each level with a
            wall; ``rigid_impacts``; over the finished contacts ``restitution_mean``,
            ``contact_time_mean_s`` (those that last: holds and deformable contacts) and ``peak_force_max_n``
            (inf with rigid impacts; NaN without contacts), from :attr:`impacts`; ``input_work_j`` and
            ``energy_residual_j`` (NaN for one of two adjacent structures: the pair's are
            ``AdjacentRun.summary()``'s); ``status`` (its name).

        Examples
        --------
        >>> import pounding
        >>> iso = pounding.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[],
        ...                         damping_n_s_m=2.0e3)
        >>> stop = pounding.Wall(2, 0.05, 0.05, pounding.KelvinVoigt(1.0e8, 1.0e4))
        >>> storeys = [pounding.Storey(1.0e3, 2.0e6)] * 2
        >>> b = pounding.Structure(2.0e3, iso, storeys, [stop])
        >>> s = pounding.simulate(b, pounding.Harmonic(0.3, 1.5), 5.0).summary()
        >>> int(s["contacts"]) == int(s["contacts_level_2"]) > 0, s["status"]
        (True, 'SUCCESS')
        """
        from ..metrics.impacts import impact_summary

        nan = float("nan")
        table = self.contact_table
        rigid = int(impulses(table).sum())
        peak = abs(self.excitation.peak_m_s2)
        acc = float(np.max(self.abs_acceleration_max))
        kinds = np.asarray(self.events["kind"], dtype=object)
        t_end = (self.final_state.time_s if self.final_state is not None
                 else float(self.t[-1]) if self.t.size else nan)
        return pd.Series({
            "t_end_s": t_end,
            "displacement_max_m": float(self.displacement_max[0]),
            "displacement_min_m": float(self.displacement_min[0]),
            "displacement_end_m": float(self.displacement[-1, 0]) if self.t.size else nan,
            "sticks": int((kinds == "stick").sum()), "slips": int((kinds == "slip").sum()),
            "surface_slips": int((kinds == "surface_slip").sum()), "rings": int((kinds == "ring").sum()),
            "abs_acceleration_max_m_s2": acc, "alpha": acc / peak if peak else nan,
            **self.contact_counts(per_level=bool(self.structure.storeys)),
            "rigid_impacts": rigid, **impact_summary(self.impacts, rigid),
            "input_work_j": self.energy.input_work if self.energy is not None else nan,
            "energy_residual_j": self.energy.residual if self.energy is not None else nan,
            "status": self.status.name,
        }, name="summary", dtype=object)

    def contact_counts(self, per_level: bool = True) -> dict[str, int]:
        """The contacts at its walls: ``contacts``, ``contacts_left`` (at their left sides) and, with
        ``per_level``, ``contacts_level_<k>`` at each level with a wall."""
        table = self.contact_table
        out = {"contacts": len(table), "contacts_left": int((table[:, C_SLOT] % 2 == 0.0).sum())}
        if per_level:
            at = self.contacts["level"].value_counts()
            out.update({f"contacts_level_{lv}": int(at.get(lv, 0))
                        for lv in sorted({w.level for w in self.structure.walls})})
        return out

    def quantities(self) -> dict[str, float]:
        """The run in a few peaks (a study's point, a pounding spectrum's run, a design's stripe): the base's
        and the top floor's largest displacements, the largest accelerations (g), drift ratio, contacts,
        force and approach speed; see :func:`peaks_of`."""
        return peaks_of(self, self.excitation.g)

    # ------------------------------------------------------------------ tables
    def to_xarray(self) -> Any:
        """The histories as a Dataset along ``sample`` (its coordinate ``time_s``), ``level``, ``storey`` (the
        drifts: storey ``i`` between levels ``i`` and ``i + 1``) and ``contact`` (the wall sides, labelled
        ``wall 0 left``, with their ``wall`` and ``side``), each variable's unit in its ``units``; the exact
        extrema along ``level`` and ``storey``; ``status`` and ``message`` as attributes.  Each variable's
        name ends with its unit, as a single mass's (``displacement_m``, ``abs_acceleration_m_s2``,
        ``contact_force_n``, ``drift_max_m``, ...)."""
        import xarray as xr

        n = self.structure.n_levels
        walls = range(self.contact_force.shape[1] // 2)
        ds = xr.Dataset(
            {"displacement_m": (("sample", "level"), self.displacement, {"units": "m"}),
             "velocity_m_s": (("sample", "level"), self.velocity, {"units": "m/s"}),
             "abs_acceleration_m_s2": (("sample", "level"), self.abs_acceleration, {"units": "m/s^2"}),
             "drift_m": (("sample", "storey"), self.drift, {"units": "m"}),
             "isolator_force_n": ("sample", self.isolator_force, {"units": "N"}),
             "contact_force_n": (("sample", "contact"), self.contact_force, {"units": "N"}),
             "displacement_max_m": ("level", self.displacement_max, {"units": "m"}),
             "displacement_min_m": ("level", self.displacement_min, {"units": "m"}),
             "abs_acceleration_max_m_s2": ("level", self.abs_acceleration_max, {"units": "m/s^2"}),
             "drift_max_m": ("storey", self.drift_max, {"units": "m"}),
             "drift_min_m": ("storey", self.drift_min, {"units": "m"})},
            coords={"time_s": ("sample", self.t, {"units": "s"}), "level": np.arange(n),
                    "storey": np.arange(n - 1),
                    "contact": np.array([f"wall {w} {side}" for w in walls for side in ("left", "right")],
                                        dtype=str),
                    "wall": ("contact", np.repeat(np.arange(len(walls)), 2)),
                    "side": ("contact", np.array(["left", "right"] * len(walls), dtype=str))},
            attrs={"status": self.status.name, "message": self.message})
        if self.stand_displacement.shape[1]:
            ds["stand_displacement_m"] = (("sample", "stand"), self.stand_displacement, {"units": "m"})
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
        for q in range(self.stand_displacement.shape[1]):
            cols[f"stand_displacement_m[{q}]"] = self.stand_displacement[:, q]
        return pd.DataFrame(cols)

    def plot(self, **kwargs: Any) -> Any:
        """Each level's displacement and absolute acceleration against time, and the peak envelopes over
        the height; see :func:`pounding.plots.plot_structure_run`.

        Returns its Figure.
        """
        from ..plots import plot_structure_run, figure_of

        return figure_of(plot_structure_run(self, **kwargs), kwargs.get("axes"))

    def plot_isolator_loop(self, ax: Any = None, **kwargs: Any) -> Any:
        """The isolator's force against the base's displacement; see
        :func:`pounding.plots.plot_isolator_loop`.  Returns its Figure."""
        from ..plots import figure_of, plot_isolator_loop

        return figure_of(plot_isolator_loop(self, ax=ax, **kwargs), ax)


def _columns(samples: np.ndarray, cols: list) -> np.ndarray:
    """The samples' columns ``cols``, shape (k, len(cols)): a view where they are consecutive (every
    system's run is read this way, a single mass's too: no copy of its histories)."""
    if cols and cols == list(range(cols[0], cols[0] + len(cols))):
        return samples[:, cols[0]:cols[0] + len(cols)]
    return samples[:, cols]
