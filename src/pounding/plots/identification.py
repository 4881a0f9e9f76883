"""Plot of a model updating result: each target's normalized residual against the +-1 band."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .._docs import fill_doc

if TYPE_CHECKING:  # pragma: no cover
    from ..identification.identify import Identification


@fill_doc
def plot_identification(fit: Identification, ax: Any = None) -> list:
    """Horizontal bars of ``(model - target) / allowed`` per target; within +-1 is met.

    Parameters
    ----------
    fit : Identification
        A result of :func:`pounding.identify`.
    {ax}

    Returns
    -------
    list of matplotlib artists
        One bar per target, the points at the bars' ends, the +-1 band.

    Examples
    --------
    The isolator's damping of the damped paper system fitted to the paper's alpha targets, on a
    tiny budget (one generation of two candidates, three frequencies of ten cycles):

    >>> import pounding
    >>> damped = pounding.presets.paper_damped()
    >>> fixed = pounding.ModelFamily(500.0).values_of(damped)
    >>> del fixed["isolator_damping"]  # the number fitted
    >>> family = pounding.ModelFamily(500.0, fixed=fixed)
    >>> fit = pounding.identify(pounding.paper_targets(quantities=("alpha",)),
    ...                         family,
    ...                         {"isolator_damping": (500.0, 2000.0)}, popsize=2,
    ...                         maxiter=1, refine=False,
    ...                         freqs_hz=[1.0, 1.5, 2.0], cycles=10,
    ...                         measure_cycles=2)
    >>> artists = pounding.plots.plot_identification(fit)
    >>> len(fit.residuals), len(artists) > 0
    (7, True)
    """
    import matplotlib.pyplot as plt

    df = fit.to_dataframe()
    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 0.22 * len(df) + 1.2))
    r = df["normalized"].to_numpy(dtype=float)
    shown = np.clip(np.nan_to_num(r, nan=0.0), -5.0, 5.0)
    colors = np.where(df["within"].to_numpy(), "C2", "C3")
    labels = [f"{c} {a:g} {d} {q}" for c, a, d, q in
              df[["configuration", "a_g", "direction", "quantity"]].itertuples(index=False)]
    y = np.arange(len(df))
    artists = list(ax.barh(y, shown, color=colors))
    artists.append(ax.scatter(shown, y, c=colors, s=12, zorder=3))  # a zero residual shows too
    artists.append(ax.axvspan(-1.0, 1.0, color="0.9", zorder=0))
    ax.set_yticks(y, labels, fontsize="x-small")
    ax.invert_yaxis()
    ax.set_xlim(-5.2, 5.2)
    ax.set_xlabel("(model - target) / tolerance [-] (clipped at +-5)")
    ax.set_title(f"{fit.n_within} of {len(df)} targets met", fontsize="small")
    return artists
