"""Parameter studies that outgrow one machine: a spec (a system, what each point computes, a grid),
a resumable Zarr store filled region by region, and the shared task runner's schedulers (threads,
processes, Dask) to fill it."""

from .result import StudyResult, open_study
from .run import study
from .spec import StudySpec

__all__ = ["StudyResult", "StudySpec", "open_study", "study"]
