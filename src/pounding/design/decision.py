"""The decision: which gap (and bumper) meets the target probability, and what it costs.

From a :class:`StripeAnalysis`: per design point, the probability of pounding at the design and
MCE intensities (the fitted fragility's), the median peak acceleration and impact force at the
stripe nearest the MCE intensity, and with a hazard curve the probability in N years; the
smallest gap of the grid that meets the target, and the code's minimum clearance beside it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._checks import instance_of, one_of, positive
from .._docs import fill_doc
from .._errors import InputError, Problem
from ..model.dotted import unit_of
from .hazard import HazardCurve
from .decision_table import table_rows
from .stripe_result import EVENTS, StripeAnalysis

LEVELS = ("design", "mce")


@dataclass(frozen=True, eq=False)
class Decision:
    """What a stripe analysis says of each design point, and the one recommended (:func:`decide`).

    Attributes
    ----------
    data : pandas.DataFrame
        One row per design point (its grid values, and ``bumper``, the bumper type's name, when
        :func:`decide` was given one analysis per type), with ``p_contact_design``, ``p_contact_mce``,
        ``p_contact_years`` (with a hazard curve; NaN otherwise), ``acc_median_g`` and
        ``force_median_n`` (medians over the records at the stripe nearest the MCE intensity,
        ``stripe_g``), ``acc_pounding_median_g`` (the median over the records that pounded there;
        NaN when none did), ``acc_penalty_median`` (with bumpers over without, given the runs
        without; NaN otherwise), ``meets_target``, and ``p_capacity_mce``: the probability of compressing
        a bumper beyond its ``capacity_m`` at the MCE intensity (NaN without a capacity).
    recommended : dict or None
        The design point chosen (its grid values and row): the smallest gap meeting the target,
        then (of every bumper type and other design number at that gap) the lowest probability of
        pounding at ``level``, then the lowest median peak acceleration of the runs that pounded at
        the stripe nearest the MCE intensity (``acc_pounding_median_g``, a point where none pounded
        first: the bumper matters only when the mass reaches it), then the lowest median peak
        acceleration of all runs; None when no point meets it.
    target_probability : float
        The largest probability of pounding accepted, at ``level``.
    level : {"design", "mce"}
    design_sa_g, mce_sa_g : float
        The intensities (g) of the two levels.
    gap_dim : str
        The design grid's gap dimension.
    code_minimum_gap_m : float or None
        The code's least clearance (e.g. ASCE 7-16's D_TM), shown beside the recommendation.
    years : float
        The exposure time of ``p_contact_years``.
    event : str
        The demand the target applies to: ``"contact"`` (pounding), or ``"drift"``, ``"acceleration"``,
        ``"top_acceleration"``, ``"displacement"`` beyond ``limit`` (its probabilities in the columns
        ``p_<event>_design``, ``p_<event>_mce``, ``p_<event>_years``).
    limit : float or None
        The demand's threshold (None for pounding).
    units : dict
        The design dimensions' units (``"bumpers.gap_m"`` -> ``"m"``), per bumper type (keyed by its name,
        None for a single analysis), as the stores record them: what the labels show.

    Examples
    --------
    Three gaps under El Centro scaled to two stripes; the smallest gap whose pounding at the MCE
    (0.45 g) is at most 10 % likely:

    >>> import pounding
    >>> from pounding import design
    >>> gaps = {"bumpers.gap_m": [0.02, 0.05, 0.2]}
    >>> msa = design.stripe_analysis(pounding.presets.paper_damped(), "el-centro",
    ...                              [0.2, 0.5], period_s=1.0, grid=gaps,
    ...                              store="decide.zarr", progress=False)
    >>> choice = design.decide(msa, 0.3, 0.45, target_probability=0.1)
    >>> choice.level, choice.recommended["bumpers.gap_m"]
    ('mce', 0.05)
    """

    data: Any
    recommended: dict | None
    target_probability: float
    level: str
    design_sa_g: float
    mce_sa_g: float
    gap_dim: str
    code_minimum_gap_m: float | None
    years: float
    units: dict = field(default_factory=dict)
    event: str = "contact"
    limit: float | None = None

    @property
    def probability_column(self) -> str:
        """The table's column of the probability the target applies to, without its level:
        ``"p_contact"``, or the demand's (``"p_drift"``, ``"p_acceleration"``...)."""
        return f"p_{self.event}"

    def event_words(self) -> str:
        """What the target's event is, in words."""
        if self.event == "contact" or self.limit is None:
            return "pounding" if self.event == "contact" else self.event
        words = {"drift": "a storey drift ratio above {:g}",
                 "acceleration": "a floor acceleration above {:g} g",
                 "top_acceleration": "a top-floor acceleration above {:g} g",
                 "displacement": "a displacement above {:g} m"}
        return words.get(self.event, self.event + " above {:g}").format(self.limit)

    def to_xarray(self) -> Any:
        """The table of :meth:`to_dataframe` as a Dataset along ``option`` (one per design point)."""
        from .._tables import frame_to_xarray

        return frame_to_xarray(self.to_dataframe(), "option", {"target_probability": self.target_probability,
                                                               "level": self.level})

    def to_dataframe(self) -> Any:
        """The table (a copy)."""
        return self.data.copy()

    def verdict(self) -> str:
        """The gap recommended, the probabilities behind it and the runs they rest on, or that no gap
        of the grid meets the target; a caution when the runs cannot show the target is met."""
        level = "MCE" if self.level == "mce" else "design"
        other = "design" if self.level == "mce" else "MCE"
        code = (
            ""
            if self.code_minimum_gap_m is None
            else f" The code's minimum clearance is {1e3 * self.code_minimum_gap_m:.0f} mm."
        )
        if self.recommended is None:
            return (
                f"No gap of the grid keeps the probability of {self.event_words()} at the {level} level at "
                f"or below {self.target_probability:g}: widen the grid.{code}"
            )
        row = self.recommended
        others = _label([(d, row[d]) for d in self._dims() if d not in (self.gap_dim, "bumper")],
                        self._units_of(row))
        bumper = f" with the {row['bumper']} bumpers" if "bumper" in row else ""
        p = self.probability_column
        parts = [
            f"A gap of {1e3 * row[self.gap_dim]:.0f} mm{bumper}{' (' + others + ')' if others else ''}: "
            f"probability of {self.event_words()} {row[f'{p}_{self.level}']:.3f} at the {level} level "
            f"(target {self.target_probability:g}), {row[f'{p}_{other.lower()}']:.3f} at the {other} level.",
            f"At the stripe nearest the {level} level, {int(row['pounded_at_level'])} of "
            f"{int(row['runs_at_level'])} runs " + ("pounded." if self.event == "contact" else
                                                    f"had {self.event_words()}."),
        ]
        if self.event != "contact":
            parts.append(f"Probability of pounding: {row[f'p_contact_{self.level}']:.3f} at the {level} "
                         "level.")
        rivals = self.data[(self.data[self.gap_dim] == row[self.gap_dim]) & self.data["meets_target"]]
        if len(rivals) > 1:
            if math.isnan(row["acc_pounding_median_g"]):
                parts.append(
                    f"At this gap none of its runs pounded at the stripe nearest the MCE level; of the "
                    f"{len(rivals)} options there meeting the target, those whose runs did not pound rank "
                    "first, and these runs do not tell them apart further ('what pounding costs' compares "
                    "them at smaller gaps)."
                )
            else:
                parts.append(
                    f"Of the {len(rivals)} options at this gap meeting the target, it pounds least, and its "
                    f"runs that pounded at the stripe nearest the MCE level peaked at "
                    f"{row['acc_pounding_median_g']:.3g} g (median)."
                )
        if not math.isnan(row.get(f"{p}_years", math.nan)):
            parts.append(f"In {self.years:g} years at the site: {row[f'{p}_years']:.3f}.")
        if not math.isnan(row.get("p_capacity_mce", math.nan)):
            parts.append(
                f"Probability of compressing a bumper beyond its capacity at the MCE level: "
                f"{row['p_capacity_mce']:.3f}."
            )
        if code:
            parts.append(code.strip())
        if not row["fitted"] or row["p_upper_95"] > self.target_probability:
            why = "no lognormal curve could be fitted, and " if not row["fitted"] else ""
            parts.append(
                f"Caution: the runs do not settle it ({why}{int(row['pounded_at_level'])} of "
                f"{int(row['runs_at_level'])} runs at that stripe allow a probability up to "
                f"{row['p_upper_95']:.2f} at 95 % confidence): run more records."
            )
        return " ".join(parts)

    def plot(self, ax: Any = None) -> Any:
        """The design chart: the probability of pounding at both levels against the gap (one line
        per value of the other design dimensions), the target and the code's minimum.

        Returns its Figure.
        """
        from ..plots.design import plot_decision
        from ..plots import figure_of

        return figure_of(plot_decision(self, ax=ax), ax)

    def by_gap(self) -> list[tuple[str, Any]]:
        """The table's rows grouped by the other design dimensions: ``(label, rows sorted by gap)``
        per group (label empty without other dimensions)."""
        gap = self.gap_dim
        others = [d for d in self._dims() if d != gap]
        groups = self.data.groupby(others, dropna=False, sort=False) if others else [((), self.data)]
        out = []
        for key, part in groups:
            key = key if isinstance(key, tuple) else (key,)
            named = dict(zip(others, key))
            out.append((_label(list(named.items()), self._units_of(named)), part.sort_values(gap)))
        return out

    def _units_of(self, row: Any) -> dict:
        """The units of the design dimensions of ``row``'s bumper type."""
        return self.units.get(row.get("bumper") if hasattr(row, "get") else None) or self.units.get(None, {})

    def _dims(self) -> list[str]:
        return [c for c in self.data.columns if not _is_metric(c)]


