"""Impacts at one instant (issue 51): a mass struck while it rests against a rigid stop that shares it with
the striking contact.  Taken one after the other, such impacts repeat at that instant without end (each
plastic pair of them shrinks the velocities by a fixed ratio) and the run stopped with ZENO; they are now
resolved at once by Moreau's law over the touching rigid stops (each separates at least e times its
closing speed, the impulses pushing only), whose closed form here is the struck mass's rebound off an
immovable one."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

import pounding
from pounding import Status

M1, M2, V0 = 3.0, 2.0, 0.5  # kg (striking), kg (resting), m/s


def _pair(e_wall: float, e_link: float, k: float = 4.0) -> pounding.Adjacent:
    """The first structure's base against the second's through a link, the second's against its wall's right
    side, both gaps zero; each base on a linear isolator of ``k`` rad^2/s^2 per kg."""
    def iso(m: float) -> pounding.Isolator:
        return pounding.Isolator(slopes_n_m=[m * k], damping_n_s_m=0.0)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (a stop at zero gap)
        first = pounding.Structure(M1, iso(M1), [])
        second = pounding.Structure(M2, iso(M2), [], [pounding.Wall(0, 0.5, 0.0, pounding.RigidStop(e_wall))])
        return pounding.Adjacent(first, second, [pounding.Link(0, 0, 0.0, pounding.RigidStop(e_link))])


@pytest.mark.parametrize("e_wall", [0.0, 0.8, 1.0])
@pytest.mark.parametrize("e_link", [0.0, 0.5, 1.0])
def test_a_mass_struck_against_one_resting_on_a_stop_rebounds_as_off_an_immovable_one(e_wall, e_link):
    pair = _pair(e_wall, e_link)
    still = pounding.Record(np.array([0.0, 1.0]), np.array([0.0, 0.0]))
    start = pounding.State.at_rest(pair, velocity_m_s=V0)  # (the first moving into the second)
    run = pounding.simulate(pair, still, 0.1, state=start, sample_rate_hz=0)
    assert run.status == Status.SUCCESS, run.message
    link = run.links.iloc[0]
    wall = run.second.contacts.iloc[0]
    impulse = M1 * (1.0 + e_link) * V0
    assert link.t_start_s == link.t_end_s == wall.t_start_s == 0.0  # (one instant, one row each)
    assert link.v_in_m_s == pytest.approx(V0, rel=1e-15)
    assert link.v_out_m_s == pytest.approx(-e_link * V0, abs=1e-15)
    assert link.impulse_n_s == pytest.approx(impulse, rel=1e-14)
    assert wall.impulse_n_s == pytest.approx(impulse, rel=1e-14)  # (through the resting mass to the wall)
    assert link.bumper_dissipation_j == pytest.approx(0.5 * M1 * V0 ** 2 * (1.0 - e_link ** 2), rel=1e-12,
                                                      abs=1e-15)
    assert len(run.links[run.links.t_end_s == 0.0]) == 1  # (not a sequence of them)
    assert abs(run.energy.residual) <= 1e-12 * 0.5 * M1 * V0 ** 2


def test_plastic_impacts_at_one_instant_no_longer_stop_the_run():
    """A random pair that stopped with ZENO at 1.09 s: 70 link impacts and 67 wall impacts at that instant,
    each pair shrinking the velocities by m2 / (m1 + m2) = 0.52."""
    iso = [pounding.Isolator(slopes_n_m=[m * w * w], damping_n_s_m=0.1 * m * w)
           for m, w in ((2.930841294302915, 11.461258479291144), (3.159865012553199, 15.560433687671601))]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        first = pounding.Structure(2.930841294302915, iso[0], [],
                                   [pounding.Wall(0, 0.0, 0.5, pounding.RigidStop(0.0))])
        second = pounding.Structure(3.159865012553199, iso[1], [])
        pair = pounding.Adjacent(first, second, [pounding.Link(0, 0, 0.0, pounding.RigidStop(0.0))])
    table = pounding.Harmonic(a_g=0.23813826823514767, freq_hz=0.8968585421526554)
    run = pounding.simulate(pair, table, 5.0, sample_rate_hz=200)
    assert run.status == Status.SUCCESS, run.message
    rows = pd.concat([run.first.contacts, run.links])
    at_once = rows[rows.t_start_s == rows.t_end_s]
    assert at_once.groupby("t_start_s").size().max() <= 2  # (the wall and the link, once each)
    assert abs(run.energy.residual) < 1e-9 * run.energy.input_work
    assert np.nanmin(run.link_force) >= 0.0 and np.nanmin(run.first.contact_force) >= 0.0  # (never pulls)
