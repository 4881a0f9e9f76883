"""Preloaded by the forkserver that the task runner's worker processes are forked from (never
imported otherwise): pounding's modules and its compiled core are loaded once in the server, so that each
worker starts with them in memory.  At the top of the package's layers (it imports everything)."""

from . import engine, protocols, studies  # noqa: F401
from .studies import worker_preload  # noqa: F401
