"""A building in plan in the protocols that run many runs: a parameter study's points (pounding.study) and a
multiple-stripe analysis (design.stripe_analysis) are each the run simulate gives, under a pair's two
components turned by the point's angle, or one record along it; the moat's four gaps as one axis; what a
building in plan cannot do refused by name."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import pounding
from pounding import InputError, PlanBuilding, design
from pounding.design.stripes import suite_sources
from pounding.studies.points import PLAN_RUN_QUANTITIES, load_pair, pair_factor

EXAMPLES = Path(__file__).parents[1] / "examples"


def _building(gap_m=0.15):
    b = PlanBuilding.from_toml(EXAMPLES / "plan_building.toml")
    return replace(b, moat=replace(b.moat, gap_m=gap_m))


def test_a_study_s_points_are_the_runs_of_a_building_in_plan(tmp_path):
    source = "fema-p695-pair:far_field:3"
    spec = pounding.StudySpec(_building(), {"kind": "record", "record": source, "scale_pga_g": 0.5,
                                            "duration_s": 6.0},
                              {"moat.gap_m": [0.04, 0.2], "angle_deg": [0.0, 70.0]})
    ds = pounding.study(spec, str(tmp_path / "s.zarr"), scheduler="serial", progress=False).load()
    assert tuple(ds.attrs["quantities"]) == PLAN_RUN_QUANTITIES
    assert ds["theta_max_rad"].attrs["units"] == "rad" and ds["clearance_min_m"].attrs["units"] == "m"
    pair = load_pair(source).scaled(pair_factor(source, 0.5, None, None, 0.05))
    for gap in (0.04, 0.2):
        for angle in (0.0, 70.0):
            # moat.gap_m sets the four walls' gaps; the pair is turned by the angle, both components
            run = pounding.simulate(_building((gap,) * 4), pair.rotated(angle), 6.0)
            expected = run.quantities()
            point = ds.sel({"moat.gap_m": gap, "angle_deg": angle})
            for name in PLAN_RUN_QUANTITIES:
                assert float(point[name]) == pytest.approx(expected[name], rel=1e-12, nan_ok=True), name
    assert float(ds["impacts"].sel({"moat.gap_m": 0.04}).min()) > 0  # (the runs reach the narrow moat)
    assert float(ds["impacts"].sel({"moat.gap_m": 0.2}).max()) == 0


def test_one_record_and_a_sine_move_a_building_in_plan_along_a_direction(tmp_path):
    quake = pounding.records.el_centro()
    spec = pounding.StudySpec(_building(), {"kind": "record", "record": "el-centro", "scale_pga_g": 0.4,
                                            "duration_s": 5.0}, {"angle_deg": [0.0, 30.0]})
    ds = pounding.study(spec, str(tmp_path / "r.zarr"), scheduler="serial", progress=False).load()
    for angle in (0.0, 30.0):
        # (turned as a pair is, its second component nil: the same motion as the pair (rec, 0) turned)
        nil = quake._derived(0.0 * quake.accel, quake.meta)
        turned = pounding.RecordPair(quake.scaled(pga_g=0.4), nil).rotated(angle)
        along = pounding.RecordPair.of_direction(quake.scaled(pga_g=0.4), -angle)
        assert np.allclose(along.x.accel, turned.x.accel, rtol=0, atol=1e-15)
        assert np.allclose(along.y.accel, turned.y.accel, rtol=0, atol=1e-15)
        run = pounding.simulate(_building(), along, 5.0)
        assert float(ds["disp_max_m"].sel(angle_deg=angle)) == run.quantities()["disp_max_m"]
    sine = pounding.StudySpec(_building(), {"kind": "simulate", "freq_hz": 0.5, "duration_s": 4.0},
                              {"a_g": [0.1]})
    ds = pounding.study(sine, str(tmp_path / "h.zarr"), scheduler="serial", progress=False).load()
    run = pounding.simulate(_building(), pounding.Harmonic(0.1, 0.5), 4.0)
    assert float(ds["theta_max_rad"].values[0]) == run.quantities()["theta_max_rad"]


def test_what_a_building_in_plan_cannot_study_is_refused_by_name():
    b = _building()
    with pytest.raises(InputError, match="compute.kind.*record"):
        pounding.StudySpec(b, {"kind": "sweep", "a_g": 0.1}, {"moat.gap_m": [0.1]})
    with pytest.raises(InputError, match="v0_m_s.*at rest"):
        pounding.StudySpec(b, {"kind": "simulate", "freq_hz": 1.0, "duration_s": 2.0, "v0_m_s": 0.1},
                           {"a_g": [0.1]})
    with pytest.raises(InputError, match="moat.gap_m"):
        pounding.StudySpec(b.without_bumpers(), {"kind": "simulate", "freq_hz": 1.0, "duration_s": 2.0},
                           {"moat.gap_m": [0.1]})


def test_stripes_of_a_building_in_plan_under_pairs(tmp_path):
    assert suite_sources("fema-p695-pair:far_field") == [f"fema-p695-pair:far_field:{i}"
                                                              for i in range(22)]
    assert len(suite_sources("fema-p695-pair:near_field")) == 28
    sources = ["fema-p695-pair:far_field:0", "fema-p695-pair:far_field:5"]
    levels, period = [0.2, 0.6], 2.5
    msa = design.stripe_analysis(_building(), sources, levels, period_s=period,
                                 store=str(tmp_path / "a.zarr"), grid={"moat.gap_m": [0.08, 0.3]},
                                 scheduler="serial", progress=False)
    assert msa.has_bumpers and design.open_stripe_analysis(str(tmp_path / "a.zarr")).has_bumpers
    hits = msa.outcomes("contact")
    with pytest.raises(InputError, match="leave limit out"):  # (with its moat: a contact is an impact)
        msa.outcomes("contact", 0.2)
    for source in sources:
        for level in levels:
            factor = pair_factor(source, None, level, period, 0.05)  # (the pair's RotD100 at the level)
            for gap in (0.08, 0.3):
                pair = load_pair(source).scaled(factor)
                run = pounding.simulate(_building(gap), pair, pair.t[-1])
                point = {"record": source, "sa_g": level, "moat.gap_m": gap}
                assert float(hits.sel(point)) == float(run.quantities()["impacts"] > 0)
                assert float(msa.data["disp_max_m"].sel(point)) == run.quantities()["disp_max_m"]
    # without its moat: a contact is the largest bearing displacement in plan reaching the gap asked
    free = design.stripe_analysis(_building().without_bumpers(), sources, levels, period_s=period,
                                  store=str(tmp_path / "f.zarr"), scheduler="serial", progress=False)
    assert not free.has_bumpers
    with pytest.raises(InputError, match="single components"):  # (a pair on a line: refused)
        design.stripe_analysis(pounding.presets.paper_damped(), sources, levels, period_s=period,
                               store=str(tmp_path / "line.zarr"), progress=False)
    with pytest.raises(InputError, match="limit"):
        free.outcomes("contact")
    reach = free.outcomes("contact", 0.1)
    assert np.array_equal(reach.values, (free.data["moat_demand_m"] >= 0.1).astype(float).values)


def test_the_moat_s_demand_is_where_a_moat_begins_to_be_struck():
    """Without a moat, the base's corners' largest displacement towards a wall is the gap a moat of equal
    gaps needs: a hair wider and no corner touches it, a hair narrower and one does. The bearings, inside
    the floor, say less when the building turns: the moat's demand is not their displacement."""
    b = _building()
    pair = load_pair("fema-p695-pair:far_field:3").scaled(0.8)
    free = pounding.simulate(b.without_bumpers(), pair, 12.0)
    demand = free.quantities()["moat_demand_m"]
    corners = np.array(b.floors[0].corners_m())  # (the demand from the sampled corners: never above)
    th, cx, cy = free.displacement[:, 0, 2], b.floors[0].centre_m[0], b.floors[0].centre_m[1]
    x = free.displacement[:, 0, 0][:, None] - (corners[None, :, 1] - cy) * th[:, None]
    y = free.displacement[:, 0, 1][:, None] + (corners[None, :, 0] - cx) * th[:, None]
    sampled = max(np.abs(x).max(), np.abs(y).max())
    assert sampled <= demand < sampled * 1.05
    assert demand == np.max(free.wall_demand_m)
    assert len(pounding.simulate(_building(demand * (1 + 1e-7)), pair, 12.0).contacts) == 0
    assert len(pounding.simulate(_building(demand * (1 - 1e-4)), pair, 12.0).contacts) > 0
    with_moat = pounding.simulate(_building(0.8 * demand), pair, 12.0)
    assert with_moat.clearance_m == pytest.approx(0.8 * demand - with_moat.wall_demand_m, abs=1e-15)


