"""Analysis: periodic orbits of the impacting oscillator, their exact Floquet stability, and
their branches followed through folds with the bifurcations located."""

from .branch import Bifurcation, Branch
from .continuation import continuation
from .periodic import PeriodicOrbit, periodic_orbit

__all__ = ["Bifurcation", "Branch", "PeriodicOrbit", "continuation", "periodic_orbit"]
