"""Design for a building (``pounding.design`` with a Structure): stripes over its moat's gap, its demands as
storey drift and floor acceleration besides pounding, and the decision of the gap under either."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

import pounding as pd_
from pounding import design


def building() -> pd_.Structure:
    iso = pd_.Isolator(slopes_n_m=[4.0e5, 1.0e5], breakpoints_m=[0.02], damping_n_s_m=2.0e3)
    wall = pd_.Wall(0, 0.05, 0.05, pd_.KelvinVoigt(2.0e7, 1.0e4))
    return pd_.Structure(3.0e3, iso, [pd_.Storey(2.0e3, 4.0e6, 4.0e3)] * 2, [wall])


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    path = str(tmp_path_factory.mktemp("design") / "b.zarr")
    design.stripe_analysis(building(), "el-centro", [0.2, 0.5, 1.0], period_s=1.5, store=path, progress=False,
                           scheduler="serial", grid={"walls[0].gap_m": [0.02, 0.1, 0.6]})
    return path


@pytest.fixture()
def msa(store):
    return design.open_stripe_analysis(store)


def test_a_building_stripe_analysis_keeps_its_demands(msa):
    assert msa.has_bumpers and msa.capacity_m is None
    ds = msa.data
    for name in ("disp_max_m", "drift_ratio_max", "acc_max_g", "top_acc_max_g", "impacts",
                 "compression_max_m"):
        assert name in ds
    # each event is its quantity against the limit, run by run
    drift = ds["drift_ratio_max"]
    limit = float(drift.median())
    np.testing.assert_array_equal(msa.outcomes("drift", limit).values, (drift > limit).astype(float).values)
    np.testing.assert_array_equal(msa.outcomes("displacement", 0.05).values,
                                  (ds["disp_max_m"] > 0.05).astype(float).values)
    np.testing.assert_array_equal(msa.outcomes("top_acceleration", 0.5).values,
                                  (ds["top_acc_max_g"] > 0.5).astype(float).values)
    assert float(msa.fraction("contact").sel({"walls[0].gap_m": 0.6}).max()) == 0.0
    assert float(msa.fraction("contact").sel({"walls[0].gap_m": 0.02}).min()) == 1.0
    assert msa.design_dims == ("walls[0].gap_m",)


def test_a_building_without_storeys_reads_back_with_its_wall(tmp_path):
    iso = pd_.Isolator(slopes_n_m=[4.0e5], breakpoints_m=[], damping_n_s_m=2.0e3)
    base = pd_.Structure(3.0e3, iso, [], [pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(2.0e7, 1.0e4))])
    design.stripe_analysis(base, "el-centro", [0.5], period_s=1.5, store=str(tmp_path / "s.zarr"),
                           progress=False, scheduler="serial")
    again = design.open_stripe_analysis(str(tmp_path / "s.zarr"))
    assert again.has_bumpers and float(again.fraction("contact").max()) == 1.0


def _building_plan(tmp_path, **choices) -> dict:
    """A building's design file's tables (the example's, on El Centro at two stripes, three gaps)."""
    building().to_toml(tmp_path / "b.toml")
    table = tomllib.loads((Path(__file__).parents[1] / "examples" / "design_building.toml").read_text())
    table["system"] = {"file": "b.toml"}
    table["records"] = {"suite": "el-centro", "period_s": 1.5, "levels_g": [0.5, 1.0]}
    table["design"] = {"gaps_m": [0.02, 0.1, 0.6], "target_probability": 0.1, **choices}
    table["run"] = {"scheduler": "serial"}
    return table


def test_a_building_design_file_decides_the_moat_gap_for_drift(tmp_path):
    import pandas as pd
    import tomli_w
    from typer.testing import CliRunner

    from pounding.cli import app
    from pounding.design.plan import DesignPlan, run_plan

    table = _building_plan(tmp_path, event="drift", limit=0.001)
    plan = DesignPlan.from_dict(table, tmp_path / "plan.toml")
    assert plan.building and plan.gap_dim == "walls[0].gap_m" and plan.kinds[0].name == "kelvin_voigt"
    outcome = run_plan(plan, str(tmp_path / "runs.zarr"), progress=False)
    d = outcome.decision
    # the decision is the Python chain's on the same runs
    again = design.decide(outcome.analyses["kelvin_voigt"], d.design_sa_g, d.mce_sa_g, target_probability=0.1,
                          gap_dim="walls[0].gap_m", event="drift", limit=0.001)
    cols = ["walls[0].gap_m", "p_drift_design", "p_drift_mce"]
    pd.testing.assert_frame_equal(d.to_dataframe()[cols], again.to_dataframe()[cols])
    assert "storey drift ratio above 0.001" in d.verdict()
    # the command line writes the report, in the demand's words
    (tmp_path / "plan.toml").write_text(tomli_w.dumps(table))
    result = CliRunner().invoke(app, ["design", str(tmp_path / "plan.toml"), "--out",
                                      str(tmp_path / "report")])
    assert result.exit_code == 0, result.output
    page = (tmp_path / "report" / "index.html").read_text()
    assert "Fragility of a storey drift ratio above 0.001" in page and "moat gap [m]" in page
    assert "bumpers" not in page and "with / without the moat" in page  # (a building's walls: its moat)
    assert "P(a storey drift ratio above 0.001 | MCE)" in page
    written = pd.read_csv(tmp_path / "report" / "decision.csv")
    np.testing.assert_allclose(written["p_drift_mce"], d.to_dataframe()["p_drift_mce"])


@pytest.mark.parametrize("change, field", [
    (lambda t: t.update(bumpers={"gap_left_m": 0.1, "gap_right_m": 0.1}), "bumpers"),
    (lambda t: t["design"].update(wall=1), "design.wall"),
    (lambda t: t["design"].update(event="drift"), "design.limit"),
    (lambda t: t["design"].update(limit=0.01), "design.limit"),
    (lambda t: t["design"].update(event="compression", limit=0.01), "design.event"),
    (lambda t: t["design"].update(grid={"walls[0].gap_left_m": [0.1]}), "design.grid.walls[0].gap_left_m"),
    (lambda t: t["design"].update(bumper_types={"rubber": {"law": {"type": "kelvin_voigt",
                                                                    "stiffness": 1e6}}}),
     "design.bumper_types"),
])
def test_a_building_design_file_names_what_it_refuses(tmp_path, change, field):
    from pounding.design.plan import DesignPlan

    table = _building_plan(tmp_path)
    change(table)
    with pytest.raises(pd_.InputError) as err:
        DesignPlan.from_dict(table, tmp_path / "plan.toml")
    assert err.value.field == field, err.value


def test_one_mass_design_file_refuses_a_building_s_demands(tmp_path):
    from pounding.design.plan import DesignPlan

    table = tomllib.loads((Path(__file__).parents[1] / "examples" / "design_ups.toml").read_text())
    for key, value, field in (("event", "drift", "design.event"), ("wall", 0, "design.wall")):
        bad = {**table, "design": {**table["design"], key: value, "limit": 0.01}}
        with pytest.raises(pd_.InputError) as err:
            DesignPlan.from_dict(bad, Path(__file__).parents[1] / "examples" / "plan.toml")
        assert err.value.field == field


def test_the_gap_decided_for_pounding_and_for_drift(msa):
    pounding_choice = design.decide(msa, 0.5, 1.0, target_probability=0.1, gap_dim="walls[0].gap_m")
    assert pounding_choice.recommended["walls[0].gap_m"] == 0.6  # (the only gap never reached)
    table = pounding_choice.to_dataframe()
    assert list(table.columns[:1]) == ["walls[0].gap_m"]
    # the drift the pounding brings: a limit between the runs' drifts at the narrowest and the widest gaps
    drift = msa.data["drift_ratio_max"].sel(sa_g=1.0, record="el-centro")
    narrow, wide = float(drift.sel({"walls[0].gap_m": 0.02})), float(drift.sel({"walls[0].gap_m": 0.6}))
    assert narrow > wide
    limit = 0.5 * (narrow + wide)
    drift_choice = design.decide(msa, 0.5, 1.0, target_probability=0.1, gap_dim="walls[0].gap_m",
                                 event="drift", limit=limit)
    p = drift_choice.to_dataframe().set_index("walls[0].gap_m")["p_drift_mce"]
    assert p[0.02] == 1.0 and p[0.6] == 0.0
    smallest = min(g for g, v in p.items() if v <= 0.1)
    assert drift_choice.recommended["walls[0].gap_m"] == smallest
    assert "storey drift ratio above" in drift_choice.verdict()
    assert len(pd_.plots.plot_decision(drift_choice)) >= 3
    with pytest.raises(pd_.InputError, match="limit"):
        design.decide(msa, 0.5, 1.0, gap_dim="walls[0].gap_m", event="drift")
    with pytest.raises(pd_.InputError, match="limit"):
        design.decide(msa, 0.5, 1.0, gap_dim="walls[0].gap_m", limit=0.01)
    with pytest.raises(pd_.InputError, match="event"):
        design.decide(msa, 0.5, 1.0, gap_dim="walls[0].gap_m", event="storey", limit=0.01)
