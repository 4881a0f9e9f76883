"""The report's opening verdict: how many of the paper's targets a system meets, its worst misses,
and which measurements no model can meet together (:meth:`pounding.Targets.check_consistency`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..data import PAPER_MASS_KG
from ..identification import paper_targets
from ..identification.consistency import CONSISTENCY_QUANTITIES

WORST_MISSES = 6  # rows of the worst misses the page shows


@dataclass(frozen=True, eq=False)
class Verdict:
    """What a system reaches against :func:`pounding.paper_targets`.

    Attributes
    ----------
    met, total : int
        Targets met (within tolerance) and all targets.
    residuals : DataFrame
        :func:`pounding.identification.evaluate`'s table, with ``difference_pct``
        (``(model - measured) / |measured|`` in percent) and ``flagged`` (a consistency check
        on that quantity of that case failed: no model meets it together with the rest).
    consistency : DataFrame
        :meth:`pounding.Targets.check_consistency` of the paper's measurements.
    """

    met: int
    total: int
    residuals: pd.DataFrame
    consistency: pd.DataFrame

    @property
    def worst_misses(self) -> pd.DataFrame:
        """The misses furthest outside their tolerance, worst first."""
        misses = self.residuals[~self.residuals["within"]]
        order = misses["normalized"].abs().sort_values(ascending=False).index
        cols = ["configuration", "a_g", "quantity", "target", "model", "difference_pct", "normalized",
                "flagged"]
        return misses.loc[order, cols].head(WORST_MISSES).reset_index(drop=True)

    @property
    def flags(self) -> pd.DataFrame:
        """The consistency checks the measurements fail."""
        cols = ["configuration", "a_g", "check", "kind", "quantity", "measured", "bound", "explanation"]
        return self.consistency.loc[~self.consistency["consistent"], cols].reset_index(drop=True)

    def summary(self) -> str:
        """One sentence: met, the worst miss, the flags."""
        out = f"meets {self.met} of {self.total} targets"
        if self.met < self.total:
            w = self.worst_misses.iloc[0]
            out += (f"; worst miss {w['configuration']} a_G {w['a_g']:g} {w['quantity']}: "
                    f"{w['model']:.4g} against {w['target']:.4g} ({w['difference_pct']:+.0f} %)")
        n = len(self.flags)
        return out + f"; {n} measured combination{'s' if n != 1 else ''} flagged by the consistency checks"


def verdict(residuals: pd.DataFrame) -> Verdict:
    """The verdict from a residual table of the paper's targets (``evaluate(system, paper_targets())``).

    The consistency checks are the paper's measurements' own, with its mass and its nominal total
    gap (``paper_targets``' ``eta_gap_total_m``).
    """
    consistency = paper_targets(quantities=CONSISTENCY_QUANTITIES).check_consistency(PAPER_MASS_KG)
    bad = {(c, float(a), q) for c, a, q in
           consistency.loc[~consistency["consistent"], ["configuration", "a_g",
                                                        "quantity"]].itertuples(index=False)}
    res = residuals.copy()
    with np.errstate(divide="ignore", invalid="ignore"):
        res["difference_pct"] = (100.0 * res["difference"] / res["target"].abs()).where(res["target"] != 0)
    res["flagged"] = [(c, float(a), q) in bad for c, a, q in res[["configuration", "a_g", "quantity"]]
                      .itertuples(index=False)]
    return Verdict(int(res["within"].sum()), len(res), res, consistency)
