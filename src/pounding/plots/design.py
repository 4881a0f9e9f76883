"""Plots of the design chain: target spectra, hazard curves, scaled suites, fragility curves."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._docs import fill_doc
from .._tables import percentiles
from .legend import place_legend


def _axes(ax: Any, size: tuple[float, float] = (6.0, 3.8)) -> Any:
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=size, constrained_layout=True)
    return ax


@fill_doc
def plot_design_spectrum(spectrum: Any, ax: Any = None, **line: Any) -> list:
    """A design spectrum (:class:`pounding.design.DesignSpectrum`): Sa (g) against the period (s),
    its corner periods marked.

    Parameters
    ----------
    spectrum : DesignSpectrum
        From :func:`pounding.design.asce7_spectrum`, ``ec8_spectrum`` or ``user_spectrum``.
    {ax}
    **line
        Passed to ``ax.plot`` (``label``, ``color``, ...).

    Returns
    -------
    list of matplotlib artists
        The line, then one marker per corner period drawn.

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> spectrum = design.asce7_spectrum(1.0, 0.6)
    >>> artists = pounding.plots.plot_design_spectrum(spectrum)
    >>> len(artists)  # the line, T_0 and T_S
    3
    """
    ax = _axes(ax)
    t = spectrum.default_periods()
    (ln,) = ax.plot(t, spectrum.sa_g(t), label=line.pop("label", spectrum.name), **line)
    artists = [ln]
    for key, mark in (
        ("t_0_s", "T_0"),
        ("t_s_s", "T_S"),
        ("t_l_s", "T_L"),
        ("t_b_s", "T_B"),
        ("t_c_s", "T_C"),
        ("t_d_s", "T_D"),
    ):
        tk = spectrum.params.get(key)
        if tk is not None and tk <= t[-1]:
            artists.append(ax.plot([tk], [spectrum.sa_g(tk)], "o", color=ln.get_color(), ms=4)[0])
            ax.annotate(mark, (tk, spectrum.sa_g(tk)), xytext=(3, 3), textcoords="offset points", fontsize=8)
    ax.set_xlabel("period T [s]")
    ax.set_ylabel("spectral acceleration Sa [g]")
    ax.set_xlim(0.0, max(t[-1], ax.get_xlim()[1]))
    ax.relim()  # (the axes may hold another spectrum already: room for both, its plateau too)
    ax.set_autoscaley_on(True)  # (an earlier spectrum's set_ylim turned it off: the MCE's plateau was cut)
    ax.autoscale_view(scalex=False)
    ax.set_ylim(bottom=0.0)
    place_legend(ax)
    return artists


@fill_doc
def plot_hazard_curve(curve: Any, ax: Any = None) -> list:
    """A hazard curve: the annual frequency of exceedance against Sa, log-log.

    Parameters
    ----------
    curve : HazardCurve
        The site's hazard curve.
    {ax}

    Returns
    -------
    list of matplotlib artists
        The curve's line.

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> curve = design.HazardCurve([0.1, 0.5, 1.0], [1e-2, 1e-3, 2e-4],
    ...                            period_s=2.0)
    >>> len(pounding.plots.plot_hazard_curve(curve))
    1
    """
    ax = _axes(ax)
    (ln,) = ax.loglog(
        curve.sa_g,
        curve.annual_frequency_per_year,
        "o-",
        ms=3,
        label=curve.name or f"Sa({curve.period_s:g} s)",
    )
    ax.set_xlabel(f"Sa({curve.period_s:g} s) [g]")
    ax.set_ylabel("annual frequency of exceedance (1/year)")
    ax.grid(True, which="both", alpha=0.3)
    place_legend(ax)
    return [ln]


@fill_doc
def plot_scaled_suite(suite: Any, ax: Any = None) -> list:
    """A scaled suite (:class:`pounding.design.ScaledSuite`): each record's pseudo-spectral
    acceleration (thin), the suite's mean (thick), the target (dashed) and the rule's periods
    (shaded, or a line for one period).

    Parameters
    ----------
    suite : ScaledSuite
        From :func:`pounding.design.scale_suite`.
    {ax}

    Returns
    -------
    list of matplotlib artists
        One line per record, the mean, the target, the rule's span or line.

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> suite = design.scale_suite(pounding.records.el_centro(),
    ...                            design.asce7_spectrum(1.0, 0.6), period_s=2.0)
    >>> len(pounding.plots.plot_scaled_suite(suite))  # records, mean, target, T
    4
    """
    ax = _axes(ax, (6.5, 4.0))
    psa = suite.spectra["psa_g"]
    t = psa["period_s"].values
    artists = []
    for row in psa.values:
        artists.append(ax.plot(t, row, color="0.65", lw=0.6)[0])
    artists.append(
        ax.plot(
            t,
            suite.mean_psa_g().values,
            color="C0",
            lw=2.2,
            label=(f"mean RotD100 of {len(suite.records)} scaled pairs" if suite.spectra.attrs.get("measure")
                   else f"mean of {len(suite.records)} scaled records"),
        )[0]
    )
    tt = t[(t >= t.min()) & (t <= t.max())]
    if suite.target.kind == "user":
        tt = tt[(tt >= suite.target.periods_s[0]) & (tt <= suite.target.periods_s[-1])]
    elif suite.target.kind == "en1998-1":
        tt = tt[tt <= 4.0]  # (the code's spectrum stops at 4 s)
    artists.append(ax.plot(tt, suite.target.sa_g(tt), "k--", lw=1.6, label=suite.target.name)[0])
    lo, hi = suite.period_range_s
    if hi > lo:
        artists.append(
            ax.axvspan(
                lo,
                hi,
                color="C1",
                alpha=0.15,
                label=f"scaled over {lo:g}-{hi:g} s (x {suite.factors[0]:.3g})",
            )
        )
    else:
        artists.append(ax.axvline(lo, color="C1", lw=1.0, label=f"scaled at {lo:g} s"))
    ax.set_xscale("log")
    ax.set_xlabel("period T [s]")
    measure = suite.spectra.attrs.get("measure")
    ax.set_ylabel(f"{measure + ' ' if measure else ''}PSa [g], {100 * suite.damping_ratio:g} % damping")
    ax.set_ylim(bottom=0.0)
    place_legend(ax)
    return artists


@fill_doc
def plot_fragility(fragility: Any, ax: Any = None, *, data: bool = True, **line: Any) -> list:
    """A fragility curve with its bootstrap band and (``data``) what it was fitted to.

    Parameters
    ----------
    fragility : Fragility
        From :func:`pounding.design.fit_fragility` or ``fit_fragility_capacities``.
    {ax}
    data : bool
        Draw the stripes' fractions (or the capacities' empirical distribution).
    **line
        Passed to ``ax.plot`` for the curve.

    Returns
    -------
    list of matplotlib artists
        The curve, the band, then the data's markers or steps.

    Examples
    --------
    >>> import pounding
    >>> from pounding import design
    >>> curve = design.fit_fragility([0.2, 0.4, 0.6, 0.8], [20, 20, 20, 20],
    ...                              [1, 7, 13, 17], n_bootstrap=200)
    >>> len(pounding.plots.plot_fragility(curve))
    3
    """
    ax = _axes(ax)
    if fragility.method == "stripes":
        top = 1.15 * float(np.max(fragility.data["im_g"]))
    else:
        finite = fragility.data["capacity_g"][~fragility.data["censored"]]
        top = 1.15 * float(np.max(finite))
    top = max(top, 2.0 * fragility.median_g)
    x = np.linspace(0.0, top, 301)
    label = line.pop(
        "label", f"{fragility.event or 'event'}: median {fragility.median_g:.3g} g, beta {fragility.beta:.2f}"
    )
    (ln,) = ax.plot(x, fragility.probability(x), label=label, **line)
    lo, hi = fragility.band(x)
    band = ax.fill_between(
        x,
        lo,
        hi,
        color=ln.get_color(),
        alpha=0.2,
        lw=0,
        label=f"{100 * fragility.confidence:g} % bootstrap band",
    )
    artists = [ln, band]
    if data and fragility.method == "stripes":
        d = fragility.data
        artists.append(
            ax.plot(
                d["im_g"],
                d["n_events"] / d["n_runs"],
                "o",
                color=ln.get_color(),
                ms=4,
                label="fraction of runs",
            )[0]
        )
    elif data:
        c = np.sort(fragility.data["capacity_g"])
        n = c.size
        finite = np.isfinite(c)
        artists.append(
            ax.step(
                c[finite],
                (np.arange(n)[finite] + 1) / n,
                where="post",
                color=ln.get_color(),
                lw=0.8,
                label="records' capacities",
            )[0]
        )
    ax.set_xlabel("intensity [g]")
    ax.set_ylabel("probability of the event")
    ax.set_xlim(0.0, top)
    ax.set_ylim(0.0, 1.0)
    place_legend(ax)
    return artists


@fill_doc
def plot_stripes(analysis: Any, event: str = "contact", limit: float | None = None, ax: Any = None) -> list:
    """A stripe analysis: the fraction of runs with the event at each stripe (markers) and its
    fitted fragility (lines), one per value of the design grid's first dimension (the others at
    their first value).

    Parameters
    ----------
    analysis : StripeAnalysis
        From :func:`pounding.design.stripe_analysis`.
    event : str
        The event (``StripeAnalysis.outcomes``).
    limit : float, optional
        Its threshold.
    {ax}

    Returns
    -------
    list of matplotlib artists
        Per design value, its markers and (where it has an estimate) its curve.

    Examples
    --------
    The damped paper system as it is (no design grid) under El Centro scaled to three stripes:

    >>> import pounding
    >>> msa = pounding.design.stripe_analysis(
    ...     pounding.presets.paper_damped(), "el-centro", [0.1, 0.2, 0.5],
    ...     period_s=1.0, store="plot.zarr", progress=False)
    >>> msa.fraction("contact", None).values.tolist()  # of the records, pounding
    [0.0, 1.0, 1.0]
    >>> len(pounding.plots.plot_stripes(msa))  # markers; one record: no curve
    1
    """
    from .._errors import InputError

    ax = _axes(ax, (6.5, 4.0))
    frac = analysis.fraction(event, limit)
    dims = analysis.design_dims
    first = dims[0] if dims else None
    fixed = {d: 0 for d in dims[1:]}
    x = analysis.levels_g
    xs = np.linspace(0.0, 1.1 * x.max(), 200)
    artists = []
    for i in range(frac.sizes[first] if first else 1):
        sel = {**fixed, **({first: i} if first else {})}
        value = float(analysis.data[first].values[i]) if first else None
        label = f"{first} = {value:g} {analysis.unit(first)}".rstrip(" -") if first else event
        (pts,) = ax.plot(x, frac.isel(sel).values, "o", ms=4, label=label)
        artists.append(pts)
        at = {d: float(analysis.data[d].values[j]) for d, j in sel.items()}
        try:
            curve = analysis.fragility(event, limit, at=at, n_bootstrap=0)
        except InputError:  # (all or nothing at every stripe, or separated: no curve to draw)
            continue
        artists.append(ax.plot(xs, curve.probability(xs), color=pts.get_color(), lw=1.2)[0])
    ax.set_xlabel(f"Sa({analysis.period_s:g} s) [g]")
    ax.set_ylabel(f"probability of {event}" + ("" if limit is None else f" > {limit:g}"))
    ax.set_xlim(0.0, xs[-1])
    ax.set_ylim(-0.02, 1.02)
    place_legend(ax)
    return artists


OPTION_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*", "<", ">")  # (one shape per design option)


@fill_doc
def plot_decision(decision: Any, ax: Any = None) -> list:
    """The design chart of a :class:`pounding.design.Decision`: the probability of pounding at the
    design (dashed) and MCE (solid) intensities against the gap, one colour per value of the
    other design dimensions, the target (horizontal), the gap recommended and the code's minimum
    clearance (vertical).

    Parameters
    ----------
    decision : Decision
        From :func:`pounding.design.decide`.
    {ax}

    Returns
    -------
    list of matplotlib artists
        Two lines per group of the other dimensions, then the target's, the recommendation's and
        the code minimum's lines (those that apply).

    Examples
    --------
    {two_gaps_msa}
    >>> choice = design.decide(msa, 0.3, 0.45)
    >>> len(pounding.plots.plot_decision(choice))  # 2 lines, target, choice
    4
    """
    ax = _axes(ax, (6.5, 4.0))
    gap = decision.gap_dim
    artists = []
    groups = decision.by_gap()
    # options often give the same probabilities (contact does not depend on the bumper): each is drawn
    # thinner and with smaller markers of its own shape than the one before it, so none hides another
    n = len(groups)
    for i, (label, part) in enumerate(groups):
        lw, ms = 1.0 + 2.2 * (n - 1 - i) / max(n - 1, 1), 3.0 + 5.0 * (n - 1 - i) / max(n - 1, 1)
        marker = OPTION_MARKERS[i % len(OPTION_MARKERS)]
        p = decision.probability_column
        (solid,) = ax.plot(1e3 * part[gap], part[f"{p}_mce"], marker=marker, ls="-", lw=lw, ms=ms,
                           mfc="none", color=f"C{i % 10}", zorder=2 + i,
                           label=f"MCE ({decision.mce_sa_g:.3g} g){', ' + label if label else ''}")
        (dashed,) = ax.plot(1e3 * part[gap], part[f"{p}_design"], marker=marker, ls="--", lw=lw, ms=ms,
                            color=solid.get_color(), zorder=2 + i,
                            label=f"design ({decision.design_sa_g:.3g} g){', ' + label if label else ''}")
        artists += [solid, dashed]
    # reference lines in black and grey: no option's colour
    artists.append(ax.axhline(decision.target_probability, color="0.45", lw=0.9, ls=":",
                              label=f"target {decision.target_probability:g}"))
    if decision.recommended is not None:
        artists.append(ax.axvline(1e3 * decision.recommended[gap], color="k", lw=1.6,
                                  label=f"recommended {1e3 * decision.recommended[gap]:.0f} mm"))
    if decision.code_minimum_gap_m is not None:
        artists.append(ax.axvline(1e3 * decision.code_minimum_gap_m, color="0.45", lw=1.0, ls="-.",
                                  label=f"code minimum {1e3 * decision.code_minimum_gap_m:.0f} mm"))
    ax.set_xlabel("gap [mm]")
    ax.set_ylabel(f"probability of {decision.event_words()}")
    ax.set_ylim(-0.02, 1.02)
    place_legend(ax)
    return artists


@fill_doc
def plot_responses(analysis: Any, quantity: str = "acc_max_g", ax: Any = None) -> list:
    """A stripe analysis's response against the intensity: the median over the records (line) and
    the 16-84 % band (shaded) per stripe, one colour per value of the design grid's first dimension
    (the others at their first value); runs that did not finish are left out.

    Parameters
    ----------
    analysis : StripeAnalysis
        From :func:`pounding.design.stripe_analysis`.
    quantity : str
        A run quantity (every system's, ``Run.quantities()``): ``acc_max_g``, ``disp_max_m`` (a
        building's: its base's), ``impacts``, ``impact_force_max_n``, ``impact_speed_max_m_s``,
        ``compression_max_m``, ``top_disp_max_m``, ``top_acc_max_g`` or ``drift_ratio_max``
        (a building's ``base_disp_max_m`` of before answers, with a ``FutureWarning``).
    {ax}

    Returns
    -------
    list of matplotlib artists
        A line and a band per design value.

    Examples
    --------
    {two_gaps_msa}
    >>> len(pounding.plots.plot_responses(msa, "acc_max_g"))  # line, band
    4
    """

    from .._errors import InputError, Problem
    from .._tables import RunQuantities
    from ..engine.run_quantities import RUN_QUANTITIES

    ds = analysis.data
    names = RUN_QUANTITIES[:-1]  # (not the status)
    quantity = RunQuantities.name_now(quantity)
    if quantity not in names or quantity not in ds:
        raise InputError(Problem.NOT_IN_RESULT, "quantity", quantity,
                         choices=", ".join(n for n in names if n in ds))
    ax = _axes(ax)
    ok = analysis.finished()
    values = ds[quantity].where(ok)
    dims = analysis.design_dims
    first = dims[0] if dims else None
    fixed = {d: 0 for d in dims[1:]}
    x = analysis.levels_g
    artists = []
    for i in range(ds.sizes[first] if first else 1):
        sel = {**fixed, **({first: i} if first else {})}
        v = values.isel(sel).transpose("sa_g", "record").values
        mid, lo, hi = percentiles(v, (50.0, 16.0, 84.0), axis=1)  # (a stripe with no finished run: NaN)
        label = (f"{first} = {float(ds[first].values[i]):g} {analysis.unit(first)}".rstrip(" -") if first
                 else quantity)
        (ln,) = ax.plot(x, mid, "o-", ms=3, label=label)
        artists += [ln, ax.fill_between(x, lo, hi, color=ln.get_color(), alpha=0.15, lw=0)]
    ax.set_xlabel(f"Sa({analysis.period_s:g} s) [g]")
    ax.set_ylabel(quantity)
    place_legend(ax)
    return artists
