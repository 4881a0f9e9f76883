"""Preloaded by the forkserver that a study's worker processes are forked from (never imported
otherwise): what a chunk needs besides the engine (``pounding._worker_boot`` loads that), the
store's code and Zarr, is loaded once in the server."""

import zarr  # noqa: F401

from . import points, store  # noqa: F401
