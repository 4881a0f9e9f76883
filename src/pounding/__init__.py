"""pounding: base-isolated masses pounding against deformable bumpers, simulated exactly.

The public surface is re-exported here; modules with a leading underscore are private.
"""

from . import data, lab, plots, presets, records  # noqa: F401 (lab: public as pounding.lab)
from .analysis import (Bifurcation, BifurcationCurve, Branch, CoexistenceMap, LyapunovSpectrum, PeriodicOrbit,
                       bifurcation_curve, coexistence_map, continuation, largest_exponents, lyapunov,
                       periodic_orbit)
from ._errors import InputError, Interrupted, OutputError, PoundingWarning, Problem, Status, StoreError
from ._warm_up import WarmUp, warm_up
from .engine import EnergyLedger, Run, State, simulate
from .excitation import Harmonic, Record
from .excitation.spectrum import response_spectrum
from .identification import (ContactLawFit, Identification, ModelFamily, Targets, fit_contact_law, identify,
                             paper_targets, rank_contact_laws)
from .metrics import HysteresisLoop, impact_table
from .model import (BoucWen, Bumpers, ElasticPlastic, Hertzdamp, HuntCrossley, Isolator, Jankowski,
                    KelvinVoigt, MeasurementChain, MultilinearBumper, Oscillator, Sensor)
from .protocols import (BasinStabilityMap, Basins, BifurcationDiagram, CampaignResult, PoundingSpectrum,
                        SweepResult, basin_stability_map, basins, bifurcation_diagram, campaign,
                        paper_frequencies_hz, pounding_spectrum, sweep)
from .studies import StudyResult, StudySpec, open_study, study

__version__ = "0.1.0"

__all__ = [
    "Bumpers", "CampaignResult", "ContactLawFit", "Identification", "ModelFamily", "Targets", "EnergyLedger",
    "Harmonic", "HuntCrossley", "HysteresisLoop",
    "BoucWen", "ElasticPlastic", "Hertzdamp", "InputError", "Interrupted", "OutputError",
    "StoreError", "PoundingWarning",
    "Isolator",
    "Jankowski", "MultilinearBumper", "KelvinVoigt", "Oscillator", "Problem", "Record",
    "Run", "State", "Status", "SweepResult", "campaign", "impact_table", "paper_frequencies_hz",
    "data", "fit_contact_law", "identify", "paper_targets", "rank_contact_laws", "presets", "simulate",
    "sweep",
    "WarmUp", "warm_up", "plots", "records", "response_spectrum", "PoundingSpectrum", "pounding_spectrum",
    "StudyResult", "StudySpec", "open_study", "study", "PeriodicOrbit", "periodic_orbit",
    "Bifurcation", "Branch", "continuation", "BifurcationCurve", "CoexistenceMap", "bifurcation_curve",
    "coexistence_map", "BifurcationDiagram", "bifurcation_diagram", "Basins", "basins",
    "BasinStabilityMap", "basin_stability_map", "LyapunovSpectrum", "lyapunov", "largest_exponents",
    "MeasurementChain", "Sensor",
]