# ---------------------------------------------------------------------------------------- the design
def test_a_suite_of_pairs_is_scaled_by_its_rotd100():
    pairs = pounding.records.fema_p695_pairs("far_field")[:3]
    target = design.asce7_spectrum(1.0, 0.6)
    suite = design.scale_suite(pairs, target, period_range_s=(1.5, 2.5), n_periods=5)
    rule = np.geomspace(1.5, 2.5, 5)
    rotd100 = pounding.rotd_spectrum(pairs, rule)["rotd100_psa_g"].values  # (pairs, periods)
    # one factor, the smallest that keeps the mean RotD100 nowhere below the target (ASCE 7-16 17.3.3)
    factor = float(np.max(target.sa_g(rule) / rotd100.mean(axis=0)))
    assert suite.factors == pytest.approx([factor] * 3, rel=1e-12)
    assert suite.shortfall() == pytest.approx(1.0, rel=1e-9)
    assert all(isinstance(p, pounding.RecordPair) for p in suite.records)
    assert suite.records[1].x.accel == pytest.approx(factor * pairs[1].x.accel, rel=1e-15)
    assert suite.records[1].y.accel == pytest.approx(factor * pairs[1].y.accel, rel=1e-15)
    assert float(suite.spectra["pga_g"][0]) == pytest.approx(factor * pairs[0].peak_vector_g, rel=1e-12)
    assert "3 pairs" in repr(suite)
    with pytest.raises(InputError, match="records"):
        design.scale_suite([pairs[0], pounding.records.el_centro()], target, period_s=2.0)


