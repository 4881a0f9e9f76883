"""Analysis: periodic orbits of the impacting oscillator and their exact Floquet stability."""

from .periodic import PeriodicOrbit, periodic_orbit

__all__ = ["PeriodicOrbit", "periodic_orbit"]
