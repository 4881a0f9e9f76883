"""fit_contact_law: recovers the laws that generated a cyclic test, and refuses bad input."""

from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest

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
