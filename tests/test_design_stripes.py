"""The design chain's runs: multiple-stripe analysis on the study runner, capacities, the decision."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize, stats
from test_design import binomial_mle_by_scipy

import pounding
from pounding import design


@pytest.fixture(scope="module")
def far_field():
    return pounding.records.fema_p695()[:12]


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
    got = msa.data["disp_max_m"].values
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
    grid = {"bumpers.gap_m": [0.03, 0.06, 0.12], "bumpers.law.stiffness": [5e5, 2e6]}
    store = tmp_path / "grid.zarr"
    msa = design.stripe_analysis(
        system, names, [0.3, 0.6], period_s=1.0, store=store, grid=grid, progress=False, scheduler="serial"
    )
    ds = msa.data
    assert dict(ds["impacts"].sizes) == {"sa_g": 2, "record": 3, "bumpers.gap_m": 3,
                                         "bumpers.law.stiffness": 2}
    # each point is the run of that system under that scaled record
    rec = pounding.records.fema_p695()[1]
    f = design.stripe_factors(rec, [0.6], 1.0)[0, 0]
    one = pounding.Oscillator(
        500.0, system.isolator, pounding.Bumpers(0.06, 0.06, pounding.KelvinVoigt(2e6, 200.0))
    )
    run = pounding.simulate(one, rec.scaled(factor=f), rec.duration_s, sample_rate_hz=0)
    point = ds.sel({"sa_g": 0.6, "record": names[2], "bumpers.gap_m": 0.06, "bumpers.law.stiffness": 2e6})
    assert float(point["impacts"]) == len(run.contacts)
    assert float(point["acc_max_g"]) == pytest.approx(run.abs_acceleration_max / rec.g, rel=1e-12)
    deepest = run.contacts["max_compression_m"].max() if len(run.contacts) else 0.0
    assert float(point["compression_max_m"]) == pytest.approx(deepest, rel=1e-12)
    # contact means impacts; wider gaps pound no more often
    frac = msa.fraction("contact").values
    assert np.all(np.diff(frac, axis=1) <= 0.0)
    p = msa.probability(0.45)
    assert p.dims == ("bumpers.gap_m", "bumpers.law.stiffness") and np.all((p.values >= 0) & (p.values <= 1))
    # resumed: nothing computed again, the same numbers
    again = design.stripe_analysis(
        system, names, [0.3, 0.6], period_s=1.0, store=store, grid=grid, progress=False
    )
    assert int(again.data["session"].max()) == 1
    reopened = design.open_stripe_analysis(store)
    assert reopened.period_s == 1.0 and reopened.has_bumpers
    assert np.array_equal(reopened.data["impacts"].values, ds["impacts"].values)
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
        "[0.2, 0.3, 0.4, 0.5, 0.6, 0.8], period_s=1.0, store=%r, grid={'bumpers.gap_m': [0.02, 0.05, 0.1]}, "
        "progress=False, scheduler='serial')\n" % str(store)
    )
    proc = subprocess.Popen([sys.executable, "-c", script])
    deadline = time.monotonic() + 240.0
    import zarr

    done = 0
    while time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.2)
        try:
            done = int(np.asarray(zarr.open_group(str(store), mode="r", zarr_format=2)["done"][...]).sum())
        except Exception:  # noqa: BLE001 - not written yet
            continue
        if done >= 1:  # (the first chunk is in: kill now, part way)
            break
    proc.kill()
    proc.wait()
    done = int(np.asarray(zarr.open_group(str(store), mode="r", zarr_format=2)["done"][...]).sum())
    assert 0 < done < 6 * 44 * 3, "the kill should land part way"
    msa = design.stripe_analysis(
        pounding.presets.paper_damped(),
        "fema-p695:far_field",
        [0.2, 0.3, 0.4, 0.5, 0.6, 0.8],
        period_s=1.0,
        store=store,
        grid={"bumpers.gap_m": [0.02, 0.05, 0.1]},
        progress=False,
    )
    ds = msa.data
    assert bool(ds["done"].all())
    assert int(ds["session"].min()) == 1 and int(ds["session"].max()) == 2  # the rest in a second session


def test_study_specs_scale_records_to_a_spectral_acceleration_and_set_both_gaps():
    system = pounding.presets.paper_damped()
    spec = pounding.StudySpec(
        system,
        {"kind": "record", "record": "el-centro", "sa_g": 0.4, "sa_period_s": 1.0},
        {"bumpers.gap_m": [0.01, 0.03]},
    )
    osc, options = spec.point((1,))
    assert osc.bumpers.gap_left_m == osc.bumpers.gap_right_m == 0.03
    from pounding.studies.points import excitation_of

    rec = excitation_of(options)
    assert pounding.response_spectrum(rec, [1.0])["psa_g"].values[0, 0] == pytest.approx(0.4, rel=1e-12)
    with pytest.raises(pounding.InputError, match="sa_period_s"):
        pounding.StudySpec(
            system, {"kind": "record", "record": "el-centro", "sa_g": 0.4}, {"bumpers.gap_m": [0.01]}
        )
    with pytest.raises(pounding.InputError, match="scale_pga_g"):
        pounding.StudySpec(
            system,
            {"kind": "record", "record": "el-centro", "sa_g": 0.4, "sa_period_s": 1.0, "scale_pga_g": 0.3},
            {"bumpers.gap_m": [0.01]},
        )
    with pytest.raises(pounding.InputError, match="sa_g"):
        pounding.StudySpec(
            system, {"kind": "record", "record": "el-centro", "sa_period_s": 1.0}, {"bumpers.gap_m": [0.01]}
        )


def test_capacities_read_the_stripes_as_an_incremental_dynamic_analysis(tmp_path):
    names = [f"fema-p695:far_field:{i}" for i in range(6)]
    levels = [0.1, 0.3, 0.5, 0.6, 0.7, 0.8]
    msa = design.stripe_analysis(
        linear_isolated(1.2, 0.05), names, levels, period_s=1.0, store=tmp_path / "ida.zarr", progress=False
    )
    disp = msa.data["disp_max_m"].values  # (levels, records)
    for gap in (0.07, 0.17):
        cap = msa.capacities("contact", limit=gap)
        for r in range(len(names)):
            reached = np.flatnonzero(disp[:, r] >= gap)
            assert cap[r] == (levels[reached[0]] if reached.size else np.inf)
    spread = msa.capacities("contact", limit=0.07)
    assert np.unique(spread).size >= 2 and np.isfinite(spread).all()  # (this suite: 0.3 and 0.5 g)
    for gap in (0.07, 0.17):
        cap = msa.capacities("contact", limit=gap)
        lower = np.array(
            [
                0.0 if c == levels[0] else levels[-1] if np.isinf(c) else levels[levels.index(c) - 1]
                for c in cap
            ]
        )
        median, beta, best = interval_mle_by_scipy(lower, cap)
        fit = msa.capacity_fragility("contact", limit=gap, n_bootstrap=0)
        assert fit.method == "intervals"
        # the same maximum of the likelihood (flat near it with 6 records: the parameters agree less)
        assert interval_nll(lower, cap, math.log(fit.median_g), fit.beta) == pytest.approx(best, rel=1e-9)
        assert fit.median_g == pytest.approx(median, rel=1e-3) and fit.beta == pytest.approx(beta, rel=1e-2)
    assert np.isinf(msa.capacities("contact", limit=0.17)).any()  # (the censored case is exercised)


def interval_nll(lower, upper, mu, beta):
    from scipy import stats

    with np.errstate(divide="ignore"):
        p = stats.norm.cdf((np.log(upper) - mu) / beta) - stats.norm.cdf((np.log(lower) - mu) / beta)
    return -float(np.sum(np.log(p)))


def interval_mle_by_scipy(lower, upper):
    """An independent interval-censored fit: scipy.stats' normal CDF, Nelder-Mead on (ln theta, ln beta)."""

    res = optimize.minimize(
        lambda par: interval_nll(lower, upper, par[0], math.exp(par[1])),
        [math.log(0.5), math.log(0.3)],
        method="Nelder-Mead",
        options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 50_000},
    )
    return math.exp(res.x[0]), math.exp(res.x[1]), float(res.fun)


