"""The design chain's pieces: code spectra, hazard curves, scaled suites, fragility fits, risk."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy import optimize, stats

import pounding
from pounding import design
from pounding.design.risk import cornell


# ---- ASCE 7-16 and EN 1998-1, against the code's formulas written out branch by branch ----------
def asce7_by_hand(t: float, s_ds: float, s_d1: float, t_l: float) -> float:
    t0, ts = 0.2 * s_d1 / s_ds, s_d1 / s_ds
    if t < t0:
        return s_ds * (0.4 + 0.6 * t / t0)  # (11.4-5)
    if t <= ts:
        return s_ds
    if t <= t_l:
        return s_d1 / t  # (11.4-6)
    return s_d1 * t_l / t**2  # (11.4-7)


@pytest.mark.parametrize("s_ds, s_d1, t_l", [(1.0, 0.6, 8.0), (0.5, 0.2, 4.0), (2.1, 1.3, 12.0)])
def test_asce7_equals_its_formulas_at_every_branch(s_ds, s_d1, t_l):
    t0, ts = 0.2 * s_d1 / s_ds, s_d1 / s_ds
    periods = [
        0.0,
        0.5 * t0,
        t0,
        0.5 * (t0 + ts),
        ts,
        0.5 * (ts + 1.0),
        1.0,
        0.5 * (1 + t_l),
        t_l,
        1.3 * t_l,
        2.0 * t_l,
    ]
    design_level = design.asce7_spectrum(s_ds, s_d1, t_l)
    mce = design.asce7_spectrum(s_ds, s_d1, t_l, level="mce")
    got = design_level.sa_g(periods)
    for t, sa in zip(periods, got):
        assert sa == pytest.approx(asce7_by_hand(t, s_ds, s_d1, t_l), rel=1e-14, abs=0.0)
    assert np.allclose(mce.sa_g(periods), 1.5 * got, rtol=1e-14, atol=0.0)
    assert design_level.sa_g(0.0) == pytest.approx(0.4 * s_ds, rel=1e-14)
    # continuous at its corners
    for tc in (t0, ts, t_l):
        assert design_level.sa_g(tc * (1 - 1e-12)) == pytest.approx(
            design_level.sa_g(tc * (1 + 1e-12)), rel=1e-9
        )
    assert design_level.params["t_0_s"] == pytest.approx(t0) and design_level.params[
        "t_s_s"
    ] == pytest.approx(ts)


def ec8_by_hand(t: float, a_g: float, s: float, tb: float, tc: float, td: float, eta: float) -> float:
    if t <= tb:
        return a_g * s * (1 + t / tb * (eta * 2.5 - 1))  # (3.2)
    if t <= tc:
        return a_g * s * eta * 2.5  # (3.3)
    if t <= td:
        return a_g * s * eta * 2.5 * tc / t  # (3.4)
    return a_g * s * eta * 2.5 * tc * td / t**2  # (3.5)


# Tables 3.2 and 3.3 of EN 1998-1, copied again here
TABLES = {
    (1, "A"): (1.0, 0.15, 0.4, 2.0),
    (1, "B"): (1.2, 0.15, 0.5, 2.0),
    (1, "C"): (1.15, 0.2, 0.6, 2.0),
    (1, "D"): (1.35, 0.2, 0.8, 2.0),
    (1, "E"): (1.4, 0.15, 0.5, 2.0),
    (2, "A"): (1.0, 0.05, 0.25, 1.2),
    (2, "B"): (1.35, 0.05, 0.25, 1.2),
    (2, "C"): (1.5, 0.1, 0.25, 1.2),
    (2, "D"): (1.8, 0.1, 0.3, 1.2),
    (2, "E"): (1.6, 0.05, 0.25, 1.2),
}


@pytest.mark.parametrize("kind, ground", sorted(TABLES))
@pytest.mark.parametrize("xi, eta", [(0.05, 1.0), (0.10, math.sqrt(10 / 15)), (0.30, 0.55)])
def test_ec8_equals_its_formulas_at_every_branch(kind, ground, xi, eta):
    s, tb, tc, td = TABLES[(kind, ground)]
    spec = design.ec8_spectrum(0.2, ground, kind, importance=1.2, damping_ratio=xi)
    a_g = 0.2 * 1.2
    periods = [0.0, 0.5 * tb, tb, 0.5 * (tb + tc), tc, 0.5 * (tc + td), td, 0.5 * (td + 4.0), 4.0]
    for t, sa in zip(periods, spec.sa_g(periods)):
        assert sa == pytest.approx(ec8_by_hand(t, a_g, s, tb, tc, td, eta), rel=1e-14, abs=0.0)
    assert spec.sa_g(0.0) == pytest.approx(a_g * s)
    with pytest.warns(pounding.PoundingWarning, match="up to 4 s"):
        beyond = spec.sa_g(5.0)
    assert beyond == pytest.approx(ec8_by_hand(5.0, a_g, s, tb, tc, td, eta), rel=1e-14)


def test_code_spectra_refuse_bad_input():
    with pytest.raises(pounding.InputError, match="s_ds_g"):
        design.asce7_spectrum(-1.0, 0.6)
    with pytest.raises(pounding.InputError, match="level"):
        design.asce7_spectrum(1.0, 0.6, level="MCE_R")
    with pytest.raises(pounding.InputError, match="t_l_s"):
        design.asce7_spectrum(0.1, 1.5, 4.0)  # T_S = 15 s beyond T_L
    with pytest.raises(pounding.InputError, match="ground_type"):
        design.ec8_spectrum(0.2, "F")
    with pytest.raises(pounding.InputError, match="spectrum_type"):
        design.ec8_spectrum(0.2, "B", 3)
    with pytest.raises(pounding.InputError, match="damping_ratio"):
        design.ec8_spectrum(0.2, "B", damping_ratio=5.0)
    with pytest.raises(pounding.InputError, match="period_s"):
        design.asce7_spectrum(1.0, 0.6).sa_g(-1.0)
    with pytest.warns(pounding.PoundingWarning, match="s_ds_g"):
        design.asce7_spectrum(9.81, 0.6)


def test_a_user_spectrum_from_arrays_and_csv(tmp_path):
    mine = design.user_spectrum([0.0, 0.5, 1.0, 3.0], [0.4, 1.0, 0.6, 0.2], name="site")
    assert mine.sa_g(2.0) == pytest.approx(0.4)
    assert np.allclose(mine.sa_g([0.25, 0.75]), [0.7, 0.8])
    path = tmp_path / "target.csv"
    path.write_text("# my site\nperiod_s,sa_g\n0.0,0.4\n0.5,1.0\n1.0,0.6\n3.0,0.2\n")
    read = design.user_spectrum(path=path)
    assert np.array_equal(read.periods_s, mine.periods_s) and np.array_equal(read.values_g, mine.values_g)
    assert read.name == "target"
    with pytest.raises(pounding.InputError, match="periods_s.*strictly increasing"):
        design.user_spectrum([0.0, 1.0, 1.0], [0.1, 0.2, 0.3])
    with pytest.raises(pounding.InputError, match=r"sa_g\[1\]"):
        design.user_spectrum([0.0, 1.0], [0.1, -0.2])
    with pytest.raises(pounding.InputError, match="period_s"):
        mine.sa_g(4.0)
    with pytest.raises(pounding.InputError, match="sa_g"):
        design.user_spectrum([0.0, 1.0], [0.1, 0.2, 0.3])
    bad = tmp_path / "bad.csv"
    bad.write_text("0.0,0.4\n0.5,x\n")
    with pytest.raises(pounding.InputError, match="line 2"):
        design.user_spectrum(path=bad)


# ---- hazard curves and risk ---------------------------------------------------------------------
def test_a_hazard_curve_interpolates_in_log_log_and_inverts():
    curve = design.HazardCurve.from_return_periods([0.1, 0.4, 1.2], [43.0, 475.0, 2475.0], period_s=2.0)
    assert curve.annual_frequency(0.4) == pytest.approx(1 / 475.0, rel=1e-12)
    mid = math.sqrt(0.1 * 0.4)  # halfway in log: the geometric mean of the frequencies
    assert curve.annual_frequency(mid) == pytest.approx(math.sqrt(1 / 43.0 / 475.0), rel=1e-12)
    assert curve.sa_at(1 / 2475.0) == pytest.approx(1.2, rel=1e-12)
    assert curve.sa_at(curve.annual_frequency(0.7)) == pytest.approx(0.7, rel=1e-12)
    with pytest.raises(pounding.InputError, match="does not decrease"):
        design.HazardCurve([0.1, 0.2], [1e-3, 2e-3], period_s=1.0)
    with pytest.raises(pounding.InputError, match="strictly increasing"):
        design.HazardCurve([0.2, 0.1], [1e-2, 1e-3], period_s=1.0)
    with pytest.raises(pounding.InputError, match=r"sa_g\[0\]"):
        design.HazardCurve([0.0, 0.1], [1e-2, 1e-3], period_s=1.0)
    with pytest.raises(pounding.InputError, match="annual_frequency_per_year"):
        curve.sa_at(0.5)
    with pytest.raises(pounding.InputError, match="sa_g"):
        curve.annual_frequency(0.0)
    with pytest.raises(pounding.InputError, match="annual_frequency_per_year"):
        design.probability_in_years(-1.0)


@pytest.mark.parametrize(
    "k0, k, median, beta", [(1e-4, 2.0, 0.5, 0.4), (3e-5, 3.1, 0.8, 0.6), (2e-3, 1.2, 0.2, 0.25)]
)
def test_annual_frequency_equals_cornells_closed_form_on_a_power_law(k0, k, median, beta):
    sa = np.geomspace(0.01, 20.0, 12)
    curve = design.HazardCurve(sa, k0 * sa ** (-k), period_s=2.0)
    frag = design.Fragility(median, beta, "contact", "stripes", {}, np.empty((0, 2)), 0.9)
    assert design.annual_frequency(frag, curve) == pytest.approx(cornell(k0, k, median, beta), rel=1e-9)
    out = design.risk(frag, curve, years=50.0)
    assert out["probability"] == pytest.approx(
        1.0 - math.exp(-50.0 * out["annual_frequency_per_year"]), rel=1e-12
    )


def test_risk_warns_when_the_curve_is_extended():
    curve = design.HazardCurve([0.1, 0.3], [1e-2, 1e-3], period_s=2.0)
    frag = design.Fragility(1.0, 0.5, "contact", "stripes", {}, np.empty((0, 2)), 0.9)
    with pytest.warns(pounding.PoundingWarning, match="beyond the hazard curve"):
        design.annual_frequency(frag, curve)
    assert design.probability_in_years(1 / 475.0, 50.0) == pytest.approx(
        0.1, abs=1e-3
    )  # the 10 % in 50 years


# ---- fragility fits -----------------------------------------------------------------------------
def binomial_mle_by_scipy(x, n, k):
    """An independent fit: scipy.stats' binomial log-pmf, Nelder-Mead on (ln theta, ln beta)."""

    def neg(par):
        p = stats.norm.cdf((np.log(x) - par[0]) / math.exp(par[1]))
        return -np.sum(stats.binom.logpmf(k, n, p))

    res = optimize.minimize(
        neg,
        [math.log(np.median(x)), math.log(0.5)],
        method="Nelder-Mead",
        options={"xatol": 1e-13, "fatol": 1e-15, "maxiter": 50_000, "maxfev": 50_000},
    )
    return math.exp(res.x[0]), math.exp(res.x[1])


