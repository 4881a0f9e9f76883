"""The analogues of the paper's Figs. 4-11 and 14-17, model beside the measured points.

:func:`paper_figures` returns every figure by name (``fig04`` ...).  The paper gives its
curves only as figures: what is overlaid as measured are the numbers it prints (Tables
2-4, Sects. 3.2-3.4), as hollow markers at the resonance they were read at: in the colour of
their a_G's curve in the pseudo-FRFs, in a shape of their own per configuration elsewhere.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from ..data import paper_gap_total_m, paper_measurements
from ..plots.legend import place_legend
from ..plots.sweep import DIRECTION_STYLE, plot_hysteresis

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from ..protocols.campaign import CampaignResult

NU = r"$\nu = f/f_R$ [-]"
ALPHA = r"$\alpha = A_{max}/A_t$ [-]"
# eta over the rig's nominal total gap (Table 2's), whatever a model's own gap: one eta in every figure
ETA = rf"$\eta = E/\Delta$, $\Delta$ = {paper_gap_total_m() * 1e3:g} mm [-]"
E_NBS = r"$e = E/D_{tmax}$ [-]"
A_G = r"$a_G = A_t/g$ [-]"
MEASURED = dict(marker="o", mfc="none", mec="k", ls="none", ms=8, mew=1.5)
CONF_STYLE = {"NBs": dict(color="tab:blue", marker="o"), "YBs": dict(color="tab:red", marker="*", ms=10)}
# measured points: hollow, black-edged, in the shape of their configuration's model markers
MEASURED_OF = {"NBs": dict(MEASURED, marker="s"), "YBs": dict(MEASURED, marker="P", ms=9)}
# up and down sweeps: solid with filled markers, dashed with hollow ones (legend entries differ)
DIRECTION_LOOK = {"up": dict(ls="-"), "down": dict(ls="--", mfc="none")}
LOOP_A_G = (0.05, 0.075, 0.1)   # Fig. 7
FRF_A_G = (0.03, 0.05, 0.1)     # Fig. 8


def measured_value(quantity: str, configuration: str) -> pd.Series:
    """A measured quantity by a_G (from :func:`pounding.data.paper_measurements`)."""
    df = paper_measurements()
    df = df[(df["quantity"] == quantity) & (df["configuration"] == configuration) & df["a_g"].notna()]
    return df.set_index("a_g")["value"]


def steps(result: "CampaignResult") -> pd.DataFrame:
    """Every finished step, long form, with ``e_gap`` = E / Delta for both configurations and
    ``eta`` = E / Delta for YBs, over the rig's nominal Delta (``paper_gap_total_m``, what the
    measured eta is over), whatever the model's own gap."""
    df = result.data.to_dataframe().reset_index()
    df = df[df["ran"]].copy()
    df["e_gap"] = df["excursion_m"] / paper_gap_total_m()
    df["eta"] = df["e_gap"].where(df["configuration"] == "YBs")
    return df


def maxima(result: "CampaignResult", df: pd.DataFrame | None = None) -> pd.DataFrame:
    """Per sweep: ``nu_r``, ``alpha`` and ``e_gap`` maxima, and the impacts at resonance
    (``df``: :func:`steps` of the result, if already at hand)."""
    df = steps(result) if df is None else df
    rows = []
    for (conf, ag, d), sub in df.groupby(["configuration", "a_g", "direction"]):
        at = sub.loc[sub["alpha"].idxmax()]
        rows.append({"configuration": conf, "a_g": ag, "direction": d, "nu_r": at["nu"],
                     "alpha": at["alpha"], "e_gap": sub["e_gap"].max(),
                     "mean_force_over_mg": at["mean_force_n"] / _mg(result, conf, ag, d),
                     "contact_time_ms": at["contact_time_s"] * 1e3,
                     "dissipated_energy_per_mass": at["dissipated_energy_j"] / _mass(result, conf, ag, d),
                     "restitution": at["restitution"]})
    return pd.DataFrame(rows)


def _mass(result, conf, ag, d) -> float:
    return result.sweeps[(conf, ag, d)].system.mass_kg


def _mg(result, conf, ag, d) -> float:
    sw = result.sweeps[(conf, ag, d)]
    return sw.system.mass_kg * sw.g


def _figure(title: str, panels: int = 2, sharex: bool = True):
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(panels, 1, figsize=(6.5, 3.4 * panels), sharex=sharex, squeeze=False,
                             constrained_layout=True)
    suptitle(fig, title)
    return fig, axes[:, 0]


def suptitle(fig, title: str, fontsize: float = 12.0) -> None:
    """The figure's title, wrapped to the figure's width (a long title on a narrow figure is cut at
    both ends otherwise)."""
    import textwrap

    width_in = fig.get_size_inches()[0]
    chars = max(20, int(width_in * 72.0 / (0.56 * fontsize)))
    fig.suptitle(textwrap.fill(title, chars), fontsize=fontsize)


