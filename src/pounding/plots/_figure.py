"""The Figure a plot drew on: what every result's ``.plot()`` returns."""

from __future__ import annotations

from typing import Any


def _first_figure(drawn: Any) -> Any:
    figure = getattr(drawn, "figure", None)
    if figure is not None:
        return figure
    axes = getattr(drawn, "axes", None)  # (an artist not yet given its figure: its axes' one)
    if axes is not None and getattr(axes, "figure", None) is not None:
        return axes.figure
    if isinstance(drawn, dict):
        drawn = list(drawn.values())
    if isinstance(drawn, (list, tuple)) or hasattr(drawn, "flat"):
        for item in getattr(drawn, "flat", drawn):
            figure = _first_figure(item)
            if figure is not None:
                return figure
    return None


def figure_of(drawn: Any, ax: Any = None) -> Any:
    """The Figure a plot drew on.

    Parameters
    ----------
    drawn : Artist, Axes, or a list, tuple, dict or array of them
        What a plot function returned.
    ax : Axes or array of Axes, optional
        The axes it was given: their Figure, whatever was drawn.

    Returns
    -------
    matplotlib.figure.Figure
        The Figure of ``ax`` when given, else of the first thing drawn; the current Figure when nothing
        was drawn.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from pounding.plots import figure_of
    >>> fig, ax = plt.subplots()
    >>> figure_of(ax.plot([0, 1], [0, 1])) is fig
    True
    >>> plt.close(fig)
    """
    for source in (ax, drawn):
        if source is not None:
            figure = _first_figure(source)
            if figure is not None:
                return figure
    import matplotlib.pyplot as plt

    return plt.gcf()
