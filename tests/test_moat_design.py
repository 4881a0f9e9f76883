"""A moat's gap for a building in plan (pounding.design.moat_design): each pair at its most critical
orientation, the suite's mean (seven pairs or more) or largest; the code's total maximum displacement with
torsion (design.asce7_torsion) against ASCE 7-16's formula written out here."""

from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest

import pounding
from pounding import Bearing, Floor, InputError, PlanBuilding, RectangularMoat, design

matplotlib.use("Agg")


def _building(centre=(1.2, 0.0), at=(10.0, 6.0), moat=None):
    iso = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], damping_n_s_m=2e4)
    bearings = [Bearing((sx * at[0], sy * at[1]), iso) for sx in (-1, 1) for sy in (-1, 1)]
    return PlanBuilding([Floor(6.0e5, (24.0, 16.0), centre_m=centre)], bearings, moat=moat)


@pytest.mark.parametrize("centre, at", [((1.2, 0.0), (10.0, 6.0)), ((-2.0, 1.5), (11.0, 7.0)),
                                        ((0.0, 0.0), (2.0, 1.0))])
def test_the_code_s_torsion_is_its_formula(centre, at):
    b = _building(centre, at)
    d_m = 0.3
    out = design.asce7_torsion(b, d_m)
    # ASCE 7-16 17.5-3: D_TM = D_M (1 + y / P_T^2 12 e / (b^2 + d^2)), e with 5 % of the side across the
    # motion; P_T = sqrt(mean(x_i^2 + y_i^2)) / r_I >= 1, r_I = sqrt((b^2 + d^2) / 12); D_TM >= 1.15 D_M
    short, long_ = 16.0, 24.0
    r_i = math.sqrt((short**2 + long_**2) / 12.0)
    dist2 = [(sx * at[0] - centre[0]) ** 2 + (sy * at[1] - centre[1]) ** 2
             for sx in (-1, 1) for sy in (-1, 1)]
    p_t = max(1.0, math.sqrt(sum(dist2) / 4.0) / r_i)
    along_x = d_m * (1.0 + at[1] / p_t**2 * 12.0 * (abs(centre[1]) + 0.05 * 16.0) / (short**2 + long_**2))
    along_y = d_m * (1.0 + at[0] / p_t**2 * 12.0 * (abs(centre[0]) + 0.05 * 24.0) / (short**2 + long_**2))
    assert out["p_t"] == pytest.approx(p_t, rel=1e-12)
    assert out["d_tm_x_m"] == pytest.approx(max(along_x, 1.15 * d_m), rel=1e-12)
    assert out["d_tm_y_m"] == pytest.approx(max(along_y, 1.15 * d_m), rel=1e-12)
    assert out["d_tm_m"] == max(out["d_tm_x_m"], out["d_tm_y_m"])
    # the moat's clearance: y to the base's farthest edge (its sides 24 by 16 m, the centre of stiffness at
    # the plan's centre: symmetric bearings)
    edge = design.asce7_torsion(b, d_m, "edge")
    along_x = d_m * (1.0 + 8.0 / p_t**2 * 12.0 * (abs(centre[1]) + 0.05 * 16.0) / (short**2 + long_**2))
    along_y = d_m * (1.0 + 12.0 / p_t**2 * 12.0 * (abs(centre[0]) + 0.05 * 24.0) / (short**2 + long_**2))
    assert edge["d_tm_x_m"] == pytest.approx(max(along_x, 1.15 * d_m), rel=1e-12)
    assert edge["d_tm_y_m"] == pytest.approx(max(along_y, 1.15 * d_m), rel=1e-12)
    # a building given its accidental eccentricity: the code adds its own 5 %, never twice
    from dataclasses import replace

    assert design.asce7_torsion(replace(b, accidental_eccentricity=(0.05, -0.05)), d_m) == out


