"""The measurement chain: its filters' gains against the closed form, the shorthands of a synthetic
test against the chain they state, and bad chains named."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pounding
from pounding import MeasurementChain, Sensor


@settings(max_examples=25, deadline=None)
@given(
    cutoff=st.floats(5.0, 100.0),
    ratio=st.floats(0.2, 3.0),
    order=st.integers(1, 6),
    zero_phase=st.booleans(),
)
def test_a_sine_through_the_chain_keeps_the_butterworth_gain(cutoff, ratio, order, zero_phase):
    chain = MeasurementChain.lowpass(cutoff, order=order, zero_phase=zero_phase)
    f = ratio * cutoff
    t = np.arange(0.0, 40.0 / f + 4.0, 1.0 / chain.internal_rate_hz)
    x = np.sin(2.0 * math.pi * f * t)
    ts, tab, acc, d = chain.measure(t, x, 2.0 * x, x)
    # (away from both ends: the filters' start and, zero-phase, their end)
    mid = (ts > ts[0] + chain.settle_s + 1.0 / f) & (ts < ts[-1] - chain.settle_s - 1.0 / f)
    rate = chain.sample_rate_hz if zero_phase else chain.internal_rate_hz
    warped = math.tan(math.pi * f / rate) / math.tan(math.pi * cutoff / rate)  # (the bilinear transform's)
    expected = 1.0 / math.sqrt(1.0 + warped ** (2 * order))
    expected = expected**2 if zero_phase else expected
    assert chain.gain(f) == pytest.approx(expected, rel=1e-12)
    assert chain.mass.gain(f) == pytest.approx(
        (1.0 + ratio ** (2 * order)) ** (-1.0 if zero_phase else -0.5), rel=1e-12
    )
    fit = np.linalg.lstsq(
        np.column_stack([np.sin(2 * math.pi * f * ts[mid]), np.cos(2 * math.pi * f * ts[mid])]),
        acc[mid],
        rcond=None,
    )[0]
    assert math.hypot(*fit) == pytest.approx(2.0 * expected, rel=2e-3, abs=1e-6)
    assert np.array_equal(d, x[:: chain.oversample])  # (the laser as read)
    if zero_phase:  # no lag: the sine's phase kept
        assert abs(math.atan2(fit[1], fit[0])) < 2e-3 + 1e-4 / max(expected, 1e-3)


def test_the_default_chain_is_ideal_sampling_and_apply_reads_a_run():
    chain = MeasurementChain()
    assert chain.describe() == "sampled at 1000 Hz, no filter (ideal sampling)"
    run = pounding.simulate(
        pounding.presets.paper_damped(),
        pounding.Harmonic(0.05, 1.5),
        2.0,
        sample_rate_hz=chain.internal_rate_hz,
    )
    rec = chain.apply(run)
    uniform = run.to_dataframe()["event"].to_numpy() == ""
    assert np.allclose(rec["mass_acc_m_s2"], run.abs_acceleration[uniform][::10], rtol=0, atol=1e-9)
    assert np.allclose(rec["displacement_m"], run.displacement[uniform][::10], rtol=0, atol=1e-12)
    assert np.allclose(
        rec["table_acc_m_s2"], run.excitation.acceleration(rec["time_s"].to_numpy()), atol=1e-12
    )


def test_a_synthetic_tests_shorthands_are_the_chain_they_state():
    system = pounding.presets.paper_damped()
    kw = dict(cycles=6, noise=0.0)
    a = pounding.lab.synthetic_test(
        system, 0.05, [1.2, 1.5], anti_alias_hz=100.0, laser_resolution_m=1e-5, **kw
    )
    sensor = Sensor(100.0)
    chain = MeasurementChain(1000.0, sensor, sensor, Sensor(100.0, resolution=1e-5))
    b = pounding.lab.synthetic_test(system, 0.05, [1.2, 1.5], measurement=chain, **kw)
    assert np.array_equal(a.mass_acc_m_s2, b.mass_acc_m_s2) and np.array_equal(
        a.displacement_m, b.displacement_m
    )
    # a zero-phase filter runs on the record as read: equal to filtering the unfiltered test's samples
    post = MeasurementChain.lowpass(15.0)
    c = pounding.lab.synthetic_test(system, 0.05, [1.2, 1.5], measurement=post, **kw)
    raw = pounding.lab.synthetic_test(system, 0.05, [1.2, 1.5], **kw)
    from scipy import signal

    sos = signal.butter(4, 15.0, fs=1000.0, output="sos")
    assert np.allclose(c.mass_acc_m_s2[:, 0], signal.sosfiltfilt(sos, raw.mass_acc_m_s2[:, 0]), atol=1e-12)
    assert np.array_equal(c.displacement_m, raw.displacement_m)
    with pytest.raises(pounding.InputError, match="anti_alias_hz"):
        pounding.lab.synthetic_test(system, 0.05, [1.5], measurement=post, anti_alias_hz=100.0)


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda: Sensor(lowpass_hz=-1.0), "lowpass_hz"),
        (lambda: Sensor(lowpass_hz=10.0, order=0), "order"),
        (lambda: Sensor(resolution=-1e-3), "resolution"),
        (lambda: Sensor(zero_phase="yes"), "zero_phase"),
        (lambda: MeasurementChain(sample_rate_hz=0.0), "sample_rate_hz"),
        (lambda: MeasurementChain.lowpass(600.0), "table.lowpass_hz"),
        (lambda: MeasurementChain(mass="15 Hz"), "mass"),
        (lambda: MeasurementChain(oversample=0), "oversample"),
        (lambda: MeasurementChain.lowpass(15.0, laser="no"), "laser"),
        (lambda: MeasurementChain().measure([0.0, 0.001], [0.0], [0.0, 0.0], [0.0, 0.0]), "table"),
        (lambda: MeasurementChain.lowpass(15.0).measure(*[np.zeros(20)] * 4), "samples"),
    ],
)
def test_a_bad_chain_is_named(make, field):
    with pytest.raises(pounding.InputError) as err:
        make()
    assert err.value.field == field


def test_a_causal_filter_may_run_above_the_records_nyquist_rate():
    chain = MeasurementChain.lowpass(600.0, zero_phase=False)  # (before sampling, at 10 kHz)
    assert chain.gain(600.0) == pytest.approx(math.sqrt(0.5))
    assert "causal Butterworth low-pass, 4 poles at 600 Hz" in chain.describe()
