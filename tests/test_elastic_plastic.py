"""The elastic-plastic impact law (issue 16): closed-form restitution of a free impact, random
systems against the reference (which restates OpenSees' ImpactMaterial with the force as its
state), the energy ledger, no pull, chained runs, the fit from loops it generated."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from strategies import harmonics, oscillators
from test_reference import _compare

import pounding as pd_
from pounding.engine.kernels import law_forces

SETTINGS = settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
LAW = pd_.ElasticPlastic(2e6, 2e5, 0.002)


def _free_impact(law, v0, mass=500.0):
    """``mass`` at v0 into the right bumper, an isolator of 1e-9 N/m, no table motion."""
    osc = pd_.Oscillator(mass, pd_.Isolator((1e-9,), (), "elastic", 0.0), pd_.Bumpers(0.05, 0.01, law))
    return pd_.simulate(osc, pd_.Harmonic(0.0, 1.0), 0.01 / v0 + 0.3, pd_.State.at_rest(osc, velocity_m_s=v0),
                        sample_rate_hz=0)


def _path_forces(law, d):
    return law_forces(law.LAW_ID, law.params(), d, d)


def test_free_impacts_meet_the_closed_form_restitution():
    v_yield = LAW.yield_velocity_m_s(500.0)
    assert v_yield == pytest.approx(0.002 * np.sqrt(2e6 / 500.0))
    times = []
    for v0 in (0.5 * v_yield, 0.99 * v_yield, 1.5 * v_yield, 4.0 * v_yield, 20.0 * v_yield):
        run = _free_impact(LAW, v0)
        c = run.contacts.iloc[0]
        e = -c["v_out_m_s"] / c["v_in_m_s"]
        assert e == pytest.approx(float(LAW.restitution(500.0, v0)), abs=1e-12)
        # the dissipated energy is the kinetic energy lost, and the ledger closes
        assert c["bumper_dissipation_j"] == pytest.approx(0.5 * 500.0 * (v0**2 - c["v_out_m_s"] ** 2),
                                                          rel=1e-10, abs=1e-12)
        assert abs(run.energy.residual) < 1e-12 * 0.5 * 500.0 * v0**2
        times.append(c["t_end_s"] - c["t_start_s"])
    assert times[0] == pytest.approx(np.pi * np.sqrt(500.0 / 2e6), rel=1e-9)  # elastic: half a period
    assert float(LAW.restitution(500.0, 0.99 * v_yield)) == 1.0
    assert times[1] < times[2] < times[3] < times[4]  # contacts lengthen with the impact velocity
    e = LAW.restitution(500.0, np.array([1.5, 4.0, 100.0, 1000.0]) * v_yield)
    assert 1.0 > e[0] > e[1]  # and restitution falls above the yield velocity, at first;
    assert e[1] < e[2] < e[3] < 1.0  # far above, it comes back towards 1 (the lines are parallel)


def test_a_deep_contact_goes_elastic_yield_elastic_unload():
    run = _free_impact(LAW, 4.0 * LAW.yield_velocity_m_s(500.0))
    c = run.contacts.iloc[0]
    inside = run.events[(run.events["t_s"] > c["t_start_s"]) & (run.events["t_s"] < c["t_end_s"])]
    # onto the yield line, turned, onto the unloading line
    assert list(inside["kind"]) == ["bumper_branch"] * 3
    assert c["max_compression_m"] > LAW.yield_compression


@SETTINGS
@given(osc=oscillators(law="elastic_plastic"), exc=harmonics(), v0=st.floats(-0.8, 0.8))
def test_random_elastic_plastic_systems_match_reference(osc, exc, v0):
    _compare(osc, exc, v0=v0, drawn=True)


def test_turns_on_the_yield_line_match_reference():
    # found by hypothesis: K2 = 0.8 K1, the mass turning on the yield line again and again (the
    # reference's events were differences of forces, whose rounding flipped it between modes)
    osc = pd_.Oscillator(100.0, pd_.Isolator((5000.0,), (), "kinematic", 1.0),
                         pd_.Bumpers(0.015625, 0.015625, pd_.ElasticPlastic(1e5, 8e4, 0.0012374249974633597)))
    run, _ = _compare(osc, pd_.Harmonic(0.25, 1.0), v0=0.5)
    assert len(run.contacts) == 12 and (run.events["kind"] == "bumper_branch").sum() > 12


@SETTINGS
@given(osc=oscillators(law="elastic_plastic"), exc=harmonics(), v0=st.floats(-0.8, 0.8))
def test_elastic_plastic_ledger_closes_and_the_bumper_never_pulls(osc, exc, v0):
    run = pd_.simulate(osc, exc, 3.0, pd_.State.at_rest(osc, velocity_m_s=v0), sample_rate_hz=2000)
    e = run.energy
    flows = max(abs(e.input_work), abs(e.kinetic), e.viscous + abs(e.hysteretic) + e.contact_dissipation)
    assert abs(e.residual) <= 1e-10 * flows
    assert e.contact_dissipation >= -1e-10 * flows
    assert run.bumper_force_left.min() >= 0.0 and run.bumper_force_right.min() >= 0.0
    done = run.contacts.dropna()
    assert (done["bumper_dissipation_j"] >= -1e-9 * max(1.0, float(done["bumper_dissipation_j"].abs().max()
                                                                   if len(done) else 1))).all()


@SETTINGS
@given(osc=oscillators(law="elastic_plastic"), exc=harmonics(), v0=st.floats(-0.8, 0.8),
       cut=st.floats(0.2, 2.8))
def test_a_chained_run_equals_one_run(osc, exc, v0, cut):
    start = pd_.State.at_rest(osc, velocity_m_s=v0)
    whole = pd_.simulate(osc, exc, 3.0, start, sample_rate_hz=0)
    first = pd_.simulate(osc, exc, cut, start, sample_rate_hz=0)
    second = pd_.simulate(osc, exc, 3.0 - cut, first.final_state, sample_rate_hz=0)
    scale = max(abs(whole.displacement_max), abs(whole.displacement_min), 1e-6)
    assert abs(second.final_state.displacement_m - whole.final_state.displacement_m) <= 1e-7 * scale


def test_mirror_symmetry():
    osc = pd_.Oscillator(500.0, pd_.Isolator((2e4, 5e3), (0.01,), "kinematic", 300.0),
                         pd_.Bumpers(0.012, 0.012, LAW))
    a = pd_.simulate(osc, pd_.Harmonic(0.2, 1.8), 4.0, sample_rate_hz=500)
    b = pd_.simulate(osc, pd_.Harmonic(-0.2, 1.8), 4.0, sample_rate_hz=500)
    assert len(a.contacts) > 4
    np.testing.assert_allclose(a.displacement, -b.displacement, rtol=0, atol=1e-12)


def test_path_forces_stay_between_the_lines_and_unload_with_k1():
    d = np.concatenate([np.linspace(0.0, 0.01, 200), np.linspace(0.01, 0.006, 100),
                        np.linspace(0.006, 0.012, 150)])
    f = _path_forces(LAW, d)
    k1, k2, dy = LAW.stiffness, LAW.post_yield_stiffness, LAW.yield_compression
    assert np.all(f >= k2 * d - 1e-9) and np.all(f <= k1 * dy + k2 * (d - dy) + 1e-9)
    np.testing.assert_allclose(f[:20], k1 * d[:20])  # elastic at first
    np.testing.assert_allclose(np.diff(f[200:230]) / np.diff(d[200:230]), k1)  # unloading with K1


@pytest.mark.parametrize("truth", [pd_.ElasticPlastic(3e6, 4e5, 0.004), pd_.ElasticPlastic(1.5e6, 1e4,
                                                                                           0.0015)])
def test_fit_contact_law_recovers_an_elastic_plastic_law_and_ranks_it_first(truth):
    # the paper's Fig. 3 test: +-10 mm around 10 mm of precompression, at 1 Hz, growing in
    t = np.linspace(0.0, 6.0, 3000)
    d = 0.010 + 0.010 * np.sin(2.0 * np.pi * t) * np.minimum(1.0, t / 2.0)
    f = _path_forces(truth, d)
    fit = pd_.fit_contact_law(d, f, time_s=t, law="elastic_plastic").law
    for name in ("stiffness", "post_yield_stiffness", "yield_compression"):
        assert getattr(fit, name) == pytest.approx(getattr(truth, name), rel=0.02)
    ranked = pd_.rank_contact_laws(d, f, time_s=t)
    assert ranked["law"].iloc[0] == "elastic_plastic"
    # rate-independent: it needs no times or rates
    alone = pd_.fit_contact_law(d, f, law="elastic_plastic").law
    assert alone.stiffness == pytest.approx(truth.stiffness, rel=0.02)


def test_a_force_no_elastic_plastic_law_gives_is_named_and_a_ranking_of_no_law_too():
    d = np.linspace(0.001, 0.01, 40)
    with pytest.raises(pd_.InputError, match="force_n") as exc:
        pd_.fit_contact_law(d, -1e6 * d, law="elastic_plastic")
    assert exc.value.problem is pd_.Problem.NO_FIT
    # forces that no law describes (all negative): named, not a ranking of stiffnesses of 2.2e-308
    with pytest.raises(pd_.InputError, match="none of the contact laws") as exc:
        pd_.rank_contact_laws(d, -1e6 * d, velocity_m_s=np.ones_like(d))
    assert exc.value.problem is pd_.Problem.NO_FIT and exc.value.field == "force_n"


def test_a_nearly_flat_unloading_line_releases_at_zero_compression():
    # K2 = 1e-12 K1: the release's rounding is the branch's (K2 x), not K1's; with K1's the
    # contact ended 1 mm deep, where a sub-interval happened to end, and the ledger missed 0.97 J
    osc = pd_.Oscillator(500.0, pd_.Isolator((2e4, 5e3), (0.01,), "kinematic", 300.0),
                         pd_.Bumpers(0.01, 0.01, pd_.ElasticPlastic(2e6, 1e-6, 0.002)))
    ends = []
    for t_end in (0.6, 0.65):
        run = pd_.simulate(osc, pd_.Harmonic(0.3, 1.8), t_end, sample_rate_hz=0)
        c = run.contacts.dropna().iloc[-1]
        ends.append(c["t_end_s"])
        assert abs(run.energy.residual) < 1e-10 * run.energy.contact_dissipation
    assert ends[0] == pytest.approx(ends[1], abs=1e-12)


def test_bad_parameters_are_named():
    with pytest.raises(pd_.InputError, match="law.post_yield_stiffness"):
        pd_.ElasticPlastic(1e6, 2e6, 0.002)
    with pytest.raises(pd_.InputError, match="law.yield_compression"):
        pd_.ElasticPlastic(1e6, 1e5, 0.0)
    with pytest.raises(pd_.InputError, match="law.stiffness"):
        pd_.ElasticPlastic(float("nan"), 1e5, 0.002)
    with pytest.raises(pd_.InputError, match="mass_kg"):
        LAW.restitution(-1.0, 0.3)
    for bad in (float("nan"), -0.1, "fast", [0.2, float("inf")]):
        with pytest.raises(pd_.InputError, match="velocity_m_s"):
            LAW.restitution(500.0, bad)


def test_toml_round_trip(tmp_path):
    osc = pd_.Oscillator(500.0, pd_.Isolator((2e4,), ()), pd_.Bumpers(0.015, 0.015, LAW))
    path = tmp_path / "ep.toml"
    osc.to_toml(path)
    assert pd_.Oscillator.from_toml(path) == osc


def test_model_family_builds_and_reads_elastic_plastic_systems():
    family = pd_.ModelFamily(500.0, branches=1, law="elastic_plastic", fixed={"gap": 0.015})
    values = {"slope_1": 3e4, "isolator_damping": 500.0, "bumper_stiffness": 2e7,
              "bumper_post_yield_ratio": 0.05, "bumper_yield_compression": 0.001}
    osc = family.oscillator(values)
    assert osc.bumpers.law == pd_.ElasticPlastic(2e7, 1e6, 0.001)
    back = family.values_of(osc)
    assert back == pytest.approx({**values, "gap": 0.015})
    with pytest.raises(pd_.InputError, match="bumper_post_yield_ratio"):
        family.oscillator({**values, "bumper_post_yield_ratio": 1.0})


def test_model_family_builds_and_reads_multilinear_systems(tmp_path):
    family = pd_.ModelFamily(500.0, branches=1, law="multilinear", fixed={"gap": 0.015}, bumper_branches=3)
    assert family.law_parameters == ("bumper_slope_1", "bumper_slope_2", "bumper_slope_3",
                                     "bumper_breakpoint_1", "bumper_breakpoint_2", "bumper_damping")
    values = {"slope_1": 3e4, "isolator_damping": 500.0, "bumper_slope_1": 1.5e6, "bumper_slope_2": 1e5,
              "bumper_slope_3": 5e6, "bumper_breakpoint_1": 0.001, "bumper_breakpoint_2": 0.004,
              "bumper_damping": 500.0}
    osc = family.oscillator(values)
    assert osc.bumpers.law == pd_.MultilinearBumper((1.5e6, 1e5, 5e6), (0.001, 0.004), 500.0)
    assert family.values_of(osc) == pytest.approx({**values, "gap": 0.015})
    with pytest.raises(pd_.InputError, match="family.bumper_branches"):
        pd_.ModelFamily(500.0, law="multilinear", bumper_branches=5)
    path = tmp_path / "family.toml"
    path.write_text('mass = 500.0\nbranches = 1\nlaw = "multilinear"\nbumper_branches = 2\n'
                    "[fixed]\ngap = 0.015\n[bounds]\nslope_1 = [1e4, 5e4]\n"
                    "isolator_damping = [100.0, 1000.0]\nbumper_slope_1 = [1e5, 1e7]\n"
                    "bumper_slope_2 = [1e5, 1e7]\nbumper_breakpoint_1 = [0.001, 0.01]\n"
                    "bumper_damping = [0.0, 1e4]\n")
    read, bounds = pd_.ModelFamily.from_toml(path)
    assert read.bumper_branches == 2 and set(bounds) >= {"bumper_slope_2", "bumper_breakpoint_1"}


def test_the_example_file_reads_and_sweeps():
    from pathlib import Path

    osc = pd_.Oscillator.from_toml(Path(__file__).parents[1] / "examples" / "elastic_plastic_ybs.toml")
    assert osc.bumpers.law == pd_.ElasticPlastic(2e7, 1e6, 0.002)
    assert osc.bumpers.law.yield_velocity_m_s(osc.mass_kg) == pytest.approx(0.4)
    res = pd_.sweep(osc, 0.1, freqs_hz=[1.5, 2.5], steady="fixed", cycles=8, measure_cycles=2)
    assert res.to_dataframe()["contact"].all()