STRIPES = [
    ([0.2, 0.4, 0.6, 0.8], [20, 20, 20, 20], [1, 7, 13, 17]),
    ([0.1, 0.2, 0.3, 0.5, 0.8, 1.2], [44, 44, 44, 44, 44, 44], [0, 2, 9, 25, 38, 44]),
    ([0.3, 0.6, 0.9], [10, 15, 30], [2, 3, 29]),
    ([0.05, 1.0], [7, 9], [1, 8]),
]


@pytest.mark.parametrize("x, n, k", STRIPES)
def test_the_stripe_fit_equals_an_independent_maximum_likelihood_fit(x, n, k):
    got = design.fit_fragility(x, n, k, n_bootstrap=0)
    median, beta = binomial_mle_by_scipy(np.array(x), np.array(n), np.array(k))
    assert got.median_g == pytest.approx(median, rel=1e-6)
    assert got.beta == pytest.approx(beta, rel=1e-6)


def simulated_stripes(median, beta, levels, runs, rng):
    capacities = median * np.exp(beta * rng.standard_normal((len(levels), runs)))
    return np.array([(capacities[i] <= lv).sum() for i, lv in enumerate(levels)])


def test_the_stripe_fit_recovers_a_known_curve_within_its_band():
    median, beta = 0.5, 0.4
    levels = np.linspace(0.2, 1.1, 10)
    rng = np.random.default_rng(2026)
    k = simulated_stripes(median, beta, levels, 44, rng)
    fit = design.fit_fragility(levels, [44] * 10, k, n_bootstrap=2000, confidence=0.95, seed=1)
    ci = fit.interval()
    assert ci["median_g"][0] <= median <= ci["median_g"][1]
    assert ci["beta"][0] <= beta <= ci["beta"][1]
    assert ci["median_g"][1] - ci["median_g"][0] < 0.1 and ci["beta"][1] - ci["beta"][0] < 0.3  # informative
    lo, hi = fit.band(levels)
    assert np.all(lo <= fit.probability(levels) + 1e-12) and np.all(fit.probability(levels) <= hi + 1e-12)
    # coverage over many data sets: the 90 % interval holds the true median most of the time
    hits = 0
    for seed in range(60):
        kk = simulated_stripes(median, beta, levels, 20, np.random.default_rng(seed))
        lo_m, hi_m = design.fit_fragility(levels, [20] * 10, kk, n_bootstrap=400, seed=seed).interval()[
            "median_g"
        ]
        hits += lo_m <= median <= hi_m
    assert 0.75 <= hits / 60 <= 1.0


