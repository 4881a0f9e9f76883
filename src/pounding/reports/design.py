"""The design report: the verdict first, then the hazard, the scaled suite, the responses, the
fragility curves and the design chart, as one self-contained HTML page with its CSV tables."""

from __future__ import annotations

import html
from pathlib import Path
from typing import Any

import pandas as pd

from .._io import atomic_write, write_text
from .html import CSS, figure_html

ONE_DIRECTION = ("The records are single horizontal components and the mass moves in one direction: the "
                 "codes' maximum-direction or SRSS spectra of two components are not formed.")
IN_PLAN = ("Each run takes a pair's two components at once, in the building's axes as recorded; each pair is "
           "scaled by one factor (its maximum-direction spectrum, RotD100, for the intensity measure and the "
           "suite's scaling). A run pounds when a corner of the floor the moat surrounds strikes a wall; the "
           "code's clearance is its total maximum displacement D_TM with the building's torsion (actual and "
           "5 % accidental eccentricity). Other orientations of the pairs are not run: pounding.orientations "
           "and pounding moat turn them.")
NOTES = (
    "The intensity measure is the pseudo-spectral acceleration at the stated period, with the stated "
    "damping, of each record as the engine sees it (linear between samples); each record is scaled to each "
    "stripe by its own factor.",
    "A run pounds when it has at least one impact. The fragility of pounding is lognormal, fitted by maximum "
    "likelihood to the stripes (binomial likelihood); its band is a 90 % bootstrap band (records "
    "resampled, each with its runs at every stripe). Where no curve can be fitted (no run pounds, every "
    "run does, or the outcomes separate between stripes) the probability is the runs' own fraction, "
    "linear between stripes, and blank outside them "
    "unless an end stripe settles it (0 below a stripe where no run pounded, 1 above one where all did).",
    "'Runs at level' and 'pounded at level' are the runs at the stripe nearest the target's level; 'P 95 % "
    "upper' is the largest probability those runs allow at 95 % confidence (Clopper-Pearson): when it is "
    "above the target, the runs cannot show the target is met, and the verdict says so.",
    "The probability in the exposure time needs the site's hazard curve for the same intensity and a fitted "
    "curve; it is blank for a design point without one.",
    ONE_DIRECTION,
    "A run that stopped early (over its budget, a Zeno sequence) counts when it had already pounded, and "
    "is left out otherwise; the table of statuses says how many stopped.",
)


COLUMN_WORDS = {
    "bumper": "bumper type",
    "bumpers.gap_m": "gap [m]",
    "bumpers.law.stiffness": "bumper stiffness [N/m]",
    "p_contact_design": "P(pounding | design)",
    "p_contact_mce": "P(pounding | MCE)",
    "p_capacity_mce": "P(compression > capacity | MCE)",
    "p_contact_years": "P(pounding in the exposure time)",
    "fitted": "lognormal fitted",
    "runs_at_level": "runs at level",
    "pounded_at_level": "pounded at level",
    "p_upper_95": "P 95 % upper",
    "acc_median_g": "peak acceleration, median [g]",
    "acc_pounding_median_g": "peak acceleration of the runs that pounded, median [g]",
    "force_median_n": "impact force, median [N]",
    "acc_penalty_median": "acceleration with / without bumpers",
    "stripe_g": "stripe of the medians [g]",
    "meets_target": "meets the target",
}


def _words(plan: Any, decision: Any) -> dict:
    """The decision table's column names in words: the gap's, and the chosen event's probabilities."""
    words = dict(COLUMN_WORDS)
    words[plan.gap_dim] = "moat gap [m]" if plan.building else "gap [m]"
    if plan.building:  # (a building's walls are its moat's)
        words["acc_penalty_median"] = "acceleration with / without the moat"
    if decision.event != "contact":
        for lvl, at in (("design", " | design"), ("mce", " | MCE"), ("years", " in the exposure time")):
            words[f"p_{decision.event}_{lvl}"] = f"P({decision.event_words()}{at})"
    return words