def _label(values: list[tuple[str, Any]], units: dict | None = None) -> str:
    """A design point's other dimensions in words (a bumper type by its name; a dimension another
    bumper type does not have, left out)."""
    words = []
    for dim, value in values:
        if isinstance(value, str):
            words.append(value if dim == "bumper" else f"{dim} {value}")
        elif not math.isnan(value):
            unit = (units or {}).get(dim) or unit_of(dim)
            words.append(f"{dim} {value:g}" + (f" {unit}" if unit and unit not in ("-", "1") else ""))
    return ", ".join(words)


_COLUMNS = (
    "p_contact_design",
    "p_contact_mce",
    "p_contact_years",
    "acc_median_g",
    "acc_pounding_median_g",
    "force_median_n",
    "stripe_g",
    "meets_target",
    "p_capacity_mce",
    "acc_penalty_median",
    "fitted",
    "runs_at_level",
    "pounded_at_level",
    "p_upper_95",
)
_DEMANDS = ("contact", "drift", "acceleration", "top_acceleration", "displacement")


def _is_metric(column: str) -> bool:
    """A column of what a design point gives (not of the design point itself): a probability among them."""
    return column in _COLUMNS or column.startswith("p_")


@fill_doc
def decide(
    analysis: StripeAnalysis | Mapping[str, StripeAnalysis],
    design_sa_g: float,
    mce_sa_g: float,
    *,
    target_probability: float = 0.1,
    level: str = "mce",
    gap_dim: str = "bumpers.gap_m",
    hazard: HazardCurve | None = None,
    years: float = 50.0,
    code_minimum_gap_m: float | None = None,
    free: StripeAnalysis | None = None,
    event: str = "contact",
    limit: float | None = None,
) -> Decision:
    """Choose the gap: the smallest of the grid whose probability of pounding (or of another demand:
    ``event``) at ``level`` is at most ``target_probability``.

    Parameters
    ----------
    analysis : StripeAnalysis or dict of str to StripeAnalysis
        A stripe analysis with bumpers over a grid with a gap dimension, or one per bumper type
        (e.g. ``{"rubber": msa_kv, "hertz": msa_hz}``, each with its own law and grid, over the same
        stripes): the table then has a ``bumper`` column, and the choice is made over them all.
    design_sa_g, mce_sa_g : float
        The design and MCE intensities (g) at the analysis's period (e.g.
        ``asce7_spectrum(...).sa_g(period_s)``).
    target_probability : float
        The largest probability of pounding accepted, in (0, 1).
    level : {"design", "mce"}
        Where the target applies.
    gap_dim : str
        The grid's gap dimension (``"bumpers.gap_m"``).
    hazard : HazardCurve, optional
        The site's curve for the same intensity: adds the probability of pounding in ``years``.
    years : float
        The exposure time (50).
    code_minimum_gap_m : float, optional
        The code's least clearance, reported beside the choice (e.g. ``asce7_displacement``'s
        ``d_tm_m``).
    free : StripeAnalysis, optional
        The same stripes and records on the system without bumpers: adds ``acc_penalty_median``,
        the median over the records of the peak acceleration with bumpers over without, at the
        stripe nearest the MCE intensity (1 for a record that does not pound).
    event : {"contact", "drift", "acceleration", "top_acceleration", "displacement"}
        The demand the target applies to: pounding (default), or exceeding ``limit`` (a building's
        storey drift ratio, its floors' or top floor's peak acceleration in g, its base's displacement in
        m: :data:`EVENTS`).  The table then has its probabilities ``p_<event>_design`` and
        ``p_<event>_mce`` beside pounding's.
    limit : float, optional
        The demand's threshold (needed for every event but contact).

    Returns
    -------
    Decision

    Examples
    --------
    {two_gaps_msa}
    >>> choice = design.decide(msa, 0.3, 0.45, target_probability=0.1)
    >>> columns = ["bumpers.gap_m", "p_contact_design", "p_contact_mce"]
    >>> choice.data[columns].values.round(3)
    array([[0.02 , 0.443, 0.885],
           [0.2  , 0.   , 0.   ]])
    """
    import pandas as pd

    analyses = _analyses(analysis)
    design_sa = positive("design_sa_g", design_sa_g, "g")
    mce_sa = positive("mce_sa_g", mce_sa_g, "g")
    target = positive("target_probability", target_probability, "(a probability)")
    if target >= 1.0:
        raise InputError(Problem.OUT_OF_RANGE, "target_probability", target_probability, range="(0, 1)")
    level = one_of("level", level, LEVELS)
    event = one_of("event", event, _DEMANDS)
    if event != "contact":
        if limit is None:
            raise InputError(Problem.MISSING_INPUT, "limit", None,
                             what=f"the threshold of {event}: {EVENTS[event]}")
        unit = "g" if "acceleration" in event else "(a ratio)" if event == "drift" else "m"
        limit = positive("limit", limit, unit)
    elif limit is not None:
        raise InputError(Problem.WRONG_MODE, "limit", limit, mode="an event other than contact",
                         fix="leave it None for pounding, or name the demand (event='drift', ...)")
    yrs = positive("years", years, "years")
    if hazard is not None:
        instance_of("hazard", hazard, HazardCurve, "pounding.design.HazardCurve or None")
    if design_sa > mce_sa:
        raise InputError(
            Problem.BAD_STATE,
            "design_sa_g",
            design_sa,
            why=f"is above mce_sa_g = {mce_sa:g}",
            fix="give the design level's intensity first, then the MCE level's",
        )
    for name, one in analyses.items():
        _check_analysis(one, "analysis" if name is None else f"analysis[{name!r}]", gap_dim, hazard)
    first_name, first = next(iter(analyses.items()))
    for name, one in analyses.items():
        same = (
            np.array_equal(one.levels_g, first.levels_g)
            and list(one.data["record"].values) == list(first.data["record"].values)
            and one.period_s == first.period_s
            and one.damping_ratio == first.damping_ratio
        )
        if not same:
            raise InputError(
                Problem.BAD_STATE,
                f"analysis[{name!r}]",
                repr(one),
                why=f"has other stripes, records or intensity measure than analysis[{first_name!r}]",
                fix="run every bumper type over the same records, levels_g, period_s and damping",
            )
    code_min = None if code_minimum_gap_m is None else positive("code_minimum_gap_m", code_minimum_gap_m, "m")
    rows = []
    for name, one in analyses.items():
        for row in table_rows(one, design_sa, mce_sa, level, target, hazard, yrs, free, event, limit):
            rows.append(row if name is None else {"bumper": name, **row})
    table = pd.DataFrame(rows)
    dims = [c for c in table.columns if not _is_metric(c)]  # (the design point first, then what it gives)
    table = table[dims + [c for c in table.columns if _is_metric(c)]]
    candidates = table[table["meets_target"]]
    recommended = None
    if len(candidates):
        # at the smallest gap: the least pounding, then the softest pounding (a point where nothing
        # pounded has no such acceleration: it ranks first), then the lowest acceleration
        ranked = candidates.assign(_soft=candidates["acc_pounding_median_g"].fillna(-math.inf))
        by = [gap_dim, f"p_{event}_{level}", "_soft", "acc_median_g"]
        best = ranked.sort_values(by, kind="stable").drop(columns="_soft").iloc[0]
        recommended = {k: _plain(k, v) for k, v in best.items()}
    units = {name: {d: one.unit(d) for d in one.design_dims} for name, one in analyses.items()}
    return Decision(table, recommended, target, level, design_sa, mce_sa, gap_dim, code_min, yrs, units,
                    event, limit)


