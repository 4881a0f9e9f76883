"""The report's figures show what the runs show: Fig. 5's branches pass through the sweeps' settled steps
and share their eta; no two figures are the same picture; every title, label and annotation is inside
its picture; lines are joined in the order of their x axis; every curve is inside its axes; and the
coexistence map's witnesses (tests/test_coexistence_witnesses.py has the rule's own tests): one campaign
and one map, built once, serve both."""

from __future__ import annotations

import itertools
import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import pounding  # noqa: E402
from pounding.data import paper_gap_total_m  # noqa: E402
from pounding.reports.branches import add_branches, coexistence_of, fig_coexistence  # noqa: E402
from pounding.reports.figures import paper_figures  # noqa: E402

# the loops' figures draw closed curves: no x order to keep
CLOSED = {"fig07", "fig15"}


@pytest.fixture(scope="module")
def drawn():
    """The calibrated campaign's figures, Fig. 5 with its branches, and the map with its witnesses (the
    branch, the sweeps and a basin sample at each test point), as ``pounding reproduce`` builds them."""
    ybs = pounding.presets.paper_calibrated()
    result = pounding.campaign(pounding.presets.paper_calibrated(bumpers=False), ybs)
    cmap, why = coexistence_of(result, ybs)
    assert cmap is not None, why
    figs = paper_figures(result)
    caption = add_branches(figs["fig05"], cmap, float(result.data.attrs["f_ref_hz"]))
    figs["coexistence"] = fig_coexistence(cmap)
    yield result, cmap, figs, caption
    plt.close("all")


def _lines(fig):
    return [ln for ax in fig.axes for ln in ax.get_lines()]


def test_fig5_branch_passes_through_the_settled_sweep_step_with_the_same_eta(drawn):
    result, cmap, figs, caption = drawn
    sw = result.sweeps[("YBs", 0.1, "up")]
    df = sw.exact_dataframe()
    step = df[np.isclose(df["freq_hz"], 2.0)].iloc[0]
    assert bool(step["steady"]) and int(step["period_multiple"]) == 1
    assert step["alpha"] == pytest.approx(21.50, abs=5e-3)  # (the number)
    eta = step["excursion_m"] / paper_gap_total_m()
    ax_alpha, ax_eta = figs["fig05"].axes[:2]
    # a drawn stable branch (solid, thin) has a point at nu = 2.0 with the step's alpha and its eta
    hits_alpha = [ln for ln in ax_alpha.get_lines() if ln.get_gid() == "branch" and ln.get_linestyle() == "-"
                  and any(math.isclose(x, 2.0, abs_tol=1e-12) and math.isclose(y, step["alpha"], rel_tol=1e-6)
                          for x, y in zip(ln.get_xdata(), ln.get_ydata()))]
    hits_eta = [ln for ln in ax_eta.get_lines() if ln.get_gid() == "branch" and ln.get_linestyle() == "-"
                and any(math.isclose(x, 2.0, abs_tol=1e-12) and math.isclose(y, eta, rel_tol=1e-6)
                        for x, y in zip(ln.get_xdata(), ln.get_ydata()))]
    assert hits_alpha and hits_eta
    # the sweep's own point in the eta panel: the same eta (over the nominal gap, not the model's own)
    sweep_eta = [y for ln in ax_eta.get_lines() if ln.get_gid() != "branch"
                 for x, y in zip(ln.get_xdata(), ln.get_ydata()) if math.isclose(x, 2.0, abs_tol=1e-12)]
    assert any(math.isclose(y, eta, rel_tol=1e-12) for y in sweep_eta)
    assert cmap.oscillator.bumpers.total_gap != pytest.approx(paper_gap_total_m())  # (so the test can fail)
    assert "30 mm" in ax_eta.get_ylabel() and "30 mm" in caption


def test_every_settled_period1_step_lies_on_a_drawn_branch_or_is_marked(drawn):
    result, cmap, figs, caption = drawn
    steps = cmap.steps
    settled = steps[steps["steady"].astype(bool)]
    assert len(settled) > 300
    off = settled[~settled["on_branch"].astype(bool)]
    assert (off["period_multiple"] != 1).all() or off["why"].str.contains("no period-1 orbit").any()
    assert (off["why"] != "").all()
    # every one on a branch: some drawn branch there within the drawing's reading
    from pounding.analysis.witnesses import branch_responses

    branches = list(cmap.branches) + list(cmap.seeded)
    for _, row in settled[settled["on_branch"].astype(bool)].iterrows():
        found = [r for br in branches if math.isclose(br.a_g, row["a_g"], rel_tol=1e-9)
                 for r in branch_responses(br, row["freq_hz"])]
        assert any(math.isclose(r[2], row["alpha"], rel_tol=1e-3) for r in found), row.to_dict()
    # the steps off every branch are marked in the figure
    marks = [ln for ln in figs["fig05"].axes[0].get_lines() if ln.get_marker() == "x"]
    assert len(off) == 0 or (marks and len(marks[0].get_xdata()) == len(off))
    assert f"{len(settled)} settled steps" in caption


def _signature(fig):
    return tuple(sorted((tuple(np.round(np.asarray(ln.get_xdata(), float), 9)),
                         tuple(np.round(np.asarray(ln.get_ydata(), float), 9))) for ln in _lines(fig)))


def test_no_two_figures_are_the_same_picture(drawn):
    figs = drawn[2]
    for (a, fa), (b, fb) in itertools.combinations(figs.items(), 2):
        assert _signature(fa) != _signature(fb), (a, b)


