"""The reproduce report tells both stories: the exact metrics and the metrics as measured."""

from __future__ import annotations

import pytest

import pounding
import pounding.reports
from pounding.identification.identify import evaluate

SMALL = dict(
    freqs_hz=[1.5, 2.0, 2.5], nbs_a_g=(0.05,), ybs_a_g=(0.05,), directions=("up",), steady="fixed", cycles=10
)


def test_the_report_tells_the_exact_and_the_measured_story(tmp_path):
    ybs = pounding.presets.paper_calibrated()
    chain = pounding.MeasurementChain.lowpass(15.0)
    report = pounding.reports.reproduce(
        ybs.without_bumpers(), ybs, tmp_path / "r", measured=(ybs, chain), **SMALL
    )
    page = report.index_html.read_text()
    assert "Which story" in page and "does not state how its accelerations were filtered" in page
    met = int(evaluate(ybs, pounding.paper_targets(), measurement=chain)["within"].sum())
    assert f"<b>{met} of 36</b>" in page and f"<b>{report.verdict.met} of 36</b>" in page
    assert met != report.verdict.met  # (the two stories differ here: the test can tell them apart)
    for t in ("2", "3", "4"):
        assert (tmp_path / "r" / f"table{t}_measured.csv").is_file()
    assert "fig05_measured" in report.figures and "as measured" in page
    measured_alpha = report.comparisons["2 measured"].set_index("configuration").loc["YBs", "alpha_model"]
    exact_alpha = report.comparisons["2"].set_index("configuration").loc["YBs", "alpha_model"]
    assert measured_alpha < 0.7 * exact_alpha
    plain = pounding.reports.reproduce(ybs.without_bumpers(), ybs, tmp_path / "p", **SMALL)
    assert "Which story" not in plain.index_html.read_text()


def test_a_bad_measured_pair_is_refused_before_any_work(tmp_path):
    ybs = pounding.presets.paper_calibrated()
    with pytest.raises(pounding.InputError, match="measured"):
        pounding.reports.reproduce(ybs.without_bumpers(), ybs, tmp_path / "r", measured=(ybs, 15.0), **SMALL)
