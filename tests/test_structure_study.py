"""Parameter studies of structures (``pounding.study`` with a Structure or Adjacent): grid names reach any
storey's, wall's or link's number, each point keeps what a direct run of its structure gives, and the spec
refuses what a structure cannot take, naming it."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import pounding as pd_

ROOT = Path(__file__).resolve().parents[1]


def building() -> pd_.Structure:
    iso = pd_.Isolator(slopes_n_m=[4.0e5, 1.0e5], breakpoints_m=[0.02], damping_n_s_m=2.0e3)
    wall = pd_.Wall(0, 0.03, 0.03, pd_.KelvinVoigt(2.0e7, 1.0e4))
    return pd_.Structure(3.0e3, iso, [pd_.Storey(2.0e3, 4.0e6, 4.0e3)] * 3, [wall])


def test_each_point_keeps_what_a_direct_run_of_its_structure_gives(tmp_path):
    b = building()
    spec = pd_.StudySpec(b, {"kind": "simulate", "a_g": 0.3, "freq_hz": 0.9, "duration_s": 6.0},
                         {"walls[0].gap_m": [0.02, 0.5], "storeys[2].stiffness_n_m": [2.0e6, 6.0e6]})
    ds = pd_.study(spec, str(tmp_path / "s.zarr"), scheduler="serial").compute()
    assert tuple(ds.attrs["quantities"]) == pd_.engine.run_quantities.RUN_QUANTITIES
    assert ds["walls[0].gap_m"].attrs["units"] == "m"
    assert ds["storeys[2].stiffness_n_m"].attrs["units"] == "N/m"
    for gap in (0.02, 0.5):
        for k in (2.0e6, 6.0e6):
            storeys = list(b.storeys)
            storeys[2] = dataclasses.replace(storeys[2], stiffness_n_m=k)
            wall = dataclasses.replace(b.walls[0], gap_left_m=gap, gap_right_m=gap)
            run = pd_.simulate(dataclasses.replace(b, storeys=tuple(storeys), walls=(wall,)),
                               pd_.Harmonic(0.3, 0.9), 6.0)
            point = ds.sel({"walls[0].gap_m": gap, "storeys[2].stiffness_n_m": k})
            heights = np.array([s.height_m for s in b.storeys])
            base = max(abs(run.displacement_max[0]), abs(run.displacement_min[0]))
            assert float(point["disp_max_m"]) == base
            assert float(point["top_acc_max_g"]) == run.abs_acceleration_max[-1] / 9.81
            assert float(point["acc_max_g"]) == run.abs_acceleration_max.max() / 9.81
            assert float(point["drift_ratio_max"]) == np.max(run.peak_drift / heights)
            assert float(point["impacts"]) == len(run.contacts)
            force = run.contacts["peak_force_n"].max() if len(run.contacts) else 0.0
            assert float(point["impact_force_max_n"]) == force
            for name, value in run.quantities().items():  # (and every other of the run's own)
                np.testing.assert_array_equal(float(point[name]), value)
    # the wide moat is never reached
    assert float(ds["impacts"].sel({"walls[0].gap_m": 0.5}).max()) == 0.0
    assert float(ds["impacts"].sel({"walls[0].gap_m": 0.02}).min()) > 0.0


def test_a_store_written_before_the_base_s_displacement_was_disp_max_m_resumes_and_reads_by_the_new_name(
        tmp_path):
    """A building's store of before keeps the base's displacement as ``base_disp_max_m`` (and has no arrays
    for the quantities added since): it resumes into its own arrays, and reads as ``disp_max_m``."""
    import xarray as xr

    spec = pd_.StudySpec(building(), {"kind": "simulate", "a_g": 0.3, "freq_hz": 0.9, "duration_s": 3.0},
                         {"walls[0].gap_m": [0.02, 0.03, 0.5]})
    fresh = pd_.study(spec, str(tmp_path / "new.zarr"), scheduler="serial").compute()
    old = xr.open_zarr(str(tmp_path / "new.zarr")).load()
    old = old.drop_vars(["impact_speed_max_m_s", "compression_max_m"])
    old = old.rename({"disp_max_m": "base_disp_max_m"})
    old["done"][1:] = False  # (cut short: its last two points to do)
    for name in ("base_disp_max_m", "top_disp_max_m"):
        old[name][1:] = np.nan
    for name in old.variables:
        old[name].encoding = {k: v for k, v in old[name].encoding.items() if k in ("chunks", "_FillValue")}
    old.to_zarr(str(tmp_path / "old.zarr"), zarr_format=2, consolidated=True)
    resumed = pd_.study(spec, str(tmp_path / "old.zarr"), scheduler="serial").compute()
    assert bool(resumed["done"].all())
    for data in (resumed, pd_.open_study(str(tmp_path / "old.zarr")).data):
        np.testing.assert_array_equal(data["disp_max_m"], fresh["disp_max_m"])
        np.testing.assert_array_equal(data["top_disp_max_m"], fresh["top_disp_max_m"])
        assert "base_disp_max_m" not in data and "compression_max_m" not in data
    import zarr

    group = zarr.open_group(str(tmp_path / "old.zarr"), mode="r", zarr_format=2)
    assert "base_disp_max_m" in group and "disp_max_m" not in group  # (written into its own arrays)


def test_a_structure_s_points_start_pushed_as_one_body_as_a_single_mass_s_do(tmp_path):
    b = building()
    options = {"kind": "simulate", "a_g": 0.3, "freq_hz": 0.9, "duration_s": 4.0, "v0_m_s": 0.4}
    ds = pd_.study(pd_.StudySpec(b, options, {"walls[0].gap_m": [0.02, 0.03]}), str(tmp_path / "v.zarr"),
                   scheduler="serial").compute()
    for gap in (0.02, 0.03):
        wall = dataclasses.replace(b.walls[0], gap_left_m=gap, gap_right_m=gap)
        s = dataclasses.replace(b, walls=(wall,))
        pushed = pd_.simulate(s, pd_.Harmonic(0.3, 0.9), 4.0, pd_.State.at_rest(s, velocity_m_s=0.4))
        at_rest = pd_.simulate(s, pd_.Harmonic(0.3, 0.9), 4.0)
        point = ds.sel({"walls[0].gap_m": gap})
        assert float(point["impacts"]) == len(pushed.contacts)
        assert float(point["top_acc_max_g"]) == pushed.abs_acceleration_max[-1] / 9.81
        assert pushed.abs_acceleration_max[-1] != at_rest.abs_acceleration_max[-1]  # (the push is felt)


def test_a_sweep_study_of_a_pair_and_a_study_file_of_a_building(tmp_path):
    isolated = dataclasses.replace(building(), walls=())
    old = pd_.Structure.fixed_base([pd_.Storey(2.5e3, 3.0e6, 5.0e3)] * 3)
    pair = pd_.Adjacent(isolated, old, [pd_.Link(3, 3, 0.05, pd_.KelvinVoigt(5.0e7, 2.0e4))])
    spec = pd_.StudySpec(pair, {"kind": "sweep", "a_g": 0.3, "freqs_hz": [0.7, 1.0], "cycles": 6,
                                "measure_cycles": 2}, {"links[0].gap_m": [0.01, 1.0]})
    walled = dataclasses.replace(pair, second=dataclasses.replace(
        old, walls=(pd_.Wall(3, 0.05, 0.05, pd_.KelvinVoigt(1e7, 1e3)),)))
    at, _ = pd_.StudySpec(walled, {"kind": "simulate", "a_g": 0.3, "freq_hz": 1.0, "duration_s": 1.0},
                          {"second.walls[0].gap_m": [0.07]}).point((0,))
    assert (at.second.walls[0].gap_left_m, at.second.walls[0].gap_right_m) == (0.07, 0.07)
    ds = pd_.study(spec, str(tmp_path / "p.zarr"), scheduler="serial").compute()
    direct = pd_.sweep(dataclasses.replace(pair, links=(dataclasses.replace(pair.links[0], gap_m=0.01),)),
                       0.3, [0.7, 1.0], steady="fixed", cycles=6, measure_cycles=2)
    near = ds.sel({"links[0].gap_m": 0.01})
    assert float(near["alpha_top_max"]) == np.max(direct.alpha_top)
    assert float(near["contact_nu_min"]) == 0.7 and np.isnan(float(ds["contact_nu_min"].sel(
        {"links[0].gap_m": 1.0})))
    # a study file whose [system] is a building's file, run from the command line
    from typer.testing import CliRunner

    from pounding.cli import app

    result = CliRunner().invoke(app, ["study", str(ROOT / "examples" / "study_moat.toml"), "--store",
                                      str(tmp_path / "moat.zarr"), "--scheduler", "serial"])
    assert result.exit_code == 0, result.output
    moat = pd_.open_study(str(tmp_path / "moat.zarr")).to_xarray().compute()
    assert moat["impacts"].shape == (4, 2) and bool(moat["done"].all())
    assert float(moat["impacts"].sel({"walls[0].gap_m": 0.05}).min()) > 0


def test_what_a_structure_cannot_take_is_refused_and_named(tmp_path):
    b = building()
    with pytest.raises(pd_.InputError, match=r"storeys.*has 3 values"):
        pd_.StudySpec(b, {"kind": "simulate", "a_g": 0.3, "freq_hz": 0.9, "duration_s": 1.0},
                      {"storeys[3].mass_kg": [1e3, 2e3]})
    with pytest.raises(pd_.InputError, match=r"grid.walls\[0\].gap_left_m"):
        pd_.StudySpec(b, {"kind": "simulate", "a_g": 0.3, "freq_hz": 0.9, "duration_s": 1.0},
                      {"walls[0].gap_m": [0.02], "walls[0].gap_left_m": [0.03]})
    with pytest.raises(pd_.InputError, match="storeys"):  # (a value the structure refuses, named)
        pd_.StudySpec(b, {"kind": "simulate", "a_g": 0.3, "freq_hz": 0.9, "duration_s": 1.0},
                      {"storeys[1].stiffness_n_m": [-1.0]})
    b.to_toml(tmp_path / "b.toml")
    compute = {"kind": "simulate", "a_g": 0.3, "freq_hz": 0.9, "duration_s": 1.0}
    # bumpers = false: the file's structure without its walls, as a single mass's file without its bumpers
    nbs = pd_.StudySpec.from_dict({"system": {"file": "b.toml", "bumpers": False}, "compute": compute,
                                   "grid": {"storeys[1].stiffness_n_m": [1e7]}}, base_dir=tmp_path)
    assert b.walls and nbs.system == b.without_bumpers() and nbs.system.walls == ()
    with pytest.raises(pd_.InputError, match=r"walls\[0\]"):  # (then no wall is left to vary)
        pd_.StudySpec.from_dict({"system": {"file": "b.toml", "bumpers": False}, "compute": compute,
                                 "grid": {"walls[0].gap_m": [0.02]}}, base_dir=tmp_path)
