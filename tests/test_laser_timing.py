"""Contacts timed by the laser (``MeasurementChain(contact_timing="laser")``): each contact from the
displacement's gap crossing in to its crossing out, the velocities from the laser alone, against the
exact motion of the same steady windows."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pounding
from pounding import MeasurementChain

DENSE_HZ = 100_000.0  # the exact motion sampled this finely to locate its own gap crossings


def window_motion(sw, i):
    """The exact motion of step ``i``'s window (its measured cycles), sampled at :data:`DENSE_HZ`."""
    f = float(sw.freqs_hz[i])
    state = pounding.State(sw.window_states[i])
    exc = pounding.Harmonic(sw.a_g, f, phase=-(2.0 * math.pi * f * state.time_s))
    return pounding.simulate(sw.system, exc, sw.measure_cycles / f, state, sample_rate_hz=DENSE_HZ)


def gap_crossings(run):
    """The exact motion's gap crossings, per contact: (time in, time out, speed in, speed out), by linear
    interpolation between the dense samples (1e-5 s apart: exact to well below a microsecond)."""
    keep = np.append(np.diff(run.t) > 0.0, True)  # (an event's row repeats its time)
    t, d, v = run.t[keep], run.displacement[keep], run.velocity[keep]
    bumpers = run.oscillator.bumpers
    out = []
    for sign, gap in ((1.0, bumpers.gap_right_m), (-1.0, bumpers.gap_left_m)):
        y = sign * d - gap
        edges = np.diff((y > 0.0).astype(np.int8))
        ins, outs = np.flatnonzero(edges == 1) + 1, np.flatnonzero(edges == -1) + 1
        for a in ins:
            later = outs[outs > a]
            if later.size == 0:
                continue
            b = int(later[0])
            t0 = np.interp(0.0, y[a - 1:a + 1], t[a - 1:a + 1])
            t1 = np.interp(0.0, -y[b - 1:b + 1], t[b - 1:b + 1])
            out.append((t0, t1, abs(np.interp(t0, t, v)), abs(np.interp(t1, t, v))))
    return np.array(sorted(out))


def means(impacts, f):
    """The measured contacts of the step at ``f``: mean contact time and speeds."""
    m = impacts[impacts["freq_hz"] == f]
    return m["contact_time_s"].mean(), m["v_in_m_s"].abs().mean(), m["v_out_m_s"].abs().mean(), len(m)


DAMPED = dict(a_g=0.1, freqs=[1.5, 2.0, 2.5])
CALIBRATED = dict(a_g=0.05, freqs=[1.5, 1.8, 2.0, 2.2])  # (2.2 Hz: the resonance step, reached from below)


def swept(system, case, chain):
    return pounding.sweep(system, case["a_g"], case["freqs"], measurement=chain, steady="fixed", cycles=40)


def test_an_ideal_laser_times_the_damped_systems_contacts_as_the_exact_metrics():
    # the damped paper system's Kelvin-Voigt bumpers have no set: a contact starts and ends at the gap,
    # so the laser's gap crossings are the exact contact instants
    sw = swept(pounding.presets.paper_damped(), DAMPED, MeasurementChain(contact_timing="laser"))
    exact = sw.exact_dataframe()
    for i, f in enumerate(sw.freqs_hz):
        contacts = window_motion(sw, i).contacts
        ct, v_in, v_out, n = means(sw.measured_impacts, f)
        assert n == len(contacts) == 2 * sw.measure_cycles
        # measured: 3 microseconds apart (the crossings interpolated linearly between the 1 ms samples)
        assert ct == pytest.approx(exact.loc[i, "contact_time_s"], abs=1e-5)
        # the speeds from the laser alone (a cubic over 40 ms of flight): measured within 2.2e-3 here,
        # 6e-3 with a 0.01 mm quantum on the laser (a cubic over 20 ms: 2.4e-4 and 2.3e-2)
        assert v_in == pytest.approx(contacts["v_in_m_s"].abs().mean(), rel=4e-3)
        assert v_out == pytest.approx(contacts["v_out_m_s"].abs().mean(), rel=4e-3)
        assert sw.to_dataframe().loc[i, "restitution"] == pytest.approx(exact.loc[i, "restitution"], abs=4e-3)