def _plain(key: str, value: Any) -> Any:
    """A table cell as a plain Python value (the bumper's name, a flag or a number)."""
    if key in ("meets_target", "fitted"):
        return bool(value)
    return value if isinstance(value, str) else float(value)


def _analyses(analysis: Any) -> dict:
    """One stripe analysis (keyed None) or several by bumper type, checked."""
    if isinstance(analysis, Mapping):
        if not analysis:
            raise InputError(
                Problem.EMPTY, "analysis", {}, fix="give at least one stripe analysis, by bumper type"
            )
        for name in analysis:
            if not isinstance(name, str) or not name:  # (an empty name too)
                raise InputError(Problem.WRONG_TYPE, "analysis", name, got=type(name).__name__,
                                 expected="a name (text) per bumper type, e.g. {'rubber': msa}")
        return dict(analysis)
    return {None: analysis}


def _check_analysis(analysis: Any, field: str, gap_dim: str, hazard: HazardCurve | None) -> None:
    instance_of(field, analysis, StripeAnalysis,
                "pounding.design.StripeAnalysis (stripe_analysis), or a dict of them by bumper type")
    if gap_dim not in analysis.design_dims:
        raise InputError(
            Problem.NOT_IN_RESULT, "gap_dim", gap_dim, choices=", ".join(analysis.design_dims) or "none"
        )
    if not analysis.has_bumpers:
        raise InputError(
            Problem.BAD_STATE,
            field,
            repr(analysis),
            why="ran without bumpers",
            fix="run the stripe analysis with bumpers and a grid of gaps",
        )
    if hazard is not None and not math.isclose(hazard.period_s, analysis.period_s, rel_tol=1e-9):
        raise InputError(
            Problem.BAD_STATE,
            "hazard",
            repr(hazard.name or hazard.period_s),
            why=f"is for Sa({hazard.period_s:g} s), but the stripes are of Sa({analysis.period_s:g} s)",
            fix="give the site's hazard curve at the stripes' period",
        )