def test_seven_pairs_take_their_mean_each_at_its_critical_orientation():
    quake = pounding.records.el_centro().scaled(pga_g=0.4)
    pairs = [pounding.RecordPair(quake, quake.scaled(factor=f), name=f"pair {k}")
             for k, f in enumerate((0.3, 0.45, 0.6, 0.75, 0.9, 1.05, 1.2))]
    moat = RectangularMoat(0.02, pounding.KelvinVoigt(1e9, 1e6))  # (taken away: the gap is what runs find)
    b = _building(moat=moat)
    found = design.moat_design(b, pairs, [0.0, 60.0, 135.0], duration_s=6.0, d_m_m=0.1)
    assert found.attrs["rule"] == "mean" and len(found.critical) == 7
    assert found.design_displacement_m == pytest.approx(found.critical["disp_max_m"].mean(), rel=1e-15)
    assert (found.data["impacts"] == 0).all()  # (no moat in the runs)
    one = pounding.orientations(b.without_bumpers(), pairs[3], [0.0, 60.0, 135.0], duration_s=6.0)
    angle, value = one.critical("disp_max_m")
    assert found.critical.loc["pair 3", "angle_deg"] == angle
    assert found.critical.loc["pair 3", "disp_max_m"] == value
    assert found.code == design.asce7_torsion(b, 0.1, "edge")
    # the moat's demand by the same rule: each pair's largest over the angles
    demand = found.data["moat_demand_m"].groupby(level="pair").max()
    assert found.critical["moat_demand_m"].tolist() == demand.loc[found.critical.index].tolist()
    assert found.moat_demand_m == pytest.approx(demand.mean(), rel=1e-15)
    # the figure: seven bars, the design value, the pairs' demands and the suite's, the code's D_TM
    assert len(pounding.plots.plot_moat_design(found)) == 7 + 1 + 2 + 1
    assert found.plot().axes[0].get_ylabel() == "displacement (mm)"
    # and a moat's gap across (the file's own, in pounding moat's figure)
    labels = [a.get_label() for a in pounding.plots.plot_moat_design(found, gap_m=0.3)]
    assert len(labels) == 7 + 1 + 2 + 1 + 1 and labels[-1] == "the moat's gap: 300 mm"
    with pytest.raises(pounding.InputError, match="gap_m"):
        found.plot(gap_m=-0.1)
    assert found.to_xarray().attrs["rule"] == "mean"
    # fewer than seven: the largest
    few = design.moat_design(b, pairs[:2], [0.0], duration_s=6.0)
    assert few.attrs["rule"] == "largest"
    assert few.design_displacement_m == few.critical["disp_max_m"].max() and not few.code


def test_the_accidental_eccentricity_runs_its_four_cases_and_takes_the_largest():
    # accidental=0.05: every pair at every angle at the four shifted buildings, each pair's critical run the
    # largest of them, named by its case: the same as designing each shifted building alone and taking the
    # largest
    quake = pounding.records.el_centro().scaled(pga_g=0.5)
    pairs = [pounding.RecordPair(quake, quake.scaled(factor=f), name=f"pair {k}")
             for k, f in enumerate((0.4, 0.9))]
    b = _building(centre=(0.0, 0.0), moat=RectangularMoat(0.02, pounding.KelvinVoigt(1e9, 1e6)))
    found = design.moat_design(b, pairs, [0.0, 60.0], duration_s=5.0, accidental=0.05)
    assert found.data.index.names == ["pair", "eccentricity", "angle_deg"] and len(found.data) == 2 * 4 * 2
    alone = {case: design.moat_design(shifted, pairs, [0.0, 60.0], duration_s=5.0)
             for case, shifted in zip(("+x+y", "+x-y", "-x+y", "-x-y"), b.accidental_cases(0.05))}
    for name in ("pair 0", "pair 1"):
        peaks = {case: d.critical.loc[name, "disp_max_m"] for case, d in alone.items()}
        case = max(peaks, key=peaks.get)
        assert found.critical.loc[name, "disp_max_m"] == peaks[case]
        assert found.critical.loc[name, "eccentricity"] == case
        assert found.critical.loc[name, "angle_deg"] == alone[case].critical.loc[name, "angle_deg"]
        demands = {c: d.critical.loc[name, "moat_demand_m"] for c, d in alone.items()}
        assert found.critical.loc[name, "moat_demand_m"] == max(demands.values())
    # a symmetric building shifted turns: its bearings move further than as built
    as_built = design.moat_design(b, pairs, [0.0, 60.0], duration_s=5.0)
    assert found.design_displacement_m > as_built.design_displacement_m
    import matplotlib.pyplot as plt

    _, ax = plt.subplots()
    assert len(pounding.plots.plot_moat_design(found, ax=ax)) == 2 + 1 + 2
    labels = [t.get_text() for t in ax.texts]  # (each bar's angle and case)
    critical = found.critical
    assert labels == [f"{a:g} deg\n{c}" for a, c in zip(critical["angle_deg"], critical["eccentricity"])]
    plt.close("all")
    # the building's own accidental eccentricity and this one together: refused, as are bad fractions
    edge = _building(centre=(11.5, 0.0))  # (its centre of mass 0.5 m from its side: 5 % moves it off)
    with pytest.raises(InputError, match="four cases") as info:
        design.moat_design(edge, pairs, [0.0], duration_s=5.0, accidental=0.05)
    assert info.value.field == "accidental"
    own = pounding.PlanBuilding(b.floors, b.bearings, accidental_eccentricity=(0.05, 0.0))
    for building, fraction in ((own, 0.05), (b, -0.05), (b, 0.5), (b, float("nan"))):
        with pytest.raises(InputError) as info:
            design.moat_design(building, pairs, [0.0], duration_s=5.0, accidental=fraction)
        assert info.value.field == "accidental", str(info.value)


