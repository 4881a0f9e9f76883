"""What every run's result is made of, whatever the system: how it ended (:class:`Outcome`), where the
energy went (:class:`EnergyLedger`), and its tables of events, contacts and impacts read off the core's rows
(the results: :mod:`.structure_result`, :mod:`.result`, :mod:`.adjacent_result`)."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

import numpy as np
import pandas as pd

from .._errors import Status, renamed_fields
from .._tables import ContactTable, EventTable
from .layout import CONTACT_COLUMNS as CORE_CONTACT_COLUMNS
from .layout import (C_SLOT, E_ACTION, E_INDEX, E_T, EVENT_NAMES, L_BUMPER, L_BUMPER_LOSS, L_HYSTERETIC,
                     L_INPUT, L_ISOLATOR, L_KINETIC, L_VISCOUS)

# a run's exact extrema and their times (a single mass's floats; a structure's per level)
EXTREMA_FIELDS = ("displacement_max", "displacement_max_time_s", "displacement_min",
                  "displacement_min_time_s", "abs_acceleration_max", "abs_acceleration_max_time_s")


class Outcome:
    """What every run result (a dataclass with a ``status``) says of how it ended: ``success`` and
    ``message``."""

    @property
    def success(self) -> bool:
        """Whether the run reached its end time (``status`` is ``Status.SUCCESS``)."""
        return self.status == Status.SUCCESS  # type: ignore[attr-defined]

    @property
    def message(self) -> str:
        """The status in words: why the run stopped early and what to do."""
        return self.status.message  # type: ignore[attr-defined]


@renamed_fields({"isolator_elastic": "elastic", "bumper_elastic": "contact_elastic",
                 "bumper_dissipation": "contact_dissipation"}, why="one ledger for every system")
@dataclass(frozen=True, kw_only=True)
class EnergyLedger:
    """Where the energy went over a run, J: a single mass's, a structure's or a pair's.

    ``input_work`` (the work of the inertial forcing ``-M A(t)`` on the motion relative to the ground)
    equals what the dashpots, the hysteresis and the contacts dissipated plus the change of the kinetic
    and elastic energies; ``residual`` is what is left, a check on the integration (at rounding level for
    an exact run).

    Attributes
    ----------
    input_work : float
        Work of ``-M A(t)`` on the relative motion over the run, J.
    viscous : float
        Dissipated by the dashpots (the isolators' ``C_d``, the storeys'), J.
    hysteretic : float
        Dissipated by the hysteresis of the isolators (their slipping springs and Bouc-Wen spring) and
        of the multi-linear storeys, J.
    contact_dissipation : float
        Taken by the contacts' laws and not given back (bumpers' and walls' dashpots and slips, a rigid
        stop's impacts), J.
    kinetic : float
        Change of the kinetic energy, J.
    elastic : float
        Change of the elastic energy of the isolators' and the storeys' springs, J.
    contact_elastic : float
        Change of the contacts' laws' elastic energy (what they would give back when unloaded), J.

    The terms are given by keyword (their order changed from 0.1's); the names of 0.1
    (``isolator_elastic``, ``bumper_elastic``, ``bumper_dissipation``) still answer for one release, with a
    ``FutureWarning``.

    Examples
    --------
    Where the first 10 s of El Centro, scaled to 0.3 g, put their energy in the damped paper
    system:

    >>> import pounding
    >>> quake = pounding.records.el_centro().scaled(pga_g=0.3)
    >>> ledger = pounding.simulate(pounding.presets.paper_damped(), quake,
    ...                            duration=10.0).energy
    >>> (f"{ledger.input_work:.1f} J in: {ledger.viscous:.1f} J viscous, "
    ...  f"{ledger.hysteretic:.1f} J hysteretic")
    '140.2 J in: 117.5 J viscous, 21.9 J hysteretic'
    >>> bool(abs(ledger.residual) < 1e-9)  # J: every joule accounted for
    True
    >>> list(ledger.to_series().index)[:4]
    ['input_work', 'viscous', 'hysteretic', 'contact_dissipation']
    """

    input_work: float
    viscous: float
    hysteretic: float
    contact_dissipation: float
    kinetic: float
    elastic: float
    contact_elastic: float

    @classmethod
    def of(cls, ledger: np.ndarray) -> "EnergyLedger":
        """The ledger of the core's run (its ``ledger``, the core's ``LEDGER`` slots)."""
        return cls(**{name: float(ledger[k]) for name, k in (
            ("input_work", L_INPUT), ("viscous", L_VISCOUS), ("hysteretic", L_HYSTERETIC),
            ("contact_dissipation", L_BUMPER_LOSS), ("kinetic", L_KINETIC), ("elastic", L_ISOLATOR),
            ("contact_elastic", L_BUMPER))})

    @property
    def residual(self) -> float:
        """``input_work`` minus every stored and dissipated term, J."""
        return self.input_work - (self.viscous + self.hysteretic + self.contact_dissipation + self.kinetic
                                  + self.elastic + self.contact_elastic)

    def to_series(self) -> pd.Series:
        """Every term and the ``residual``, J, as a Series named ``energy_J``."""
        data = {f.name: getattr(self, f.name) for f in fields(self)}
        data["residual"] = self.residual
        return pd.Series(data, name="energy_J")


def events_frame(e: np.ndarray) -> pd.DataFrame:
    """An event table from the core's rows (time, action code, index): ``t_s``, ``kind`` (the action's name,
    categorical) and ``index``; the columns' names of 0.1 (``t``, ``event``) still answer, with a warning."""
    codes = e[:, E_ACTION].astype(int)
    kinds = pd.Categorical.from_codes(codes, categories=list(EVENT_NAMES))
    return EventTable({"t_s": e[:, E_T], "kind": kinds, "index": e[:, E_INDEX].astype(int)})


# every run's contacts at walls (a single mass's bumpers are wall 0, at level 0): the wall, its level and
# side, then the core's columns by their names
CONTACT_COLUMNS = ("wall", "level", "side", "t_start_s", "t_end_s", "v_in_m_s", "v_out_m_s", "impulse_n_s",
                   "peak_force_n", "max_compression_m", "bumper_dissipation_j")


def wall_contacts(table: np.ndarray, wall_levels: Any) -> pd.DataFrame:
    """A contact table's frame from the core's rows of contacts at walls (slot ``2 wall + side``):
    :data:`CONTACT_COLUMNS`, each wall at its level in ``wall_levels``."""
    slot = table[:, C_SLOT].astype(int)
    return ContactTable({
        "wall": slot // 2,
        "level": np.asarray(wall_levels, dtype=int)[slot // 2],
        "side": np.where(slot % 2 == 0, "left", "right"),
        **{name: table[:, CORE_CONTACT_COLUMNS[name]] for name in CONTACT_COLUMNS[3:]},
    })


def impact_frame(contacts: pd.DataFrame, labels: tuple[str, ...], table: np.ndarray,
                 masses_kg: Any) -> pd.DataFrame:
    """A per-impact table: the ``labels`` columns and ``t_start_s`` of a contact table's frame
    (``contacts``), then the quantities of each row of the core's ``table`` (``metrics.impacts``) for the
    impacting masses ``masses_kg`` (one for every row, or one a row)."""
    from ..metrics.impacts import IMPACT_COLUMNS, impact_values

    df = pd.DataFrame(contacts[[*labels, "t_start_s"]])  # (a plain frame: no names of 0.1 to answer)
    df[list(IMPACT_COLUMNS)] = impact_values(table, np.array(masses_kg, dtype=float))
    return df
