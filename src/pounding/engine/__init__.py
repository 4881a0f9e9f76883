"""Compiled, event-driven integration (private modules) behind :func:`simulate`."""

from .result import EnergyLedger, Run, State
from .simulate import simulate

__all__ = ["EnergyLedger", "Run", "State", "simulate"]
