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

__all__ = ["Bifurcation", "BifurcationCurve", "Branch", "CoexistenceMap", "LyapunovSpectrum", "PeriodicOrbit",
           "bifurcation_curve", "coexistence_map", "continuation",
           "largest_exponents", "lyapunov", "periodic_orbit"]


def __getattr__(name: str) -> object:
    if name == "StructurePeriodicOrbit":  # (its name before one orbit served every system, for one release)
        from .._errors import warn_renamed

        warn_renamed("pounding.analysis.StructurePeriodicOrbit", "pounding.analysis.PeriodicOrbit",
                     why="one class for every system")
        return PeriodicOrbit
    raise AttributeError(f"module 'pounding.analysis' has no attribute {name!r}")
