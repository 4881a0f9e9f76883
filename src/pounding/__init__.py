"""pounding: base-isolated masses pounding against deformable bumpers, simulated exactly.

The public surface is re-exported here; modules with a leading underscore are private.  Names are
imported on first use (PEP 562), so ``import pounding`` and the command line's ``--help`` start at once:
``pounding.simulate`` loads the engine when it is first touched.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

# public name -> the module that defines it (relative to this package)
_NAMES = {
    ".analysis": ("Bifurcation", "BifurcationCurve", "Branch", "CoexistenceMap", "LyapunovSpectrum",
                  "PeriodicOrbit", "bifurcation_curve", "coexistence_map",
                  "continuation", "largest_exponents", "lyapunov", "periodic_orbit"),
    "._errors": ("InputError", "Interrupted", "MissingExtra", "OutputError", "PoundingWarning", "Problem",
                 "Status", "StoreError"),
    ".engine": ("AdjacentRun", "EnergyLedger", "PlanRun", "Run", "State", "StructureRun", "simulate"),
    ".excitation": ("Harmonic", "HarmonicPair", "Record", "RecordPair"),
    ".excitation.spectrum": ("response_spectrum",),
    ".excitation.rotd": ("rotd_spectrum",),
    ".identification": ("ContactLawFit", "Identification", "ModelFamily", "SystemFamily", "Targets",
                        "fit_contact_law", "identify", "paper_targets", "rank_contact_laws"),
    ".metrics": ("HysteresisLoop", "impact_table"),
    ".model": ("Adjacent", "Link", "BoucWen", "Bumpers", "ElasticPlastic", "FrictionIsolator", "Hertzdamp",
               "HuntCrossley", "Isolator", "Jankowski",
               "KelvinVoigt", "MeasurementChain", "MultilinearBumper", "Oscillator", "RigidStop", "Sensor",
               "Stand", "Storey", "Structure", "TripleFrictionPendulum", "Wall",
               "Bearing", "CircularMoat", "Floor", "Frame", "PlanBuilding", "RectangularMoat"),
    ".protocols": ("BasinStabilityMap", "Basins", "BifurcationDiagram", "CampaignResult", "Orientations",
                   "PoundingSpectrum", "SweepResult", "basin_stability_map", "basins",
                   "bifurcation_diagram",
                   "campaign", "orientations",
                   "paper_frequencies_hz", "pounding_spectrum", "sweep"),
    ".studies": ("StudyResult", "StudySpec", "open_study", "study"),
}
_WHERE = {name: module for module, names in _NAMES.items() for name in names}
# subpackages and modules reached as attributes (pounding.presets.paper_printed(), pounding.design, ...)
_MODULES = ("data", "lab", "plots", "presets", "records", "design", "reports", "analysis", "engine",
            "excitation", "identification", "metrics", "model", "protocols", "studies", "cli")

__all__ = sorted(_WHERE) + ["data", "lab", "plots", "presets", "records"]


# names of 0.1 that still answer for one release, with a FutureWarning: the old name -> (where, the new one)
_RENAMED = {"StructureState": (".engine", "State"), "StructureEnergy": (".engine", "EnergyLedger"),
            "StructureSweepResult": (".protocols", "SweepResult"),
            "StructurePeriodicOrbit": (".analysis", "PeriodicOrbit"),
            "StructureFamily": (".identification", "SystemFamily")}


def __getattr__(name: str) -> Any:
    if name in _RENAMED:
        from ._errors import warn_renamed

        where, new = _RENAMED[name]
        warn_renamed(f"pounding.{name}", f"pounding.{new}", why="one class for every system")
        return getattr(importlib.import_module(where, __name__), new)
    if name in _WHERE:
        value = getattr(importlib.import_module(_WHERE[name], __name__), name)
    elif name in _MODULES:
        value = importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module 'pounding' has no attribute {name!r}")
    globals()[name] = value  # (looked up once)
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_WHERE) | set(_MODULES))


if TYPE_CHECKING:  # pragma: no cover  (what static tools and IDEs see)
    from . import data, lab, plots, presets, records  # noqa: F401
    from ._errors import (InputError, Interrupted, MissingExtra, OutputError, PoundingWarning,  # noqa: F401
                          Problem, Status, StoreError)
    from .analysis import (Bifurcation, BifurcationCurve, Branch, CoexistenceMap, LyapunovSpectrum,  # noqa: F401
                           PeriodicOrbit, bifurcation_curve, coexistence_map,
                           continuation, largest_exponents, lyapunov, periodic_orbit)
    from .engine import AdjacentRun, EnergyLedger, PlanRun, Run, State, StructureRun, simulate  # noqa: F401
    from .excitation import Harmonic, HarmonicPair, Record, RecordPair  # noqa: F401
    from .excitation.rotd import rotd_spectrum  # noqa: F401
    from .excitation.spectrum import response_spectrum  # noqa: F401
    from .identification import (ContactLawFit, Identification, ModelFamily, SystemFamily,  # noqa: F401
                                 Targets, fit_contact_law, identify, paper_targets, rank_contact_laws)
    from .metrics import HysteresisLoop, impact_table  # noqa: F401
    from .model import (Adjacent, BoucWen, Bumpers, ElasticPlastic, FrictionIsolator,  # noqa: F401
                        Hertzdamp, HuntCrossley, Isolator, Jankowski, KelvinVoigt, Link, MeasurementChain,
                        MultilinearBumper, Oscillator, RigidStop, Sensor, Stand, Storey, Structure,
                        TripleFrictionPendulum, Wall, Bearing, CircularMoat, Floor, Frame, PlanBuilding,
                        RectangularMoat)
    from .protocols import (BasinStabilityMap, Basins, BifurcationDiagram, CampaignResult,  # noqa: F401
                            Orientations, PoundingSpectrum, SweepResult, basin_stability_map, basins,
                            bifurcation_diagram,
                            campaign, orientations, paper_frequencies_hz, pounding_spectrum, sweep)
    from .studies import StudyResult, StudySpec, open_study, study  # noqa: F401
