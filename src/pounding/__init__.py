"""pounding: base-isolated masses pounding against deformable bumpers, simulated exactly.

The public surface is re-exported here; modules with a leading underscore are private.
"""

from . import presets
from ._errors import InputError, Problem, Status
from .engine import EnergyLedger, Run, State, simulate
from .excitation import Harmonic, Record
from .model import Bumpers, HuntCrossley, Isolator, KelvinVoigt, Oscillator

__version__ = "0.1.0"

__all__ = [
    "Bumpers", "EnergyLedger", "Harmonic", "HuntCrossley", "InputError", "Isolator",
    "KelvinVoigt", "Oscillator", "Problem", "Record", "Run", "State", "Status", "presets",
    "simulate",
]
