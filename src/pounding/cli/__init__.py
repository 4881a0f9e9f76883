"""The ``pounding`` command: ``simulate``, ``sweep``, ``campaign``, ``reproduce``, ``identify``,
``lab``, ``spectrum``, ``rotd``, ``orientations``, ``moat``, ``study``, ``design``, ``continue``,
``coexistence``, ``bifurcation``, ``basins``, ``lyapunov`` (and ``warm-up``, hidden: a no-op since the
core is compiled at install, kept for scripts).

Every command checks its inputs and its output paths before any work, writes its files
atomically, answers bad input with exit code 2 and a line naming the field and the fix, a
run that stopped early with 1, and Ctrl-C with 130 and a line saying what was kept.
"""

from . import _continue, _design, _diagram, _lab, _pairs, _paper, _runs, _campaign, _spectrum, _study  # noqa: F401,E501 - they register the commands
from ._app import app

__all__ = ["app"]