def test_the_calibrated_bumpers_set_makes_the_gap_crossings_longer_than_the_contacts():
    # the calibrated preset's hysteretic bumper keeps a set: the mass crosses the gap before it touches
    # and leaves before it crosses back. The laser times the crossings, exactly, and they are longer
    # than the exact contacts: at the resonance step, 32.2 ms against 20.2 ms
    sw = swept(pounding.presets.paper_calibrated(), CALIBRATED, MeasurementChain(contact_timing="laser"))
    exact = sw.exact_dataframe()
    i = sw.step_index(2.2)
    crossings = gap_crossings(window_motion(sw, i))
    ct, v_in, v_out, n = means(sw.measured_impacts, 2.2)
    assert n == len(crossings) == 2 * sw.measure_cycles
    assert ct == pytest.approx(np.mean(crossings[:, 1] - crossings[:, 0]), abs=1e-5)
    assert v_in == pytest.approx(crossings[:, 2].mean(), rel=4e-3)
    assert v_out == pytest.approx(crossings[:, 3].mean(), rel=4e-3)
    exact_ct = exact.loc[i, "contact_time_s"]
    assert 0.019 < exact_ct < 0.021 and 0.010 < ct - exact_ct < 0.014


def test_a_15_hz_filter_on_the_accelerometers_lowers_alpha_and_leaves_the_laser_timing():
    # the hypothesis: the accelerometers through a 15 Hz zero-phase low-pass (the YBs alphas come down
    # to the paper's), the laser as read; timed by the laser, the contacts keep the ideal laser's times
    # (the force pulse's flanks in the filtered accelerations stretch them to about 50 ms)
    filtered = MeasurementChain.lowpass(15.0, contact_timing="laser")
    ideal = MeasurementChain(contact_timing="laser")
    for system, case, f in ((pounding.presets.paper_damped(), DAMPED, 2.0),
                            (pounding.presets.paper_calibrated(), CALIBRATED, 2.2)):
        sw = swept(system, case, filtered)
        i = sw.step_index(f)
        seen, exact = sw.to_dataframe().loc[i], sw.exact_dataframe().loc[i]
        as_read = swept(system, case, ideal).to_dataframe().loc[i]
        assert seen["contact_time_s"] == pytest.approx(as_read["contact_time_s"], abs=1e-5)
        assert seen["restitution"] == pytest.approx(as_read["restitution"], abs=2e-3)
        # alpha is the filtered one: the pulse-timed chain's, whatever the timing (one alpha)
        pulse = swept(system, case, MeasurementChain.lowpass(15.0)).to_dataframe().loc[i]
        assert seen["alpha"] == pulse["alpha"] and seen["alpha"] < 0.9 * exact["alpha"]
        if system.bumpers.law != pounding.presets.paper_damped().bumpers.law:
            # the calibrated preset: 17.0 as the paper's 16.8, and the contact 32 ms, not the pulse's 50
            assert seen["alpha"] == pytest.approx(17.0, abs=0.2) and exact["alpha"] > 40.0
            assert seen["contact_time_s"] < 0.034 < 0.045 < pulse["contact_time_s"]
        else:  # no set: the exact contact time, through the filter
            assert seen["contact_time_s"] == pytest.approx(exact["contact_time_s"], abs=1e-5)


def test_the_timing_is_the_chains_named_and_checked():
    chain = MeasurementChain.lowpass(15.0, contact_timing="laser")
    assert chain.contact_timing == "laser" and MeasurementChain().contact_timing == "pulse"
    assert chain.describe().endswith("contacts timed by the laser's gap crossings")
    assert "laser" not in MeasurementChain.lowpass(15.0).describe()  # (the pulse's words as they were)
    assert chain.with_cutoff(20.0).contact_timing == "laser"
    for make in (lambda: MeasurementChain(contact_timing="displacement"),
                 lambda: MeasurementChain.lowpass(15.0, contact_timing=None)):
        with pytest.raises(pounding.InputError, match="contact_timing") as err:
            make()
        assert err.value.field == "contact_timing" and "'pulse', 'laser'" in str(err.value)
