"""Preloaded by the forkserver that a study's worker processes are forked from (never imported
otherwise): what a chunk needs, the store's code, Zarr and the compiled kernels, is loaded once
in the server, so that each worker starts with it in memory instead of loading it again."""

import zarr  # noqa: F401

from .._warm_up import warm_up
from . import study_points, study_store  # noqa: F401

warm_up()
