"""What a run of two adjacent structures returns: :class:`AdjacentRun` (each structure's
:class:`~pounding.StructureRun`, the contacts at their links, the pair's energy ledger and events)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from .._errors import Status
from .._tables import ContactTable
from ._chatter import NamedChatters
from .layout import C_SLOT
from .layout import CONTACT_COLUMNS as CORE_CONTACT_COLUMNS
from .run_parts import CONTACT_COLUMNS, EnergyLedger, Outcome, events_frame, impact_frame
from .run_quantities import peaks_of
from .structure_result import StructureRun


@dataclass(frozen=True)
class AdjacentRun(NamedChatters, Outcome):
    """A run of two adjacent structures.

    Attributes
    ----------
    adjacent : Adjacent
        The pair run.
    excitation : Harmonic or Record
        The ground's motion.
    sample_rate_hz : float
        The uniform samples' rate, Hz (0: events only).
    first, second : StructureRun
        Each structure's histories, exact extrema per level and walls' contacts.
    t : ndarray, shape (k,)
        Sample times, s.
    link_force : ndarray, shape (k, n_links)
        Each link's force, N (>= 0).
    link_table : ndarray
        The core's rows behind ``links``.
    event_table : ndarray
        Every event of the pair: time, action code, the element's index (``events`` names them).
    energy : EnergyLedger
        The energy ledger of the pair (the links' in ``contact_dissipation`` and ``contact_elastic``).
    final_state : State
        Pass as ``state`` to continue.
    status : Status
        How the run ended (``message`` says it in words).
    chatters : pandas.DataFrame
        The rigid stops' chatter sequences (``contact``: ``first wall 0 left``, ``link 0``); see
        :attr:`StructureRun.chatters`.
    chatter_table : ndarray, shape (n_sequences, 5)
        The core's rows behind ``chatters``.
    contact_names : tuple of str
        Each contact slot's name, as ``chatters`` gives it.
    clearance_m : ndarray, shape (n_slots,)
        Each contact slot's smallest clearance over the run (its gap less the largest approach, exact;
        negative: it touched), m: the first's wall sides, the second's, then the links.

    Examples
    --------
    Two fixed-base two-storey frames, a soft one and a stiff one, their roofs 1 cm apart:

    >>> import pounding
    >>> soft = pounding.Structure.fixed_base(
    ...     [pounding.Storey(2.0e4, 2.0e7, 4.0e4)] * 2)
    >>> stiff = pounding.Structure.fixed_base(
    ...     [pounding.Storey(2.0e4, 1.2e8, 4.0e4)] * 2)
    >>> roofs = pounding.Link(2, 2, 0.01, pounding.KelvinVoigt(5.0e8, 2.0e5))
    >>> run = pounding.simulate(pounding.Adjacent(soft, stiff, [roofs]),
    ...                         pounding.Harmonic(a_g=0.3, freq_hz=2.0), 5.0)
    >>> len(run.links), list(run.links.columns)[:4]
    (19, ['link', 'level_first', 'level_second', 't_start_s'])
    """

    adjacent: Any
    excitation: Any
    sample_rate_hz: float
    first: StructureRun
    second: StructureRun
    t: np.ndarray
    link_force: np.ndarray
    link_table: np.ndarray = field(repr=False)
    event_table: np.ndarray = field(repr=False)
    energy: EnergyLedger = field(repr=False)
    final_state: Any = field(repr=False)
    status: Status = Status.SUCCESS
    clearance_m: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    chatter_table: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)), repr=False)
    contact_names: tuple = field(default=(), repr=False)

    @property
    def links(self) -> pd.DataFrame:
        """One row per contact at a link: ``link``, ``level_first``, ``level_second``, ``t_start_s``,
        ``t_end_s``, the velocities in and out ``v_in_m_s``, ``v_out_m_s`` (of the first's level less the
        second's), ``impulse_n_s``, ``peak_force_n``, the deepest compression ``max_compression_m``,
        ``bumper_dissipation_j``."""
        c = self.link_table
        k = c[:, C_SLOT].astype(int)
        links = self.adjacent.links
        return ContactTable({
            "link": k,
            "level_first": [links[j].level_first for j in k],
            "level_second": [links[j].level_second for j in k],
            **{name: c[:, CORE_CONTACT_COLUMNS[name]] for name in CONTACT_COLUMNS[3:]},
        })

    @property
    def contacts(self) -> pd.DataFrame:
        """Every contact of the pair in the order they began: ``contact`` (``first wall 0 left``, ``second
        wall 1 right``, ``link 0``: the names of :attr:`chatters`), ``level_first`` and ``level_second``
        (the levels it joins: a wall's level on its own structure's side, NaN on the other), then the
        columns of :attr:`links` from ``t_start_s`` on (``v_in_m_s``: the first's level less the
        second's at a link, the level's own at a wall)."""
        frames = []
        for name, part in (("first", self.first), ("second", self.second)):
            walls = part.contacts
            level = walls["level"].astype(float)
            frames.append(pd.DataFrame({
                "contact": [f"{name} wall {w} {side}" for w, side in zip(walls["wall"], walls["side"])],
                "level_first": level if name == "first" else np.nan,
                "level_second": level if name == "second" else np.nan,
                **{c: walls[c] for c in CONTACT_COLUMNS[3:]}}))
        links = self.links
        frames.append(pd.DataFrame({"contact": [f"link {k}" for k in links["link"]],
                                    "level_first": links["level_first"].astype(float),
                                    "level_second": links["level_second"].astype(float),
                                    **{c: links[c] for c in CONTACT_COLUMNS[3:]}}))
        return ContactTable(pd.concat(frames, ignore_index=True).sort_values("t_start_s", kind="stable",
                                                                             ignore_index=True))

    @property
    def link_impacts(self) -> pd.DataFrame:
        """The paper's per-impact quantities (Sect. 3.5), one row per contact at a link: ``link``,
        ``level_first``, ``level_second``, ``t_start_s``, then the columns of
        :attr:`StructureRun.impacts` (``dissipated_energy_j`` with the pair's effective mass
        ``m1 m2 / (m1 + m2)`` of the two levels, the one level's own against a fixed base's ground)."""
        first, second = self.adjacent.structures
        mass = []
        for k in self.link_table[:, C_SLOT].astype(int):
            link = self.adjacent.links[k]
            m1, m2 = float(first.masses_kg[link.level_first]), float(second.masses_kg[link.level_second])
            mass.append(m2 if np.isnan(m1) else m1 if np.isnan(m2) else m1 * m2 / (m1 + m2))
        return impact_frame(self.links, ("link", "level_first", "level_second"), self.link_table, mass)

    def summary(self) -> pd.Series:
        """The pair's run in a few numbers: ``t_end_s``; each structure's (``first_``, ``second_``) contacts
        at its walls, ``contacts``, ``contacts_left`` and ``contacts_level_<k>`` at each level with a wall
        (:meth:`StructureRun.contact_counts`), its base's ``displacement_end_m`` and its friction isolator's
        ``sticks``, ``slips``, ``surface_slips`` and ``rings``; ``link_contacts``; ``input_work_j`` and
        ``energy_residual_j``;
        ``status``."""
        out: dict[str, Any] = {"t_end_s": float(self.t[-1]) if self.t.size else float("nan")}
        for name, part in (("first", self.first), ("second", self.second)):
            out.update({f"{name}_{k}": v for k, v in part.contact_counts().items()})
            s = part.summary()
            kept = ("displacement_end_m", "sticks", "slips", "surface_slips", "rings")
            out.update({f"{name}_{k}": s[k] for k in kept})
        out.update({"link_contacts": len(self.link_table), "input_work_j": self.energy.input_work,
                    "energy_residual_j": self.energy.residual, "status": self.status.name})
        return pd.Series(out, name="summary", dtype=object)

    def quantities(self) -> dict[str, float]:
        """The pair's run in a few peaks: the first structure's base and top floor, the largest acceleration
        and drift ratio over both, the contacts at every wall and link; see
        :func:`~pounding.engine.run_quantities.peaks_of`."""
        return peaks_of(self, self.excitation.g)

    @property
    def events(self) -> pd.DataFrame:
        """Every event of the pair: ``t_s``, what happened (``kind``) and the element's ``index``."""
        return events_frame(self.event_table)

    def to_dataframe(self) -> pd.DataFrame:
        """Both structures' histories side by side (columns ``first.``/``second.``), and the links' forces."""
        frames = [self.first.to_dataframe().add_prefix("first."),
                  self.second.to_dataframe().drop(columns="t_s").add_prefix("second.")]
        out = pd.concat(frames, axis=1).rename(columns={"first.t_s": "t_s"})
        for j in range(self.link_force.shape[1]):
            out[f"link_force_n[{j}]"] = self.link_force[:, j]
        return out

    def to_xarray(self) -> Any:
        """Each structure's Dataset (``first``/``second`` prefixes on the variables, ``_first``/``_second``
        suffixes on their dimensions) along ``sample`` (its coordinate ``time_s``), and the links' forces."""
        import xarray as xr

        parts = []
        for name, run in (("first", self.first), ("second", self.second)):
            ds = run.to_xarray().reset_coords(["wall", "side"], drop=True)
            ds = ds.rename({dim: f"{dim}_{name}" for dim in ("level", "storey", "contact", "stand")
                            if dim in ds.dims})
            parts.append(ds.rename({v: f"{name}_{v}" for v in ds.data_vars}))
        ds = xr.merge(parts, compat="override", join="exact", combine_attrs="override")
        ds["link_force_n"] = (("sample", "link"), self.link_force, {"units": "N"})
        ds.attrs = {"status": self.status.name, "message": self.message}
        return ds

    def plot(self, **kwargs: Any) -> Any:
        """The linked levels' displacements and their separation against each gap; see
        :func:`pounding.plots.plot_adjacent_run`.

        Returns its Figure.
        """
        from ..plots import plot_adjacent_run, figure_of

        return figure_of(plot_adjacent_run(self, **kwargs), kwargs.get("axes"))