def test_a_moat_design_s_bad_arguments_are_refused_by_name():
    quake = pounding.records.el_centro()
    pair = pounding.RecordPair(quake, quake)
    b = _building()
    for call, field in ((lambda: design.moat_design(b, []), "pairs"),
                        (lambda: design.moat_design(b, [quake]), "pairs[0]"),
                        (lambda: design.moat_design("building", pair), "building"),
                        (lambda: design.moat_design(b, pair, d_m_m=-0.1), "d_m_m"),
                        (lambda: design.moat_design(b, pair, duration_s=0.0), "duration_s"),
                        (lambda: design.moat_design(b, pair, [400.0]), "angles_deg[0]"),
                        (lambda: design.asce7_torsion(b, float("nan")), "d_m_m"),
                        (lambda: design.asce7_torsion(b, 0.2, "corner"), "element")):
        with pytest.raises(InputError) as info:
            call()
        assert info.value.field == field, str(info.value)
    assert np.isfinite(design.asce7_torsion(b, 0.2)["d_tm_m"])


def test_the_code_s_centre_of_stiffness_is_the_bearings_effective_one():
    # two yielding bearings on the left, two stiffer elastic ones on the right: at D_M = 0.3 m the left
    # ones' secant stiffness is (12e6 * 0.01 + 1.2e6 * 0.29) / 0.3 = 1.56e6 N/m, the right ones' 4e6 N/m
    lrb = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01])
    elastic = pounding.Isolator(slopes_n_m=[4.0e6], breakpoints_m=[])
    bearings = [Bearing((sx * 10.0, sy * 6.0), lrb if sx < 0 else elastic)
                for sx in (-1, 1) for sy in (-1, 1)]
    b = PlanBuilding([Floor(6.0e5, (24.0, 16.0))], bearings)
    out = design.asce7_torsion(b, 0.3)
    k_left, k_right = (1.2e7 * 0.01 + 1.2e6 * 0.29) / 0.3, 4.0e6
    expected = (-10.0 * k_left + 10.0 * k_right) / (k_left + k_right)
    assert out["rigidity_m"][0] == pytest.approx(expected, rel=1e-12)
    assert out["rigidity_m"][1] == pytest.approx(0.0, abs=1e-12)
    # (at rest the yielding ones are the stiffer: the centre on the other side)
    assert b.centres_of_stiffness_m()[0, 0] < 0.0 < out["rigidity_m"][0]


