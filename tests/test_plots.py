"""Plots draw on the axes they are given and return their artists."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import pounding as pd_  # noqa: E402


def test_run_plot_on_given_axes():
    osc = pd_.presets.paper_printed()
    run = pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 1.0, pd_.State.at_rest(osc, velocity_m_s=0.6))
    fig, ax = plt.subplots()
    artists = run.plot(ax=ax)
    assert artists and artists[0].axes is ax
    assert ax.get_xlabel() == "t [s]" and "mm" in ax.get_ylabel()
    # one shaded span per contact, one dotted line per bumper surface
    spans = [a for a in artists if a.__class__.__name__ in ("Polygon", "Rectangle")]
    assert len(spans) == len(run.contacts)
    plt.close(fig)
