"""A coexistence map never claims uniqueness it has not shown: each test point is judged by the branch,
the sweeps and a basin sample (issue 48)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pounding as pd_
from pounding.analysis.witnesses import _judged, distinct
from pounding.reports.branches import coexistence_of


@pytest.fixture(scope="module")
def calibrated_map():
    """The calibrated report's coexistence data: its campaign's YBs sweeps at a_G 0.05 and 0.1, up and
    down over the paper's grid (adaptive), and the map over them, as ``pounding reproduce`` builds it."""
    ybs = pd_.presets.paper_calibrated()
    result = pd_.campaign(None, ybs, ybs_a_g=(0.05, 0.1))
    cmap, why_not = coexistence_of(result, ybs)
    assert cmap is not None, why_not
    return result, cmap


@pytest.mark.parametrize("a_g, freqs", [(0.05, (2.0, 2.1, 2.2, 2.3)), (0.1, (2.7, 2.8, 2.9, 3.0))])
def test_the_calibrated_report_finds_coexistence_where_its_sweeps_differ(calibrated_map, a_g, freqs):
    result, cmap = calibrated_map
    m = cmap.matrix
    for f in freqs:
        row = m[np.isclose(m["a_g"], a_g) & np.isclose(m["freq_hz"], f)].iloc[0]
        # the witnesses: two settled sweeps on different responses, and a basin sample finding both
        up = result.sweeps[("YBs", a_g, "up")].exact_dataframe().set_index("freq_hz")
        down = result.sweeps[("YBs", a_g, "down")].exact_dataframe().set_index("freq_hz")
        assert up.loc[f, "steady"] and down.loc[f, "steady"]
        a_up, a_down = up.loc[f, "alpha"], down.loc[f, "alpha"]
        assert abs(a_up - a_down) > 0.5 * max(a_up, a_down)
        assert row["sweep_responses"] == 2 and row["basin_responses"] >= 2, row["evidence"]
        assert row["verdict"] == "coexist" and row["responses"] >= 2, row["evidence"]
        assert "sweeps settled" in row["evidence"] and "basin sample" in row["evidence"]


def test_no_point_of_the_calibrated_map_claims_one_response_without_a_sample_that_agrees(calibrated_map):
    _, cmap = calibrated_map
    m = cmap.matrix
    one = m[m["verdict"] == "one"]
    assert len(one) and (one["basin_responses"] == 1).all() and (one["basin_not_settled"] == 0).all()
    assert ((one["stable_orbits"] == 1) | (one["sweep_responses"] == 1)).all()
    # a point no witness reaches is never drawn as one response
    unreached = m[~m["branch_reached"] & m["sweep_responses"].isna() & m["basin_responses"].isna()]
    assert (unreached["verdict"] == "not assessed").all()
    assert set(m["verdict"]) <= {"coexist", "one", "not assessed"}


def test_the_map_draws_each_verdict_with_its_own_label(calibrated_map):
    import matplotlib

    matplotlib.use("Agg")
    _, cmap = calibrated_map
    assert cmap.plot().__class__.__name__ == "Figure"
    artists = pd_.plots.plot_curves(list(cmap.curves), matrix=cmap.matrix)
    labels = {a.get_label() for a in artists}
    assert any(lbl.startswith("two or more responses coexist") for lbl in labels)
    assert any(lbl.startswith("one response: a basin sample agrees") for lbl in labels)
    if (cmap.matrix["verdict"] == "not assessed").any():
        assert any(lbl.startswith("not assessed") for lbl in labels)
    assert not any("one stable response" in lbl for lbl in labels)


def _row(stable=math.nan, reached=True, sweeps=math.nan, basin=math.nan, unsettled=0.0):
    return {"a_g": 0.05, "freq_hz": 2.0, "stable_orbits": stable, "branch_reached": reached,
            "sweep_responses": sweeps, "basin_responses": basin, "basin_not_settled": unsettled,
            "evidence_sweeps": ""}


@pytest.mark.parametrize("row, sample, verdict", [
    (_row(stable=2.0), 4, "coexist"),                                      # the branch's two stable orbits
    (_row(stable=1.0, sweeps=2.0, basin=1.0), 4, "coexist"),       # the sweeps: what the branch missed
    (_row(stable=1.0, basin=2.0), 4, "coexist"),                           # an isola the basin sample found
    (_row(stable=1.0, basin=1.0), 4, "one"),                               # the sample agrees with the branch
    (_row(stable=math.nan, reached=False, sweeps=1.0, basin=1.0), 4, "one"),  # ... with the sweeps
    (_row(stable=1.0, basin=1.0, unsettled=0.25), 4, "not assessed"),      # a quarter of the sample unsettled
    (_row(stable=math.nan, reached=False, basin=1.0), 4, "not assessed"),  # the sample alone
    (_row(stable=0.0, basin=math.nan), 4, "not assessed"),                 # no stable orbit on the branch
    (_row(stable=1.0), 0, "one on the branch"),                            # no sample taken
    (_row(stable=math.nan, reached=False), 0, "not assessed"),             # nothing reached the point
])
def test_the_verdict_rule(row, sample, verdict):
    out = _judged(row, sample)
    assert out["verdict"] == verdict, out["evidence"]


def test_distinct_responses_merge_families_and_mirror_images_not_jumps():
    # a kinematic element's family of shifted orbits, alpha spread by small steps: one response
    family = [(1, True, a, 0.0175) for a in (10.62, 10.78, 10.90, 11.10, 11.33)]
    assert distinct(family) == 1
    assert distinct([(1, True, 22.49, 0.017), (1, True, 22.49, 0.017)]) == 1  # mirror images
    assert distinct([(1, True, 37.1, 0.031), (1, False, 1.05, 0.022)]) == 2  # the jump of the sweeps
    assert distinct([(1, True, 20.5, 0.017), (3, True, 24.8, 0.0176)]) == 2  # another period


def test_bad_witness_arguments_are_named():
    osc = pd_.presets.paper_damped()
    with pytest.raises(pd_.InputError, match="basin_sample"):
        pd_.coexistence_map(osc, a_g=(0.04, 0.06), freqs_hz=(1.5, 2.5), levels=[0.05], basin_sample=1)
    with pytest.raises(pd_.InputError, match="sweeps"):
        pd_.coexistence_map(osc, a_g=(0.04, 0.06), freqs_hz=(1.5, 2.5), levels=[0.05], sweeps=["up"])
