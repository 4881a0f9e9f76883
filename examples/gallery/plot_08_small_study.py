"""
A small parameter study
=======================

A study is a grid over numbers of the system and of the excitation, by dotted name; each point here is a
harmonic run of 20 s at 2 Hz. The results go to a Zarr store chunk by chunk as they finish, so a study
stopped at any moment resumes where it stopped when run again, on threads, processes or a Dask cluster.
Here: how many impacts in 20 s as the left gap (the right one stays at the paper's 15 mm) and the
table's acceleration change.
"""

import tempfile
from pathlib import Path

import numpy as np

import pounding

spec = pounding.StudySpec(pounding.presets.paper_printed(),
                          {"kind": "simulate", "freq_hz": 2.0, "duration_s": 20.0},
                          {"bumpers.gap_left_m": list(np.round(np.linspace(0.005, 0.03, 6), 3)),
                           "a_g": [0.05, 0.1, 0.2]})
store = Path(tempfile.mkdtemp()) / "gaps.zarr"
dataset = pounding.study(spec, store, progress=False)      # an xarray Dataset on the grid's axes
print(dataset["impacts"].to_pandas())

# %%
# Impacts against the left gap, one line per table acceleration (the store opened again, as a later
# session would).
result = pounding.open_study(store)
result.plot("impacts", x="bumpers.gap_left_m", hue="a_g")

# %%
# Rerunning the same study on the same store computes nothing: every point is done, and each keeps the
# session that computed it.
again = pounding.study(spec, store, progress=False)
print("all done:", bool(again["done"].all()), "; sessions:", np.unique(again["session"].values))
