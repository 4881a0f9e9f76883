"""What a simulation of a single mass returns: :class:`Run`, the run of the one-level structure it is, read
as one mass's (its parts: :mod:`.run_parts`; its state: :mod:`.state`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from .._errors import Status
from .._tables import HistoryTable
from ._chatter import SIDES, chatter_frame
from .layout import E_ACTION, E_T, EVENT_NAMES
from .run_parts import EXTREMA_FIELDS, EnergyLedger, events_frame
from .state import State
from .structure_result import StructureRun

if TYPE_CHECKING:  # pragma: no cover
    from ..excitation import Excitation
    from ..model import Oscillator

HISTORY_COLUMNS = ("t", "displacement", "velocity", "abs_acceleration", "isolator_force",
                   "bumper_force_left", "bumper_force_right")
HISTORY_UNIT_OF = {"t_s": "s", "time_s": "s", "displacement_m": "m", "velocity_m_s": "m/s",
                   "abs_acceleration_m_s2": "m/s^2",
                   "isolator_force_n": "N", "bumper_force_left_n": "N", "bumper_force_right_n": "N"}
HISTORY_UNITS = HistoryTable.OLD  # (each attribute's column: its name with its unit)


@dataclass(frozen=True, eq=False)
class Run:
    """Result of :func:`pounding.simulate`.

    Attributes
    ----------
    t, displacement, velocity, abs_acceleration : ndarray, shape (n,)
        Sampled histories in s, m, m/s and m/s^2 (relative motion; absolute acceleration
        ``D'' + A``); samples on the uniform grid plus one at every event (after its jump).
    isolator_force, bumper_force_left, bumper_force_right : ndarray, shape (n,)
        ``R_d + C_d D'`` and the bumpers' push (>= 0), N.
    displacement_max, displacement_min, abs_acceleration_max : float
        Exact extrema over the run (located events, independent of the sampling), m, m/s^2.
    displacement_max_time_s, displacement_min_time_s, abs_acceleration_max_time_s : float
        When each extremum was reached, s.
    contact_table, event_table, chatter_table : ndarray
        The raw arrays behind ``contacts``, ``events`` and ``chatters`` (side coded 0 left, 1 right).
    contacts : DataFrame
        One row per contact, each column named with its unit, as a one-level structure's:
        ``wall`` and ``level`` (0: the bumpers are the wall at the mass's level), ``side``
        ("left"/"right"), ``t_start_s``, ``t_end_s``, ``v_in_m_s``, ``v_out_m_s`` (relative velocity
        at start and end), ``impulse_n_s``, ``peak_force_n``, ``max_compression_m``, ``bumper_dissipation_j``
        (energy the bumper took from the mass, dissipated by its dashpot and slips during contact
        or while it recovers; a kinematic multi-linear bumper keeps part of it stored in its
        set).  A contact still going on at the end has NaN ``t_end_s`` and ``v_out_m_s``.
        Resolution: a touch whose added compression and impulse are both below 1e-9 of the
        run's scales (its length scale, the largest of the total gap, the first breakpoint and
        the table's acceleration over ``w^2``; ``M`` times its velocity scale, that length
        times ``w``, the faster of the forcing and the isolator's first branch) is no impact
        and not listed, though the motion goes through it exactly; an incoming velocity below
        1e-9 of the velocity scale is recorded as 0 (the mass met the surface at rest, e.g.
        at zero gap: its restitution is NaN).  A rigid stop's impact is instantaneous
        (``t_end_s == t_start_s``, NaN ``peak_force_n``); see :class:`pounding.RigidStop`.
    chatters : DataFrame
        Rigid stops' (:class:`pounding.RigidStop`) chatter sequences, one row each: ``side``,
        ``t_first_s`` (its first impact), ``t_end_s`` (where it accumulated, or its last impact),
        ``impacts`` (followed one by one; an accumulated sequence has infinitely many more, summed
        in closed form) and ``accumulated`` (the stop was then held shut).  A sequence is three
        impacts or more on one stop, each within a sub-interval (an eighth of the fastest period)
        of the one before, or any that accumulated.  Empty without rigid stops.
    events : DataFrame
        Every event: ``t_s``, ``kind`` (yield, reversal, branch, contact_start, contact_end,
        bumper_branch, bouc_wen_zero), ``index`` (spring or side).
    energy : EnergyLedger
        Where the energy went over the run, J.
    final_state : State
        The state at the end (or where the run stopped): pass it as ``state=`` to continue.
    sample_rate_hz : float
        Rate of the uniform history samples, Hz (0: events only).
    status : Status
        ``Status.SUCCESS`` (0) or why the run stopped early (negative); see ``message``.
    message : str
        The status in words: why the run stopped early and what to do.
    oscillator : Oscillator
        The system simulated.
    excitation : Harmonic or Record
        The base acceleration it was shaken with.
    levels : StructureRun
        The same run as the one-level structure the mass is (:meth:`pounding.Structure.from_oscillator`):
        what every structure's run has (``peaks()``, ``clearance_m``, ``to_xarray()`` along ``level``), the
        mass its level 0 and its bumpers wall 0.

    Examples
    --------
    >>> import pounding
    >>> run = pounding.simulate(pounding.presets.paper_damped(),
    ...                         pounding.Harmonic(a_g=0.1, freq_hz=2.0),
    ...                         duration=5.0)
    >>> run.success, run.t.shape  # 1 kHz samples plus one after every event
    (True, (5077,))
    >>> # mm, s
    >>> round(run.displacement_max * 1e3, 1), round(run.displacement_max_time_s, 3)
    (18.8, 0.934)
    >>> run.contacts["side"].value_counts().to_dict()
    {'right': 10, 'left': 9}
    >>> round(float(run.impacts["restitution"].median()), 2)
    0.97
    """

    t: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    velocity: np.ndarray = field(repr=False)
    abs_acceleration: np.ndarray = field(repr=False)
    isolator_force: np.ndarray = field(repr=False)
    bumper_force_left: np.ndarray = field(repr=False)
    bumper_force_right: np.ndarray = field(repr=False)
    displacement_max: float
    displacement_max_time_s: float
    displacement_min: float
    displacement_min_time_s: float
    abs_acceleration_max: float
    abs_acceleration_max_time_s: float
    contact_table: np.ndarray = field(repr=False)
    event_table: np.ndarray = field(repr=False)
    energy: EnergyLedger
    final_state: State
    status: Status
    message: str
    oscillator: "Oscillator" = field(repr=False)
    excitation: "Excitation" = field(repr=False)
    sample_rate_hz: float = 1000.0
    chatter_table: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)), repr=False)
    levels: "StructureRun | None" = field(default=None, repr=False)

    @classmethod
    def _of_levels(cls, levels: "StructureRun", oscillator: "Oscillator", chatter_table: np.ndarray) -> "Run":
        """The single mass's run read off the run of the one-level structure it is (``levels``: its
        level 0, its bumpers wall 0; ``chatter_table``: the core's chatter rows)."""
        force = levels.contact_force
        k = levels.t.size
        return cls(
            t=levels.t, displacement=levels.displacement[:, 0], velocity=levels.velocity[:, 0],
            abs_acceleration=levels.abs_acceleration[:, 0], isolator_force=levels.isolator_force,
            bumper_force_left=force[:, 0] if force.shape[1] else np.zeros(k),
            bumper_force_right=force[:, 1] if force.shape[1] else np.zeros(k),
            **{name: float(getattr(levels, name)[0]) for name in EXTREMA_FIELDS},
            contact_table=levels.contact_table, event_table=levels.event_table, energy=levels.energy,
            final_state=levels.final_state, status=levels.status, message=levels.status.message,
            oscillator=oscillator, excitation=levels.excitation, sample_rate_hz=levels.sample_rate_hz,
            chatter_table=chatter_table, levels=levels)

    @cached_property
    def chatters(self) -> pd.DataFrame:
        """The rigid stops' chatter sequences (see :class:`pounding.RigidStop`), one row each."""
        return chatter_frame(self.chatter_table, SIDES)

    @cached_property
    def _one_level(self) -> "StructureRun":
        """The run of the one-level structure the mass is: :attr:`levels`, or (a Run made by hand, or kept
        from before it had its levels) that run read off this one's own arrays."""
        if self.levels is not None:
            return self.levels
        from ..model.structure import Structure

        one = {name: np.array([getattr(self, name)]) for name in EXTREMA_FIELDS}
        return StructureRun(
            structure=Structure.from_oscillator(self.oscillator), excitation=self.excitation,
            sample_rate_hz=self.sample_rate_hz, t=self.t, displacement=self.displacement[:, None],
            velocity=self.velocity[:, None], abs_acceleration=self.abs_acceleration[:, None],
            isolator_force=self.isolator_force,
            contact_force=np.column_stack([self.bumper_force_left, self.bumper_force_right]),
            contact_table=self.contact_table, event_table=self.event_table, energy=self.energy,
            final_state=self.final_state, status=self.status, chatter_table=self.chatter_table, **one)

    @cached_property
    def contacts(self) -> pd.DataFrame:
        """One row per contact (see the class docstring), built on first use: the one-level structure's
        (:attr:`levels`)."""
        return self._one_level.contacts

    @cached_property
    def events(self) -> pd.DataFrame:
        """Every event: time ``t_s``, ``kind`` and ``index`` (spring or side), built on first use."""
        return events_frame(self.event_table)

    @cached_property
    def impacts(self) -> pd.DataFrame:
        """The paper's per-impact quantities (Sect. 3.5), one row per contact, the one-level structure's
        (:attr:`levels`): ``wall``, ``level``, ``side``, ``t_start_s`` and restitution, contact time,
        impulse, mean and peak force, ``E_d`` and the bumper's own dissipation; see
        :func:`pounding.impact_table` (the same without ``wall`` and ``level``)."""
        return self._one_level.impacts

    @property
    def success(self) -> bool:
        """Whether the run reached its end time (``status`` is ``Status.SUCCESS``)."""
        return self.status == Status.SUCCESS

    def quantities(self) -> dict[str, float]:
        """The run in a few peaks (a study's point, a pounding spectrum's run, a design's stripe), as every
        run's: the one-level structure's (:attr:`levels`), see
        :func:`~pounding.engine.run_quantities.peaks_of`: ``acc_max_g`` (inf where a rigid stop struck:
        an impulse), ``disp_max_m`` (the largest of ``|D|``), ``impacts``, ``impact_force_max_n`` (inf with
        rigid impacts; 0 without contact), ``impact_speed_max_m_s``, ``compression_max_m`` (the bumpers'
        deepest), ``top_disp_max_m`` and ``top_acc_max_g`` (the mass's again: it is its structure's top),
        ``drift_ratio_max`` (NaN: no storey) and ``status``."""
        return self._one_level.quantities()

    def summary(self) -> pd.Series:
        """The run in a few numbers, each name with its unit (what ``pounding simulate`` prints): the
        one-level structure's (:attr:`levels`), as every run's; see :meth:`StructureRun.summary`.

        Returns
        -------
        pandas.Series
            ``t_end_s``; the exact ``displacement_max_m``, ``displacement_min_m``, the
            ``displacement_end_m`` at the run's end, a friction isolator's ``sticks`` and ``slips`` (0
            otherwise) and ``abs_acceleration_max_m_s2`` (between a rigid stop's impacts, which are impulses);
            ``alpha``, that over the table's peak (a sine's amplitude, a record's PGA; NaN without
            shaking); ``contacts``, ``contacts_left`` and ``rigid_impacts``; over the finished contacts
            ``restitution_mean``, ``contact_time_mean_s`` (those that last: holds and deformable
            contacts) and ``peak_force_max_n`` (inf with rigid impacts; NaN without contacts);
            ``input_work_j`` and ``energy_residual_j``; ``status`` (its name).

        Examples
        --------
        >>> import pounding
        >>> run = pounding.simulate(pounding.presets.paper_damped(),
        ...                         pounding.Harmonic(a_g=0.1, freq_hz=2.0), 5.0)
        >>> s = run.summary()
        >>> int(s["contacts"]), round(s["alpha"], 2), s["status"]
        (19, 12.76, 'SUCCESS')
        """
        return self._one_level.summary()

    @property
    def excursion_m(self) -> float:
        """``E = D_max - D_min`` over the run, m."""
        return self.displacement_max - self.displacement_min

    def to_xarray(self) -> Any:
        """The sampled histories as a Dataset along ``sample``, its times the coordinate ``time_s`` (not an
        index: an event's sample may share its time with the one before it), each variable's unit in its
        ``units``; ``status`` and ``message`` as attributes."""
        from .._tables import frame_to_xarray

        ds = frame_to_xarray(self.to_dataframe(), "sample",
                             {"status": self.status.name, "message": self.message})
        ds = ds.set_coords("t_s").rename({"t_s": "time_s"})
        for name in [*ds.data_vars, "time_s"]:
            ds[name].attrs["units"] = HISTORY_UNIT_OF.get(name, "")
        return ds

    def to_dataframe(self, units: bool | None = None) -> pd.DataFrame:
        """The sampled histories, one row per sample, each column named with its unit (SI), as in the
        CSV files the command line writes: ``t_s``, ``displacement_m``, ``velocity_m_s``,
        ``abs_acceleration_m_s2``, ``isolator_force_n``, ``bumper_force_left_n``,
        ``bumper_force_right_n`` and ``event``.

        The column ``event`` names the event after which a row was taken (``contact_start``,
        ``yield``, ...; empty for the uniform samples): an event's row holds the state just
        after its jump, so it may share its time with the row before it.  The names without
        units of 0.1 (``t``, ``displacement``, ...) still answer, with a ``FutureWarning``;
        ``units=False`` (0.1's default) gives them as the columns, with one too.
        """
        if units is not None:
            from .._checks import instance_of

            instance_of("units", units, bool, "true or false (or leave it out: names with units)")
        df = HistoryTable({HISTORY_UNITS[name]: getattr(self, name) for name in HISTORY_COLUMNS})
        df["event"] = self._event_labels()
        if units is False:
            import warnings

            warnings.warn("to_dataframe(units=False): the columns' names without units go in the next "
                          "release; read them by their names with units (t_s, displacement_m, ...), "
                          "to_dataframe()'s", FutureWarning, stacklevel=2)
            return pd.DataFrame(df).rename(columns={v: k for k, v in HISTORY_UNITS.items()})
        return df

    def _event_labels(self) -> np.ndarray:
        """Per history row, the event it was taken after ("" for the uniform samples)."""
        labels = np.full(self.t.size, "", dtype=object)
        times = self.event_table[:, E_T]
        if times.size == 0 or self.t.size == 0:
            return labels
        # an event's row is the last of the rows at its time (the uniform grid may have one
        # just before the jump); k events at one instant take the last k such rows, in order
        last = np.searchsorted(self.t, times, side="right") - 1
        first_of_group = np.searchsorted(times, times, side="left")
        group_size = np.searchsorted(times, times, side="right") - first_of_group
        rows = last - (group_size - 1 - (np.arange(times.size) - first_of_group))
        ok = (rows >= 0) & (self.t[np.clip(rows, 0, None)] == times)
        names = np.array(EVENT_NAMES, dtype=object)[self.event_table[:, E_ACTION].astype(int)]
        labels[rows[ok]] = names[ok]
        return labels

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Plot displacement and absolute acceleration against time; see :func:`pounding.plots.plot_run`.
        Returns its Figure."""
        from ..plots import plot_run, figure_of

        return figure_of(plot_run(self, ax=ax, **kwargs), ax)

    def plot_isolator_loop(self, ax: Any = None, **kwargs: Any) -> Any:
        """The isolator's force against the displacement; see :func:`pounding.plots.plot_isolator_loop`.
        Returns its Figure."""
        from ..plots import figure_of, plot_isolator_loop

        return figure_of(plot_isolator_loop(self, ax=ax, **kwargs), ax)
