"""Compiled, event-driven integration (private modules) behind :func:`simulate`."""

from .result import EnergyLedger, Run
from .state import State
from .simulate import simulate, structure_runs
from .adjacent_result import AdjacentRun
from .structure_result import StructureRun
from .plan_result import PlanRun
from .._errors import old_names

__all__ = ["AdjacentRun", "EnergyLedger", "PlanRun", "Run", "State", "StructureRun", "simulate",
           "structure_runs"]


# 0.1's names, one class for every system now: they still answer for one release, with a FutureWarning
__getattr__ = old_names(__name__, {
    "StructureState": ("pounding.State", lambda: State, "one class for every system"),
    "StructureEnergy": ("pounding.EnergyLedger", lambda: EnergyLedger, "one class for every system")})
