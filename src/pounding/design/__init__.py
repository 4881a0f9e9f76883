"""From a site's hazard to a gap and a bumper: design spectra, scaled suites, fragility, risk.

- :func:`asce7_spectrum`, :func:`ec8_spectrum`, :func:`user_spectrum`: the target spectra
  (:class:`DesignSpectrum`); :class:`HazardCurve`: how often an intensity is exceeded.
- :func:`scale_suite`: a record suite scaled to a target at a period or over a period range
  (:class:`ScaledSuite`); :func:`stripe_factors`: the factors of a multiple-stripe analysis.
- :func:`fit_fragility` (stripes) and :func:`fit_fragility_capacities` (incremental dynamic
  analysis): lognormal fragility curves by maximum likelihood, with bootstrap bands
  (:class:`Fragility`).
- :func:`stripe_analysis`: a multiple-stripe analysis over a design grid, in a resumable store
  (:class:`StripeAnalysis`: events, fractions, fragility curves, probabilities).
- :func:`decide`: the smallest gap of the grid meeting a target probability of pounding, with
  the design chart (:class:`Decision`).
- :func:`annual_frequency`, :func:`risk`, :func:`probability_in_years`: the event's rate at the
  site.
"""

from .decision import Decision, decide
from .moat_in_plan import MoatDesign, asce7_bearings_displacement, asce7_torsion, moat_design
from .capacities import fit_fragility_capacities, fit_fragility_intervals
from .fragility import Fragility, fit_fragility
from .hazard import HazardCurve, probability_in_years
from .spectra import DesignSpectrum, asce7_displacement, asce7_spectrum, ec8_spectrum, user_spectrum
from .risk import annual_frequency, risk
from .stripe_result import StripeAnalysis
from .stripes import open_stripe_analysis, stripe_analysis
from .suite import ScaledSuite, scale_suite, stripe_factors

__all__ = [
    "Decision",
    "MoatDesign",
    "asce7_bearings_displacement",
    "asce7_torsion",
    "moat_design",
    "DesignSpectrum",
    "Fragility",
    "HazardCurve",
    "ScaledSuite",
    "StripeAnalysis",
    "annual_frequency",
    "decide",
    "asce7_displacement",
    "asce7_spectrum",
    "ec8_spectrum",
    "fit_fragility",
    "fit_fragility_capacities",
    "fit_fragility_intervals",
    "probability_in_years",
    "risk",
    "open_stripe_analysis",
    "scale_suite",
    "stripe_analysis",
    "stripe_factors",
    "user_spectrum",
]