def test_the_stripe_fit_refuses_what_has_no_estimate():
    with pytest.raises(pounding.InputError, match="dispersion has no estimate"):
        design.fit_fragility([0.1, 0.2, 0.3], [10, 10, 10], [0, 10, 10])  # separated
    with pytest.raises(pounding.InputError, match="no run with the event"):
        design.fit_fragility([0.1, 0.2], [10, 10], [0, 0])
    with pytest.raises(pounding.InputError, match="every run"):
        design.fit_fragility([0.1, 0.2], [10, 10], [10, 10])
    with pytest.raises(pounding.InputError, match="one intensity"):
        design.fit_fragility([0.2, 0.2], [10, 10], [3, 5])
    with pytest.raises(pounding.InputError, match=r"n_events\[1\]"):
        design.fit_fragility([0.1, 0.2], [10, 10], [3, 11])
    with pytest.raises(pounding.InputError, match="falls as the intensity rises"):
        design.fit_fragility([0.1, 0.2, 0.3], [10, 10, 10], [8, 5, 2])
    with pytest.raises(pounding.InputError, match="n_runs"):
        design.fit_fragility([0.1, 0.2], [10], [3, 5])
    with pytest.raises(pounding.InputError, match="confidence"):
        design.fit_fragility([0.1, 0.2], [10, 10], [3, 5], confidence=1.5)


