"""fit_contact_law: recovers the laws that generated a cyclic test, and refuses bad input."""

from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pounding as pd_

matplotlib.use("Agg")


def mts_test(freq_hz=1.0, cycles=3, n=2000):
    """The paper's MTS protocol (Sect. 2.2): 10 mm preload, +-10 mm, harmonic."""
    t = np.linspace(0.0, cycles / freq_hz, n)
    w = 2 * math.pi * freq_hz
    d = 0.010 + 0.010 * np.sin(w * t)
    v = 0.010 * w * np.cos(w * t)
    return t, d, v


def test_kelvin_voigt_is_recovered_exactly():
    t, d, v = mts_test()
    law = pd_.KelvinVoigt(1.46e6, 800.0)
    force = law.stiffness * d + law.damping * v
    fit = pd_.fit_contact_law(d, force, velocity_m_s=v)
    assert fit.law.stiffness == pytest.approx(law.stiffness, rel=1e-10)
    assert fit.law.damping == pytest.approx(law.damping, rel=1e-8)
    assert fit.r_squared == pytest.approx(1.0, abs=1e-12)


def test_hunt_crossley_is_recovered_from_times():
    t, d, v = mts_test(freq_hz=2.0)
    law = pd_.HuntCrossley(2.0e8, 1.5, 5.0e5)
    force = d**law.exponent * (law.stiffness + law.damping * v)
    fit = pd_.fit_contact_law(d, force, time_s=t, law="hunt_crossley")
    # the rate comes from a second-order numerical derivative of 2000 samples
    assert fit.law.exponent == pytest.approx(1.5, rel=1e-4)
    assert fit.law.stiffness == pytest.approx(2.0e8, rel=1e-3)
    assert fit.law.damping == pytest.approx(5.0e5, rel=1e-3)


def test_noisy_test_within_two_percent():
    # force noise 0.2 % of the force's spread: the damping's standard error is then about
    # 0.5 % (sigma / sqrt(sum v^2)), so 2 % is four standard errors
    rng = np.random.default_rng(7)
    t, d, v = mts_test()
    force = 1.46e6 * d + 2000.0 * v
    sigma = 0.002 * force.std()
    noisy = force + sigma * rng.standard_normal(force.size)
    fit = pd_.fit_contact_law(d, noisy, time_s=t)
    assert fit.law.stiffness == pytest.approx(1.46e6, rel=0.02)
    assert fit.law.damping == pytest.approx(2000.0, rel=0.02)
    assert fit.rms_n == pytest.approx(sigma, rel=0.1)


def test_only_samples_in_compression_are_fitted():
    t, d, v = mts_test()
    d = d - 0.012  # part of each cycle out of contact
    force = np.where(d > 0.0, 1.0e6 * d + 100.0 * v, 0.0)
    fit = pd_.fit_contact_law(d, force, velocity_m_s=v)
    assert fit.compression_m.min() > 0.0
    assert fit.law.stiffness == pytest.approx(1.0e6, rel=1e-10)
    df = fit.to_dataframe()
    assert np.abs(df["residual_n"]).max() < 1e-6
    assert np.allclose(fit.predict(df["compression_m"], df["velocity_m_s"]), df["model_force_n"])


def test_plot_returns_artists():
    t, d, v = mts_test()
    fit = pd_.fit_contact_law(d, 1.0e6 * d + 100.0 * v, velocity_m_s=v)
    artists = pd_.plots.plot_contact_law_fit(fit)
    assert len(artists) == 2


@pytest.mark.parametrize("kwargs, field", [
    (dict(force_n=np.ones(5)), "force_n"),
    (dict(velocity_m_s=None, time_s=None), "time_s"),
    (dict(law="maxwell"), "law"),
    (dict(time_s=np.zeros(2000), velocity_m_s=None), "time_s[0:2]"),
    (dict(law="hunt_crossley", exponent_bounds=(0.5, 2.0)), "exponent_bounds[0]"),
])
def test_bad_input_names_the_field(kwargs, field):
    t, d, v = mts_test()
    args = dict(displacement_m=d, force_n=1e6 * d, velocity_m_s=v)
    args.update(kwargs)
    with pytest.raises(pd_.InputError) as err:
        pd_.fit_contact_law(**args)
    assert err.value.field == field


