"""What the system is: mass, isolator, bumpers and their contact laws."""

from .bumpers import Bumpers
from .contact_laws import ElasticPlastic, HuntCrossley, Jankowski, KelvinVoigt, MultilinearBumper
from .isolator import Isolator
from .oscillator import Oscillator

__all__ = ["Bumpers", "ElasticPlastic", "HuntCrossley", "Isolator", "Jankowski", "KelvinVoigt", "MultilinearBumper", "Oscillator"]
