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
    iso = pd_.Isolator(slopes=[4.0e5, 1.0e5], breakpoints=[0.02], damping=2.0e3)
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
    for name in ("base_disp_max_m", "drift_ratio_max", "acc_max_g", "top_acc_max_g", "impacts"):
        assert name in ds
    # each event is its quantity against the limit, run by run
    drift = ds["drift_ratio_max"]
    limit = float(drift.median())
    np.testing.assert_array_equal(msa.outcomes("drift", limit).values, (drift > limit).astype(float).values)
    np.testing.assert_array_equal(msa.outcomes("displacement", 0.05).values,
                                  (ds["base_disp_max_m"] > 0.05).astype(float).values)
    np.testing.assert_array_equal(msa.outcomes("top_acceleration", 0.5).values,
                                  (ds["top_acc_max_g"] > 0.5).astype(float).values)
    assert float(msa.fraction("contact").sel({"walls[0].gap_m": 0.6}).max()) == 0.0
    assert float(msa.fraction("contact").sel({"walls[0].gap_m": 0.02}).min()) == 1.0
    assert msa.design_dims == ("walls[0].gap_m",)


def test_a_building_without_storeys_reads_back_with_its_wall(tmp_path):
    iso = pd_.Isolator(slopes=[4.0e5], breakpoints=[], damping=2.0e3)
    base = pd_.Structure(3.0e3, iso, [], [pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(2.0e7, 1.0e4))])
    design.stripe_analysis(base, "el-centro", [0.5], period_s=1.5, store=str(tmp_path / "s.zarr"),
                           progress=False, scheduler="serial")
    again = design.open_stripe_analysis(str(tmp_path / "s.zarr"))
    assert again.has_bumpers and float(again.fraction("contact").max()) == 1.0


def test_a_design_file_of_a_building_says_it_takes_one_mass(tmp_path):
    from pounding.design.plan import DesignPlan

    building().to_toml(tmp_path / "b.toml")
    text = (Path(__file__).parents[1] / "examples" / "design_ups.toml").read_text()
    table = tomllib.loads(text)
    table["system"] = {"file": "b.toml"}
    table.pop("bumpers", None)
    with pytest.raises(pd_.InputError, match="one mass"):
        DesignPlan.from_dict(table, tmp_path / "plan.toml")


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
    assert len(drift_choice.plot()) >= 3
    with pytest.raises(pd_.InputError, match="limit"):
        design.decide(msa, 0.5, 1.0, gap_dim="walls[0].gap_m", event="drift")
    with pytest.raises(pd_.InputError, match="limit"):
        design.decide(msa, 0.5, 1.0, gap_dim="walls[0].gap_m", limit=0.01)
    with pytest.raises(pd_.InputError, match="event"):
        design.decide(msa, 0.5, 1.0, gap_dim="walls[0].gap_m", event="storey", limit=0.01)