def test_the_command_line_designs_a_moat_and_refuses_a_line(tmp_path):
    from pathlib import Path

    import pandas as pd
    from typer.testing import CliRunner

    from pounding.cli import app

    examples = Path(__file__).parents[1] / "examples"
    plan, record = examples / "plan_building.toml", examples / "el_centro_ns.AT2"
    runner = CliRunner()
    args = ["moat", str(plan), "--record-x", str(record), "--record-y", str(record), "--scale", "0.5",
            "--angles", "0,45,90", "--duration", "5", "--d-m", "0.05", "--scheduler", "serial",
            "--out", str(tmp_path)]
    done = runner.invoke(app, args, catch_exceptions=False)
    assert done.exit_code == 0, done.output
    building = PlanBuilding.from_toml(plan)
    quake = pounding.Record.from_at2(record)
    pair = pounding.RecordPair(quake, quake).scaled(0.5)
    found = design.moat_design(building, pair, [0.0, 45.0, 90.0], 5.0, d_m_m=0.05, scheduler="serial")
    words = " ".join(done.output.split())
    assert f"the design displacement: {found.design_displacement_m:.4g} m, the largest of 1 pairs" in words
    assert f"D_TM: {found.code['d_tm_m']:.4g} m" in words
    assert f"the moat's demand: {found.moat_demand_m:.4g} m" in words
    need = max(found.moat_demand_m, found.code["d_tm_m"])
    verdict = "enough" if 0.15 >= need else f"short by {need - 0.15:.4g} m"
    assert f"the moat's smallest gap 0.15 m against {need:.4g} m: {verdict}" in words
    runs = pd.read_csv(tmp_path / "moat_runs.csv")
    assert runs["disp_max_m"].to_numpy() == pytest.approx(found.data["disp_max_m"].to_numpy(), rel=1e-12)
    critical = pd.read_csv(tmp_path / "moat_critical.csv")
    assert critical["angle_deg"].tolist() == found.critical["angle_deg"].tolist()
    assert (tmp_path / "moat_design.png").stat().st_size > 0
    # the accidental eccentricity's four cases: each pair's critical run and its case in the table
    shifted = runner.invoke(app, [*args[:-1], str(tmp_path / "acc"), "--accidental", "0.05"],
                            catch_exceptions=False)
    assert shifted.exit_code == 0, shifted.output
    assert "1 pair(s) x 3 orientations x 4 accidental eccentricities = 12 runs" in " ".join(
        shifted.output.split())
    found = design.moat_design(building, pair, [0.0, 45.0, 90.0], 5.0, d_m_m=0.05, accidental=0.05,
                               scheduler="serial")
    critical = pd.read_csv(tmp_path / "acc" / "moat_critical.csv")
    assert critical["eccentricity"].tolist() == found.critical["eccentricity"].tolist()
    assert critical["disp_max_m"].to_numpy() == pytest.approx(found.critical["disp_max_m"].to_numpy(),
                                                              rel=1e-12)
    assert len(pd.read_csv(tmp_path / "acc" / "moat_runs.csv")) == 12
    line = examples / "building_moat.toml"
    for bad, words in ((["moat", str(line), "--record-x", str(record), "--record-y", str(record)],
                        "not a building in plan"),
                       (["moat", str(plan), "--record-x", str(record), "--record-y", str(record),
                         "--scale", "-1"], "--scale"),
                       (["moat", str(plan), "--record-x", str(record)], "--record-y")):
        refused = runner.invoke(app, [*bad, "--out", str(tmp_path / "no")])
        assert refused.exit_code != 0 and words in " ".join(refused.output.split()), (bad, refused.output)
    assert not (tmp_path / "no").exists()


def test_the_code_s_d_m_from_the_bearings_is_a_fixed_point_of_its_formulas():
    # four bilinear bearings with dashpots: at D, each K = (k1 Dy + k2 (D - Dy)) / D, a cycle's loop
    # 4 Q (D - Dy) with Q = (k1 - k2) Dy, each dashpot's pi c w D^2; T = 2 pi sqrt(m / K), beta = E / (2 pi K
    # D^2); D_M = g S_M1 T / (4 pi^2 B(beta)): the D returned satisfies them
    k1, k2, dy, c = 1.2e7, 1.2e6, 0.01, 2e4
    b = _building()
    mass = 6.0e5
    out = design.asce7_bearings_displacement(b, 0.9)
    d = out["d_m_x_m"]
    k = 4 * (k1 * dy + k2 * (d - dy)) / d
    t = 2.0 * math.pi * math.sqrt(mass / k)
    energy = 4 * 4 * (k1 - k2) * dy * (d - dy) + 4 * math.pi * c * (2.0 * math.pi / t) * d * d
    beta = energy / (2.0 * math.pi * k * d * d)
    assert out["t_m_x_s"] == pytest.approx(t, rel=1e-8)
    assert out["beta_m_x"] == pytest.approx(beta, rel=1e-8)
    assert d == pytest.approx(design.asce7_displacement(0.9, t, beta)["d_m_m"], rel=1e-8)
    assert out["d_m_m"] == max(out["d_m_x_m"], out["d_m_y_m"])
    with pytest.raises(InputError) as info:
        design.asce7_bearings_displacement(b, -0.9)
    assert info.value.field == "s_m1_g"
