"""What the system is: mass, isolator, bumpers and their contact laws."""

from .contact_laws import ElasticPlastic, Hertzdamp, HuntCrossley, Jankowski, KelvinVoigt, MultilinearBumper
from .contact_laws import RigidStop
from .friction import FrictionIsolator
from .isolator import BoucWen, Isolator
from .measurement import MeasurementChain, Sensor
from .oscillator import Oscillator
from .plan import PlanBuilding
from .moats import CircularMoat, RectangularMoat
from .plan_parts import Bearing, Floor, Frame
from .adjacent import Adjacent, Link
from .structure import Structure
from .structure_parts import Bumpers, Stand, Storey, Wall
from .triple_friction import TripleFrictionPendulum

__all__ = ["Adjacent", "Link", "BoucWen", "Bumpers", "ElasticPlastic", "FrictionIsolator", "Hertzdamp",
           "HuntCrossley",
           "Isolator",
           "Jankowski",
           "KelvinVoigt", "MeasurementChain", "MultilinearBumper", "Oscillator", "RigidStop", "Sensor",
           "Stand", "Storey", "Structure", "TripleFrictionPendulum", "Wall",
           "Bearing", "CircularMoat", "Floor", "Frame", "PlanBuilding", "RectangularMoat"]
