"""Protocols: the virtual shaking table (stepped-sine sweeps), the paper's campaign, pounding spectra
(parameter studies are ``pounding.studies``)."""

from .basin_stability import BasinStabilityMap, basin_stability_map
from .basins import Basins, basins
from .bifurcation_diagram import BifurcationDiagram, bifurcation_diagram
from .campaign import CampaignResult, campaign
from .pounding_spectrum import pounding_spectrum
from .pounding_spectrum_result import PoundingSpectrum
from .sweep import SweepPlan, paper_frequencies_hz, sweep
from .sweep_result import SweepResult

__all__ = ["BasinStabilityMap", "Basins", "BifurcationDiagram", "CampaignResult", "PoundingSpectrum",
           "SweepPlan", "SweepResult", "campaign", "paper_frequencies_hz",
           "basin_stability_map", "basins", "bifurcation_diagram", "pounding_spectrum", "sweep"]


def __getattr__(name: str):
    if name == "StructureSweepResult":  # (its name before one result served every system, for one release)
        from .._errors import warn_renamed

        warn_renamed("pounding.protocols.StructureSweepResult", "pounding.protocols.SweepResult",
                     why="one class for every system")
        return SweepResult
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
