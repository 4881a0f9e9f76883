"""``LabSweep``: what :func:`pounding.lab.analyse_stepped_sine` measured, per step, under the names
and units of :meth:`pounding.SweepResult.to_dataframe` so that lab and model line up."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from .._checks import one_of, positive
from .._errors import InputError, Problem
from .record import LabRecord

CONFIGURATIONS = ("NBs", "YBs")


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
        The mass on the table, kg.
    gap_total_m : float or None
        ``Delta`` (YBs), m.
    f_ref_hz : float
        ``nu = f / f_ref``.
    impacts : DataFrame
        One row per contact measured (with ``gap_total_m``): ``freq_hz`` of its step and
        :data:`~pounding.metrics.measured_contacts.IMPACT_COLUMNS`.

    Examples
    --------
    What :func:`analyse_stepped_sine` returns, here for a virtual YBs test at a_G = 0.05 g:

    >>> import pounding
    >>> rec = pounding.lab.synthetic_test(pounding.presets.paper_damped(), 0.05,
    ...                                   [1.0, 1.5, 2.0], cycles=10)
    >>> sweep = pounding.lab.analyse_stepped_sine(rec, mass_kg=500.0,
    ...                                           gap_total_m=0.03)
    >>> len(sweep.steps), sweep.direction, round(sweep.a_g, 3), round(sweep.nu_r, 2)
    (3, 'up', 0.05, 1.5)
    >>> # the excursion over the total gap, per step
    >>> sweep.steps["eta"].round(2).tolist()
    [0.85, 1.07, 0.49]
    >>> # nu_r, alpha, eta, the contact range, contact time, restitution
    >>> len(pounding.Targets.from_lab(sweep, "YBs"))
    7
    """

    steps: pd.DataFrame
    record: LabRecord = field(repr=False)
    mass_kg: float
    gap_total_m: float | None
    f_ref_hz: float
    impacts: pd.DataFrame = field(default_factory=pd.DataFrame, repr=False)

    def to_xarray(self) -> Any:
        """The table of :meth:`to_dataframe` as a Dataset along ``step``."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "step")

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
        return float(self.steps["freq_hz"].iloc[self._resonance_row()])

    def _resonance_row(self) -> int:
        """The row of the largest measured alpha (steps not measured, NaN, are passed over)."""
        alpha = self.steps["alpha"].to_numpy(dtype=float)
        if not np.isfinite(alpha).any():
            raise InputError(Problem.NO_FIT, "record", self.record.source, why="no step could be measured "
                             "(every window misses samples)", fix="see the steps' missing_samples")
        return int(np.nanargmax(alpha))

    @property
    def nu_r(self) -> float:
        """``nu_R = f_R / f_ref``."""
        return self.resonance_hz / self.f_ref_hz

    @property
    def alpha_max(self) -> float:
        """The largest alpha over the measured steps."""
        return float(self.steps["alpha"].max())

    @property
    def direction(self) -> str:
        """"up" when the steps' frequencies rise, else "down"."""
        f = self.steps["freq_hz"].to_numpy()
        return "up" if f.size < 2 or f[-1] >= f[0] else "down"

    @property
    def contact_range_hz(self) -> tuple[float, float] | None:
        """The lowest and highest step frequency with contact, Hz (None without)."""
        if "contact" not in self.steps:
            return None
        seen = self.steps["contact"].to_numpy(dtype=float) > 0.5  # (NaN: a step not measured)
        if not seen.any():
            return None
        f = self.steps.loc[seen, "freq_hz"]
        return float(f.min()), float(f.max())

    def target_records(self, configuration: str, a_g: float | None = None) -> list[dict[str, Any]]:
        """The paper's quantities of this sweep as target records (the rows of
        :meth:`pounding.Targets.from_records`; :meth:`pounding.Targets.from_lab` makes the targets).

        Table 2's ``nu_r``, ``alpha`` and ``eta`` (YBs, over this sweep's ``gap_total_m``) or
        ``e`` (NBs), the contact range (YBs), and at the resonance step the contact time and
        restitution (YBs, where measured).  ``a_g`` (g) is what the model's sweeps will use:
        default the measured amplitude rounded to 0.001 g.
        """
        configuration = one_of("configuration", configuration, CONFIGURATIONS)
        a_g = round(self.a_g, 3) if a_g is None else positive("a_g", a_g, "g")
        if configuration == "YBs" and self.gap_total_m is None:
            raise InputError(Problem.MISSING_INPUT, "gap_total_m", None,
                             what="the gap: analyse_stepped_sine(..., gap_total_m=...) for YBs targets")
        df = self.steps
        at = df.iloc[self._resonance_row()]
        values = {"nu_r": self.nu_r, "alpha": self.alpha_max}
        if configuration == "YBs":
            values["eta"] = float(df["eta"].max())
            rng = self.contact_range_hz
            if rng is not None:
                values.update(contact_nu_min=rng[0] / self.f_ref_hz, contact_nu_max=rng[1] / self.f_ref_hz)
            for q, col, scale in (("contact_time_ms", "contact_time_s", 1e3),
                                  ("restitution", "restitution", 1.0)):
                if col in df and np.isfinite(at[col]):
                    values[q] = float(at[col]) * scale
        else:
            values["e"] = float(df["e"].max())
        return [{"configuration": configuration, "a_g": a_g, "quantity": q, "value": v,
                 "direction": self.direction} for q, v in values.items() if np.isfinite(v)]

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """alpha (top) and eta or e (bottom) against nu, as :meth:`pounding.SweepResult.plot`
        draws a sweep (pass the same ``ax`` to overlay lab and model); see
        :func:`pounding.plots.plot_lab_sweep`.

        Returns its Figure.
        """
        from ..plots import plot_lab_sweep, figure_of

        return figure_of(plot_lab_sweep(self, ax=ax, **kwargs), ax)
