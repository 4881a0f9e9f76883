"""Every result class names its data the same way (``data``, never ``dataset`` or ``table``) and gives
it both as a table (``to_dataframe``) and as labelled arrays (``to_xarray``)."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import pounding as pd_


def _result_classes() -> list[type]:
    out = []
    for info in pkgutil.walk_packages(pd_.__path__, "pounding."):
        if ".cli" in info.name:
            continue
        module = importlib.import_module(info.name)
        for _, cls in inspect.getmembers(module, inspect.isclass):
            mine = cls.__module__ == module.__name__ and not issubclass(cls, pd.DataFrame)  # (not tables)
            if mine and (hasattr(cls, "to_dataframe") or hasattr(cls, "to_xarray")):
                out.append(cls)
    return out


def test_every_result_class_has_both_and_one_name_for_its_data():
    classes = _result_classes()
    assert len(classes) >= 20
    for cls in classes:
        assert hasattr(cls, "to_dataframe") and hasattr(cls, "to_xarray"), cls
        if dataclasses.is_dataclass(cls):
            names = {f.name for f in dataclasses.fields(cls)}
            assert not names & {"dataset", "table"}, (cls, names & {"dataset", "table"})
    assert {"CampaignResult", "Run", "SweepResult", "Basins"} <= {c.__name__ for c in classes}


def test_a_run_and_a_campaign_as_tables_and_datasets():
    osc = pd_.presets.paper_damped()
    run = pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 2.0, state=pd_.State.at_rest(osc, velocity_m_s=0.6))
    ds = run.to_xarray()
    assert isinstance(ds, xr.Dataset) and ds.sizes["sample"] == len(run.to_dataframe())
    np.testing.assert_array_equal(ds["displacement_m"].values, run.displacement)
    assert ds["time_s"].attrs["units"] == "s" and ds.attrs["status"] == "SUCCESS"
    assert "time_s" in ds.coords and ds["time_s"].dims == ("sample",)
    np.testing.assert_array_equal(ds["time_s"].values, run.t)
    result = pd_.campaign(osc.without_bumpers(), osc, nbs_a_g=(0.05,), ybs_a_g=(0.05,),
                          freqs_hz=[1.5, 2.0], directions=("up",), steady="fixed", cycles=5)
    assert result.to_xarray() is result.data
    df = result.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == 4
    assert {"configuration", "a_g", "direction", "freq_hz", "alpha"} <= set(df.columns)


def test_every_run_gives_its_quantities_as_a_study_keeps_them():
    osc = pd_.presets.paper_damped()
    run = pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 3.0, state=pd_.State.at_rest(osc, velocity_m_s=0.6))
    q = run.quantities()
    assert q["impacts"] == len(run.contacts) > 0 and q["status"] == 0.0
    assert q["acc_max_g"] == run.abs_acceleration_max / 9.81
    assert q["disp_max_m"] == max(abs(run.displacement_max), abs(run.displacement_min))
    assert q["compression_max_m"] == run.contacts["max_compression_m"].max()
    assert q["impact_speed_max_m_s"] == run.contacts["v_in_m_s"].abs().max()
    iso = pd_.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[], damping_n_s_m=2.0e3)
    wall = pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(1e8, 1e4))
    b = pd_.Structure(2.0e3, iso, [pd_.Storey(1.0e3, 2.0e6)] * 2, [wall])
    brun = pd_.simulate(b, pd_.Harmonic(0.3, 1.5), 3.0)
    bq = brun.quantities()
    assert bq["impacts"] == len(brun.contacts) > 0
    assert bq["disp_max_m"] == max(abs(brun.displacement_max[0]), abs(brun.displacement_min[0]))
    assert bq["top_disp_max_m"] == max(abs(brun.displacement_max[-1]), abs(brun.displacement_min[-1]))
    assert bq["impact_force_max_n"] == brun.contacts["peak_force_n"].max()
    assert bq["compression_max_m"] == brun.contacts["max_compression_m"].max() > 0
    # one name, one meaning for every system: a single mass is its structure's base and top, without storeys
    assert tuple(q) == tuple(bq) == pd_.engine.run_quantities.RUN_QUANTITIES
    assert q["top_disp_max_m"] == q["disp_max_m"] and q["top_acc_max_g"] == q["acc_max_g"]
    assert np.isnan(q["drift_ratio_max"]) and bq["drift_ratio_max"] > 0
    for read in (lambda q: q["base_disp_max_m"], lambda q: q.get("base_disp_max_m")):
        with pytest.warns(FutureWarning, match="'base_disp_max_m' is now 'disp_max_m'"):
            assert read(bq) == bq["disp_max_m"]
    assert q.get("no_such_name", 1.5) == 1.5
    with pytest.raises(KeyError):
        q["disp_max"]


def test_a_single_mass_s_run_is_its_one_level_structure_s_read_as_one_mass():
    """A single mass's Run holds the run of the one-level structure it is (``levels``): its histories,
    extrema, contacts, impacts and events are that run's, number for number; a Run without its levels (made
    by hand, or kept from before) builds the same tables from its own arrays."""
    osc = pd_.presets.paper_damped()
    run = pd_.simulate(osc, pd_.Harmonic(0.1, 2.0), 3.0)
    lv = run.levels
    assert isinstance(lv, pd_.StructureRun) and lv.structure == pd_.Structure.from_oscillator(osc)
    np.testing.assert_array_equal(run.displacement, lv.displacement[:, 0])
    np.testing.assert_array_equal(run.bumper_force_right, lv.contact_force[:, 1])
    assert run.abs_acceleration_max == lv.abs_acceleration_max[0]
    assert len(run.contacts) > 0
    bare = dataclasses.replace(run, levels=None)
    for name in ("contacts", "impacts", "events"):
        pd.testing.assert_frame_equal(getattr(bare, name), getattr(run, name))
    # one summary and one point for every run: a single mass's are its one-level structure's, run as one
    structure_run = pd_.simulate(lv.structure, pd_.Harmonic(0.1, 2.0), 3.0)
    for made in (run, bare):
        pd.testing.assert_series_equal(made.summary(), structure_run.summary())
        mine, its = made.quantities(), structure_run.quantities()
        assert list(mine) == list(its)
        np.testing.assert_array_equal(list(mine.values()), list(its.values()))
    (only,) = pd_.engine.structure_runs(run)
    assert only is lv
