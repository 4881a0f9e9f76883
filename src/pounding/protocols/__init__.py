"""Protocols: the virtual shaking table (stepped-sine sweeps), the paper's campaign, pounding spectra
(parameter studies are ``pounding.studies``)."""

from .basins import Basins, basins
from .bifurcation_diagram import BifurcationDiagram, bifurcation_diagram
from .campaign import CampaignResult, campaign
from .pounding_spectrum import pounding_spectrum
from .pounding_spectrum_result import PoundingSpectrum
from .sweep import SweepPlan, paper_frequencies_hz, sweep
from .sweep_result import SweepResult

__all__ = ["Basins", "BifurcationDiagram", "CampaignResult", "PoundingSpectrum", "SweepPlan", "SweepResult",
           "campaign", "paper_frequencies_hz",
           "basins", "bifurcation_diagram", "pounding_spectrum", "sweep"]
