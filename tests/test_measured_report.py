"""The reproduce report tells both stories: the exact metrics and the metrics as measured."""

from __future__ import annotations

import pytest

import pounding
import pounding.reports
from pounding.identification.identify import evaluate

SMALL = dict(
    freqs_hz=[1.5, 2.0, 2.5], nbs_a_g=(0.05,), ybs_a_g=(0.05,), directions=("up",), steady="fixed", cycles=10
)


@pytest.fixture(scope="module")
def stories(tmp_path_factory):
    """One report that tells all three stories (the checks of each read it: a report per story cost
    a verdict's evaluation each time)."""
    ybs = pounding.presets.paper_calibrated()
    pulse = pounding.MeasurementChain.lowpass(15.0)
    laser = pounding.MeasurementChain.lowpass(15.0, contact_timing="laser")
    out = tmp_path_factory.mktemp("stories")
    report = pounding.reports.reproduce(ybs.without_bumpers(), ybs, out, measured=(ybs, pulse),
                                        laser=(ybs, laser), **SMALL)
    return ybs, pulse, laser, report


def test_the_report_tells_the_exact_and_the_measured_story(stories):
    ybs, chain, _, report = stories
    page = report.index_html.read_text()
    assert "Which story" in page and "does not state how its accelerations were filtered" in page
    met = report.measured.verdict.met
    assert f"<b>{met} of 36</b>" in page and f"<b>{report.verdict.met} of 36</b>" in page
    assert met != report.verdict.met  # (the two stories differ here: the test can tell them apart)
    for t in ("2", "3", "4"):
        assert (report.out_dir / f"table{t}_measured.csv").is_file()
    assert "fig05_measured" in report.figures and "as measured" in page
    assert "lost to the measurement" in page and "and why" in page
    assert report.measured.campaign.data.attrs["measurement"] == chain.describe()
    assert report.campaign.data.attrs["measurement"] == "exact"
    measured_alpha = report.comparisons["2 measured"].set_index("configuration").loc["YBs", "alpha_model"]
    exact_alpha = report.comparisons["2"].set_index("configuration").loc["YBs", "alpha_model"]
    assert measured_alpha < 0.7 * exact_alpha
    # (a report asked for the exact story alone tells no other: tests/test_report.py reads its small report)


def test_a_bad_measured_pair_is_refused_before_any_work(tmp_path):
    ybs = pounding.presets.paper_calibrated()
    with pytest.raises(pounding.InputError, match="measured"):
        pounding.reports.reproduce(ybs.without_bumpers(), ybs, tmp_path / "r", measured=(ybs, 15.0), **SMALL)


def test_every_measured_miss_is_explained_or_listed_as_unexplained():
    from pounding.reports.measured_story import misses_explained
    from pounding.reports.verdict import verdict

    exact_res = pounding.presets.residuals()
    measured_res = exact_res.copy()
    lost = measured_res.index[measured_res["within"]][:2]  # two targets the measurement loses
    measured_res.loc[lost, "within"] = False
    exact, measured = verdict(exact_res), verdict(measured_res)
    table = misses_explained(exact, measured)
    assert len(table) == 36 - measured.met
    why = dict(zip(zip(table["configuration"], table["a_g"], table["quantity"]), table["why"]))
    for i in lost:
        row = measured_res.loc[i]
        assert why[(row["configuration"], row["a_g"], row["quantity"])].startswith("lost to the measurement")
    flagged = measured.residuals[measured.residuals["flagged"] & ~measured.residuals["within"]]
    assert len(flagged) and all(
        why[(r.configuration, r.a_g, r.quantity)].startswith("the paper's numbers")
        for r in flagged.itertuples()
    )
    assert any(w.startswith("unexplained") for w in table["why"])


def test_the_command_line_refuses_both_stories_flags():
    from typer.testing import CliRunner

    from pounding.cli import app

    result = CliRunner().invoke(app, ["reproduce", "--exact-only", "--lowpass-hz", "15"])
    assert result.exit_code == 2 and "not both" in result.output


def test_the_report_tells_a_third_story_with_the_contacts_timed_by_the_laser(stories, tmp_path):
    ybs, pulse, laser, report = stories
    page = report.index_html.read_text()
    # one function tells both measured stories, each in its own section with its own count
    assert "Which story" in page and "The story as measured with the contacts timed by the laser" in page
    met = int(evaluate(ybs, pounding.paper_targets(), measurement=laser)["within"].sum())
    assert report.laser.verdict.met == met and f"<b>{met} of 36</b>" in page
    assert report.laser.verdict.met != report.measured.verdict.met  # (the stories differ: told apart)
    assert "where the laser&#x27;s displacement crosses the gap" in page
    for t in ("2", "3", "4"):
        assert (report.out_dir / f"table{t}_laser.csv").is_file()
        assert (report.out_dir / f"table{t}_measured.csv").is_file()
    assert {"fig05_measured", "fig05_laser"} <= set(report.figures)
    assert report.laser.campaign.data.attrs["measurement"] == laser.describe()
    # the laser keeps the contacts short where the filtered force pulses stretch them
    t3 = {k: report.comparisons[f"3 {k}"].set_index("a_g")["contact_time_ms_model"]
          for k in ("measured", "laser")}
    assert t3["laser"].loc[0.05] < 0.7 * t3["measured"].loc[0.05]
    # a chain that times the contacts by their pulses is not the laser's story
    with pytest.raises(pounding.InputError, match="contact_timing") as err:
        pounding.reports.reproduce(ybs.without_bumpers(), ybs, tmp_path / "x", laser=(ybs, pulse), **SMALL)
    assert err.value.field == "laser"


def test_the_command_line_leaves_the_laser_story_out_when_told(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    grid = ["--fmin", "1.5", "--fmax", "2.0", "--fstep", "0.5", "--no-stands", "--out", str(tmp_path / "r")]
    told = CliRunner().invoke(app, ["reproduce", "--lowpass-hz", "20", "--no-laser", *grid])
    assert told.exit_code == 0, told.output
    said = " ".join(told.output.split())
    assert "as measured (sampled at 1000 Hz" in said and "timed by the laser" not in said
    assert not (tmp_path / "r" / "table2_laser.csv").exists()
