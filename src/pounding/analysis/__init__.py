"""Analysis: periodic orbits of the impacting oscillator, their exact Floquet stability, and
their branches followed through folds with the bifurcations located, and folds and grazings
followed in two parameters (a_G, f); the Lyapunov spectrum of a response."""

from .branch import Bifurcation, Branch
from .continuation import continuation
from .curve_result import BifurcationCurve, CoexistenceMap
from .curves import bifurcation_curve, coexistence_map
from .lyapunov import largest_exponents, lyapunov
from .lyapunov_result import LyapunovSpectrum
from .periodic import PeriodicOrbit, periodic_orbit
from .._errors import old_names

__all__ = ["Bifurcation", "BifurcationCurve", "Branch", "CoexistenceMap", "LyapunovSpectrum", "PeriodicOrbit",
           "bifurcation_curve", "coexistence_map", "continuation",
           "largest_exponents", "lyapunov", "periodic_orbit"]


# its name before one orbit served every system, for one release
__getattr__ = old_names(__name__, {
    "StructurePeriodicOrbit": ("pounding.PeriodicOrbit", lambda: PeriodicOrbit,
                               "one class for every system")})
