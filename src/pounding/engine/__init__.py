"""Compiled, event-driven integration (private modules) behind :func:`simulate`."""

from .result import EnergyLedger, Run
from .state import State
from .simulate import simulate
from .structure import StructureState
from .adjacent_result import AdjacentRun
from .structure_result import StructureEnergy, StructureRun

__all__ = ["AdjacentRun", "EnergyLedger", "Run", "State", "StructureEnergy", "StructureRun", "StructureState",
           "simulate"]
