"""Preloaded by the forkserver that worker processes are forked from (never imported otherwise):
pounding and its compiled kernels are loaded once in the server, so that each worker starts with
them in memory instead of loading them again."""

from .._warm_up import warm_up

warm_up()
