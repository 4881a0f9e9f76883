"""Compiled, event-driven integration (private modules) behind :func:`simulate`."""

from .result import EnergyLedger, Run, State
from .simulate import simulate
from .structure import StructureState
from .structure_result import AdjacentRun, StructureEnergy, StructureRun

__all__ = ["AdjacentRun", "EnergyLedger", "Run", "State", "StructureEnergy", "StructureRun", "StructureState",
           "simulate"]
