"""Periodic orbits that stick (issue 51): an orbit whose chatter accumulates and holds on a rigid stop in
each period has its exact monodromy.  The impact that begins a hold brings the pair to rest (Newton's reset
with e = 0, the chatter's remainder being taken at that instant), the field after it is the held mode's (the
held group's accelerations its mass-weighted mean, a group held to the ground's zero), and the release, where
the hold's force falls to zero, leaves the field continuous."""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import pounding

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))


def _building(e: float) -> pounding.Structure:
    iso = pounding.Isolator(slopes_n_m=[4.0 * math.pi ** 2], damping_n_s_m=0.4 * math.pi)
    stop = pounding.Wall(0, 0.01, 0.01, pounding.RigidStop(e))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (a 1 kg building)
        return pounding.Structure(1.0, iso, [pounding.Storey(1.0, 16.0 * math.pi ** 2, 0.5)], [stop])


@pytest.mark.parametrize("e, a_ms2, f_hz", [(0.5, 6.0, 0.8), (0.0, 3.0, 1.2), (0.7, 10.0, 0.5)])
def test_a_building_whose_base_sticks_each_period_has_exact_multipliers_equal_to_finite_differences(e, a_ms2,
                                                                                                    f_hz):
    building, table = _building(e), pounding.Harmonic(a_ms2 / 9.81, f_hz)
    run = pounding.simulate(building, table, 20.0)
    assert (run.contacts.t_end_s > run.contacts.t_start_s).any()  # (held on the wall)
    exact = pounding.periodic_orbit(building, table)
    fd = pounding.periodic_orbit(building, table, method="finite-difference")
    assert exact.converged and fd.converged
    assert exact.method == "exact", exact.message
    np.testing.assert_allclose(np.sort_complex(exact.multipliers), np.sort_complex(fd.multipliers), atol=1e-6)
    # the base held: its two directions erased at once, the storey's left
    assert np.sum(np.abs(exact.multipliers) < 1e-12) == 2 and np.abs(exact.multipliers).max() > 0.3


def test_a_mass_that_sticks_in_each_half_cycle_forgets_every_perturbation():
    """The chatter benchmark's orbit: each half cycle an accumulated chatter and a hold on the stop, which
    fixes the mass's displacement and velocity until the table pulls it off at a time of its own."""
    import rigid_stops as rs
    orbit = pounding.periodic_orbit(rs.system(), rs.table())
    assert orbit.converged and orbit.method == "exact", orbit.message
    np.testing.assert_array_equal(orbit.multipliers, [0.0, 0.0])
