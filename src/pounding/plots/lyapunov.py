"""The Lyapunov spectrum's convergence: each exponent's running estimate against the periods counted."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc
from .legend import place_legend


@fill_doc
def plot_lyapunov(spectrum: Any, ax: Any = None, **kwargs: Any) -> list:
    """The running estimates of the finite exponents against the periods counted, the final values
    written in the legend, and zero marked (a positive largest exponent: chaos).

    Parameters
    ----------
    spectrum : LyapunovSpectrum
        From :func:`pounding.lyapunov`.
    {ax}
    **kwargs
        Passed to the lines (``lw``, ``alpha``, ...).

    Returns
    -------
    list of matplotlib artists
        One line per finite exponent, then the zero line.

    Examples
    --------
    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> spec = pounding.lyapunov(osc, pounding.Harmonic(0.05, 1.5), cycles=50)
    >>> artists = pounding.plots.plot_lyapunov(spec)
    >>> len(artists)  # the two finite exponents and the zero line
    3
    """
    import matplotlib.pyplot as plt

    if ax is None:
        ax = plt.figure(figsize=(7, 4), constrained_layout=True).add_subplot()
    hist = spectrum.history
    cycles = np.arange(1, hist.shape[0] + 1)
    artists = []
    for i, (name, value) in enumerate(zip(spectrum.coordinates, spectrum.exponents)):
        if not np.isfinite(value):
            continue
        (line,) = ax.plot(cycles, hist[:, i], label=f"lambda_{i + 1} = {value:.4g} 1/s", **kwargs)
        artists.append(line)
    artists.append(ax.axhline(0.0, color="0.5", lw=0.8, ls=":"))
    erased = int(np.sum(np.isneginf(spectrum.exponents)))
    ax.set_xlabel("periods counted")
    ax.set_ylabel("running estimate [1/s]")
    ax.set_xscale("log")
    exc = spectrum.excitation
    title = f"Lyapunov spectrum, a_G {exc.a_g:g}, {exc.freq_hz:g} Hz"
    if spectrum.period:
        title += f" (periodic, period {spectrum.period})"
    elif spectrum.chaotic:
        title += f" (chaotic, D_KY {spectrum.kaplan_yorke_dimension:.2f})"
    ax.set_title(title + (f"; {erased} erased (-inf)" if erased else ""), fontsize=10)
    place_legend(ax)
    return artists
