"""Figures, apart from computing: every function takes ``ax=`` and returns its artists; every result's
``.plot()`` returns the Figure they are on (:func:`figure_of`)."""

from .basins import plot_basin_stability, plot_basins
from .branch import plot_branch
from .contact_law import plot_contact_law_fit
from .curves import plot_curves
from .design import (plot_decision, plot_design_spectrum, plot_fragility, plot_hazard_curve,
                     plot_responses, plot_scaled_suite, plot_stripes)
from .diagram import plot_bifurcation_diagram
from ._figure import figure_of
from .identification import plot_identification
from .lyapunov import plot_lyapunov
from .periodic import plot_orbit
from .record import plot_record, plot_response_spectrum
from .run import plot_adjacent_run, plot_run, plot_structure_run
from .spectrum import plot_pounding_spectrum
from .study import plot_study
from .sweep import plot_campaign, plot_hysteresis, plot_lab_sweep, plot_sweep

__all__ = ["figure_of", "plot_adjacent_run", "plot_basin_stability", "plot_basins",
           "plot_bifurcation_diagram",
           "plot_branch",
           "plot_campaign",
           "plot_contact_law_fit", "plot_curves", "plot_decision", "plot_design_spectrum", "plot_fragility",
           "plot_hazard_curve", "plot_responses", "plot_scaled_suite", "plot_stripes", "plot_identification",
           "plot_lyapunov",
           "plot_hysteresis", "plot_lab_sweep", "plot_orbit", "plot_pounding_spectrum", "plot_record",
           "plot_response_spectrum", "plot_run", "plot_structure_run",
           "plot_study", "plot_sweep"]


def __getattr__(name: str):
    if name == "plot_structure_orbit":  # (its name before one plot drew every orbit, for one release)
        from .._errors import warn_renamed
        from .periodic import plot_structure_orbit_axes

        warn_renamed("pounding.plots.plot_structure_orbit", "pounding.plots.plot_orbit",
                     why="one plot for every system's orbit; it returns the artists, not the Axes")
        return plot_structure_orbit_axes
    if name == "plot_structure_sweep":  # (its name before one plot drew every sweep, for one release)
        from .._errors import warn_renamed

        from .sweep import plot_structure_sweep_levels

        warn_renamed("pounding.plots.plot_structure_sweep", "pounding.plots.plot_sweep",
                     why="one plot for every system's sweep")
        return plot_structure_sweep_levels
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