def test_decide_picks_the_smallest_gap_meeting_the_target(tmp_path):
    system = pounding.presets.paper_damped()
    names = ["el-centro", "fema-p695:far_field:0", "fema-p695:far_field:1", "fema-p695:far_field:2"]
    msa = design.stripe_analysis(
        system,
        names,
        [0.2, 0.4, 0.6, 0.8],
        period_s=1.0,
        store=tmp_path / "d.zarr",
        grid={"bumpers.gap_m": [0.02, 0.06, 0.12, 0.25]},
        progress=False,
    )
    choice = design.decide(msa, 0.4, 0.6, target_probability=0.25, code_minimum_gap_m=0.1)
    table = choice.data.set_index("bumpers.gap_m")
    # expected, from the runs by hand: an independent binomial fit where the stripes overlap, else the
    # fraction of runs at the 0.6 g stripe itself
    levels = np.array([0.2, 0.4, 0.6, 0.8])
    hits = (msa.data["impacts"].values > 0).sum(axis=1)  # (stripes, gaps)
    expected = {}
    for j, gap in enumerate([0.02, 0.06, 0.12, 0.25]):
        k = hits[:, j]
        n = np.full(4, 4)
        if levels[k < n].max(initial=-1) > levels[k > 0].min(initial=9):
            median, beta = binomial_mle_by_scipy(levels, n, k)
            expected[gap] = float(stats.norm.cdf(math.log(0.6 / median) / beta))
        else:
            assert np.all(np.diff(k) >= 0)  # (monotone here: the fraction at the stripe is the estimate)
            expected[gap] = k[2] / 4
        assert table.loc[gap, "p_contact_mce"] == pytest.approx(expected[gap], abs=1e-6)
    meeting = [g for g, p in expected.items() if p <= 0.25]
    assert meeting, "the grid's widest gap should meet the target here"
    assert choice.recommended["bumpers.gap_m"] == min(meeting)
    assert "A gap of" in choice.verdict() and "minimum clearance is 100 mm" in choice.verdict()
    assert (
        design.decide(msa, 0.4, 0.6, target_probability=1e-9).recommended is None
        or min(expected.values()) <= 1e-9
    )
    with pytest.raises(pounding.InputError, match="target_probability"):
        design.decide(msa, 0.4, 0.6, target_probability=1.0)
    with pytest.raises(pounding.InputError, match="gap_dim"):
        design.decide(msa, 0.4, 0.6, gap_dim="isolator.damping_n_s_m")
    with pytest.raises(pounding.InputError, match="level"):
        design.decide(msa, 0.4, 0.6, level="MCE")
    with pytest.raises(pounding.InputError, match="design_sa_g"):
        design.decide(msa, 0.7, 0.6)
    with pytest.raises(pounding.InputError, match="hazard"):
        design.decide(msa, 0.4, 0.6, hazard=design.HazardCurve([0.1, 1.0], [1e-2, 1e-4], period_s=2.0))


