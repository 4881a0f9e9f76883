"""Basins of attraction of structures: the (first) structure shifted as one body, each initial state run
until it settles, its attractor matched by its largest alpha over every mass and its contacts.

- One level is the oscillator's basins, state for state.
- Each attractor is what a plain run from one of its states settles on (its largest alpha over the levels).
"""

from __future__ import annotations

import numpy as np
import pytest

import pounding as pd_

EXC = pd_.Harmonic(0.05, 1.6)


def _building() -> pd_.Structure:
    iso = pd_.Isolator(slopes_n_m=[2e5], breakpoints_m=[], damping_n_s_m=2e3)
    return pd_.Structure(2.0e3, iso, [pd_.Storey(1.0e3, 2.0e6, 2.0e3)],
                         [pd_.Wall(0, 0.03, 0.03, pd_.KelvinVoigt(1.0e8, 2.0e4))])


def test_one_level_is_the_oscillators_basins():
    osc = pd_.presets.paper_damped()
    exc = pd_.Harmonic(0.05, 1.8)
    one = pd_.basins(osc, exc, n=(8, 8), scheduler="serial")
    many = pd_.basins(pd_.Structure.from_oscillator(osc), exc, n=(8, 8), scheduler="serial")
    np.testing.assert_array_equal(many.labels, one.labels)
    cols = ["period", "alpha", "excursion_m", "contacts_per_cycle", "fraction"]
    np.testing.assert_allclose(many.attractors[cols].to_numpy(float), one.attractors[cols].to_numpy(float),
                               rtol=1e-12)


def test_a_building_s_attractors_are_where_its_runs_settle():
    b = _building()
    result = pd_.basins(b, EXC, n=(6, 6), scheduler="serial")
    table = result.attractors
    assert table["impacts"].tolist() == [False, True] and table["fraction"].sum() == pytest.approx(1.0)
    assert result.displacement_m.min() == pytest.approx(-0.03) and result.displacement_m.max() == 0.03
    for label in (0, 1):
        i = int(np.flatnonzero(result.labels.ravel() == label)[0])
        start = pd_.State.at_rest(b, 0.0, float(result.displacement_m[i]),
                                           float(result.velocity_m_s[i]))
        settled = pd_.simulate(b, EXC, 400 / EXC.freq_hz, start, sample_rate_hz=0).final_state
        window = pd_.simulate(b, EXC, 5 / EXC.freq_hz, settled, sample_rate_hz=0)
        alpha = float(window.abs_acceleration_max.max()) / EXC.peak_m_s2
        assert alpha == pytest.approx(table["alpha"].iloc[label], rel=1e-6)
        assert (len(window.contacts) > 0) == bool(table["impacts"].iloc[label])


def test_a_structure_s_box_is_the_shifts_that_leave_its_walls_and_links_open():
    with pytest.raises(pd_.InputError, match="walls and links open"):
        pd_.basins(_building(), EXC, displacement_m=(-0.05, 0.01), n=(2, 2))
    with pytest.raises(pd_.InputError, match="wall 0's right side"):
        pd_.State.at_rest(_building(), 0.0, 0.04)
    from pathlib import Path

    pair = pd_.Adjacent.from_toml(Path(__file__).parents[1] / "examples" / "adjacent_buildings.toml")
    result = pd_.basins(pair, pd_.Harmonic(0.2, 1.0), n=(2, 2), max_cycles=60, scheduler="serial")
    # (the first building shifted towards its neighbour closes the link at its gap; away from it, no wall)
    assert result.displacement_m.max() == pytest.approx(pair.links[0].gap_m)
    assert result.displacement_m.min() == pytest.approx(-0.05)


def test_a_building_s_basin_stability_is_its_basins_share_that_pounds():
    b = _building()
    m = pd_.basin_stability_map(b, [0.05], [1.6, 2.2], samples=30, scheduler="serial")
    for f in (1.6, 2.2):
        share = float(m.data["pounding_probability"].sel(a_g=0.05, freq_hz=f))
        rng = np.random.default_rng(0)  # (the map's states: the same draw, at each point)
        d, v = rng.uniform(-0.03, 0.03, 30), rng.uniform(-1.0, 1.0, 30)
        pounded = 0
        for x, y in zip(d, v):
            start = pd_.State.at_rest(b, 0.0, float(x), float(y))
            settled = pd_.simulate(b, pd_.Harmonic(0.05, f), 400 / f, start, sample_rate_hz=0).final_state
            window = pd_.simulate(b, pd_.Harmonic(0.05, f), 5 / f, settled, sample_rate_hz=0)
            pounded += len(window.contacts) > 0
        assert share == pytest.approx(pounded / 30)
    with pytest.raises(pd_.InputError, match="walls or links"):
        pd_.basin_stability_map(pd_.Structure(2.0e3, b.isolator, b.storeys), [0.05], [1.6], samples=2)


def test_a_building_s_alpha_is_its_levels_not_its_bumpers_stands():
    # (the stands' impact accelerations are far above the floors': alpha is a floor's, as in a sweep)
    wall = pd_.Wall(0, 0.01, 0.01, pd_.KelvinVoigt(1e8, 2e4), stand=pd_.Stand(20.0, 2e6, 50.0))
    b = pd_.Structure(2.0e3, pd_.Isolator([2e5], [], damping_n_s_m=2e3), [pd_.Storey(1.0e3, 2.0e6, 2.0e3)],
                      [wall])
    exc = pd_.Harmonic(0.1, 1.6)
    result = pd_.basins(b, exc, n=(2, 1), velocity_m_s=(-0.1, 0.1), max_cycles=300, scheduler="serial")
    i = int(np.flatnonzero(result.labels.ravel() >= 0)[0])
    start = pd_.State.at_rest(b, 0.0, float(result.displacement_m[i]), float(result.velocity_m_s[i]))
    settled = pd_.simulate(b, exc, 300 / exc.freq_hz, start, sample_rate_hz=0).final_state
    window = pd_.simulate(b, exc, 5 / exc.freq_hz, settled, sample_rate_hz=0)
    levels = float(window.abs_acceleration_max.max()) / exc.peak_m_s2
    assert result.attractors["alpha"].iloc[result.labels.ravel()[i]] == pytest.approx(levels, rel=1e-6)
