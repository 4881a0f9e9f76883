"""The report's continued branches: the YBs system's period-1 branches at the campaign's a_G
levels under the Fig. 5 sweeps, and the fold curves in (a_G, f) over the test matrix."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional

import numpy as np
import pandas as pd

from .._errors import InputError, Status
from ..plots.legend import place_legend

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from ..analysis import CoexistenceMap
    from ..model import Oscillator
    from ..protocols import CampaignResult


def coexistence_of(result: "CampaignResult", ybs_system: "Oscillator", basin_sample: int = 4,
                   progress: Any = False) -> tuple[Optional["CoexistenceMap"], str]:
    """The YBs system's coexistence map over the campaign's frequencies and YBs levels (folds only),
    each test point judged by the branch, the campaign's own YBs sweeps and a basin sample; or None and
    why not."""
    from ..analysis import coexistence_map

    ds = result.data
    levels = sorted({float(a) for (conf, a, _d) in result.sweeps if conf == "YBs"})
    freqs = np.asarray(ds.freq_hz, dtype=float)
    if not levels or freqs.size < 2:
        return None, "no YBs sweeps"
    step = float(np.min(np.diff(np.sort(freqs))))
    try:
        # the test matrix at the campaign's own frequencies (its grid need not be even)
        cmap = coexistence_map(ybs_system, a_g=(0.5 * min(levels), 1.1 * max(levels)),
                               freqs_hz=(float(freqs.min()), float(freqs.max())), levels=levels,
                               freq_step_hz=step, kinds=("fold",), sweeps=result, basin_sample=basin_sample,
                               test_freqs_hz=np.sort(freqs), progress=progress)
    except InputError as exc:
        return None, f"not continued: {exc}"
    return cmap, ""


def add_branches(fig: "Figure", cmap: "CoexistenceMap", f_ref_hz: float) -> str:
    """Each level's branches on the Fig. 5 analogue's panels (alpha, eta against nu), thin, in the
    level's colour: stable solid, unstable dashed; the level's branch and those started at the sweeps'
    settled steps it does not pass through (``cmap.seeded``).  eta is over the rig's nominal total gap,
    as the sweeps' (``paper_gap_total_m``), whatever the model's own.  A settled step off every
    period-1 branch (another period, no orbit solved) is marked.  Returns what the figure shows, in
    words: its caption's second part."""
    from ..data import paper_gap_total_m

    ax_alpha, ax_eta = fig.axes[0], fig.axes[1]
    delta = paper_gap_total_m()
    colour = {float(a): f"C{i}" for i, a in enumerate(sorted({float(b.a_g) for b in cmap.branches}))}
    first = True
    for br in sorted(cmap.branches, key=lambda b: b.a_g) + list(cmap.seeded):
        df = br.to_dataframe()
        nu = df["freq_hz"].to_numpy(float) / f_ref_hz
        stable = df["stable"].to_numpy(bool)
        for ax, vals in ((ax_alpha, df["alpha"].to_numpy(float)),
                         (ax_eta, df["excursion_m"].to_numpy(float) / delta)):
            for want, style in ((True, "-"), (False, "--")):
                shown = np.where(stable == want, vals, np.nan)
                ax.plot(nu, shown, style, color=colour.get(float(br.a_g), "0.4"), lw=0.6, alpha=0.8,
                        gid="branch",
                        label=(f"continued branch, {'stable' if want else 'unstable'} (each a_G's colour)"
                               if ax is ax_alpha and first else None))
        first = False
    steps = cmap.steps
    off = steps[steps["steady"].astype(bool) & ~steps["on_branch"].astype(bool)] if len(steps) else steps
    if len(off):
        ax_alpha.plot(off["freq_hz"] / f_ref_hz, off["alpha"], "x", color="0.2", ms=6, mew=1.2,
                      label="settled step off every period-1 branch (another period)")
        ax_eta.plot(off["freq_hz"] / f_ref_hz, off["excursion_m"] / delta, "x", color="0.2", ms=6, mew=1.2)
    place_legend(ax_alpha, fontsize="x-small", ncol=2)
    fig.suptitle(fig.get_suptitle().replace("pseudo-FRFs", "FRFs + branches"))
    return branches_caption(cmap, f_ref_hz)


def branches_caption(cmap: "CoexistenceMap", f_ref_hz: float) -> str:
    """What Fig. 5's branches show, in words: eta's gap, which steps lie on which branches, and where
    two stable responses coexist (the test points the coexistence map judges so)."""
    from ..data import paper_gap_total_m

    words = [f"eta = E / Delta over the rig's nominal total gap, Delta = {paper_gap_total_m() * 1e3:g} mm "
             "(as Table 2), for the sweeps and the branches alike, whatever the model's own gap. Thin "
             "lines: the period-1 branches continued at each a_G (stable solid, unstable dashed), from the "
             "low end of the range and from each settled sweep step that branch does not pass through (a "
             "short branch each, to half way to the neighbouring steps)."]
    grid = np.unique(cmap.matrix["freq_hz"].to_numpy(float))
    step = float(np.min(np.diff(grid))) if grid.size > 1 else None
    steps = cmap.steps
    if len(steps):
        settled = steps[steps["steady"].astype(bool)]
        on = int(settled["on_branch"].astype(bool).sum())
        off = settled[~settled["on_branch"].astype(bool)]
        words.append(f"Of the sweeps' {len(settled)} settled steps, {on} lie on a drawn branch"
                     + (f"; {len(off)} lie off every period-1 branch (marked x): "
                        + "; ".join(f"a_G {a:g} {d} at {_freqs(part, step)} "
                                    f"({'; '.join(part['why'].unique())})"
                                    for (a, d), part in off.groupby(["a_g", "direction"]))
                        if len(off) else "") + ".")
    both = cmap.matrix[cmap.matrix["verdict"] == "coexist"]
    if len(both):
        words.append("Two or more stable responses coexist at " + "; ".join(
            f"a_G {a:g}: {_freqs(part, step)}" for a, part in both.groupby("a_g"))
            + " (the coexistence map's test points, each judged by the branches, the sweeps and a basin "
              "sample): there a sweep's response depends on where it came from.")
    else:
        words.append("No test point shows two stable responses.")
    return " ".join(words)


