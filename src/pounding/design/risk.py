"""Risk: how often an event happens at a site, from its fragility and the site's hazard curve."""

from __future__ import annotations

import warnings
import numpy as np
from scipy import integrate

from .._checks import instance_of, positive
from .._errors import PoundingWarning
from .fragility import Fragility
from .hazard import HazardCurve, probability_in_years

Z_GRID = np.linspace(-9.0, 9.0, 4001)  # standard normal capacity coordinates integrated over
EXTRAPOLATED_WARN = 0.05  # warn when more than this share of the answer comes from beyond the curve


def annual_frequency(fragility: Fragility, hazard: HazardCurve) -> float:
    """The mean annual frequency of the event (1/year): ``lambda_E = int P(E | x) |d lambda(x)|``.

    Integrated by parts, ``lambda_E = int lambda(x) f_C(x) dx`` with ``f_C`` the lognormal
    density of the capacity, on 4001 points of the capacity's standard normal coordinate
    (+-9).  The hazard curve is log-log linear between its points and continues its end
    segments' power laws beyond them (a warning says when more than 5 % of the answer comes
    from there).  For a power-law curve ``k0 x^-k`` it equals Cornell's closed form
    ``k0 theta^-k exp(k^2 beta^2 / 2)``.

    Parameters
    ----------
    fragility : Fragility
        The event's fragility at the hazard curve's intensity measure.
    hazard : HazardCurve
        The site's curve for the same intensity measure (Sa at the same period).

    Returns
    -------
    float
        The mean annual frequency (1/year).

    Examples
    --------
    >>> import numpy as np
    >>> from pounding import design
    >>> curve = design.HazardCurve([0.1, 1.0], [1e-2, 1e-4], period_s=2.0)
    >>> frag = design.fit_fragility_capacities([0.3, 0.45, 0.5, 0.7, 0.9],
    ...                                        n_bootstrap=0)
    >>> f"{design.annual_frequency(frag, curve):.3e}"  # per year
    '4.701e-04'
    """
    instance_of("fragility", fragility, Fragility,
                "pounding.design.Fragility (fit_fragility, fit_fragility_capacities)")
    instance_of("hazard", hazard, HazardCurve, "pounding.design.HazardCurve")
    x = fragility.median_g * np.exp(fragility.beta * Z_GRID)
    integrand = hazard.annual_frequency(x) * np.exp(-0.5 * Z_GRID**2) / np.sqrt(2.0 * np.pi)
    total = float(integrate.simpson(integrand, x=Z_GRID))
    outside = (x < hazard.sa_g[0]) | (x > hazard.sa_g[-1])
    if outside.any() and total > 0.0:
        share = float(integrate.simpson(np.where(outside, integrand, 0.0), x=Z_GRID)) / total
        if share > EXTRAPOLATED_WARN:
            warnings.warn(
                f"{share:.0%} of the annual frequency of {fragility.event or 'the event'} comes from "
                f"intensities beyond the hazard curve's [{hazard.sa_g[0]:g}, {hazard.sa_g[-1]:g}] g, "
                "where its end segments' power laws were extended; give the curve over a wider range",
                PoundingWarning,
                stacklevel=2,
            )
    return total


def risk(fragility: Fragility, hazard: HazardCurve, years: float = 50.0) -> dict[str, float]:
    """The event's annual frequency, return period and probability in ``years`` (Poisson).

    Parameters
    ----------
    fragility : Fragility
        The event's fragility.
    hazard : HazardCurve
        The site's hazard curve for the same intensity measure.
    years : float
        The exposure time (years; 50 by default).

    Returns
    -------
    dict
        ``annual_frequency_per_year``, ``return_period_yr``, ``probability`` (in ``years``),
        ``years``.

    Examples
    --------
    >>> from pounding import design
    >>> curve = design.HazardCurve([0.1, 1.0], [1e-2, 1e-4], period_s=2.0)
    >>> frag = design.fit_fragility_capacities([0.3, 0.45, 0.5, 0.7, 0.9],
    ...                                        n_bootstrap=0)
    >>> round(design.risk(frag, curve)["probability"], 4)  # in 50 years
    0.0232
    """
    yrs = positive("years", years, "years")
    lam = annual_frequency(fragility, hazard)
    return {
        "annual_frequency_per_year": lam,
        "return_period_yr": 1.0 / lam if lam > 0 else np.inf,
        "probability": probability_in_years(lam, yrs),
        "years": yrs,
    }


def cornell(k0: float, k: float, median_g: float, beta: float) -> float:
    """Cornell's closed form for a power-law hazard ``k0 x^-k``: ``k0 theta^-k exp(k^2 beta^2/2)``."""
    return float(k0 * median_g ** (-k) * np.exp(0.5 * k * k * beta * beta))
