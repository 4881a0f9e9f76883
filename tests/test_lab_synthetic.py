"""The virtual shaking-table test (issue 17): pounding.lab.synthetic_test against the simulator."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import signal

import pounding as pd_
from pounding.lab import synthetic_test

OSC = pd_.presets.paper_damped()
FREQS = [1.0, 2.0, 2.2]
A_G = 0.05


def test_ideal_sensors_record_the_simulators_motion_and_its_schedule():
    rec = synthetic_test(OSC, A_G, FREQS, cycles=10, noise=0.0, gains=(1.0,))
    assert rec.sample_rate_hz == pytest.approx(1000.0) and rec.source == "synthetic"
    np.testing.assert_allclose(rec.meta["step_start_s"], [0.0, 10.0, 15.0])
    # the first step is the engine's run from rest, sample for sample
    run = pd_.simulate(OSC, pd_.Harmonic(A_G, 1.0), 10.0, pd_.State.at_rest(OSC), sample_rate_hz=1000.0)
    uniform = run.to_dataframe()["event"].to_numpy() == ""  # (not the rows taken at events)
    n = 10_000
    np.testing.assert_allclose(rec.mass_acc_m_s2[:n, 0], run.abs_acceleration[uniform][:n], rtol=0,
                               atol=1e-12)
    np.testing.assert_allclose(rec.displacement_m[:n], run.displacement[uniform][:n], rtol=0, atol=1e-15)
    np.testing.assert_allclose(rec.table_acc_m_s2[:n], A_G * 9.81 * np.sin(2 * math.pi * rec.time_s[:n]),
                               rtol=0, atol=1e-12)
    # each step's peak over its last two cycles is the sweep's alpha (the same schedule), to sampling
    sw = pd_.sweep(OSC, A_G, FREQS, "up", steady="fixed", cycles=10, measure_cycles=2)
    for k, f in enumerate(FREQS):
        end = rec.meta["step_start_s"][k] + 10 / f
        w = (rec.time_s >= end - 2 / f) & (rec.time_s < end)
        peak = np.abs(rec.mass_acc_m_s2[w, 0]).max() / (A_G * 9.81)
        assert peak == pytest.approx(sw.to_dataframe()["alpha"][k], rel=1e-3)


def test_gains_offsets_noise_and_the_lasers_resolution():
    clean = synthetic_test(OSC, A_G, FREQS[:1], cycles=5, noise=0.0, gains=(1.0,))
    rec = synthetic_test(OSC, A_G, FREQS[:1], cycles=5, noise=0.0, gains=(1.02, 0.97),
                         offsets_m_s2=(0.05, -0.02), laser_resolution_m=1e-5)
    exact = clean.mass_acc_m_s2[:, 0]
    np.testing.assert_allclose(rec.mass_acc_m_s2, np.column_stack([1.02 * exact + 0.05, 0.97 * exact - 0.02]),
                               atol=1e-12)
    q = rec.displacement_m / 1e-5
    np.testing.assert_allclose(q, np.round(q), atol=1e-6)
    assert np.abs(rec.displacement_m - clean.displacement_m).max() <= 0.5e-5 + 1e-12
    noisy = synthetic_test(OSC, A_G, FREQS[:1], cycles=5, noise=0.01, gains=(1.0,), seed=3)
    err = noisy.mass_acc_m_s2[:, 0] - exact
    assert err.std() == pytest.approx(0.01 * np.abs(exact[3 * exact.size // 4:]).max(), rel=0.05)  # (settled)
    again = synthetic_test(OSC, A_G, FREQS[:1], cycles=5, noise=0.01, gains=(1.0,), seed=3)
    assert np.array_equal(again.mass_acc_m_s2, noisy.mass_acc_m_s2)
    assert not np.array_equal(synthetic_test(OSC, A_G, FREQS[:1], cycles=5, noise=0.01, gains=(1.0,),
                                             seed=4).mass_acc_m_s2, noisy.mass_acc_m_s2)


def test_the_anti_alias_filter_is_a_butterworth_low_pass():
    # the table's sine through the filter: the filter's gain at its frequency once settled
    f, fc = 2.0, 3.0
    rec = synthetic_test(OSC.without_bumpers(), A_G, [f], cycles=20, noise=0.0, gains=(1.0,),
                         anti_alias_hz=fc)
    late = rec.time_s > 5.0
    sos = signal.butter(4, fc, fs=10_000.0, output="sos")
    gain = abs(signal.sosfreqz(sos, worN=[f], fs=10_000.0)[1][0])
    assert np.abs(rec.table_acc_m_s2[late]).max() / (A_G * 9.81) == pytest.approx(gain, rel=1e-3)
    assert gain < 0.995  # (a test that sees the filter)


@pytest.mark.parametrize("kwargs, field", [
    ({"a_g": -0.05}, "a_g"), ({"a_g": 2000.0}, "a_g"), ({"freqs_hz": []}, "freqs_hz"),
    ({"freqs_hz": [1.0, -2.0]}, "freqs_hz[1]"), ({"cycles": 0}, "cycles"),
    ({"sample_rate_hz": 0.0}, "sample_rate_hz"),
    ({"noise": -0.01}, "noise"), ({"gains": ()}, "gains"), ({"gains": (1.0, -1.0)}, "gains[1]"),
    ({"offsets_m_s2": (0.0, 0.0)}, "offsets_m_s2"), ({"anti_alias_hz": 6000.0}, "anti_alias_hz"),
    ({"laser_resolution_m": -1e-5}, "laser_resolution_m"), ({"system": "paper"}, "system"),
    ({"state": 3}, "state"), ({"oversample": 0}, "oversample"),
])
def test_bad_arguments_are_named(kwargs, field):
    args = {"system": OSC, "a_g": A_G, "freqs_hz": FREQS, "cycles": 2, "gains": (1.0,), **kwargs}
    with pytest.raises(pd_.InputError) as info:
        synthetic_test(**args)
    assert info.value.field == field
