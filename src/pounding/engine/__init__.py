"""Compiled, event-driven integration (private modules) behind :func:`simulate`."""

from .result import EnergyLedger, Run
from .state import State
from .simulate import simulate
from .adjacent_result import AdjacentRun
from .structure_result import StructureEnergy, StructureRun

__all__ = ["AdjacentRun", "EnergyLedger", "Run", "State", "StructureEnergy", "StructureRun", "simulate"]


def __getattr__(name: str) -> object:
    if name == "StructureState":  # (0.1's name: one State for every system now)
        from .._errors import warn_renamed

        warn_renamed("pounding.engine.StructureState", "pounding.State", why="one State for every system")
        return State
    raise AttributeError(f"module 'pounding.engine' has no attribute {name!r}")