def _frf(df: pd.DataFrame, conf: str, a_gs, y: str, axes, colour_of=None, conf_label=False) -> None:
    for i, ag in enumerate(a_gs):
        for d, sub in df[(df["configuration"] == conf) & np.isclose(df["a_g"], ag)].groupby("direction"):
            colour = colour_of(conf, i) if colour_of else f"C{i}"
            style = dict(DIRECTION_STYLE[d], ms=3, lw=1.0, color=colour)
            label = f"{conf + ' ' if conf_label else ''}a_G = {ag:g} ({d})"
            axes[0].plot(sub["nu"], sub["alpha"], label=label, **style)
            axes[1].plot(sub["nu"], sub[y], **style)


def _measured_peaks(axes, conf: str, y: str, a_gs) -> None:
    """The paper's measured peak of each a_G, in the colour of that a_G's model curves
    (``a_gs`` in the order :func:`_frf` coloured them)."""
    nu = measured_value("nu_r", conf)
    alpha = measured_value("alpha", conf)
    other = _measured_excursion(conf, y)
    for i, ag in enumerate(a_gs):
        match = [m for m in nu.index if np.isclose(m, ag)]
        if not match:
            continue
        style = dict(MEASURED, mec=f"C{i}", mew=2.0)
        axes[0].plot(nu[match], alpha[match], label=f"measured peak a_G = {ag:g} (paper)", **style)
        axes[1].plot(nu[match], other.reindex(match), **style)


def _measured_excursion(conf: str, y: str) -> pd.Series:
    if y == "e":
        return measured_value("e", conf)
    if conf == "YBs":
        return measured_value("eta", conf)
    return measured_value("excursion_max_m", "NBs") / paper_gap_total_m()


def fig04(result, df, peaks):
    fig, ax = _figure("Fig. 4 analogue: NBs pseudo-FRFs (a) acceleration, (b) excursion")
    a_gs = sorted(df.loc[df["configuration"] == "NBs", "a_g"].unique())
    _frf(df, "NBs", a_gs, "e", ax)
    _measured_peaks(ax, "NBs", "e", a_gs)
    ax[0].set_ylabel(ALPHA), ax[1].set_ylabel(E_NBS), ax[1].set_xlabel(NU)
    place_legend(ax[0], fontsize="x-small", ncol=2)
    return fig


def fig05(result, df, peaks):
    fig, ax = _figure("Fig. 5 analogue: YBs pseudo-FRFs (a) acceleration, (b) excursion")
    a_gs = sorted(df.loc[df["configuration"] == "YBs", "a_g"].unique())
    _frf(df, "YBs", a_gs, "eta", ax)
    _measured_peaks(ax, "YBs", "eta", a_gs)
    ax[1].axhline(1.0, color="0.5", lw=0.8, ls=":")
    ax[0].set_ylabel(ALPHA), ax[1].set_ylabel(ETA), ax[1].set_xlabel(NU)
    place_legend(ax[0], fontsize="x-small", ncol=2)
    return fig


def fig05_measured(result, chain: str):
    """Fig. 5's analogue with every window measured through a chain (``chain``: its description)."""
    df = steps(result)
    fig = fig05(result, df, None)
    suptitle(fig, f"Fig. 5 analogue as measured ({chain}); no branches drawn: a branch's metrics are "
                  "exact, these are read through the chain (Fig. 5 has the exact ones with their branches)",
             fontsize=9.0)
    return fig


def _versus_a_g(ax, peaks: pd.DataFrame, conf: str, y: str, measured: pd.Series | None, label: str) -> None:
    for d, sub in peaks[peaks["configuration"] == conf].groupby("direction"):
        ax.plot(sub["a_g"], sub[y], label=f"{label} model ({d} sweep)", **CONF_STYLE[conf],
                **DIRECTION_LOOK[d])
    if measured is not None and len(measured):
        ax.plot(measured.index, measured.to_numpy(), label=f"{label} measured", **MEASURED_OF[conf])


def fig06(result, df, peaks):
    fig, ax = _figure("Fig. 6 analogue: YBs maxima against the table acceleration")
    _versus_a_g(ax[0], peaks, "YBs", "alpha", measured_value("alpha", "YBs"), "YBs")
    _versus_a_g(ax[1], peaks, "YBs", "e_gap", measured_value("eta", "YBs"), "YBs")
    ax[0].set_ylabel(ALPHA), ax[1].set_ylabel(ETA), ax[1].set_xlabel(A_G)
    place_legend(ax[0], fontsize="x-small")
    return fig