def test_the_capacity_fit_is_the_lognormal_mle_and_handles_censoring():
    c = np.array([0.3, 0.45, 0.5, 0.7, 0.9])
    fit = design.fit_fragility_capacities(c, n_bootstrap=200)
    assert fit.median_g == pytest.approx(math.exp(np.mean(np.log(c))), rel=1e-14)
    assert fit.beta == pytest.approx(np.std(np.log(c)), rel=1e-14)  # maximum likelihood: 1/n
    censored = np.array([0.3, 0.45, 0.5, 0.7, np.inf, np.inf])
    fit = design.fit_fragility_capacities(censored, max_im_g=1.0, n_bootstrap=100)
    logs = np.log(censored[:4])

    def neg(par):
        s = math.exp(par[1])
        return -(stats.norm.logpdf(logs, par[0], s).sum() + 2 * stats.norm.logsf(0.0, par[0], s))

    res = optimize.minimize(
        neg, [0.0, 0.0], method="Nelder-Mead", options={"xatol": 1e-13, "fatol": 1e-15, "maxiter": 50_000}
    )
    assert fit.median_g == pytest.approx(math.exp(res.x[0]), rel=1e-6)
    assert fit.beta == pytest.approx(math.exp(res.x[1]), rel=1e-6)
    assert fit.median_g > math.exp(np.mean(logs))  # the survivors pull it up
    with pytest.raises(pounding.InputError, match="max_im_g"):
        design.fit_fragility_capacities(censored)
    with pytest.raises(pounding.InputError, match="capacity_g"):
        design.fit_fragility_capacities([0.3, 2.0, np.inf], max_im_g=1.0)
    with pytest.raises(pounding.InputError, match=r"capacity_g\[1\]"):
        design.fit_fragility_capacities([0.3, -2.0])


