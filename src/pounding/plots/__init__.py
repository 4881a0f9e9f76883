"""Figures, apart from computing: every function takes ``ax=`` and returns its artists; every result's
``.plot()`` returns the Figure they are on (:func:`figure_of`)."""

from typing import Any

from .basins import plot_basin_stability, plot_basins
from .branch import plot_branch
from .contact_law import plot_contact_law_fit
from .curves import plot_curves
from .design import (plot_decision, plot_design_spectrum, plot_fragility, plot_hazard_curve,
                     plot_responses, plot_scaled_suite, plot_stripes)
from .diagram import plot_bifurcation_diagram
from ._figure import figure_of
from .identification import plot_identification
from .isolator import plot_isolator_loop
from .lyapunov import plot_lyapunov
from .orientations import plot_orientations
from .plan import plot_moat_design, plot_plan_orbit
from .periodic import plot_orbit
from .record import plot_pair, plot_record, plot_response_spectrum, plot_rotd_spectrum
from .run import plot_adjacent_run, plot_run, plot_structure_run
from .spectrum import plot_pounding_spectrum
from .study import plot_study
from .sweep import plot_campaign, plot_hysteresis, plot_lab_sweep, plot_sweep
from .._errors import old_names

__all__ = ["figure_of", "plot_adjacent_run", "plot_basin_stability", "plot_basins",
           "plot_bifurcation_diagram",
           "plot_branch",
           "plot_campaign",
           "plot_contact_law_fit", "plot_curves", "plot_decision", "plot_design_spectrum", "plot_fragility",
           "plot_hazard_curve", "plot_responses", "plot_scaled_suite", "plot_stripes", "plot_identification",
           "plot_lyapunov",
           "plot_hysteresis", "plot_isolator_loop", "plot_lab_sweep", "plot_orbit", "plot_orientations",
           "plot_plan_orbit", "plot_moat_design",
           "plot_pounding_spectrum",
           "plot_pair", "plot_record",
           "plot_response_spectrum", "plot_rotd_spectrum", "plot_run", "plot_structure_run",
           "plot_study", "plot_sweep"]


def _structure_orbit() -> Any:
    from .periodic import plot_structure_orbit_axes

    return plot_structure_orbit_axes


def _structure_sweep() -> Any:
    from .sweep import plot_structure_sweep_levels

    return plot_structure_sweep_levels


# their names before one plot drew every system's orbit and sweep, for one release
__getattr__ = old_names(__name__, {
    "plot_structure_orbit": ("pounding.plots.plot_orbit", _structure_orbit,
                             "one plot for every system's orbit; it returns the artists, not the Axes"),
    "plot_structure_sweep": ("pounding.plots.plot_sweep", _structure_sweep,
                             "one plot for every system's sweep")})