RESPONSE_COLUMNS = ("stripe_g", "acc_median_g", "acc_pounding_median_g", "force_median_n",
                    "acc_penalty_median")
VERDICT_COLUMNS = ("meets_target", "fitted", "runs_at_level", "pounded_at_level", "p_upper_95")


def _verdict_tables(table: pd.DataFrame, words: dict) -> str:
    """The decision table as two that fit a page: the design numbers with the probabilities and the
    verdict, then with the responses at the stripe nearest the level; columns with no value left out
    (``decision.csv`` has them all)."""
    empty = [c for c in table.columns if table[c].isna().all()]
    shown = table.drop(columns=empty)
    known = set(RESPONSE_COLUMNS) | set(VERDICT_COLUMNS)
    dims = [c for c in shown.columns if c not in known and not c.startswith("p_")]
    probs = [c for c in shown.columns if c.startswith("p_") and c != "p_upper_95"]
    first = dims + [c for c in VERDICT_COLUMNS[:1] if c in shown] + probs + [
        c for c in VERDICT_COLUMNS[1:] if c in shown]
    second = dims + [c for c in RESPONSE_COLUMNS if c in shown]
    note = ("" if not empty else "<p class='tnote'>Left out, with no value at any design point: "
            + html.escape(", ".join(words.get(c, c) for c in empty))
            + " (decision.csv has every column).</p>")
    return (_table(shown[first].rename(columns=words)) + "<p class='tnote'>What the runs at the stripe "
            "nearest the level show, per design point:</p>" + _table(shown[second].rename(columns=words))
            + note)


def _table(df: pd.DataFrame) -> str:
    return (
        "<div class='wide'>"
        + df.to_html(index=False, float_format=lambda x: f"{x:.4g}", na_rep="\u2013", border=0)
        + "</div>"
    )


def _save(fig: Any, path: Path) -> Path:
    import matplotlib.pyplot as plt

    try:
        atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=130))
    finally:
        plt.close(fig)
    return path