def test_decide_chooses_over_bumper_types_as_over_their_own_tables(tmp_path):
    from dataclasses import replace

    kv = pounding.presets.paper_damped()
    hc = replace(kv, bumpers=replace(kv.bumpers, law=pounding.HuntCrossley(stiffness=2e7, damping=0.3)))
    names = ["el-centro"] + [f"fema-p695:far_field:{i}" for i in range(4)]
    levels, gaps = [0.2, 0.4, 0.6], [0.03, 0.06, 0.09, 0.12]
    common = dict(period_s=1.0, progress=False)
    a = design.stripe_analysis(
        kv,
        names,
        levels,
        store=tmp_path / "kv.zarr",
        grid={"bumpers.gap_m": gaps, "bumpers.law.stiffness": [2e5, 2e6]},
        **common,
    )
    b = design.stripe_analysis(
        hc, names, levels, store=tmp_path / "hc.zarr", grid={"bumpers.gap_m": gaps}, **common
    )
    both = design.decide({"steel": b, "rubber": a}, 0.2, 0.4, target_probability=0.3)
    # each type's rows are its own decision's, under its name
    for name, one in (("rubber", a), ("steel", b)):
        alone = design.decide(one, 0.2, 0.4, target_probability=0.3).data
        part = both.data[both.data["bumper"] == name].drop(columns="bumper").dropna(axis=1, how="all")
        pytest.importorskip("pandas").testing.assert_frame_equal(
            part.reset_index(drop=True), alone.dropna(axis=1, how="all").reset_index(drop=True)
        )
    assert len(both.data) == 4 * 2 + 4
    # the choice by hand: the smallest gap meeting the target over both types, then the lowest peak
    # acceleration of the runs that pounded (here they differ: the test tells the types apart)
    rows = [r for r in both.data.to_dict("records") if r["p_contact_mce"] <= 0.3]
    best_gap = min(r["bumpers.gap_m"] for r in rows)
    at_gap = [r for r in rows if r["bumpers.gap_m"] == best_gap]
    accs = sorted(r["acc_pounding_median_g"] for r in at_gap)
    assert len(at_gap) == 3 and accs[0] < accs[1], "the runs should tell the three options apart here"
    best = min(at_gap, key=lambda r: r["acc_pounding_median_g"])
    for order in (both, design.decide({"rubber": a, "steel": b}, 0.2, 0.4, target_probability=0.3)):
        assert order.recommended["bumper"] == best["bumper"]
        assert order.recommended["acc_pounding_median_g"] == best["acc_pounding_median_g"]
        assert order.recommended.get("bumpers.law.stiffness") == pytest.approx(
            best["bumpers.law.stiffness"], nan_ok=True
        )
    assert f"with the {best['bumper']} bumpers" in both.verdict() and "it pounds least" in both.verdict()
    labels = [label for label, _ in both.by_gap()]
    assert labels == ["steel", "rubber, bumpers.law.stiffness 200000 N/m",
                      "rubber, bumpers.law.stiffness 2e+06 N/m"]
    assert len(pounding.plots.plot_decision(both)) == 2 * 3 + 2
    # where no run pounds at the chosen gap, the verdict says the runs do not tell the options apart
    wide = design.decide({"steel": b, "rubber": a}, 0.2, 0.4, target_probability=0.01)
    assert wide.recommended["bumpers.gap_m"] == 0.12
    assert "of the 3 options there meeting the target" in wide.verdict()
    c = design.stripe_analysis(
        hc, names[:2], levels, store=tmp_path / "c.zarr", grid={"bumpers.gap_m": gaps}, **common
    )
    with pytest.raises(pounding.InputError, match="other stripes, records"):
        design.decide({"rubber": a, "steel": c}, 0.2, 0.4)
    with pytest.raises(pounding.InputError, match="analysis\\['steel'\\]"):
        design.decide({"rubber": a, "steel": "hc.zarr"}, 0.2, 0.4)
    with pytest.raises(pounding.InputError, match="is empty"):
        design.decide({}, 0.2, 0.4)


