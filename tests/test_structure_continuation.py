"""Continuation of a structure's periodic orbits (pounding.continuation with a Structure or an Adjacent
pair): the exact n-dof monodromy along the branch, its folds and grazings located.

- One level is the oscillator's branch, row for row and bifurcation for bifurcation.
- At a located fold a multiplier is 1; at a located grazing the wall side's or link's clearance over the
  orbit is 0 (its run from the bifurcation's state); every row is a periodic orbit (``Branch.orbit``).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import pounding as pd_

ROOT = Path(__file__).resolve().parents[1]
ISO = pd_.Isolator(slopes_n_m=[2e5], breakpoints_m=[], damping_n_s_m=4e3)


def _building() -> pd_.Structure:
    return pd_.Structure(2.0e3, ISO, [pd_.Storey(1.0e3, 2.0e6, 2.0e3)],
                         [pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(2e6, 2e3))])


def _pair() -> pd_.Adjacent:
    first = pd_.Structure(2.0e3, ISO, [pd_.Storey(1.0e3, 2.0e6, 2.0e3)])
    second = pd_.Structure.fixed_base([pd_.Storey(2.0e3, 8.0e6, 4.0e3)])
    return pd_.Adjacent(first, second, [pd_.Link(1, 1, 0.02, pd_.KelvinVoigt(2e6, 2e3))])


def test_one_level_is_the_oscillators_branch():
    osc = pd_.presets.paper_damped()
    one = pd_.continuation(osc, 0.05, (1.5, 2.5))
    many = pd_.continuation(pd_.Structure.from_oscillator(osc), 0.05, (1.5, 2.5))
    a, b = one.to_dataframe(), many.to_dataframe()
    assert list(a.columns) == list(b.columns) and len(a) == len(b)
    numbers = [c for c in a.columns if a[c].dtype != bool]
    np.testing.assert_allclose(b[numbers].to_numpy(float), a[numbers].to_numpy(float), rtol=1e-12, atol=1e-15)
    assert [(x.kind, round(x.freq_hz, 9)) for x in many.bifurcations] == [
        (x.kind, round(x.freq_hz, 9)) for x in one.bifurcations]
    assert [x.side for x in many.bifurcations if x.kind == "grazing"] == ["wall0_left", "wall0_right"]


@pytest.mark.parametrize("make, slot", [(_building, None), (_pair, 0)])
def test_folds_have_a_multiplier_1_and_grazings_touch(make, slot):
    model = make()
    branch = pd_.continuation(model, 0.05, (1.0, 2.5))
    assert branch.success, branch.message
    kinds = [b.kind for b in branch.bifurcations]
    assert kinds.count("fold") == 2 and kinds.count("grazing") >= 2
    for bif in branch.bifurcations:
        assert bif.located and isinstance(bif.state, pd_.State)
        if bif.kind == "fold":
            assert np.abs(bif.multipliers - 1.0).min() <= 1e-6
        if bif.kind == "grazing":
            exc = pd_.Harmonic(bif.a_g, bif.freq_hz, phase=bif.phase_rad)
            run = pd_.simulate(model, exc, 1.0 / bif.freq_hz, bif.state, sample_rate_hz=0)
            names = [f"wall0_{s}" for s in ("left", "right")] if slot is None else ["link0"]
            c = run.clearance_m[names.index(bif.side)]
            assert abs(c) <= 1e-7 * 0.02, (bif.side, c)
    # a row is a periodic orbit, with the branch's multipliers
    i = len(branch) // 3
    orbit = branch.orbit(i)
    assert orbit.converged and orbit.iterations <= 1, orbit.message
    row = branch.multipliers[i][np.isfinite(branch.multipliers[i])]
    np.testing.assert_allclose(np.sort(np.abs(orbit.multipliers)), np.sort(np.abs(row)), atol=1e-7)


def test_a_number_of_the_structure_continued():
    branch = pd_.continuation(_building(), 0.05, 1.6, parameter="storeys[0].stiffness_n_m", values=(2e6, 4e6))
    assert branch.success, branch.message
    assert branch.to_dataframe().columns[0] == "storeys[0].stiffness_n_m"
    assert isinstance(branch.oscillator, pd_.Structure)


def test_refusals():
    with pytest.raises(pd_.InputError, match="state"):
        pd_.continuation(_building(), 0.05, (1.0, 2.0), guess=pd_.State.at_rest(pd_.presets.paper_damped()))
    with pytest.raises(pd_.InputError, match="parameter"):
        pd_.continuation(_building(), 0.05, 1.6, parameter="storeys[3].stiffness_n_m", values=(1e6, 2e6))


def test_the_command_line_follows_a_building_s_branch(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    _building().to_toml(tmp_path / "b.toml")
    result = CliRunner().invoke(app, ["continue", str(tmp_path / "b.toml"), "--a-g", "0.05", "--from", "1.0",
                                      "--to", "2.5", "--out", str(tmp_path / "branch.csv"), "--plot",
                                      str(tmp_path / "branch.png"), "--sweeps"])
    assert result.exit_code == 0, result.output
    assert "grazing (wall0_left and wall0_right)" in result.output and "fold" in result.output
    assert "drawn alone" in result.output
    assert (tmp_path / "branch.png").stat().st_size > 10_000


def test_a_building_s_fold_and_grazing_followed_in_two_parameters():
    b = _building()
    branch = pd_.continuation(b, 0.05, (1.0, 2.5))
    fold = branch.folds()[0]
    curve = pd_.bifurcation_curve(b, fold, a_g=(0.04, 0.06), freqs_hz=(1.0, 3.0))
    df = curve.to_dataframe()
    assert len(df) > 20 and df["a_g"].min() == pytest.approx(0.04)
    np.testing.assert_allclose(df["critical_multiplier"], 1.0, atol=1e-6)  # (a fold all along)
    grazing = next(x for x in branch.bifurcations if x.kind == "grazing")
    curve = pd_.bifurcation_curve(b, grazing, a_g=(0.04, 0.06), freqs_hz=(0.5, 3.0))
    assert curve.success, curve.message
    df = curve.to_dataframe()
    slot = ["wall0_left", "wall0_right"].index(grazing.side)
    for i in (0, len(df) // 2, len(df) - 1):  # (the orbit just touches the wall: its exact clearance 0)
        row = df.iloc[i]
        exc = pd_.Harmonic(row["a_g"], row["freq_hz"], phase=row["phase_rad"])
        state = pd_.State._of(curve.states[i], ((0, 1),), pd_.State.at_rest(b).layout)
        run = pd_.simulate(b, exc, 1.0 / row["freq_hz"], state, sample_rate_hz=0)
        assert abs(run.clearance_m[slot]) <= 1e-7 * 0.02


def test_one_level_s_coexistence_map_is_the_oscillators():
    osc = pd_.presets.paper_damped()
    kw = dict(a_g=(0.04, 0.06), freqs_hz=(1.5, 2.5), levels=[0.05], kinds=["fold"], max_step=0.05,
              basin_sample=2, test_freqs_hz=[1.6, 1.8, 2.2])
    one, many = pd_.coexistence_map(osc, **kw), pd_.coexistence_map(pd_.Structure.from_oscillator(osc), **kw)
    assert one.matrix["verdict"].tolist() == ["one", "coexist", "one"]  # (cannot pass vacuously)
    pd.testing.assert_frame_equal(many.matrix, one.matrix)
    cols = ["freq_hz", "a_g"]
    np.testing.assert_allclose(many.to_dataframe()[cols], one.to_dataframe()[cols], rtol=1e-9)


def test_a_building_s_coexistence_map_is_judged_by_its_branch_sweeps_and_basins(tmp_path):
    b = _building()
    freqs = np.round(np.arange(1.3, 1.91, 0.1), 10)
    up, down = pd_.sweep(b, 0.05, freqs), pd_.sweep(b, 0.05, freqs, direction="down")
    m = pd_.coexistence_map(b, a_g=(0.04, 0.06), freqs_hz=(1.0, 2.5), levels=[0.05], kinds=["fold"],
                            basin_sample=2, sweeps=[up, down], test_freqs_hz=freqs)
    assert m.branches[0].success and len(m.curves) >= 1
    rows = m.matrix.set_index("freq_hz")
    # the sweeps part at 1.5-1.7 Hz (up on the impacting response, down on the one that misses the wall)
    differ = np.abs(up.alpha.max(axis=1) - down.alpha.max(axis=1)[::-1]) > 0.05 * up.alpha.max(axis=1)
    assert freqs[differ].tolist() == [1.5, 1.6, 1.7]
    np.testing.assert_array_equal(rows["sweep_responses"].to_numpy(), np.where(differ, 2.0, 1.0))
    assert (rows.loc[freqs[differ], "verdict"] == "coexist").all()
    assert (rows.loc[freqs[differ], "stable_orbits"] == 2).all()  # (the branch agrees)
    assert rows.loc[1.3, "stable_orbits"] == 1 and rows.loc[1.9, "stable_orbits"] == 1
    from pounding.analysis.witnesses import sweep_witness

    blank = dataclasses.replace(up, level_metrics=up.level_metrics.copy())
    blank.level_metrics[2] = np.nan  # (its window not measured again: no metrics, not a response)
    assert np.isnan(sweep_witness([blank], 0.05, float(freqs[2]))[0])
    assert sweep_witness([up, blank], 0.05, float(freqs[2]))[0] == 1.0
    with pytest.raises(pd_.InputError, match="sweeps of this system"):
        pd_.coexistence_map(b, levels=[0.05], sweeps=[pd_.sweep(pd_.presets.paper_damped(), 0.05, [1.0])])


def test_a_branch_with_no_orbit_to_start_from_says_so_and_the_map_starts_at_the_other_end(monkeypatch):
    from pounding.analysis import curves

    moat = pd_.Structure.from_toml(ROOT / "examples" / "building_moat.toml")
    with pytest.raises(pd_.InputError, match="no periodic orbit of 1 period.* to start from at 0.5") as err:
        pd_.continuation(moat, 0.1, (0.5, 0.9))  # (100 periods from rest at 0.5 Hz do not settle near one)
    assert err.value.field == "freqs_hz" and "reversed" in str(err.value)
    real, boxes = curves.continuation, []

    def low_end_fails(osc, level, box, **kw):
        boxes.append(tuple(box))
        if box[0] < box[1]:
            raise pd_.InputError(pd_.Problem.BAD_STATE, "freqs_hz", box, why="no orbit there", fix="-")
        return real(osc, level, box, **kw)

    monkeypatch.setattr(curves, "continuation", low_end_fails)
    kw = dict(a_g=(0.04, 0.06), freqs_hz=(1.5, 2.5), levels=[0.05], kinds=["fold"], max_step=0.05,
              basin_sample=0, test_freqs_hz=[1.6, 1.8, 2.2])
    m = pd_.coexistence_map(pd_.presets.paper_damped(), **kw)
    assert boxes == [(1.5, 2.5), (2.5, 1.5)]
    assert any("started at 2.5 Hz" in note for note in m.notes)
    assert m.matrix["stable_orbits"].tolist() == [1.0, 2.0, 1.0]  # (the same branch, followed downwards)
    monkeypatch.setattr(curves, "continuation", lambda osc, level, box, **kw: low_end_fails(osc, level,
                                                                                          sorted(box)))
    with pytest.raises(pd_.InputError, match="no periodic response to start its branch") as err:
        pd_.coexistence_map(pd_.presets.paper_damped(), **kw)
    assert err.value.field == "levels"


def test_the_command_line_maps_a_building_s_coexistence(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    _building().to_toml(tmp_path / "b.toml")
    result = CliRunner().invoke(app, ["coexistence", str(tmp_path / "b.toml"), "--a-g-min", "0.045",
                                      "--a-g-max", "0.055", "--levels", "0.05", "--from", "1.4",
                                      "--to", "1.8", "--basin-sample", "0",
                                      "--matrix", str(tmp_path / "m.csv")])
    assert result.exit_code == 0, result.output
    matrix = pd.read_csv(tmp_path / "m.csv")
    assert "coexist" in set(matrix["verdict"]) and len(matrix) == 5


def test_the_command_line_exits_1_when_a_branch_left_test_points_unreached(tmp_path, monkeypatch):
    from typer.testing import CliRunner

    from pounding.analysis import curves
    from pounding.cli import app

    real = curves.coexistence_map

    def short_branch(*args, **kw):  # (the map as it is, the branch said not to reach its last two points)
        m = real(*args, **kw)
        matrix = m.matrix.copy()
        matrix.loc[matrix.index[-2:], "branch_reached"] = False
        return dataclasses.replace(m, matrix=matrix)

    monkeypatch.setattr(curves, "coexistence_map", short_branch)
    _building().to_toml(tmp_path / "b.toml")
    args = ["coexistence", str(tmp_path / "b.toml"), "--a-g-min", "0.045", "--a-g-max", "0.055", "--levels",
            "0.05", "--from", "1.4", "--to", "1.8", "--basin-sample", "0"]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 1, result.output
    assert "2 test point(s) no branch reached: a_G 0.05: 1.7-1.8" in result.output.replace("\n", " ")
    monkeypatch.setattr(curves, "coexistence_map", real)
    assert CliRunner().invoke(app, args).exit_code == 0



def test_no_bumpers_takes_a_one_mass_file_s_bumpers_away(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    pd_.presets.paper_printed().to_toml(tmp_path / "ybs.toml")
    args = ["sweep", str(tmp_path / "ybs.toml"), "--a-g", "0.05", "--fmin", "1.0", "--fmax", "1.2"]
    with_bumpers = CliRunner().invoke(app, args)
    without = CliRunner().invoke(app, [*args, "--no-bumpers"])
    preset = CliRunner().invoke(app, ["sweep", "--preset", "paper-printed", "--no-bumpers", *args[2:]])
    assert with_bumpers.exit_code == without.exit_code == preset.exit_code == 0, without.output
    assert "1.1 - 1.2" in with_bumpers.output  # (the contact range, with bumpers)
    def contact_range(output: str) -> list[str]:
        return [x for x in output.splitlines() if "contact range" in x]

    line = contact_range(without.output)
    assert line and "none" in line[0] and line == contact_range(preset.output)


def test_a_branch_starts_from_a_structure_s_state():
    # a run's final state as the first orbit's guess (its section: its time's forcing angle)
    b = _building()
    start = pd_.simulate(b, pd_.Harmonic(0.05, 1.0), 20.0, sample_rate_hz=0).final_state
    branch = pd_.continuation(b, 0.05, (1.0, 1.1), guess=start)
    assert branch.success and len(branch.to_dataframe()) > 1, branch.message
    other = pd_.simulate(_pair(), pd_.Harmonic(0.05, 1.0), 1.0).final_state
    with pytest.raises(pd_.InputError, match="guess"):  # (a state of another structure)
        pd_.continuation(b, 0.05, (1.0, 1.1), guess=other)
