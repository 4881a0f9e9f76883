"""Plot of a contact law fitted to a force-displacement test."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .._docs import fill_doc
from .legend import place_legend

if TYPE_CHECKING:  # pragma: no cover
    from ..identification.contact_law import ContactLawFit


@fill_doc
def plot_contact_law_fit(fit: "ContactLawFit", ax: Any = None) -> list:
    """Measured force (points) and the fitted law at the same samples (line) against compression.

    Parameters
    ----------
    fit : ContactLawFit
        A result of :func:`pounding.fit_contact_law`.
    {ax}

    Returns
    -------
    list of matplotlib artists
        The measured points and the fitted law's line.

    Examples
    --------
    A Hunt-Crossley law fitted to the shipped cyclic test of a bumper:

    >>> import pounding
    >>> test = pounding.data.bumper_cyclic_test()
    >>> fit = pounding.fit_contact_law(test["compression_m"], test["force_n"],
    ...                                time_s=test["time_s"], law="hunt_crossley")
    >>> artists = pounding.plots.plot_contact_law_fit(fit)
    >>> len(artists)
    2
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(5.5, 4.0))
    df = fit.to_dataframe()
    d_mm = 1e3 * df["compression_m"].to_numpy()
    artists = [ax.plot(d_mm, 1e-3 * df["force_n"].to_numpy(), ".", ms=3, color="0.5", label="measured")[0]]
    artists.append(ax.plot(d_mm, 1e-3 * df["model_force_n"].to_numpy(), "-", lw=1.2, color="C3",
                           label=f"{fit.law.TYPE}, rms {fit.rms_n:.3g} N")[0])
    ax.set_xlabel("compression [mm]")
    ax.set_ylabel("force [kN]")
    ax.set_xlim(0.0, max(1e-9, float(np.max(d_mm))) * 1.05)
    place_legend(ax, fontsize="small")
    return artists
