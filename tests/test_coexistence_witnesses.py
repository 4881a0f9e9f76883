"""A coexistence map never claims uniqueness it has not shown: each test point is judged by the branch,
the sweeps and a basin sample (issue 48). The calibrated report's own map is read by
tests/test_report_figures.py, which builds the report's campaign and map once for its figures and its
witnesses."""

from __future__ import annotations

import math

import pytest

import pounding as pd_
from pounding.analysis.witnesses import _judged, distinct


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
