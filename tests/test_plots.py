"""Plots draw on the axes they are given and return their artists."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import pounding as pd_  # noqa: E402
from pounding.plots import plot_sweep  # noqa: E402


def test_run_plot_on_given_axes():
    osc = pd_.presets.paper_printed()
    run = pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 1.0, pd_.State.at_rest(osc, velocity_m_s=0.6))
    fig, ax = plt.subplots()
    artists = pd_.plots.plot_run(run, ax=ax)
    assert run.plot(ax=ax) is fig
    assert artists and artists[0].axes is ax
    assert ax.get_xlabel() == "t [s]" and "mm" in ax.get_ylabel()
    # one shaded span per contact, one dotted line per bumper surface
    spans = [a for a in artists if a.__class__.__name__ in ("Polygon", "Rectangle")]
    assert len(spans) == len(run.contacts)
    plt.close(fig)


def test_sweep_plot_distinguishes_up_and_down():
    osc = pd_.presets.paper_printed()
    kw = dict(steady="fixed", cycles=3, measure_cycles=2)
    up = pd_.sweep(osc, 0.05, [1.0, 1.5, 2.0], "up", **kw)
    down = pd_.sweep(osc, 0.05, [1.0, 1.5, 2.0], "down", **kw)
    fig, axes = plt.subplots(2, 1)
    artists = plot_sweep([up, down], ax=axes)
    lines = [a for a in artists if a.__class__.__name__ == "Line2D" and a.axes is axes[0]]
    assert {line.get_linestyle() for line in lines} == {"-", "--"}
    assert {line.get_marker() for line in lines} == {"^", "v"}
    assert axes[1].get_ylabel() == "eta = E / Delta [-]" and axes[1].get_xlabel() == "nu = f / f_R [-]"
    # the printed system never settles: unsteady steps are ringed
    assert any(a.__class__.__name__ == "PathCollection" for a in artists)
    plt.close(fig)


def test_hysteresis_loop_plot():
    osc = pd_.presets.paper_printed()
    res = pd_.sweep(osc, 0.05, [1.5], steady="fixed", cycles=3, measure_cycles=2)
    fig, ax = plt.subplots()
    artists = pd_.plots.plot_hysteresis(res.hysteresis_loop(1.5), ax=ax)
    assert res.hysteresis_loop(1.5).plot(ax=ax) is fig
    assert artists[0].axes is ax and ax.get_xlabel() == "d = D / Delta [-]"
    assert len(artists) == 3  # the loop and the two bumper surfaces
    plt.close(fig)