def synthetic(impacts, status, levels=(0.2, 0.4), **design_dims):
    """A StripeAnalysis of made-up runs: ``impacts`` and ``status`` of shape (stripes, records)."""
    import xarray as xr

    impacts = np.asarray(impacts, dtype=float)
    dims = ("sa_g", "record")
    ds = xr.Dataset(
        {
            "impacts": (dims, impacts),
            "status": (dims, np.asarray(status, dtype=float)),
            "done": (dims, np.ones(impacts.shape, dtype=bool)),
            "disp_max_m": (dims, 0.01 * impacts),
            "acc_max_g": (dims, 0.1 * impacts),
            "compression_max_m": (dims, 0.001 * impacts),
        },
        coords={"sa_g": list(levels), "record": [f"r{i}" for i in range(impacts.shape[1])]},
    )
    return design.StripeAnalysis(ds, 1.0, 0.05, True)


def test_where_no_curve_fits_the_probability_is_the_runs_own():
    # 7 of 10 pound at the first stripe, all at the second: 0.7 there (not a step that says 0)
    a = synthetic([[1] * 7 + [0] * 3, [1] * 10], [[0] * 10] * 2)
    assert float(a.probability(0.2)) == pytest.approx(0.7)
    assert math.isnan(float(a.probability(0.15)))  # below the stripes: not known
    assert float(a.probability(0.5)) == 1.0  # above a stripe where every run pounded
    # none, then 3 of 10: 0.3 at the second stripe, 0 below the first
    b = synthetic([[0] * 10, [1] * 3 + [0] * 7], [[0] * 10] * 2)
    assert float(b.probability(0.4)) == pytest.approx(0.3) and float(b.probability(0.1)) == 0.0
    assert math.isnan(float(b.probability(0.5)))
    # fractions that fall (2/3, 1/3, 1/3): pooled to 4/9 each, not an error
    c = synthetic([[1, 1, 0], [1, 0, 0], [0, 1, 0]], [[0] * 3] * 3, levels=(0.2, 0.4, 0.6))
    assert float(c.probability(0.4)) == pytest.approx(4 / 9)


