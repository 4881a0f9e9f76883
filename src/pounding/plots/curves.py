"""Plots of bifurcation curves in the (f, a_G) plane, over a test matrix."""

from __future__ import annotations

from typing import Any, Optional

from .._docs import fill_doc
from ._labels import A_G_LABEL
from .legend import place_legend

STYLE = {"fold": "-", "grazing": ":"}
# a test point as its verdict says (witnesses: the branch, the sweeps, a basin sample)
MATRIX_LOOK = (
    ("coexist", dict(marker="o", ms=4.5, color="C3"),
     "two or more responses coexist (a witness shows them)"),
    ("one", dict(marker="o", ms=4, mfc="none", color="0.45"), "one response: a basin sample agrees with the "
                                                                 "branch or sweeps"),
    ("one on the branch", dict(marker="o", ms=4, mfc="none", color="0.75"),
     "one stable orbit on the branch (others not sought)"),
    ("not assessed", dict(marker="x", ms=4, color="0.55"),
     "not assessed (no branch there, no agreeing sample)"),
)


@fill_doc
def plot_curves(curves: list, ax: Any = None, *, matrix: Optional[Any] = None,
                box: Optional[tuple] = None, **kwargs: Any) -> list:
    """Fold curves solid, grazing curves dotted, in the (frequency, a_G) plane.

    Parameters
    ----------
    curves : list of BifurcationCurve
        From :func:`pounding.bifurcation_curve` (or ``CoexistenceMap.curves``).
    {ax}
    matrix : DataFrame, optional
        A test matrix (``CoexistenceMap.matrix``: ``a_g``, ``freq_hz``, ``verdict``): each point drawn
        as its verdict says: filled where two or more responses coexist, hollow where one response is
        shown, a cross where the number is not assessed.
    box : ((float, float), (float, float)), optional
        The map's frequencies (Hz) and a_G: an end of a curve that did not end well (its ``status``)
        and lies inside this box is marked where the curve stopped short (without ``box``, every end
        of such a curve).
    **kwargs
        Passed to the curves' lines.

    Returns
    -------
    list of matplotlib artists
        The test matrix's points, then the curves' lines.

    Examples
    --------
    The fold at 2.014 Hz of the damped paper system's branch at a_G = 0.05, followed in (f, a_G):

    >>> import pounding
    >>> osc = pounding.presets.paper_damped()
    >>> fold = pounding.continuation(osc, 0.05, (1.5, 2.5)).folds()[0]
    >>> curve = pounding.bifurcation_curve(osc, fold, a_g=(0.045, 0.055),
    ...                                    freqs_hz=(1.5, 2.5), max_step=0.1)
    >>> artists = pounding.plots.plot_curves([curve])
    >>> len(artists)
    1
    """
    import matplotlib.pyplot as plt

    if ax is None:
        ax = plt.figure(figsize=(7, 4), constrained_layout=True).add_subplot()
    artists: list = []
    if matrix is not None and len(matrix):
        for verdict, style, label in MATRIX_LOOK:
            pts = matrix[matrix["verdict"] == verdict]
            if len(pts):
                artists += ax.plot(pts["freq_hz"], pts["a_g"], ls="none", label=label, **style)
    seen = set()
    for i, c in enumerate(curves):
        df = c.to_dataframe()
        name = c.kind + (f" ({c.side})" if c.side else "")
        label = f"{name} curve" if name not in seen else None
        seen.add(name)
        left = c.side.endswith("left")
        color = kwargs.get("color") or ("C0" if c.kind == "fold" else "C2" if left else "C1")
        kw = {k: v for k, v in kwargs.items() if k != "color"}
        # (gid "curve": a curve in the plane may turn back in either parameter, its order the arclength's)
        artists += ax.plot(df["freq_hz"], df["a_g"], STYLE.get(c.kind, "-"), color=color, label=label,
                           gid="curve", **kw)
        short = _stopped_ends(c, df, box)
        if short:
            f, a = zip(*short)
            artists += ax.plot(f, a, ls="none", marker="s", ms=6, mfc="none", mec="k", mew=1.2,
                               label=None if "stopped" in seen else "a curve stopped short here (not at the "
                                                                      "map's edge: see its status)")
            seen.add("stopped")
    ax.set_xlabel("frequency f [Hz]")
    ax.set_ylabel(A_G_LABEL)
    if artists:
        place_legend(ax, fontsize="small")
    return artists


def _stopped_ends(curve: Any, df: Any, box: Optional[tuple]) -> list[tuple[float, float]]:
    """The ends of a curve that did not end well (``status`` not SUCCESS) that lie inside ``box``
    (both ends without a box): where it stopped short."""
    from .._errors import Status

    if curve.status == Status.SUCCESS or not len(df):
        return []
    ends = {(float(df["freq_hz"].iloc[0]), float(df["a_g"].iloc[0])),
            (float(df["freq_hz"].iloc[-1]), float(df["a_g"].iloc[-1]))}
    if box is None:
        return sorted(ends)
    (f0, f1), (a0, a1) = (sorted(box[0]), sorted(box[1]))

    def at_edge(v: float, lo: float, hi: float) -> bool:
        tol = 1e-6 * max(abs(hi - lo), 1e-12)
        return abs(v - lo) <= tol or abs(v - hi) <= tol

    return sorted(e for e in ends if not (at_edge(e[0], f0, f1) or at_edge(e[1], a0, a1)))
