"""Protocols: the virtual shaking table (stepped-sine sweeps), the paper's campaign, pounding spectra, the
orientations of a pair of components (parameter studies are ``pounding.studies``)."""

from .basin_stability import BasinStabilityMap, basin_stability_map
from .basins import Basins, basins
from .bifurcation_diagram import BifurcationDiagram, bifurcation_diagram
from .campaign import CampaignResult, campaign
from .orientations import Orientations, orientations
from .pounding_spectrum import pounding_spectrum
from .pounding_spectrum_result import PoundingSpectrum
from .sweep import SweepPlan, paper_frequencies_hz, sweep
from .sweep_result import SweepResult
from .._errors import old_names

__all__ = ["BasinStabilityMap", "Basins", "BifurcationDiagram", "CampaignResult", "Orientations",
           "PoundingSpectrum", "SweepPlan", "SweepResult", "campaign", "orientations", "paper_frequencies_hz",
           "basin_stability_map", "basins", "bifurcation_diagram", "pounding_spectrum", "sweep"]


# its name before one result served every system, for one release
__getattr__ = old_names(__name__, {
    "StructureSweepResult": ("pounding.protocols.SweepResult", lambda: SweepResult,
                             "one class for every system")})