def _texts(fig):
    """Every text drawn: the titles, axis labels, tick labels within the view, legends, annotations."""
    out = [t for t in (fig._suptitle,) if t is not None]
    out += list(fig.texts)
    for ax in fig.axes:
        out += [ax.title, ax._left_title, ax._right_title, ax.xaxis.label, ax.yaxis.label]
        out += list(ax.texts)
        lo, hi = sorted(ax.get_xlim())
        out += [t for t, v in zip(ax.get_xticklabels(), ax.get_xticks()) if lo <= v <= hi]
        lo, hi = sorted(ax.get_ylim())
        out += [t for t, v in zip(ax.get_yticklabels(), ax.get_yticks()) if lo <= v <= hi]
        legend = ax.get_legend()
        if legend is not None:
            out += list(legend.get_texts())
    return [t for t in out if t.get_visible() and t.get_text().strip()]


def test_every_text_is_inside_its_picture(drawn):
    for name, fig in drawn[2].items():
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        w, h = fig.canvas.get_width_height()
        for t in _texts(fig):
            box = t.get_window_extent(renderer)
            assert box.x0 >= -1 and box.y0 >= -1 and box.x1 <= w + 1 and box.y1 <= h + 1, (name, t.get_text())


def test_lines_are_joined_in_the_order_of_their_x_axis(drawn):
    for name, fig in drawn[2].items():
        if name in CLOSED:
            continue
        for ln in _lines(fig):
            if ln.get_gid() in ("branch", "curve") or ln.get_linestyle() in ("None", "", " "):
                continue  # (a branch folds back in the frequency, a fold curve in the (f, a_G) plane turns
                # back in either: their order is the arclength's)
            x = np.asarray(ln.get_xdata(), float)
            x = x[np.isfinite(x)]
            if x.size >= 3:
                d = np.diff(x)
                assert np.all(d >= 0) or np.all(d <= 0), (name, ln.get_label(), x)


def test_every_curve_is_inside_its_axes(drawn):
    for name, fig in drawn[2].items():
        for ax in fig.axes:
            (x0, x1), (y0, y1) = sorted(ax.get_xlim()), sorted(ax.get_ylim())
            for ln in ax.get_lines():
                if ln.get_transform() != ax.transData:
                    continue  # (a line in axes coordinates: axhline, axvline)
                x, y = np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)
                ok = np.isfinite(x) & np.isfinite(y)
                inside = (x[ok] >= x0) & (x[ok] <= x1) & (y[ok] >= y0) & (y[ok] <= y1)
                assert np.all(inside), (name, ln.get_label())


def test_the_design_spectra_keep_the_mce_plateau_inside_the_axes():
    from pounding import design

    fig, ax = plt.subplots()
    design.asce7_spectrum(1.0, 0.6).plot(ax=ax)
    design.asce7_spectrum(1.0, 0.6, level="mce", name="MCE_R").plot(ax=ax)
    top = max(float(np.max(ln.get_ydata())) for ln in ax.get_lines())
    assert top == pytest.approx(1.5) and ax.get_ylim()[1] >= top
    plt.close(fig)


# ---- the map's witnesses (issue 48): each test point judged by the branch, the sweeps and a basin sample
@pytest.mark.parametrize("a_g, freqs", [(0.05, (2.0, 2.1, 2.2, 2.3)), (0.1, (2.7, 2.8, 2.9, 3.0))])
def test_the_calibrated_report_finds_coexistence_where_its_sweeps_differ(drawn, a_g, freqs):
    result, cmap = drawn[:2]
    m = cmap.matrix
    for f in freqs:
        row = m[np.isclose(m["a_g"], a_g) & np.isclose(m["freq_hz"], f)].iloc[0]
        # the witnesses: two settled sweeps on different responses, and a basin sample finding both
        up = result.sweeps[("YBs", a_g, "up")].exact_dataframe().set_index("freq_hz")
        down = result.sweeps[("YBs", a_g, "down")].exact_dataframe().set_index("freq_hz")
        assert up.loc[f, "steady"] and down.loc[f, "steady"]
        a_up, a_down = up.loc[f, "alpha"], down.loc[f, "alpha"]
        assert abs(a_up - a_down) > 0.5 * max(a_up, a_down)
        assert row["sweep_responses"] == 2 and row["basin_responses"] >= 2, row["evidence"]
        assert row["verdict"] == "coexist" and row["responses"] >= 2, row["evidence"]
        assert "sweeps settled" in row["evidence"] and "basin sample" in row["evidence"]


def test_no_point_of_the_calibrated_map_claims_one_response_without_a_sample_that_agrees(drawn):
    cmap = drawn[1]
    m = cmap.matrix
    one = m[m["verdict"] == "one"]
    assert len(one) and (one["basin_responses"] == 1).all() and (one["basin_not_settled"] == 0).all()
    assert ((one["stable_orbits"] == 1) | (one["sweep_responses"] == 1)).all()
    # a point no witness reaches is never drawn as one response
    unreached = m[~m["branch_reached"] & m["sweep_responses"].isna() & m["basin_responses"].isna()]
    assert (unreached["verdict"] == "not assessed").all()
    assert set(m["verdict"]) <= {"coexist", "one", "not assessed"}


def test_the_map_draws_each_verdict_with_its_own_label(drawn):
    cmap = drawn[1]
    assert cmap.plot().__class__.__name__ == "Figure"
    artists = pounding.plots.plot_curves(list(cmap.curves), matrix=cmap.matrix)
    labels = {a.get_label() for a in artists}
    assert any(lbl.startswith("two or more responses coexist") for lbl in labels)
    assert any(lbl.startswith("one response: a basin sample agrees") for lbl in labels)
    if (cmap.matrix["verdict"] == "not assessed").any():
        assert any(lbl.startswith("not assessed") for lbl in labels)
    assert not any("one stable response" in lbl for lbl in labels)
