"""The pounding spectrum of a building (``pounding.pounding_spectrum(..., structure=)``): over its
superstructure's fixed-base period and its moat's gap, each point a direct run of the building scaled to that
period with its walls at that gap, the reference without walls, and what it refuses named."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import pounding as pd_
from pounding.protocols.pounding_spectrum import superstructure_at


def building() -> pd_.Structure:
    iso = pd_.Isolator(slopes_n_m=[4.0e5, 1.0e5], breakpoints_m=[0.02], damping_n_s_m=2.0e3)
    storeys = [pd_.Storey(2.0e3, 4.0e6, 4.0e3), pd_.Storey(1.5e3, 3.0e6, 3.0e3, slopes_after_n_m=(1.0e6,),
                                                            breakpoints_m=(0.01,))]
    return pd_.Structure(3.0e3, iso, storeys, [pd_.Wall(0, 0.03, 0.03, pd_.KelvinVoigt(2.0e7, 1.0e4))])


def test_the_superstructure_is_scaled_to_each_period_with_its_damping_ratios():
    b = building()
    for period in (0.15, 0.6):
        scaled = superstructure_at(b, period)
        assert scaled.modes(fixed_base=True).periods_s[0] == pytest.approx(period, rel=1e-12)
        factor = scaled.storeys[0].stiffness_n_m / b.storeys[0].stiffness_n_m
        assert scaled.storeys[1].slopes_after_n_m[0] == pytest.approx(1.0e6 * factor, rel=1e-12)
        for old, new in zip(b.storeys, scaled.storeys):  # (c / sqrt(k m): each storey's ratio kept)
            assert new.damping_n_s_m / math.sqrt(new.stiffness_n_m) == pytest.approx(
                old.damping_n_s_m / math.sqrt(old.stiffness_n_m), rel=1e-12)
        assert scaled.isolator == b.isolator and scaled.walls == b.walls


def test_each_point_is_a_run_of_the_building_at_that_period_and_gap():
    b = building()
    quake = pd_.records.el_centro().scaled(pga_g=0.5)
    quake = pd_.Record(quake.t[quake.t <= 8.0], quake.accel[quake.t <= 8.0])
    ps = pd_.pounding_spectrum([quake], [0.2, 0.5], gaps_m=[0.02, 0.5], structure=b, scheduler="serial")
    ds = ps.data.isel(record=0)
    assert ds.attrs["period"].startswith("the superstructure's")
    for period in (0.2, 0.5):
        scaled = superstructure_at(b, period)
        bare = dataclasses.replace(scaled, walls=())
        free = pd_.simulate(bare, quake, 8.0, sample_rate_hz=0).quantities()
        point = ds.sel(period_s=period)
        assert float(point["disp_max_free_m"]) == free["disp_max_m"]
        assert float(point["drift_ratio_max_free"]) == free["drift_ratio_max"]
        assert float(point["acc_max_free_g"]) == free["acc_max_g"]
        for gap in (0.02, 0.5):
            wall = dataclasses.replace(b.walls[0], gap_left_m=gap, gap_right_m=gap)
            walled = dataclasses.replace(scaled, walls=(wall,))
            hit = pd_.simulate(walled, quake, 8.0, sample_rate_hz=0).quantities()
            at = point.sel(gap_m=gap)
            for name in ("acc_max_g", "impacts", "impact_force_max_n", "impact_speed_max_m_s",
                         "top_acc_max_g", "drift_ratio_max"):
                assert float(at[name]) == hit[name], name
            assert float(at["disp_max_m"]) == hit["disp_max_m"]
    # the wide moat is never reached: as without walls
    wide = ds.sel(gap_m=0.5)
    assert float(wide["impacts"].max()) == 0.0
    np.testing.assert_array_equal(wide["amplification"], 1.0)
    assert float(ds["impacts"].sel(gap_m=0.02).min()) > 0
    assert len(pd_.plots.plot_pounding_spectrum(ps, quantity="drift_ratio_max")) > 0


def test_each_wall_keeps_its_own_laws_unless_one_is_given_and_a_budget_stop_is_kept():
    b = building()
    top = pd_.Wall(2, 0.03, 0.03, pd_.KelvinVoigt(2.0e5, 1.0e3), law_right=pd_.KelvinVoigt(5.0e7, 1.0e4))
    b = dataclasses.replace(b, walls=(b.walls[0], top))
    quake = pd_.records.el_centro().scaled(pga_g=0.5)
    quake = pd_.Record(quake.t[quake.t <= 6.0], quake.accel[quake.t <= 6.0])
    soft = pd_.KelvinVoigt(1.0e6, 0.0)
    for law in (None, soft):
        ps = pd_.pounding_spectrum([quake], [0.4], gaps_m=[0.02], structure=b, bumper=law, scheduler="serial")
        walls = tuple(dataclasses.replace(w, gap_left_m=0.02, gap_right_m=0.02,
                                          **({} if law is None else {"law": law, "law_right": None}))
                      for w in superstructure_at(b, 0.4).walls)
        run = pd_.simulate(dataclasses.replace(superstructure_at(b, 0.4), walls=walls), quake, 6.0,
                           sample_rate_hz=0)
        hit = run.quantities()
        point = ps.data.isel(record=0, period_s=0, gap_m=0)
        assert float(point["impacts"]) == hit["impacts"] > 0
        assert float(point["impact_force_max_n"]) == hit["impact_force_max_n"]
        assert float(point["top_acc_max_g"]) == hit["top_acc_max_g"]
    over = pd_.pounding_spectrum([quake], [0.4], gaps_m=[0.02], structure=b, max_steps=100,
                                 scheduler="serial").data.isel(record=0)
    budget = float(pd_.Status.BUDGET)
    assert (over["status"] == budget).all() and (over["status_free"] == budget).all()
    assert np.isnan(over["drift_ratio_max"]).all() and np.isnan(over["drift_ratio_max_free"]).all()


def test_what_the_building_spectrum_refuses_is_named():
    b = building()
    quake = pd_.records.el_centro()
    with pytest.raises(pd_.InputError, match="structure"):
        pd_.pounding_spectrum([quake], [0.5], gaps_m=[0.1], structure=dataclasses.replace(b, walls=()))
    with pytest.raises(pd_.InputError, match="structure"):
        pd_.pounding_spectrum([quake], [0.5], gaps_m=[0.1], structure=pd_.presets.paper_damped())
    with pytest.raises(pd_.InputError, match="isolated base"):
        pd_.pounding_spectrum([quake], [0.5], gaps_m=[0.1], structure=pd_.Structure.fixed_base(
            [pd_.Storey(2.0e3, 4.0e6)] * 2, [pd_.Wall(2, 0.05, 0.05, pd_.KelvinVoigt(1e7, 1e3))]))
    with pytest.raises(pd_.InputError, match="mass_kg"):
        pd_.pounding_spectrum([quake], [0.5], gaps_m=[0.1], structure=b, mass_kg=100.0)
