"""Legends that never cover data: inside the axes where there is room, outside where there is not.

:func:`place_legend` tries the axes' corners and sides in turn and keeps the first place whose
box touches no plotted point or line (what a reader looks at), measured on the drawn figure;
where every place inside covers something, the legend goes outside, to the right of the axes, and
the figure grows by its width.
:func:`legends_over_data` lists the legends of a figure that cover data; the tests run it on
every figure the package draws.

Reference lines drawn across the whole axes (``axhline``, ``axvline``) and colour meshes are
not data in this sense: a legend may sit over them.
"""

from __future__ import annotations

from typing import Any

import numpy as np

# the places tried inside the axes, in order (Matplotlib's names)
INSIDE = ("upper right", "upper left", "lower right", "lower left", "center right", "center left",
          "upper center", "lower center")
PAD_PX = 2.0  # clearance kept between a legend's box and the data, display pixels
STEP_PX = 1.5  # lines are checked at points this far apart along them, display pixels


def place_legend(ax: Any, **kwargs: Any) -> Any:
    """Add ``ax``'s legend where it covers no data; return it (None without labelled artists).

    Parameters
    ----------
    ax : matplotlib Axes
        The axes whose labelled artists the legend lists.
    **kwargs
        Passed on to :meth:`matplotlib.axes.Axes.legend` (``fontsize``, ``ncol``, ...); ``loc``
        and ``bbox_to_anchor`` are this function's to choose.

    Returns
    -------
    matplotlib.legend.Legend or None
    """
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    kwargs = {k: v for k, v in kwargs.items() if k not in ("loc", "bbox_to_anchor")}
    fig = ax.figure
    renderer = _laid_out(fig)
    data = _data_px(ax)
    for loc in INSIDE:
        legend = ax.legend(handles, labels, loc=loc, **kwargs)
        box = legend.get_window_extent(renderer)
        if _inside(box, ax.get_window_extent(renderer)) and not _covers(box, data):
            return legend
    # outside, to the right, in one column; the figure grows by the legend's width so that the axes keep
    # theirs
    kwargs["ncol"] = 1
    legend = ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                       **kwargs)
    width_px = legend.get_window_extent(renderer).width + 0.03 * ax.get_window_extent(renderer).width
    width_in = width_px / fig.dpi
    fig.set_size_inches(fig.get_figwidth() + width_in, fig.get_figheight(), forward=False)
    return legend


def _laid_out(fig: Any) -> Any:
    """Lay ``fig`` out as it will be saved (constrained layout moves the axes) and return a renderer
    to measure boxes with, whatever its canvas: Agg, a notebook's, or another backend's (a PDF
    canvas has no renderer of its own)."""
    fig.draw_without_rendering()
    return fig._get_renderer()


def legends_over_data(fig: Any) -> list[tuple[Any, Any]]:
    """The ``(axes, legend)`` pairs of ``fig`` whose legend box covers a point or a line drawn in
    its axes (the figure is drawn first, as it would be saved)."""
    renderer = _laid_out(fig)
    out = []
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is not None and legend.get_visible() and _covers(legend.get_window_extent(renderer),
                                                                   _data_px(ax)):
            out.append((ax, legend))
    return out


def _inside(box: Any, frame: Any) -> bool:
    return (box.x0 >= frame.x0 - 0.5 and box.x1 <= frame.x1 + 0.5
            and box.y0 >= frame.y0 - 0.5 and box.y1 <= frame.y1 + 0.5)


def _data_px(ax: Any) -> list[tuple[np.ndarray, bool, float]]:
    """What is drawn in ``ax`` as ``(points, connected, radius)`` in display pixels: each line's
    points (joined when it has a line style; ``radius`` its markers'), each scatter's points, each
    band's outline (joined, and closed: ``radius`` -1 marks an area, whose inside counts too)."""
    from matplotlib.collections import LineCollection, PathCollection, PolyCollection

    dpi_scale = ax.figure.dpi / 72.0
    out: list[tuple[np.ndarray, bool, float]] = []
    for line in ax.get_lines():
        if not line.get_visible() or not line.get_transform().contains_branch(ax.transData):
            continue  # (axhline, axvline: reference lines across the axes)
        pts = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
        marker = line.get_marker()
        radius = 0.5 * line.get_markersize() * dpi_scale if marker not in (None, "None", "", " ",
                                                                           "none") else 0.0
        joined = line.get_linestyle() not in ("None", "", " ", "none")
        out.append((pts, joined, radius))
    for coll in ax.collections:
        if not coll.get_visible():
            continue
        if isinstance(coll, PathCollection):
            offsets = np.asarray(coll.get_offsets(), dtype=float)
            if offsets.size:
                sizes = coll.get_sizes()
                radius = 0.5 * np.sqrt(float(np.max(sizes))) * dpi_scale if len(sizes) else 0.0
                out.append((coll.get_offset_transform().transform(offsets), False, radius))
        elif isinstance(coll, (LineCollection, PolyCollection)):
            if not coll.get_transform().contains_branch(ax.transData):
                continue
            area = isinstance(coll, PolyCollection)
            for path in coll.get_paths():
                pts = coll.get_transform().transform(np.asarray(path.vertices, dtype=float))
                out.append((np.vstack([pts, pts[:1]]) if area else pts, True, -1.0 if area else 0.0))
    return out


def _covers(box: Any, data: list[tuple[np.ndarray, bool, float]]) -> bool:
    """Whether ``box`` (display pixels) comes within ``PAD_PX`` of any of ``data``."""
    for pts, joined, radius in data:
        if radius < 0.0 and _area_holds(pts, (0.5 * (box.x0 + box.x1), 0.5 * (box.y0 + box.y1))):
            return True
        pad = PAD_PX + max(radius, 0.0)
        x0, y0, x1, y1 = box.x0 - pad, box.y0 - pad, box.x1 + pad, box.y1 + pad
        finite = np.all(np.isfinite(pts), axis=1)
        p = pts[finite]
        if p.size and np.any((p[:, 0] >= x0) & (p[:, 0] <= x1) & (p[:, 1] >= y0) & (p[:, 1] <= y1)):
            return True
        if not joined or len(pts) < 2:
            continue
        a, b = pts[:-1], pts[1:]
        both = finite[:-1] & finite[1:]
        a, b = a[both], b[both]
        if not len(a):
            continue
        # the segments near the box only, sampled every STEP_PX along their length
        near = ~((np.maximum(a[:, 0], b[:, 0]) < x0) | (np.minimum(a[:, 0], b[:, 0]) > x1)
                 | (np.maximum(a[:, 1], b[:, 1]) < y0) | (np.minimum(a[:, 1], b[:, 1]) > y1))
        a, b = a[near], b[near]
        if not len(a):
            continue
        n = np.maximum(1, np.ceil(np.hypot(*(b - a).T) / STEP_PX).astype(int))
        n = np.minimum(n, 10_000)
        seg = np.repeat(np.arange(len(a)), n)
        frac = (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n, n)
        s = a[seg] + (b[seg] - a[seg]) * frac[:, None]
        if np.any((s[:, 0] >= x0) & (s[:, 0] <= x1) & (s[:, 1] >= y0) & (s[:, 1] <= y1)):
            return True
    return False


def _area_holds(outline: np.ndarray, point: tuple[float, float]) -> bool:
    """Whether the closed ``outline`` (display pixels) holds ``point``."""
    from matplotlib.path import Path

    finite = outline[np.all(np.isfinite(outline), axis=1)]
    return len(finite) >= 3 and bool(Path(finite).contains_point(point))