def fig_coexistence(cmap: "CoexistenceMap") -> "Figure":
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.2), constrained_layout=True)
    cmap.plot(ax=ax)
    fig.suptitle("YBs: fold curves in (a_G, f); each test point judged by the branch, the sweeps and a "
                 "basin sample", wrap=True)
    return fig


def continuation_statuses(cmap: Optional["CoexistenceMap"], why_not: str) -> pd.DataFrame:
    """Rows for the report's status table: each branch and fold curve, how it ended, and what that
    means for the figure it is drawn in (``in the figures``)."""
    if cmap is None:
        return pd.DataFrame([{"configuration": "YBs branches", "a_g": np.nan, "direction": "continued",
                              "steps": 0, "not steady": 0, "message": why_not,
                              "in the figures": "no branches under Fig. 5 and no coexistence map"}])
    rows = []
    for br in cmap.branches:
        f = br.to_dataframe()["freq_hz"] if len(br) else pd.Series([np.nan])
        drawn = (f"drawn under Fig. 5 from {f.min():.4g} to {f.max():.4g} Hz" if len(br)
                 else "not drawn under Fig. 5 (no orbit found)")
        if br.status != Status.SUCCESS and len(br):
            drawn += "; it stopped there: beyond, Fig. 5 shows the sweeps alone at this a_G"
        rows.append({"configuration": "YBs branch", "a_g": br.a_g, "direction": "continued", "steps": len(br),
                     "not steady": 0, "message": f"{br.status.name}: {br.message}", "in the figures": drawn})
    for c in cmap.curves:
        df = c.to_dataframe()
        ends = (f"from {df['freq_hz'].iloc[0]:.4g} Hz, a_G {df['a_g'].iloc[0]:.3g} to "
                f"{df['freq_hz'].iloc[-1]:.4g} Hz, a_G {df['a_g'].iloc[-1]:.3g}") if len(df) else ""
        drawn = (f"drawn in the coexistence map {ends}" if len(df) > 1
                 else "a single point: not drawn as a curve")
        if c.status != Status.SUCCESS:
            drawn += ("; it stopped short of the map's edge, so the region where two responses coexist is "
                      "not closed on that side (the test points are judged by their witnesses all the same)")
        rows.append({"configuration": "YBs fold curve", "a_g": np.nan, "direction": "(a_G, f)",
                     "steps": len(c),
                     "not steady": 0, "message": f"{c.status.name}: {c.message}", "in the figures": drawn})
    rows += [{"configuration": "YBs fold", "a_g": np.nan, "direction": "", "steps": 0, "not steady": 0,
              "message": note, "in the figures": "this fold's curve is missing from the coexistence map; "
                                                 "the fold itself is on its branch under Fig. 5"}
             for note in cmap.notes]
    m = cmap.matrix
    for a_g, part in m.groupby("a_g"):
        counts = part["verdict"].value_counts()
        words = ", ".join(f"{VERDICT_WORDS[v]} at {counts[v]}" for v in VERDICT_WORDS if v in counts)
        unknown = part[part["verdict"] == "not assessed"]
        rows.append({"configuration": "YBs test points", "a_g": a_g, "direction": "judged",
                     "steps": len(part), "not steady": 0, "message": words,
                     "in the figures": "the coexistence map; each point's witnesses in coexistence.csv"
                                       + (f"; not assessed: {_freqs(unknown)}" if len(unknown) else "")})
    return pd.DataFrame(rows)


VERDICT_WORDS = {"coexist": "two or more responses", "one": "one response (a basin sample agrees)",
                 "one on the branch": "one stable orbit on the branch (not checked)",
                 "not assessed": "not assessed"}


def _freqs(rows: pd.DataFrame, step_hz: float | None = None) -> str:
    """The rows' frequencies in words; with the grid's ``step_hz``, runs of consecutive ones joined
    (``0.5, 1.3-2.3 Hz``)."""
    f = np.unique(np.round(rows["freq_hz"].to_numpy(float), 9))
    if not f.size:
        return "no frequency"
    runs, start = [], 0
    for i in range(1, f.size + 1):
        if i == f.size or step_hz is None or not np.isclose(f[i] - f[i - 1], step_hz, rtol=1e-6):
            runs.append(f"{f[start]:g}" if i - 1 == start else f"{f[start]:g}-{f[i - 1]:g}")
            start = i
    return ", ".join(runs) + " Hz"