PLAN_DESIGN = """
title = "a moat in plan"
[system]
file = "{plan}"
[site]
code = "asce7-16"
s_ds_g = 1.0
s_d1_g = 0.6
[records]
suite = ["fema-p695-pair:far_field:0", "fema-p695-pair:far_field:4"]
period_s = 2.5
levels_g = [0.2, 0.5]
[design]
gaps_m = [0.1, 0.5]
target_probability = 0.5
t_m_s = 2.5
beta_m = 0.15
[run]
scheduler = "serial"
"""


def _design_file(tmp_path, text=PLAN_DESIGN):
    path = tmp_path / "design.toml"
    path.write_text(text.replace("{plan}", (EXAMPLES / "plan_building.toml").as_posix()))
    return path


def test_a_design_file_designs_a_building_in_plan_s_moat(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app
    from pounding.design.plan import DesignPlan

    plan = DesignPlan.from_toml(_design_file(tmp_path))
    b = PlanBuilding.from_toml(EXAMPLES / "plan_building.toml")
    assert plan.in_plan and plan.gap_dim == "moat.gap_m" and plan.grid == {"moat.gap_m": [0.1, 0.5]}
    # the code's clearance: D_TM with the building's torsion, from D_M at T_M
    d_m = design.asce7_displacement(1.5 * 0.6, 2.5, 0.15)["d_m_m"]
    assert plan.code_minimum_gap_m == design.asce7_torsion(b, d_m, "edge")["d_tm_m"] > 1.15 * d_m
    # without t_m_s and beta_m: D_M from the bearings' effective properties
    given = "t_m_s = 2.5\nbeta_m = 0.15\n"
    auto = DesignPlan.from_toml(_design_file(tmp_path, PLAN_DESIGN.replace(given, "")))
    d_auto = design.asce7_bearings_displacement(b, 1.5 * 0.6)["d_m_m"]
    assert auto.code_minimum_gap_m == design.asce7_torsion(b, d_auto, "edge")["d_tm_m"]
    out = tmp_path / "report"
    done = CliRunner().invoke(app, ["design", str(_design_file(tmp_path)), "--out", str(out)])
    assert done.exit_code == 0, done.output
    analysis = design.open_stripe_analysis(out / "runs.zarr")
    alone = design.stripe_analysis(b, plan.records, plan.levels_g, period_s=2.5,
                                   store=str(tmp_path / "again.zarr"), grid=plan.grid, scheduler="serial",
                                   progress=False)
    assert np.array_equal(analysis.data["impacts"].values, alone.data["impacts"].values)
    page = (out / "index.html").read_text()
    assert "a corner of the floor the moat surrounds strikes a wall" in page and "mean RotD100" in page
    import pandas as pd

    table = pd.read_csv(out / "decision.csv")
    assert list(table["moat.gap_m"]) == [0.1, 0.5]


SUITE = 'suite = ["fema-p695-pair:far_field:0", "fema-p695-pair:far_field:4"]'


@pytest.mark.parametrize("change, field, words", [
    ((SUITE, 'suite = "fema-p695:far_field"'), "records.suite", "pairs of components"),
    (("gaps_m = [0.1, 0.5]", "gaps_m = [0.1, 0.5]\nwall = 0"), "design.wall", "moat.gap_m"),
    (("gaps_m = [0.1, 0.5]", 'gaps_m = [0.1, 0.5]\ngrid = { "moat.gap_m[0]" = [0.3] }'),
     "design.grid.moat.gap_m[0]", "sets moat.gap_m[0]"),
])
def test_a_bad_design_of_a_building_in_plan_is_named(tmp_path, change, field, words):
    from pounding.design.plan import DesignPlan

    with pytest.raises(InputError) as err:
        DesignPlan.from_toml(_design_file(tmp_path, PLAN_DESIGN.replace(*change)))
    assert err.value.field == field and words in str(err.value)


def test_a_design_needs_a_moat_in_plan_and_a_line_refuses_pairs(tmp_path):
    from pounding.design.plan import DesignPlan

    free = tmp_path / "free.toml"
    PlanBuilding.from_toml(EXAMPLES / "plan_building.toml").without_bumpers().to_toml(free)
    with pytest.raises(InputError, match="moat"):
        DesignPlan.from_toml(_design_file(tmp_path, PLAN_DESIGN.replace("{plan}", free.as_posix())))
    line = PLAN_DESIGN.replace("{plan}", (EXAMPLES / "building_moat.toml").as_posix())
    with pytest.raises(InputError) as err:
        DesignPlan.from_toml(_design_file(tmp_path, line))
    assert err.value.field == "records.suite" and "single components" in str(err.value)


# ---------------------------------------------------------------------------------------- pounding spectra
def test_a_pounding_spectrum_of_a_building_in_plan_is_its_runs():
    from pounding.protocols.pounding_spectrum import PLAN_QUANTITIES, bearings_at, isolated_period_s

    b = _building()
    mass = sum(f.mass_kg for f in b.floors)
    stiffness = sum(bearing.isolator.slopes_n_m[0] for bearing in b.bearings)
    assert isolated_period_s(b) == pytest.approx(2.0 * np.pi * np.sqrt(mass / stiffness), rel=1e-15)
    at = bearings_at(b, 2.5)
    assert isolated_period_s(at) == pytest.approx(2.5, rel=1e-12)
    factor = (isolated_period_s(b) / 2.5) ** 2
    iso, now = b.bearings[0].isolator, at.bearings[0].isolator
    assert now.slopes_n_m == pytest.approx([k * factor for k in iso.slopes_n_m], rel=1e-15)
    assert now.breakpoints_m == iso.breakpoints_m
    assert now.damping_n_s_m == pytest.approx(iso.damping_n_s_m * np.sqrt(factor), rel=1e-15)
    # bearings with a Bouc-Wen spring: its a k in the initial stiffness, its stiffness scaled with the slopes
    bw = pounding.BoucWen(2e6, 0.02, a=0.9)
    rubber = replace(b, bearings=tuple(replace(q, isolator=replace(q.isolator, bouc_wen=bw), isolator_y=None)
                                       for q in b.bearings))
    stiffness = sum(q.isolator.slopes_n_m[0] + 0.9 * 2e6 for q in rubber.bearings)
    assert isolated_period_s(rubber) == pytest.approx(2.0 * np.pi * np.sqrt(mass / stiffness), rel=1e-15)
    at = bearings_at(rubber, 2.5)
    assert isolated_period_s(at) == pytest.approx(2.5, rel=1e-12)
    factor = (isolated_period_s(rubber) / 2.5) ** 2
    for q, now in zip(rubber.bearings, at.bearings):
        assert now.isolator.slopes_n_m == pytest.approx([k * factor for k in q.isolator.slopes_n_m],
                                                        rel=1e-15)
        assert now.isolator.bouc_wen.stiffness_n_m == pytest.approx(2e6 * factor, rel=1e-15)
        assert now.isolator.bouc_wen.yield_displacement_m == 0.02 and now.isolator.bouc_wen.a == 0.9
    pairs = [p.scaled(0.6) for p in pounding.records.fema_p695_pairs("far_field")[:2]]
    ps = pounding.pounding_spectrum(pairs, [1.5, 3.0], gaps_m=[0.08, 0.3], structure=b, scheduler="serial")
    assert "isolated period" in ps.data.attrs["period"] and "clearance_min_m_free" not in ps.data
    assert ps.data["pga_g"].values.tolist() == [p.peak_vector_g for p in pairs]
    for r, pair in enumerate(pairs):
        for period in (1.5, 3.0):
            building = bearings_at(b, period)
            free = pounding.simulate(building.without_bumpers(), pair, pair.t[-1]).quantities()
            point = {"record": r, "period_s": period}
            assert float(ps.data["disp_max_free_m"].isel(record=r).sel(period_s=period)) == free["disp_max_m"]
            assert float(ps.data["theta_max_rad_free"][point["record"]].sel(period_s=period)) == \
                free["theta_max_rad"]
            for gap in (0.08, 0.3):
                moat = replace(building.moat, gap_m=gap)
                q = pounding.simulate(replace(building, moat=moat), pair, pair.t[-1]).quantities()
                cell = ps.data.isel(record=r).sel(period_s=period, gap_m=gap)
                for name in PLAN_QUANTITIES:
                    assert float(cell[name]) == pytest.approx(q[name], rel=1e-12, nan_ok=True), name
    assert float(ps.data["impacts"].sel(gap_m=0.08).min()) > 0


def test_a_pounding_spectrum_in_plan_refuses_a_building_without_its_moat():
    quake = pounding.records.el_centro()
    with pytest.raises(InputError, match="moat"):
        pounding.pounding_spectrum(quake, [2.0], gaps_m=[0.1], structure=_building().without_bumpers())
    with pytest.raises(InputError, match="RecordPair, not pounding.Record"):  # (a pair, on a line)
        pounding.pounding_spectrum(pounding.RecordPair(quake, quake), [2.0], gaps_m=[0.1])


def test_pounding_spectrum_on_the_command_line_takes_a_building_in_plan(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    out = tmp_path / "sp"
    done = CliRunner().invoke(app, ["spectrum", "--structure", str(EXAMPLES / "plan_building.toml"),
                                    "--set", "fema-p695-far-field", "--periods", "2", "--gaps", "0.2",
                                    "--scale-pga", "0.4", "--scheduler", "serial", "--out", str(out)],
                              catch_exceptions=False)
    assert done.exit_code == 0, done.output
    assert "22 pair(s) x 1 periods x 1 gaps" in " ".join(done.output.split())
    import xarray as xr

    with xr.open_dataset(out / "pounding_spectrum.nc") as ds:
        assert ds.sizes["record"] == 22 and "theta_max_rad" in ds
        assert ds["pga_g"].values == pytest.approx(0.4, rel=1e-12)  # (each pair's peak vector at 0.4 g)
    for name in ("rotation.png", "elastic_spectrum.csv", "drift_ratio.png"):
        assert (out / name).stat().st_size > 0


def test_a_study_s_floor_follows_its_mass_and_size_and_a_moat_s_gap_warns_as_a_moat_s():
    import warnings

    # a uniform slab's inertia follows the mass and the size a grid sets; one given stays as given
    spec = pounding.StudySpec(_building(), {"kind": "simulate", "freq_hz": 0.5, "duration_s": 1.0,
                                            "a_g": 0.1},
                              {"floors[0].mass_kg": [4e5, 8e5], "floors[0].size_m[0]": [30.0, 36.0]})
    for i, m in enumerate((4e5, 8e5)):
        for j, a in enumerate((30.0, 36.0)):
            floor = spec.point((i, j))[0].floors[0]
            assert floor.inertia_kg_m2 == m * (a**2 + 12.0**2) / 12.0
    given = pounding.Floor(4e5, (30.0, 12.0), inertia_kg_m2=4e7)
    assert given.to_dict()["inertia_kg_m2"] == 4e7
    assert "inertia_kg_m2" not in pounding.Floor(4e5, (30.0, 12.0)).to_dict()
    # a pounding spectrum's moat of 0.6 m is a moat's gap, not a bumper's: no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", pounding.PoundingWarning)
        pounding.pounding_spectrum(pounding.records.el_centro().scaled(pga_g=0.3), [2.0], gaps_m=[0.6],
                                   structure=_building(), scheduler="serial")


def test_a_line_s_design_file_refuses_a_pair_among_its_records(tmp_path):
    from pounding.design.plan import DesignPlan

    line = PLAN_DESIGN.replace("{plan}", (EXAMPLES / "building_moat.toml").as_posix()).replace(
        SUITE, 'suite = ["fema-p695:far_field:0", "fema-p695-pair:far_field:1"]')
    with pytest.raises(InputError) as err:
        DesignPlan.from_toml(_design_file(tmp_path, line))
    assert err.value.field == "records.suite" and "single components" in str(err.value)


def test_a_spectrum_s_period_is_the_isolated_building_s_with_its_floors_rigid():
    # a centred building on bearings of another law along y, its frames all but rigid: its translational
    # periods on the scaled bearings are the period asked (x) and that times the laws' ratio (y)
    from pounding.protocols.pounding_spectrum import bearings_at

    iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], damping_n_s_m=2e4)
    iso_y = pounding.Isolator(slopes_n_m=[3.0e7, 1.0e6], breakpoints_m=[0.02], damping_n_s_m=1e4)
    bearings = [pounding.Bearing((sx * 10.0, sy * 6.0), iso, iso_y) for sx in (-1, 1) for sy in (-1, 1)]
    frames = [pounding.Frame(1, axis, at, 1e13, 0.0) for axis, at in (("x", -6.0), ("x", 6.0), ("y", -10.0),
                                                                      ("y", 10.0))]
    b = PlanBuilding([pounding.Floor(6.0e5, (24.0, 16.0))] * 2, bearings, frames)
    at = bearings_at(b, 2.0)
    periods = np.sort(at.modes().periods_s)[::-1]
    assert periods[0] == pytest.approx(2.0, rel=1e-4)  # (x: the period asked)
    assert periods[1] == pytest.approx(2.0 * np.sqrt(1.2e7 / 3.0e7), rel=1e-4)  # (y: the laws' ratio)
    assert at.bearings[0].isolator_y.slopes_n_m[1] / iso_y.slopes_n_m[1] == pytest.approx(
        at.bearings[0].isolator.slopes_n_m[0] / iso.slopes_n_m[0], rel=1e-15)


def test_a_pair_is_scaled_to_a_pga_by_its_peak_vector():
    pair = load_pair("fema-p695-pair:far_field:3")
    scaled = pair.scaled(pga_g=0.5)
    assert scaled.peak_vector_g == pytest.approx(0.5, rel=1e-14)
    assert scaled.x.accel == pytest.approx(0.5 / pair.peak_vector_g * pair.x.accel, rel=1e-15)
    for bad in ({}, {"factor": 2.0, "pga_g": 0.5}):
        with pytest.raises(InputError, match="factor"):
            pair.scaled(**bad)
    with pytest.raises(InputError, match="pga_g"):
        pair.scaled(pga_g=-0.5)
