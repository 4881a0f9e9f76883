"""``pounding design``: a design file read and checked, run end to end, resumed; bad files named."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import pounding
from pounding.cli import app
from pounding.design.plan import DesignPlan

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()

SMALL = """
title = "small"
[system]
preset = "paper-calibrated"
[bumpers]
gap_left = 0.1
gap_right = 0.1
[bumpers.law]
type = "kelvin_voigt"
stiffness = 1.5e6
damping = 400.0
[site]
code = "asce7-16"
s_ds_g = 1.0
s_d1_g = 0.6
hazard_curve = "hazard.csv"
[records]
suite = ["el-centro", "fema-p695:far_field:0", "fema-p695:far_field:1"]
period_s = 1.0
levels_g = [0.3, 0.6, 0.9]
[design]
gaps_m = [0.05, 0.15, 0.3]
target_probability = 0.5
t_m_s = 1.0
beta_m = 0.15
[run]
scheduler = "serial"
"""


def write(tmp_path: Path, text: str = SMALL) -> Path:
    (tmp_path / "hazard.csv").write_text((ROOT / "examples" / "ups_hazard_sa1.csv").read_text())
    path = tmp_path / "design.toml"
    path.write_text(text)
    return path


def test_the_example_design_file_reads():
    plan = DesignPlan.from_toml(ROOT / "examples" / "design_ups.toml")
    assert len(plan.records) == 44 and plan.levels_g.size == 10
    assert plan.grid == {
        "bumpers.gap": [0.05, 0.1, 0.15, 0.2, 0.25],
        "bumpers.law.stiffness": [0.5e6, 1.5e6, 4.5e6],
    }
    assert plan.mce_spectrum.sa_g(1.0) == pytest.approx(0.9)
    assert plan.code_minimum_gap_m == pytest.approx(1.15 * 9.80665 * 0.9 * 1.0 / (4 * math.pi**2 * 1.35))
    assert plan.hazard is not None and plan.hazard.period_s == 1.0
    assert isinstance(plan.system.bumpers.law, pounding.KelvinVoigt)


@pytest.mark.parametrize(
    "change, field",
    [
        (("gaps_m = [0.05, 0.15, 0.3]", "gaps_m = [0.05, -0.15]"), "design.gaps_m[1]"),
        (("gaps_m = [0.05, 0.15, 0.3]", "gaps_m = [0.15, 0.05]"), "design.gaps_m"),
        (("target_probability = 0.5", "target_probability = 1.5"), "design.target_probability"),
        (("levels_g = [0.3, 0.6, 0.9]", "levels_g = [0.6, 0.3]"), "records.levels_g"),
        (("s_d1_g = 0.6", "sd1 = 0.6"), "site.sd1"),
        (('code = "asce7-16"', 'code = "nbc"'), "site.code"),
        (("period_s = 1.0", "period_s = -1.0"), "records.period_s"),
        (('hazard_curve = "hazard.csv"', 'hazard_curve = "nope.csv"'), "site.hazard_curve"),
        (("[run]", "[runs]"), "runs"),
    ],
)
def test_a_bad_design_file_is_named_before_any_work(tmp_path, change, field):
    path = write(tmp_path, SMALL.replace(*change))
    with pytest.raises(pounding.InputError) as err:
        DesignPlan.from_toml(path)
    assert err.value.field == field
    result = runner.invoke(app, ["design", str(path), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and field in result.output
    assert not (tmp_path / "out").exists()


def test_an_en1998_site(tmp_path):
    text = SMALL.replace(
        'code = "asce7-16"\ns_ds_g = 1.0\ns_d1_g = 0.6', 'code = "en1998-1"\na_gr_g = 0.25\nground_type = "C"'
    ).replace("t_m_s = 1.0\nbeta_m = 0.15\n", "")
    plan = DesignPlan.from_toml(write(tmp_path, text))
    assert plan.design_spectrum.kind == "en1998-1"
    assert plan.mce_spectrum.sa_g(1.0) == pytest.approx(1.5 * plan.design_spectrum.sa_g(1.0), rel=1e-12)
    with pytest.raises(pounding.InputError, match="ASCE 7-16"):
        DesignPlan.from_toml(
            write(tmp_path, text.replace("target_probability = 0.5", "target_probability = 0.5\nt_m_s = 1.0"))
        )


def test_pounding_design_runs_reports_and_resumes(tmp_path):
    path = write(tmp_path)
    out = tmp_path / "report"
    result = runner.invoke(app, ["design", str(path), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "27 runs" in result.output and "code's minimum clearance" in result.output
    page = (out / "index.html").read_text()
    assert "Verdict" in page and "Design chart" in page and "data:image/png;base64" in page
    for name in ("decision.csv", "runs.csv", "fragility.csv", "suite.csv"):
        assert (out / name).is_file()
    import pandas as pd

    table = pd.read_csv(out / "decision.csv")
    assert list(table["bumpers.gap"]) == [0.05, 0.15, 0.3]
    assert np.all(np.diff(table["p_contact_mce"]) <= 0.0)  # wider gaps pound no more often
    analysis = pounding.design.open_stripe_analysis(out / "runs.zarr")
    assert bool(analysis.dataset["done"].all())
    again = runner.invoke(app, ["design", str(path), "--out", str(out)])
    assert again.exit_code == 0
    assert int(pounding.design.open_stripe_analysis(out / "runs.zarr").dataset["session"].max()) == 1
