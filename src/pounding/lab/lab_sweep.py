"""``LabSweep``: what :func:`pounding.lab.analyse_stepped_sine` measured, per step, under the names
and units of :meth:`pounding.SweepResult.to_dataframe` so that lab and model line up."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .record import LabRecord


@dataclass(frozen=True, eq=False)
class LabSweep:
    """A measured stepped sine, step by step.

    Attributes
    ----------
    steps : DataFrame
        One row per measured step in the order run (see :func:`analyse_stepped_sine`).
    record : LabRecord
        What was measured.
    mass_kg : float
    gap_total_m : float or None
        ``Delta`` (YBs), m.
    f_ref_hz : float
        ``nu = f / f_ref``.
    impacts : DataFrame
        One row per contact measured (with ``gap_total_m``): ``freq_hz`` of its step and
        :data:`~pounding.lab.contacts.IMPACT_COLUMNS`.
    """

    steps: pd.DataFrame
    record: LabRecord = field(repr=False)
    mass_kg: float
    gap_total_m: float | None
    f_ref_hz: float
    impacts: pd.DataFrame = field(default_factory=pd.DataFrame, repr=False)

    def to_dataframe(self) -> pd.DataFrame:
        """A copy of :attr:`steps`."""
        return self.steps.copy()

    @property
    def a_g(self) -> float:
        """The table's amplitude, g: the median of the steps' fitted amplitudes."""
        return float(np.median(self.steps["a_g"]))

    @property
    def resonance_hz(self) -> float:
        """The step frequency where alpha peaks (the pseudo-resonance), Hz."""
        return float(self.steps["freq_hz"].iloc[int(np.argmax(self.steps["alpha"].to_numpy()))])

    @property
    def nu_r(self) -> float:
        """``nu_R = f_R / f_ref``."""
        return self.resonance_hz / self.f_ref_hz

    @property
    def alpha_max(self) -> float:
        return float(self.steps["alpha"].max())
