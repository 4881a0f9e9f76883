"""Bifurcation diagrams of structures of several masses: every level's stroboscopic samples.

- A one-level structure's diagram is the oscillator's, sample for sample (to 1e-12 of each quantity's
  largest: the oscillator's samples are its step's cycle ends, the structure's its window's samples at the
  same instants, which round differently: 4e-14 m/s measured).
- On a periodic response every sample of every level is the periodic orbit's state at table phase 0.
- A chaotic impacting response is not periodic and has a positive largest exponent.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
import pytest

import pounding as pd_


def _building(gap: float = 0.02) -> pd_.Structure:
    iso = pd_.Isolator(slopes_n_m=[2e5, 5e4], breakpoints_m=[0.005], damping_n_s_m=4e3)
    return pd_.Structure(2.0e3, iso, [pd_.Storey(1.0e3, 2.0e6, 2.0e3)],
                         [pd_.Wall(0, gap, gap, pd_.KelvinVoigt(1.0e8, 2.0e4))])


def test_one_level_is_the_oscillators_diagram():
    osc = pd_.presets.paper_damped()
    freqs = [1.6, 1.8, 2.0, 2.2]
    one = pd_.bifurcation_diagram(osc, 0.05, freqs, transient_cycles=30, record_cycles=10)
    many = pd_.bifurcation_diagram(pd_.Structure.from_oscillator(osc), 0.05, freqs, transient_cycles=30,
                                   record_cycles=10)
    # (a one-level structure is the single mass: the same diagram, to the bit, without a level axis)
    xr.testing.assert_identical(many.data.drop_attrs(), one.data.drop_attrs())
    assert many.message == one.message


def test_period_one_samples_are_the_periodic_orbit_of_every_level():
    b = _building()
    freqs = (0.8, 1.0, 2.0)
    d = pd_.bifurcation_diagram(b, 0.05, freqs, transient_cycles=60, record_cycles=10)
    assert d.message.endswith("every response is periodic (period 1).")
    ds = d.data
    assert ds["contacts_per_cycle"].sel(freq_hz=0.8).values.tolist() == [2.0, 2.0]  # (an impacting one)
    for sw in d.sweeps:  # (from the state each step recorded from: a hysteretic isolator's free orbits are
        # a family, set by the slips it keeps)
        for i, f in enumerate(sw.freqs_hz):
            exc = pd_.Harmonic(0.05, f, phase=-(2 * np.pi * f * sw.step_start_s[i]))
            guess = pd_.State._of(sw.window_states[i], ((0, 1),), pd_.State.at_rest(b).layout)
            orbit = pd_.periodic_orbit(b, exc, guess=guess)
            assert orbit.converged, orbit.message
            x = ds.strobe_displacement_m.sel(direction=sw.direction, freq_hz=f).values  # (cycle, level)
            v = ds.strobe_velocity_m_s.sel(direction=sw.direction, freq_hz=f).values
            scale = np.abs(orbit.state.displacements_m).max()
            np.testing.assert_allclose(x, np.broadcast_to(orbit.state.displacements_m, x.shape), rtol=0,
                                       atol=1e-6 * scale)
            np.testing.assert_allclose(v, np.broadcast_to(orbit.state.velocities_m_s, v.shape), rtol=0,
                                       atol=1e-6 * scale * 2 * np.pi * f)
    rows = d.to_dataframe()
    assert set(rows["level"]) == {0, 1} and len(rows) == 2 * len(freqs) * 10 * 2
    steps = d.to_dataframe(cycles=False)
    assert {"alpha", "excursion_m", "level_number"} <= set(steps.columns)


def test_a_chaotic_building_is_not_periodic_and_its_largest_exponent_is_positive():
    d = pd_.bifurcation_diagram(_building(), 0.2, [1.5], direction="up", transient_cycles=40,
                                record_cycles=10)
    assert int(d.data["period"].sel(direction="up", freq_hz=1.5)) == 0
    d = pd_.largest_exponents(d, cycles=40)
    assert float(d.data["largest_exponent"].sel(direction="up", freq_hz=1.5)) > 1.0


def test_the_diagram_plots_a_level_and_refuses_one_it_has_not():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    d = pd_.bifurcation_diagram(_building(), 0.1, [1.0, 2.0], direction="up", transient_cycles=20,
                                record_cycles=10)
    artists = pd_.plots.plot_bifurcation_diagram(d, level=0)
    assert artists[0].axes.get_title().endswith("level 0")
    assert "x at table phase 0" in artists[0].axes.get_ylabel()
    with pytest.raises(pd_.InputError, match="level"):
        d.plot(level=5)