def test_nan_and_no_contact_are_refused():
    t, d, v = mts_test()
    f = 1e6 * d
    f[10] = np.nan
    with pytest.raises(pd_.InputError, match=r"force_n\[10\]"):
        pd_.fit_contact_law(d, f, velocity_m_s=v)
    with pytest.raises(pd_.InputError, match="compression"):
        pd_.fit_contact_law(-d, 1e6 * d, velocity_m_s=v)


def _family_system_by_hand(family, p):
    """The system of a ModelFamily for the numbers ``p``, built law by law with the constructors (the way
    the family built it before its numbers were paths): the reference its paths must reproduce."""
    n, k = family.branches, family.bumper_branches
    bw = pd_.BoucWen(p["bw_stiffness"], p["bw_yield_displacement"], n=p["bw_n"]) if family.bouc_wen else None
    iso = pd_.Isolator(tuple(p[f"slope_{i + 1}"] for i in range(n)),
                       tuple(p[f"breakpoint_{i + 1}"] for i in range(n - 1)), family.hysteresis,
                       p["isolator_damping"], bw)
    if family.law == "kelvin_voigt":
        law = pd_.KelvinVoigt(p["bumper_stiffness"], p["bumper_damping"])
    elif family.law.startswith("multilinear"):
        law = pd_.MultilinearBumper(tuple(p[f"bumper_slope_{i + 1}"] for i in range(k)),
                                    tuple(p[f"bumper_breakpoint_{i + 1}"] for i in range(k - 1)),
                                    p["bumper_damping"],
                                    "kinematic" if family.law == "multilinear_kinematic" else "elastic")
    elif family.law == "elastic_plastic":
        law = pd_.ElasticPlastic(p["bumper_stiffness"], p["bumper_post_yield_ratio"] * p["bumper_stiffness"],
                                 p["bumper_yield_compression"])
    else:
        law = pd_.HuntCrossley(p["bumper_stiffness"], p["bumper_exponent"], p["bumper_damping"])
    return pd_.Oscillator(family.mass, iso, pd_.Bumpers(p["gap"], p["gap"], law))


def _a_number(name, rng):
    """A plausible value of a ModelFamily's number (softening backbones, increasing breakpoints)."""
    kind, _, index = name.rpartition("_")
    if index.isdigit():
        i = int(index)
        return {"slope": rng.uniform(3e4, 5e4) / i, "breakpoint": 0.005 * i * rng.uniform(0.9, 1.1),
                "bumper_slope": rng.uniform(5e5, 1e6) / i,
                "bumper_breakpoint": 0.003 * i * rng.uniform(0.9, 1.1)}[kind]
    ranges = {"bumper_post_yield_ratio": (0.05, 0.9), "bumper_yield_compression": (1e-3, 5e-3),
              "bumper_exponent": (1.0, 2.0), "bw_n": (1.0, 3.0), "bw_yield_displacement": (0.002, 0.01),
              "gap": (0.005, 0.02)}
    return float(rng.uniform(*ranges.get(name, (100.0, 2000.0))))


@settings(max_examples=60, deadline=None)
@given(law=st.sampled_from(["kelvin_voigt", "hunt_crossley", "elastic_plastic", "multilinear",
                            "multilinear_kinematic"]),
       branches=st.integers(1, 3), bumper_branches=st.integers(1, 3), bouc_wen=st.booleans(),
       seed=st.integers(0, 2**32 - 1))
def test_a_model_familys_paths_build_the_system_its_numbers_name(law, branches, bumper_branches, bouc_wen,
                                                                 seed):
    family = pd_.ModelFamily(500.0, branches=branches, law=law, bumper_branches=bumper_branches,
                             bouc_wen=bouc_wen)
    rng = np.random.default_rng(seed)
    p = {name: _a_number(name, rng) for name in family.parameter_names}
    built = family.oscillator(p)
    assert built == _family_system_by_hand(family, p)
    back = family.values_of(built)
    assert list(back) == list(family.parameter_names)
    assert all(back[name] == p[name] for name in back if name != "bumper_post_yield_ratio")
    if law == "elastic_plastic":
        assert back["bumper_post_yield_ratio"] == pytest.approx(p["bumper_post_yield_ratio"], rel=1e-15)
    assert set(family.paths) == set(family.parameter_names) - {"bumper_post_yield_ratio"}
