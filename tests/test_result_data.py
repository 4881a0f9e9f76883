"""Every result class names its data the same way (``data``, never ``dataset`` or ``table``) and gives
it both as a table (``to_dataframe``) and as labelled arrays (``to_xarray``)."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil

import numpy as np
import pandas as pd
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
