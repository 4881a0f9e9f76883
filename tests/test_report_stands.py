"""The report's test of the stands hypothesis (``reproduce(..., stands=True)``, ``pounding reproduce`` by
default): the YBs system on four stands, each evaluated on the paper's targets; its numbers are those of
the shipped scan of the calibrated preset, its verdict follows them, and the page and ``stands.csv`` hold
it."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import pounding as pd_
from pounding.identification import evaluate
from pounding.reports.stands import STAND_MASS_KG, STAND_STIFFNESSES_N_M, _verdict, stands_test


def test_the_calibrated_preset_on_stands_is_the_shipped_scan_and_says_no():
    own = pd_.presets.residuals()
    test = stands_test(pd_.presets.paper_calibrated(), own, lambda system, targets, label: evaluate(system,
                                                                                                    targets))
    scan = pd_.presets.rig_stands_scan()
    for k in STAND_STIFFNESSES_N_M:
        row = test.table[test.table["stiffness [N/m]"] == k].iloc[0]
        ref = scan[(scan["mass_kg"] == STAND_MASS_KG) & (scan["stiffness_n_m"] == k)].iloc[0]
        assert row["targets met"] == ref["met"]
        for a in (0.05, 0.075, 0.1):
            np.testing.assert_allclose(row[f"YBs alpha {a:g}"], ref[f"alpha_{a:g}"], rtol=1e-9)
            np.testing.assert_allclose(row[f"contact time [ms] {a:g}"], ref[f"contact_time_ms_{a:g}"],
                                       rtol=1e-9)
    assert test.verdict.startswith("No: no stand tried brings every YBs acceleration within its tolerance")
    assert "40.3, 31.0, 32.4 (without stands 40.3, 31.3, 32.6)" in test.verdict
    measured = test.table.iloc[-1]
    assert measured["YBs alpha 0.05"] == 16.8 and measured["contact time [ms] 0.1"] == 31.0
    assert stands_test(pd_.presets.paper_calibrated(bumpers=False), own, None) is None


def _table(alphas_met: list[int], times_met: list[int]) -> pd.DataFrame:
    rows = [{"stand": f"{k:g}", "stiffness [N/m]": k, "targets met": 20 + i, "YBs alphas met": a,
             "contact times met": c, **{f"YBs alpha {g:g}": 30.0 for g in (0.05, 0.075, 0.1)}}
            for i, (k, a, c) in enumerate(zip(STAND_STIFFNESSES_N_M, alphas_met, times_met))]
    alone = {f"YBs alpha {g:g}": 40.0 for g in (0.05, 0.075, 0.1)}
    rows.append({"stand": "none (the system as it is)", "stiffness [N/m]": np.nan, "targets met": 27,
                 "YBs alphas met": 0, "contact times met": 2, **alone})
    return pd.DataFrame(rows)


@pytest.mark.parametrize("alphas, times, words", [
    ([0, 3, 3, 3], [3, 3, 1, 0], "on stands of 1e7 N/m (10 kg) the YBs accelerations and the contact times"),
    ([0, 3, 3, 3], [3, 3, 1, 0], "this stand is 1.4 times softer than the softest"),
    ([3, 0, 0, 0], [3, 0, 0, 0], "this stand is stiffer than that"),
    ([0, 0, 3, 3], [2, 2, 1, 3], "Yes: on stands of 1e5 N/m"),
    ([0, 0, 3, 3], [2, 2, 1, 2], "No: the YBs accelerations are met only on stands of 1e6 N/m and softer"),
    ([0, 0, 3, 3], [2, 2, 1, 2], "(14 times softer than a steel post; a steel post is 1.4e7 to 9.8e7 N/m)"),
])
def test_the_verdict_follows_the_table(alphas, times, words):
    assert words in _verdict(_table(alphas, times))


def test_the_report_holds_the_section_and_its_table(tmp_path):
    ybs = pd_.presets.paper_damped()
    small = dict(freqs_hz=[1.5, 2.0], nbs_a_g=(0.05,), ybs_a_g=(0.05,), directions=("up",), steady="fixed",
                 cycles=5)
    report = pd_.reports.reproduce(ybs.without_bumpers(), ybs, tmp_path, stands=True, **small)
    assert report.stands is not None and report.tables["stands"].name == "stands.csv"
    table = pd.read_csv(report.tables["stands"])
    assert len(table) == len(STAND_STIFFNESSES_N_M) + 2
    page = report.index_html.read_text()
    assert "Do the bumpers' stands explain the YBs accelerations?" in page
    assert report.stands.verdict.split(":")[0] in page
    # (a report without stands=True has no such section: tests/test_report.py reads its small report)