def test_a_run_that_stopped_early_counts_when_it_had_the_event():
    zeno, budget = float(pounding.Status.ZENO), float(pounding.Status.BUDGET)
    a = synthetic([[2, 0, 0, 1], [3, 1, 0, 0]], [[zeno, budget, 0, 0], [0, 0, budget, 0]])
    out = a.outcomes("contact").values
    assert out[0, 0] == 1.0  # stopped (Zeno) after impacts: it pounded
    assert np.isnan(out[0, 1]) and np.isnan(out[1, 2])  # stopped without an impact: not known
    n, k = a.counts("contact")
    assert n.values.tolist() == [3, 3] and k.values.tolist() == [2, 2]


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
        grid={"bumpers.gap_m": [0.04, 0.08]},
    )
    assert msa.capacity_m == 0.004 and design.open_stripe_analysis(tmp_path / "cap.zarr").capacity_m == 0.004
    beyond = msa.outcomes("compression")
    expected = (msa.data["compression_max_m"] > 0.004).astype(float)
    assert np.array_equal(beyond.values, expected.values)
    assert float(expected.sum()) > 0  # (some runs do compress beyond it: the check can fail)
    choice = design.decide(msa, 0.6, 0.9, target_probability=0.5)
    levels = np.array([0.3, 0.6, 0.9])
    comp = msa.data["compression_max_m"].values  # (stripes, records, gaps)
    for j, gap in enumerate([0.04, 0.08]):
        k = (comp[:, :, j] > 0.004).sum(axis=1)
        n = np.full(3, 3)
        if levels[k < n].max(initial=-1) > levels[k > 0].min(initial=9):
            median, beta = binomial_mle_by_scipy(levels, n, k)
            want = float(stats.norm.cdf(math.log(0.9 / median) / beta))
        else:
            want = float(np.maximum.accumulate(k / n)[2]) if np.all(np.diff(k) >= 0) else math.nan
        got = float(choice.data.set_index("bumpers.gap_m").loc[gap, "p_capacity_mce"])
        assert got == pytest.approx(want, abs=1e-6)


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
        grid={"bumpers.gap_m": [0.01, 0.5]},
    )
    free = design.stripe_analysis(
        system.without_bumpers(), names, levels, period_s=1.0, store=tmp_path / "without.zarr", progress=False
    )
    choice = design.decide(msa, 0.2, 0.5, free=free)
    table = choice.data.set_index("bumpers.gap_m")
    with_b = msa.data.sel({"sa_g": 0.5})["acc_max_g"].load()
    without = free.data.sel(sa_g=0.5)["acc_max_g"].load()
    expected = float((with_b.sel({"bumpers.gap_m": 0.01}) / without).median("record"))
    assert table.loc[0.01, "acc_penalty_median"] == pytest.approx(expected, rel=1e-12)
    assert table.loc[0.01, "acc_penalty_median"] > 1.0  # pounding at 10 mm raises the peak acceleration
    assert table.loc[0.5, "acc_penalty_median"] == pytest.approx(1.0, rel=1e-9)  # no contact at 500 mm
    with pytest.raises(pounding.InputError, match="free"):
        design.decide(msa, 0.2, 0.5, free=msa)