# ---- scaled suites ------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def far_field():
    return pounding.records.fema_p695()[:12]


def test_each_record_scaled_to_the_target_at_a_period(far_field):
    mce = design.asce7_spectrum(1.0, 0.6, level="mce")
    suite = design.scale_suite(far_field, mce, period_s=2.0)
    again = pounding.response_spectrum(list(suite.records), [2.0])["psa_g"].values[:, 0]
    assert np.allclose(again, mce.sa_g(2.0), rtol=1e-9, atol=0.0)
    assert len(set(np.round(suite.factors, 12))) == len(far_field)
    for rec, f in zip(suite.records, suite.factors):
        assert rec.meta["scale_factor"] == pytest.approx(f, rel=1e-15)


@pytest.mark.parametrize("fraction", [1.0, 0.9])
def test_one_factor_keeps_the_suites_mean_above_the_target_over_a_range(far_field, fraction):
    target = design.asce7_spectrum(1.0, 0.6, level="mce")
    lo, hi = 0.75 * 2.5, 1.25 * 2.5
    suite = design.scale_suite(far_field, target, period_range_s=(lo, hi), not_below=fraction, n_periods=25)
    assert np.ptp(suite.factors) == 0.0
    periods = np.geomspace(lo, hi, 25)
    mean = pounding.response_spectrum(list(suite.records), periods)["psa_g"].values.mean(axis=0)
    ratio = mean / target.sa_g(periods)
    assert ratio.min() == pytest.approx(fraction, rel=1e-9)  # touches the rule at one period
    assert np.all(ratio >= fraction * (1 - 1e-9))
    assert suite.shortfall() == pytest.approx(fraction, rel=1e-9)
    assert list(suite.to_dataframe().columns[:3]) == ["record", "scale_factor", "pga_g"]


def test_a_suite_that_no_factor_scales_is_named(far_field):
    target = design.asce7_spectrum(1.0, 0.6)
    silent = pounding.Record(np.linspace(0.0, 10.0, 1001), np.zeros(1001), "silent")
    with pytest.raises(pounding.InputError, match="no factor"):
        design.scale_suite([far_field[0], silent], target, period_s=1.0)
    with pytest.raises(pounding.InputError, match="no factor"):
        design.scale_suite([silent, silent], target, period_range_s=(1.0, 2.0))
    with pytest.raises(pounding.InputError, match="period_s"):
        design.scale_suite(far_field[:2], target)
    with pytest.raises(pounding.InputError, match="period_range_s"):
        design.scale_suite(far_field[:2], target, period_range_s=(2.0, 1.0))
    with pytest.raises(pounding.InputError, match="target"):
        design.scale_suite(far_field[:2], 0.5, period_s=1.0)
    with pytest.warns(pounding.PoundingWarning, match="scale factors outside"):
        design.scale_suite(far_field[:2], design.asce7_spectrum(0.05, 0.02), period_s=1.0)


def test_stripe_factors_bring_each_record_to_each_level(far_field):
    factors = design.stripe_factors(far_field[:3], [0.2, 0.5], 1.5)
    psa = pounding.response_spectrum(far_field[:3], [1.5])["psa_g"].values[:, 0]
    assert np.allclose(factors * psa[None, :], [[0.2] * 3, [0.5] * 3], rtol=1e-14)