def _loops(result, a_gs, title, linestyle="-"):
    """The loops at resonance, one panel per a_G side by side on shared axes (drawn on one, the smaller
    loops hid inside the larger ones)."""
    import matplotlib.pyplot as plt

    shown = [(i, ag, result.sweeps.get(("YBs", ag, "up"))) for i, ag in enumerate(a_gs)]
    shown = [(i, ag, sw) for i, ag, sw in shown if sw is not None and sw.steps_done > 0]
    n = max(len(shown), 1)
    fig, axes = plt.subplots(1, n, figsize=(3.3 * n + 0.6, 4.4), sharex=True, sharey=True, squeeze=False,
                             constrained_layout=True)
    suptitle(fig, title)
    for ax, (i, ag, sw) in zip(axes[0], shown):
        loop = sw.hysteresis_loop(sw.resonance_hz)
        plot_hysteresis(loop, ax=ax, per="half_gap", color=f"C{i}", ls=linestyle,
                        label=f"model a_G = {ag:g}, nu_R = {sw.nu_r:g}")
        ax.set_title(f"a_G = {ag:g}", fontsize="medium")
        # as the paper's figures: bumpers at d = +-1 (its text defines d = D/Delta, which puts them at +-0.5)
        ax.set_xlabel(r"$d = D/(\Delta/2)$ [-], bumpers at $\pm 1$", fontsize="small")
        ax.set_ylabel("")
    axes[0, 0].set_ylabel(r"$r = F_I/(M g)$ [-]")
    return fig


def fig07(result, df, peaks):
    return _loops(result, LOOP_A_G, "Fig. 7 analogue: YBs inertia force against displacement at resonance")


def fig08(result, df, peaks):
    fig, ax = _figure("Fig. 8 analogue: NBs and YBs pseudo-FRFs (excursion over the YBs gap)")
    for conf in ("NBs", "YBs"):
        _frf(df, conf, FRF_A_G, "e_gap", ax, colour_of=lambda c, i: f"C{i + (3 if c == 'YBs' else 0)}",
             conf_label=True)
    ax[0].set_ylabel(ALPHA), ax[1].set_ylabel(ETA), ax[1].set_xlabel(NU)
    place_legend(ax[0], fontsize="x-small", ncol=2)
    return fig


def _nbs_vs_ybs(peaks, title, x: str, xlabel: str, annotate: str | None = None, nu_r_panel: bool = False):
    """NBs against YBs maxima: against a_G (``x="a_g"``) or against their resonance (``x="nu_r"``), each
    line joined in the order of its x axis; ``annotate`` ("nu_r" or "a_g") labels each model point with
    that number; ``nu_r_panel`` adds a third panel, the resonance against a_G."""
    fig, ax = _figure(title, panels=3 if nu_r_panel else 2, sharex=True)
    for conf in ("NBs", "YBs"):
        meas_alpha = measured_value("alpha", conf)
        meas_e = _measured_excursion(conf, "eta")
        nu = measured_value("nu_r", conf)
        if x == "a_g":
            _versus_a_g(ax[0], peaks, conf, "alpha", meas_alpha, conf)
            _versus_a_g(ax[1], peaks, conf, "e_gap", meas_e, conf)
            if nu_r_panel:
                _versus_a_g(ax[2], peaks, conf, "nu_r", nu, conf)
        else:  # against the resonance: the envelope of the peaks, joined in the order of nu_R
            for d, sub in peaks[peaks["configuration"] == conf].groupby("direction"):
                sub = sub.sort_values(["nu_r", "a_g"])
                style = dict(CONF_STYLE[conf], **DIRECTION_LOOK[d])
                ax[0].plot(sub["nu_r"], sub["alpha"], label=f"{conf} model ({d} sweep)", **style)
                ax[1].plot(sub["nu_r"], sub["e_gap"], **style)
            ax[0].plot(nu, meas_alpha.reindex(nu.index), label=f"{conf} measured", **MEASURED_OF[conf])
            ax[1].plot(nu, meas_e.reindex(nu.index), **MEASURED_OF[conf])
        if annotate:
            _annotate(ax[:2], peaks[peaks["configuration"] == conf], x, annotate)
    ax[0].set_ylabel(ALPHA), ax[1].set_ylabel(ETA), ax[-1].set_xlabel(xlabel)
    if nu_r_panel:
        ax[2].set_ylabel(r"$\nu_R$ [-]")
    place_legend(ax[0], fontsize="x-small")
    return fig