def figures(outcome: Any, folder: Path) -> dict[str, tuple[Path, str]]:
    """The report's figures as PNG files in ``folder``: name -> (path, caption)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plots.design import plot_responses

    plan, decision = outcome.plan, outcome.decision
    out = {}
    fig, ax = plt.subplots(figsize=(6.5, 4.0), constrained_layout=True)
    plan.design_spectrum.plot(ax=ax)
    plan.mce_spectrum.plot(ax=ax)
    ax.axvline(plan.period_s, color="k", lw=0.8, ls=":")
    out["Hazard: the target spectra"] = (
        _save(fig, folder / "spectra.png"),
        f"design and MCE level spectra; dotted: the intensity measure's period {plan.period_s:g} s",
    )
    if plan.hazard is not None:
        fig, ax = plt.subplots(figsize=(6.0, 4.0), constrained_layout=True)
        plan.hazard.plot(ax=ax)
        out["Hazard curve"] = (
            _save(fig, folder / "hazard_curve.png"),
            "the site's annual frequency of exceedance",
        )
    fig, ax = plt.subplots(figsize=(6.5, 4.0), constrained_layout=True)
    outcome.suite.plot(ax=ax)
    out["The suite scaled to the MCE level"] = (
        _save(fig, folder / "suite.png"),
        "each record (grey), their mean and the target over the scaling "
        "range; the stripes scale each record on its own",
    )
    analyses = outcome.analyses
    several = len(analyses) > 1
    fig, axes = plt.subplots(
        len(analyses), 2, figsize=(11.0, 4.0 * len(analyses)), constrained_layout=True, squeeze=False
    )
    shown = ("top_acc_max_g", "drift_ratio_max") if plan.building else ("acc_max_g", "impact_force_max_n")
    for row, (name, analysis) in zip(axes, analyses.items()):
        plot_responses(analysis, shown[0], ax=row[0])
        plot_responses(analysis, shown[1], ax=row[1])
        if several:
            row[0].set_title(f"{name} bumpers", fontsize=10)
    out["Responses"] = (
        _save(fig, folder / "responses.png"),
        ("the top floor's peak absolute acceleration and the largest storey drift ratio: " if plan.building
         else "")
        + "median over the records (16-84 % shaded) per stripe, one colour per gap (the other "
        f"design numbers at their first value){'; one row per bumper type' if several else ''}",
    )
    fig, axes = plt.subplots(
        1, len(analyses), figsize=(6.5 * len(analyses), 4.0), constrained_layout=True, squeeze=False
    )
    for ax, (name, analysis) in zip(axes[0], analyses.items()):
        analysis.plot(plan.event, plan.limit, ax=ax)
        if several:
            ax.set_title(f"{name} bumpers", fontsize=10)
    out[f"Fragility of {decision.event_words()}"] = (
        _save(fig, folder / "fragility.png"),
        f"fraction of runs with {'an impact' if plan.event == 'contact' else decision.event_words()} per "
        "stripe, and the fitted lognormal curves"
        f"{'; one panel per bumper type' if several else ''}",
    )
    fig, axes = plt.subplots(2, 2, figsize=(11.0, 8.0), constrained_layout=True)
    _cost(decision, axes.ravel(), "the moat" if plan.building else "bumpers")
    out["What pounding costs"] = (
        _save(fig, folder / "cost.png"),
        f"median over the records at the stripe nearest the MCE level "
        f"({decision.data['stripe_g'].iloc[0]:g} g) against the gap, one line per "
        "value of the other design numbers; the last panel: the median over the runs that pounded (the "
        "bumper options told apart where few runs pound)",
    )
    fig, ax = plt.subplots(figsize=(6.5, 4.0), constrained_layout=True)
    decision.plot(ax=ax)
    out["Design chart"] = (
        _save(fig, folder / "design_chart.png"),
        f"the probability of {decision.event_words()} at the design and MCE levels against the gap",
    )
    return out


def _cost(decision: Any, axes: Any, walls: str = "bumpers") -> None:
    """Median peak acceleration, its penalty (with the ``walls``, bumpers or the moat, over without), impact
    force, and peak acceleration of the runs that pounded against the gap, per value of the other
    dimensions."""
    gap = decision.gap_dim
    columns = (
        ("acc_median_g", "peak absolute acceleration (g)"),
        ("acc_penalty_median", f"peak acceleration with {walls} / without"),
        ("force_median_n", "peak impact force (N)"),
        ("acc_pounding_median_g", "peak acceleration of the runs that pounded (g)"),
    )
    for label, part in decision.by_gap():
        label = label or "median"
        for ax, (column, _) in zip(axes, columns):
            ax.plot(1e3 * part[gap], part[column], "o-", ms=3, label=label)
    for ax, (_, words) in zip(axes, columns):
        ax.set_xlabel("gap [mm]")
        ax.set_ylabel(words)
        ax.legend(fontsize=8)


def _statuses(name: str, analysis: Any) -> dict:
    """How many runs of one analysis are done, finished, or stopped early."""
    status = analysis.data["status"].where(analysis.data["done"] == 1)
    return {
        "bumper type": name,
        "runs": int(analysis.data["done"].size),
        "done": int(analysis.data["done"].sum()),
        "finished (SUCCESS)": int((status == 0.0).sum()),
        "stopped early": int(((status != 0.0) & status.notnull()).sum()),
    }


def write_report(outcome: Any, folder: Path) -> Path:
    """Write ``folder/index.html`` and its CSV tables (``decision.csv``, ``runs.csv``,
    ``fragility.csv``, ``suite.csv``); returns the page's path."""
    e = html.escape
    plan, decision = outcome.plan, outcome.decision
    folder.mkdir(parents=True, exist_ok=True)
    table = decision.to_dataframe()
    frag_rows = [
        {
            **dict(at),
            "median_g": f.median_g,
            "beta": f.beta,
            "median_lo_g": f.interval()["median_g"][0],
            "median_hi_g": f.interval()["median_g"][1],
            "beta_lo": f.interval()["beta"][0],
            "beta_hi": f.interval()["beta"][1],
            "resamples_without_estimate": f.n_failed_resamples,
        }
        for at, f in outcome.fragilities.items()
    ]
    fragility = pd.DataFrame(frag_rows)
    suite = outcome.suite.to_dataframe()
    several = len(outcome.analyses) > 1
    statuses = pd.DataFrame([_statuses(name, a) for name, a in outcome.analyses.items()])
    runs = pd.concat(
        [
            a.to_dataframe().assign(**({"bumper": name} if several else {}))
            for name, a in outcome.analyses.items()
        ],
        ignore_index=True,
    )
    for name, df in (
        ("decision", table),
        ("fragility", fragility),
        ("suite", suite),
        ("runs", runs),
    ):
        atomic_write(folder / f"{name}.csv", lambda tmp, df=df: df.to_csv(tmp, index=False))
    figs = figures(outcome, folder)
    settings = pd.DataFrame(
        [
            {"item": "site", "value": f"{plan.design_spectrum.name}; MCE level: {plan.mce_spectrum.name}"},
            {"item": "intensity measure", "value": f"PSa({plan.period_s:g} s), 5 % damping"},
            {
                "item": "design / MCE intensity",
                "value": f"{decision.design_sa_g:.4g} g / {decision.mce_sa_g:.4g} g",
            },
            {"item": "records", "value": f"{len(plan.records)} ({plan.records[0]} ...)"},
            {"item": "stripes (g)", "value": ", ".join(f"{x:g}" for x in plan.levels_g)},
            *(
                {
                    "item": f"design grid{f' of the {kind.name} bumpers' if several else ''}",
                    "value": "; ".join(
                        f"{k}: {', '.join(f'{v:g}' for v in vals)}" for k, vals in kind.grid.items()
                    ),
                }
                for kind in plan.kinds
            ),
            {
                "item": "target",
                "value": f"P({decision.event_words()} | {'MCE' if plan.level == 'mce' else 'design'}) <= "
                f"{plan.target_probability:g}",
            },
        ]
    )
    parts = [
        f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{e(plan.title)}</title>",
        f"<style>{CSS}</style></head><body>",
        f"<h1>{e(plan.title)}</h1>",
        "<h2>Verdict</h2>",
        f"<p><b>{e(decision.verdict())}</b></p>",
        _verdict_tables(table, _words(plan, decision)),
        "<h2>The design</h2>",
        _table(settings),
        _table(statuses),
        f"<h2>Fragility of {e(decision.event_words())} per design point</h2>",
        _table(fragility) if len(fragility) else "<p>No design point has a fitted curve.</p>",
        "<h2>The suite scaled to the MCE level</h2>",
        f"<p>One factor for the suite so that its mean{' RotD100' if plan.in_plan else ''} is not below the "
        f"MCE spectrum from "
        f"{plan.scale_range_s[0]:g} to {plan.scale_range_s[1]:g} s: "
        f"x {outcome.suite.factors[0]:.4g}.</p>",
        "<h2>Figures</h2>",
    ]
    for name, (png, caption) in figs.items():
        parts.append(figure_html(name, png, caption))
    parts.append("<h2>System</h2>")
    for kind in plan.kinds:
        parts += [f"<h3>{e(kind.name)} bumpers</h3>" if several else "", f"<pre>{e(repr(kind.system))}</pre>"]
    parts.append("<h2>Reading the results</h2><ul>")
    parts += [f"<li>{e(IN_PLAN if n == ONE_DIRECTION and plan.in_plan else n)}</li>" for n in NOTES]
    parts += ["</ul></body></html>"]
    page = folder / "index.html"
    write_text(page, "\n".join(parts))
    return page
