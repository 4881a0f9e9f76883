"""No legend covers data: the check itself, where place_legend puts a legend, and every plot of the
package (the report's figures are checked in test_report.py)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import pounding as pd_  # noqa: E402
from pounding.plots.legend import legends_over_data, place_legend  # noqa: E402


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def _figure():
    fig, ax = plt.subplots(figsize=(5, 3.5), constrained_layout=True)
    return fig, ax


def test_the_check_sees_a_legend_over_a_line_markers_or_a_band():
    x = np.linspace(0.0, 1.0, 200)
    fig, ax = _figure()
    ax.plot(x, x, label="a line up to the upper right")  # (no markers: only the line is data)
    ax.legend(loc="upper right")
    ax.set_xlim(0.0, 1.0)
    assert len(legends_over_data(fig)) == 1
    fig, ax = _figure()
    ax.plot([0.9], [0.9], "o", label="one marker in the upper right")
    ax.plot([0.1], [0.1], "s")
    ax.legend(loc="upper right")
    assert len(legends_over_data(fig)) == 1
    fig, ax = _figure()
    ax.fill_between(x, 0.0, 1.0, alpha=0.2, label="a band over everything")
    ax.plot(x, np.zeros_like(x), label="a line at the bottom")
    ax.legend(loc="center")  # (inside the band, crossing none of its edges)
    assert len(legends_over_data(fig)) == 1


def test_the_check_passes_a_legend_in_empty_space_or_over_a_reference_line():
    x = np.linspace(0.0, 1.0, 200)
    fig, ax = _figure()
    ax.plot(x, x**4, label="low, then up at the right")
    ax.axhline(0.9, color="0.5", ls=":")  # (a reference line across the axes is no data)
    ax.legend(loc="upper left")
    assert legends_over_data(fig) == []


def test_place_legend_takes_a_free_corner_or_goes_outside():
    x = np.linspace(0.0, 1.0, 200)
    fig, ax = _figure()
    ax.plot(x, 1.0 - x, label="down from the upper left")
    legend = place_legend(ax)
    assert legend._loc in (1, 3)  # (upper right or lower left: the empty corners)
    assert legends_over_data(fig) == []
    # data everywhere: the legend goes to the right of the axes, the figure grows for it
    fig, ax = _figure()
    rng = np.random.default_rng(0)
    ax.plot(rng.uniform(size=400), rng.uniform(size=400), ".", label="points everywhere")
    width = fig.get_figwidth()
    legend = place_legend(ax)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    assert legend.get_window_extent(renderer).x0 >= ax.get_window_extent(renderer).x1
    assert fig.get_figwidth() > width and legends_over_data(fig) == []
    fig, ax = _figure()
    assert place_legend(ax) is None  # (nothing labelled: no legend)


def test_every_plot_of_the_package_keeps_its_legend_off_the_data():
    osc = pd_.presets.paper_damped()
    figures = []
    kw = dict(steady="fixed", cycles=6, measure_cycles=2)
    freqs = [1.2, 1.5, 1.8, 2.1, 2.4]
    up, down = pd_.sweep(osc, 0.05, freqs, "up", **kw), pd_.sweep(osc, 0.05, freqs, "down", **kw)
    figures.append(pd_.plots.plot_sweep([up, down])[0].figure)
    figures.append(up.hysteresis_loop(2.1).plot())
    run = pd_.simulate(osc, pd_.Harmonic(0.05, 1.5), 3.0)
    figures.append(run.plot())
    campaign = pd_.campaign(osc.without_bumpers(), osc, nbs_a_g=[0.05], ybs_a_g=[0.05], freqs_hz=freqs, **kw)
    figures.append(campaign.plot())
    orbit = pd_.periodic_orbit(osc, pd_.Harmonic(0.05, 1.5))
    figures.append(orbit.plot())
    branch = pd_.continuation(osc, 0.05, (1.5, 2.5))
    figures.append(branch.plot())
    diagram = pd_.bifurcation_diagram(osc, 0.05, freqs, transient_cycles=10, record_cycles=9)
    figures.append(diagram.plot(branches=branch))
    figures.append(pd_.basins(osc, pd_.Harmonic(0.05, 1.8), n=(8, 8)).plot())
    stability = pd_.basin_stability_map(osc, [0.04, 0.05], [1.5, 1.8], samples=6)
    figures.append(stability.plot())
    quake = pd_.records.el_centro()
    figures.append(quake.plot())
    spectrum = pd_.pounding_spectrum([quake, quake.scaled(pga_g=0.2)], [1.0, 2.0, 3.0], gaps_m=[0.02, 0.05])
    figures.append(spectrum.plot())
    test = pd_.data.bumper_cyclic_test()
    fit = pd_.fit_contact_law(test["compression_m"], test["force_n"], time_s=test["time_s"],
                              law="kelvin_voigt")
    figures.append(fit.plot())
    from matplotlib.figure import Figure

    for fig in figures:  # (every result's plot() returns its Figure)
        assert isinstance(fig, Figure)
        covered = legends_over_data(fig)
        assert covered == [], (fig.axes[0].get_title(), [leg.get_texts()[0].get_text() for _, leg in covered])
