"""Compiled, event-driven integration (private modules) behind :func:`simulate`."""

from .result import EnergyLedger, Run
from .state import State
from .simulate import simulate, structure_runs
from .adjacent_result import AdjacentRun
from .structure_result import StructureRun

__all__ = ["AdjacentRun", "EnergyLedger", "Run", "State", "StructureRun", "simulate", "structure_runs"]


# 0.1's names, one class for every system now: they still answer for one release, with a FutureWarning
_RENAMED = {"StructureState": ("State", State), "StructureEnergy": ("EnergyLedger", EnergyLedger)}


def __getattr__(name: str) -> object:
    if name in _RENAMED:
        from .._errors import warn_renamed

        new, cls = _RENAMED[name]
        warn_renamed(f"pounding.engine.{name}", f"pounding.{new}", why="one class for every system")
        return cls
    raise AttributeError(f"module 'pounding.engine' has no attribute {name!r}")
