"""Preloaded by the forkserver that the task runner's worker processes are forked from (never
imported otherwise): pounding and its compiled kernels are loaded once in the server, so that each
worker starts with them in memory instead of loading them again.  At the top of the package's
layers, beside ``_warm_up`` (it imports everything)."""

from ._warm_up import warm_up

warm_up()