def _annotate(axes, peaks: pd.DataFrame, x: str, what: str) -> None:
    """Each model point labelled with its ``what`` (``"nu_r"``: nu_R, ``"a_g"``: a_G), small, beside it;
    the up sweep's above, the down sweep's below (where they coincide, both are read)."""
    if not len(peaks):
        return
    mid = 0.5 * (float(peaks[x].min()) + float(peaks[x].max()))
    for _, row in peaks.iterrows():
        text = (rf"$\nu_R$ {row['nu_r']:.2g}" if what == "nu_r" else f"a_G {row['a_g']:g}")
        dy = 6 if row["direction"] == "up" else -10
        right = row[x] > mid  # (the text towards the middle: inside the axes at either end)
        for ax, y in zip(axes, ("alpha", "e_gap")):
            ax.annotate(text, (row[x], row[y]), xytext=(-4 if right else 4, dy), textcoords="offset points",
                        fontsize=6, ha="right" if right else "left",
                        color=CONF_STYLE[row["configuration"]]["color"], annotation_clip=True)


def fig09(result, df, peaks):
    return _nbs_vs_ybs(peaks, "Fig. 9 analogue: NBs vs YBs maxima against the table acceleration, each "
                       "labelled with its resonance nu_R", "a_g", A_G, annotate="nu_r")


def fig10(result, df, peaks):
    fig, ax = _figure("Fig. 10 analogue: mean contact force and contact time at resonance (YBs)")
    _versus_a_g(ax[0], peaks, "YBs", "mean_force_over_mg", None, "YBs")
    printed = measured_value("mean_force_over_mg", "YBs")
    # on the same axis as the model, as printed: Table 3's scale factor is unclear, and a second
    # axis with its own scale would make any miss look like agreement
    ax[0].plot(printed.index, printed.to_numpy(), label="YBs measured, as printed (Table 3's scale unclear)",
               **MEASURED_OF["YBs"])
    _versus_a_g(ax[1], peaks, "YBs", "contact_time_ms", measured_value("contact_time_ms", "YBs"), "YBs")
    ax[0].set_ylabel(r"$F_m/(M g)$ [-]"), ax[1].set_ylabel(r"$\Delta t_c$ [ms]"), ax[1].set_xlabel(A_G)
    place_legend(ax[0], fontsize="x-small")
    place_legend(ax[1], fontsize="x-small")
    return fig


def fig11(result, df, peaks):
    fig, ax = _figure("Fig. 11 analogue: dissipated energy and restitution at resonance (YBs)")
    _versus_a_g(ax[0], peaks, "YBs", "dissipated_energy_per_mass",
                measured_value("dissipated_energy_per_mass", "YBs"), "YBs")
    _versus_a_g(ax[1], peaks, "YBs", "restitution", measured_value("restitution", "YBs"), "YBs")
    ax[0].set_ylabel(r"$E_d/M$ [m$^2$/s$^2$]"), ax[1].set_ylabel(r"$s = -v_o/v_i$ [-]"), ax[1].set_xlabel(A_G)
    place_legend(ax[0], fontsize="x-small")
    return fig


def fig14(result, df, peaks):
    fig, ax = _figure("Fig. 14 analogue: YBs, a_G = 0.05 (dashed: model; markers: measured peak)")
    sub = df[(df["configuration"] == "YBs") & np.isclose(df["a_g"], 0.05)]
    for d, part in sub.groupby("direction"):
        style = dict(ls="--", marker=DIRECTION_STYLE[d]["marker"], ms=3, lw=1.0,
                     color="C0" if d == "up" else "C1")
        ax[0].plot(part["nu"], part["alpha"], label=f"model ({d})", **style)
        ax[1].plot(part["nu"], part["eta"], **style)
    _measured_peaks(ax, "YBs", "eta", [0.05])
    ax[0].set_ylabel(ALPHA), ax[1].set_ylabel(ETA), ax[1].set_xlabel(NU)
    place_legend(ax[0], fontsize="x-small")
    return fig


def fig15(result, df, peaks):
    return _loops(result, (0.05,), "Fig. 15 analogue: YBs, a_G = 0.05, at resonance (dashed: model)", "--")


def fig16(result, df, peaks):
    return _nbs_vs_ybs(peaks, "Fig. 16 analogue: NBs (circles) and YBs (stars) maxima at their resonance, "
                       "each labelled with its a_G", "nu_r", r"$\nu_R$ [-]", annotate="a_g")


def fig17(result, df, peaks):
    return _nbs_vs_ybs(peaks, "Fig. 17 analogue: NBs (circles) vs YBs (stars) against the table "
                       "acceleration, with the resonance's shift (c)", "a_g", A_G, nu_r_panel=True)


FIGURES = {"fig04": fig04, "fig05": fig05, "fig06": fig06, "fig07": fig07, "fig08": fig08, "fig09": fig09,
           "fig10": fig10, "fig11": fig11, "fig14": fig14, "fig15": fig15, "fig16": fig16, "fig17": fig17}


def paper_figures(result: "CampaignResult") -> dict[str, "Figure"]:
    """Every figure analogue, by name (``fig04`` ... ``fig17``)."""
    df = steps(result)
    peaks = maxima(result, df)
    return {name: make(result, df, peaks) for name, make in FIGURES.items()}