def test_an_alias_and_what_it_sets_are_not_both_axes():
    with pytest.raises(pounding.InputError, match="bumpers.gap_m"):
        pounding.StudySpec(
            pounding.presets.paper_damped(),
            {"kind": "simulate", "freq_hz": 1.5, "duration_s": 1.0, "a_g": 0.05},
            {"bumpers.gap_m": [0.01, 0.02], "bumpers.gap_left_m": [0.01]},
        )


def test_the_band_resamples_records_and_covers_where_resampling_runs_does_not():
    """The same records are in every stripe: a record whose capacity is low pounds at every stripe above
    it. Resampling runs within stripes treats them as independent and gives intervals too narrow."""
    levels = (0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0)
    covered_records = covered_runs = 0
    for seed in range(100, 160):
        capacity = 0.5 * np.exp(0.4 * np.random.default_rng(seed).standard_normal(20))
        impacts = (capacity[None, :] <= np.array(levels)[:, None]).astype(float)
        a = synthetic(impacts, np.zeros_like(impacts), levels=levels)
        by_records = a.fragility("contact", n_bootstrap=400, seed=seed)
        by_runs = design.fit_fragility(
            levels, [20] * 7, impacts.sum(axis=1).astype(int), n_bootstrap=400, seed=seed
        )
        assert by_records.median_g == pytest.approx(by_runs.median_g, rel=1e-12)  # (the same estimate)
        lo, hi = by_records.interval()["median_g"]
        covered_records += lo <= 0.5 <= hi
        lo, hi = by_runs.interval()["median_g"]
        covered_runs += lo <= 0.5 <= hi
    assert covered_records / 60 >= 0.78  # (nominal 0.9; measured 0.88)
    assert covered_records > covered_runs  # (measured 0.70 resampling runs)


def test_at_the_chosen_gap_the_option_that_pounds_least_wins_before_the_softest_pounding():
    import xarray as xr

    # two isolator dampings at one gap: damping 300 never pounds at the MCE stripe, damping 200 pounds
    # in one run of ten (softly): both meet a target of 0.2, and the one that does not pound is chosen
    levels, records = [0.1, 0.3], [f"r{i}" for i in range(10)]
    impacts = np.zeros((2, 10, 1, 2))
    impacts[1, 0, 0, 0] = 1.0  # (damping 200, the MCE stripe, one run)
    dims = ("sa_g", "record", "bumpers.gap_m", "isolator.damping_n_s_m")
    ds = xr.Dataset(
        {
            "impacts": (dims, impacts),
            "status": (dims, np.zeros_like(impacts)),
            "done": (dims, np.ones(impacts.shape, dtype=bool)),
            "disp_max_m": (dims, 0.05 + 0.06 * impacts),
            "acc_max_g": (dims, 0.3 + 0.5 * impacts),
            "compression_max_m": (dims, 0.001 * impacts),
            "impact_force_max_n": (dims, 100.0 * impacts),
        },
        coords={"sa_g": levels, "record": records, "bumpers.gap_m": [0.1],
                "isolator.damping_n_s_m": [200.0, 300.0]},
    )
    choice = design.decide(design.StripeAnalysis(ds, 1.0, 0.05, True), 0.1, 0.3, target_probability=0.2)
    assert choice.recommended["isolator.damping_n_s_m"] == 300.0
    assert "it pounds least" not in choice.verdict() and "did not pound rank first" in choice.verdict()
    # and an analysis of another intensity measure is not decided with it
    other = design.StripeAnalysis(ds, 2.0, 0.05, True)
    with pytest.raises(pounding.InputError, match="intensity measure"):
        design.decide({"a": design.StripeAnalysis(ds, 1.0, 0.05, True), "b": other}, 0.1, 0.3)
