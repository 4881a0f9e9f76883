"""The report's measured stories: the paper's targets with the metrics measured through a chain.

The paper does not state how its accelerations were filtered. :func:`measured_story` runs the campaign
and the verdict again with every window measured through a :class:`~pounding.MeasurementChain` (the
lab pipeline's method), and the page says which story each number tells: the exact metrics, or the
metrics as the lab's instruments would have read them. The same function tells both measured stories:
the contacts timed by their force pulses in the filtered accelerations, and timed by the laser's gap
crossings (the chain's ``contact_timing``); :func:`story_html` words each as its chain reads.
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from typing import Any

import pandas as pd

from ..identification import evaluate, paper_targets
from ..model import MeasurementChain, Oscillator
from .compare import comparison
from .verdict import Verdict, verdict

NO_FILTER_STATED = ("The paper does not state how its accelerations were filtered or sampled: the chain is a "
                    "hypothesis tested against its numbers, not a fact of its test.")
# per contact timing: the section's heading, how the contacts are read, the shipped fit's name
READINGS = {
    "pulse": ("Which story: exact metrics, or as measured?",
              "contacts found on the displacement, confirmed and timed by the filtered force pulses",
              "presets.paper_calibrated_measured()"),
    "laser": ("The story as measured with the contacts timed by the laser",
              "contacts found and timed where the laser's displacement crosses the gap, their speeds from "
              "the laser alone, their forces from the filtered accelerations between the crossings",
              "presets.paper_calibrated_laser()"),
}


@dataclass(frozen=True, eq=False)
class MeasuredStory:
    """The campaign, tables and verdict of a system measured through a chain (:func:`measured_story`).

    Attributes
    ----------
    system : Oscillator
        The YBs system (its NBs: without bumpers).
    chain : MeasurementChain
    campaign : CampaignResult
        The campaign with every window measured through ``chain``.
    comparisons : dict of str to DataFrame
        Tables 2-4 (:func:`comparison`) of that campaign.
    verdict : Verdict
        The paper's targets met with the measured metrics.
    profile : DataFrame or None
        Targets met against the cutoff (a profile of fits at fixed cutoffs), when known.
    exact : Verdict or None
        The same system's verdict with exact metrics (what its measured misses are judged against).
    """

    system: Oscillator
    chain: MeasurementChain
    campaign: Any
    comparisons: dict
    verdict: Verdict
    profile: pd.DataFrame | None = None
    exact: Verdict | None = None


def measured_story(system: Oscillator, chain: MeasurementChain, campaign_of: Any,
                   profile: pd.DataFrame | None = None, evaluate_of: Any = evaluate) -> MeasuredStory:
    """Run ``campaign_of(nbs, ybs, measurement=chain)`` (the report's own campaign call; NBs is
    ``system`` without its bumpers, as the verdict's) and the verdict of ``system`` with the
    metrics measured through ``chain``, and with its own exact metrics (what a miss is judged
    against); ``evaluate_of(system, targets, label=..., **options)`` runs the targets' sweeps."""
    result = campaign_of(system.without_bumpers(), system, measurement=chain)
    tables = {t: comparison(result, t) for t in ("2", "3", "4")}
    timed = ", timed by the laser" if chain.contact_timing == "laser" else ""
    judged = verdict(evaluate_of(system, paper_targets(), label=f"targets as measured{timed}",
                                 measurement=chain))
    own_exact = verdict(evaluate_of(system, paper_targets(), label="targets of the measured system, exact"))
    return MeasuredStory(system, chain, result, tables, judged, profile, own_exact)


def story_html(exact: Verdict, story: MeasuredStory, exact_label: str, table: Any) -> list[str]:
    """The section that says which story the report tells (``table``: the page's table writer), worded
    as the story's chain times the contacts (:data:`READINGS`)."""
    e = html.escape
    cutoff = story.chain.mass.lowpass_hz
    heading, reading, shipped = READINGS[story.chain.contact_timing]
    parts = [
        f"<h2>{e(heading)}</h2>",
        f"<p><b>{e(NO_FILTER_STATED)}</b></p>",
        f"<p>Exact metrics (the model's own peaks and located contacts), {e(exact_label)}: "
        f"<b>{exact.met} of {exact.total}</b> targets met. As measured through the chain "
        f"({e(story.chain.describe())}), the system measured through it: <b>{story.verdict.met} of "
        f"{story.verdict.total}</b> targets met"
        + (f", with the accelerometers' cutoff at {cutoff:.3g} Hz" if cutoff is not None else "")
        + ". Measured metrics are taken as the lab pipeline takes them from a recording (alpha from the "
        f"filtered accelerometers; {e(reading)}).</p>",
    ]
    both = exact.residuals[["configuration", "a_g", "quantity", "target", "model", "within"]].merge(
        story.verdict.residuals[["configuration", "a_g", "quantity", "model", "within"]],
        on=["configuration", "a_g", "quantity"], suffixes=(" exact", " measured"))
    differ = both[both["within exact"] != both["within measured"]]  # (met in one story, missed in the other)
    parts += ["<h3>The targets where the two stories' verdicts differ</h3>",
              f"<p>{len(differ)} target{'s' if len(differ) != 1 else ''} met by one story and missed by the "
              "other; a target both meet or both miss is left out (its values in both stories are in the "
              "tables below).</p>",
              table(differ.rename(columns={"target": "measured (paper)"}))]
    parts += ["<h3>Every target the measured story misses, and why</h3>",
              table(misses_explained(story.exact or exact, story.verdict))]
    if story.profile is not None and len(story.profile):
        parts += ["<h3>Targets met against the cutoff</h3>",
                  "<p>The bumper's pulse-shaping numbers refitted at each fixed cutoff (a local fit from the "
                  "exact calibration: <code>scripts/calibrate_measured.py</code>); the fit with the cutoff "
                  f"free marked shipped is <code>{e(shipped)}</code>.</p>",
                  table(story.profile)]
    return parts


def misses_explained(exact: Verdict, measured: Verdict) -> pd.DataFrame:
    """The targets the measured metrics miss, each with what accounts for it: a consistency check of
    the paper's own numbers that fails (no model meets it), the measurement (the same system's exact
    metrics, ``exact``, meet it), or nothing known (listed as unexplained)."""
    res = measured.residuals.merge(exact.residuals[["configuration", "a_g", "quantity", "within"]],
                                   on=["configuration", "a_g", "quantity"], suffixes=("", "_exact"))
    miss = res[~res["within"]].copy()
    miss["why"] = [
        "the paper's numbers fail a consistency check (no model meets them together)" if flagged
        else "lost to the measurement: the exact metrics meet it" if exact_met
        else "unexplained: the exact metrics miss it too"
        for flagged, exact_met in zip(miss["flagged"], miss["within_exact"])]
    cols = ["configuration", "a_g", "quantity", "target", "model", "normalized", "why"]
    return miss[cols].rename(columns={"target": "measured (paper)", "normalized": "in tolerances"}
                             ).reset_index(drop=True)