def test_the_design_plots_return_their_artists(far_field):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    target = design.asce7_spectrum(1.0, 0.6, level="mce")
    assert len(pounding.plots.plot_design_spectrum(target)) >= 3
    ec8 = design.ec8_spectrum(0.25, "C")
    assert len(pounding.plots.plot_design_spectrum(ec8)) == 4  # the line and T_B, T_C, T_D
    assert ec8.plot().__class__.__name__ == "Figure"
    suite = design.scale_suite(far_field[:4], target, period_range_s=(1.5, 2.5))
    assert len(pounding.plots.plot_scaled_suite(suite)) == 4 + 3
    fit = design.fit_fragility_capacities([0.3, 0.45, np.inf], max_im_g=1.0, n_bootstrap=50)
    assert len(pounding.plots.plot_fragility(fit)) == 3
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fit.to_dataframe()
    plt.close("all")


def test_a_record_scaled_by_a_factor():
    rec = pounding.records.el_centro()
    twice = rec.scaled(factor=2.0)
    assert np.array_equal(twice.accel, 2.0 * rec.accel) and twice.meta["scale_factor"] == 2.0
    assert twice.scaled(factor=1.5).meta["scale_factor"] == 3.0
    with pytest.raises(pounding.InputError, match="one of"):
        rec.scaled(factor=2.0, pga_g=0.3)
    with pytest.raises(pounding.InputError, match="factor"):
        rec.scaled(factor=-1.0)
    with pytest.raises(pounding.InputError, match="period_s"):
        rec.scaled(factor=2.0, period_s=1.0)


def test_asce7_isolator_displacement_and_its_damping_table():
    g = 9.81  # (the package's one g: pounding._units.GRAVITY_M_S2)
    for beta, b_m in [
        (0.0, 0.8),
        (0.02, 0.8),
        (0.05, 1.0),
        (0.10, 1.2),
        (0.20, 1.5),
        (0.30, 1.7),
        (0.40, 1.9),
        (0.50, 2.0),
        (0.15, 1.35),
        (0.35, 1.8),
    ]:
        out = design.asce7_displacement(0.9, 2.5, beta)
        assert out["b_m"] == pytest.approx(b_m, rel=1e-12)
        assert out["d_m_m"] == pytest.approx(g * 0.9 * 2.5 / (4 * math.pi**2 * b_m), rel=1e-12)
        assert out["d_tm_m"] == pytest.approx(1.15 * out["d_m_m"], rel=1e-12)
    with pytest.raises(pounding.InputError, match="s_m1_g"):
        design.asce7_displacement(0.0, 2.5)


def test_interval_censored_capacities_are_unbiased_where_first_levels_are_not():
    """Capacities read as the first level with the event overstate the median; the interval fit does not."""
    rng = np.random.default_rng(7)
    median, beta = 0.5, 0.4
    capacity = median * np.exp(beta * rng.standard_normal(2000))
    levels = np.round(np.linspace(0.1, 1.5, 10) * 0.9, 4)
    index = np.searchsorted(levels, capacity)  # the first level at or above each capacity
    upper = np.where(index < levels.size, levels[np.minimum(index, levels.size - 1)], np.inf)
    lower = np.where(index == 0, 0.0, levels[np.maximum(index - 1, 0)])
    lower = np.where(index >= levels.size, levels[-1], lower)
    fit = design.fit_fragility_intervals(lower, upper, n_bootstrap=0)
    naive = design.fit_fragility_capacities(upper, max_im_g=float(levels[-1]), n_bootstrap=0)
    assert fit.median_g == pytest.approx(median, rel=0.04) and fit.beta == pytest.approx(beta, rel=0.1)
    assert naive.median_g > 1.08 * median  # (the bias the interval fit removes)
    with pytest.raises(pounding.InputError, match="same interval"):
        design.fit_fragility_intervals([0.2, 0.2], [0.4, 0.4])
    with pytest.raises(pounding.InputError, match=r"upper_g\[0\]"):
        design.fit_fragility_intervals([0.4, 0.2], [0.3, 0.4])
