"""A record's samples at its own step taken by their own (the core's ``run.cpp``, ``own_samples_of``): in
a run that asks for no history, a sample of the same linear phase that no event, no velocity's turn or zero
and no absolute acceleration's extremum falls inside is taken by the step's kept transition and the functions
the loop's steps would call for it, without those steps' other cases.  Its numbers are theirs: every output of
a run is the same to the bit with ``own_samples`` off, where every sample goes through the loop's steps."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding._control import CTL_OWN, CTL_WORK, new_control
from pounding._core import run as run_kernel
from pounding.engine.assembly import assemble
from pounding.engine.simulate import kernel_forcing
from strategies import LINEAR_LAWS, buildings, oscillators
from test_whole_steps import sub_interval_s

OUTPUTS = ("state", "samples", "contacts", "events", "ledger", "extrema", "chatters", "norms")


def both(model, rec, with_energy, sample_dt=0.0, t_end=None):
    """The core's run of ``model`` from rest under ``rec``, its samples taken by their own where they may and
    through the loop's steps: (outputs, control) for each."""
    system, forcing = assemble(model).system, kernel_forcing(rec)
    y0 = pd_.State.at_rest(model).vector
    runs = []
    for own in (True, False):
        ctl = new_control(10**9)
        out = run_kernel(system, forcing, np.array(y0, dtype=float), rec.t[-1] if t_end is None else t_end,
                         sample_dt, 1e-10, 10**6, with_energy, ctl, own_samples=own)
        runs.append((out, ctl))
    return runs


def assert_same(a, b):
    assert a.status == b.status
    for name in OUTPUTS:
        x, y = getattr(a, name), getattr(b, name)
        assert x.shape == y.shape and np.array_equal(x, y, equal_nan=True), name


def own_step_record(seed, dt, duration_s, pga):
    """A record of step ``dt`` (s) over ``duration_s``, white noise smoothed, peak ``pga`` (m/s^2), ending at
    rest."""
    rng = np.random.default_rng(seed)
    t = dt * np.arange(int(duration_s / dt) + 1)
    accel = np.convolve(rng.normal(0.0, 1.0, t.size), np.ones(5) / 5, mode="same")
    accel *= pga / max(np.abs(accel).max(), 1e-12)
    accel[-1] = 0.0
    return pd_.Record(t, accel)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data(), law=st.sampled_from(LINEAR_LAWS), seed=st.integers(0, 2**32 - 1),
       ratio=st.floats(0.3, 0.95), pga=st.floats(0.5, 8.0), with_energy=st.booleans())
def test_random_masses_are_the_same_to_the_bit(data, law, seed, ratio, pga, with_energy):
    # random isolated masses (multi-linear isolators, elastic or kinematic; bumpers of the closed-form laws,
    # relaxing or not) under a record whose step is 0.3 to 0.95 of their free phases' shortest sub-interval
    # (their isolator's stiffest slope, 20 ms at most): samples are taken by their own, and the run is the
    # loop's to the bit
    osc = data.draw(oscillators(law=law))
    m, c = osc.mass_kg, osc.isolator.damping_n_s_m
    rate = max(np.sqrt(max(osc.isolator.slopes_n_m) / m + (0.5 * c / m) ** 2), c / m)
    rec = own_step_record(seed, min(ratio * 2.0 * np.pi / (8.0 * rate), 0.02), 4.0, pga)
    (own, ctl), (loop, ctl_loop) = both(osc, rec, with_energy)
    assert_same(own, loop)
    assert ctl[CTL_OWN] > 0 and ctl_loop[CTL_OWN] == 0, (int(ctl[CTL_OWN]), int(ctl[CTL_WORK]))
    assert ctl[CTL_WORK] == ctl_loop[CTL_WORK]  # (a sample by its own: one sub-interval, as in the loop)


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(building=buildings(), ratio=st.floats(0.3, 0.95), seed=st.integers(0, 2**32 - 1),
       pga=st.floats(0.5, 8.0), with_energy=st.booleans())
def test_random_buildings_are_the_same_to_the_bit(building, ratio, seed, pga, with_energy):
    # random buildings (linear, bilinear and friction isolators, a wall or none; storeys' drifts tracked)
    # under a record whose step is 0.3 to 0.95 of their storeys' phases' sub-interval (5 ms at most: a storey
    # stiffer than the isolator): the run is the loop's to the bit; a friction isolator's stick (a tie the
    # loop's steps look after) leaves every sample to them
    dt = min(ratio * sub_interval_s(assemble(building).system), 0.005)
    rec = own_step_record(seed, dt, 3.0, pga)
    (own, ctl), (loop, _) = both(building, rec, with_energy)
    assert_same(own, loop)
    if isinstance(building.isolator, pd_.Isolator):
        assert ctl[CTL_OWN] > 0, (int(ctl[CTL_OWN]), int(ctl[CTL_WORK]))
    else:
        assert ctl[CTL_OWN] == 0


@pytest.mark.parametrize("preset", ["paper_printed", "paper_calibrated"])
def test_most_samples_of_a_pounding_mass_under_a_record_are_taken_by_their_own(preset):
    # the YBs systems under El Centro at its own step (0.02 s; their phases' sub-interval about 0.1 s), the
    # printed one with 94 contacts, the calibrated one's multi-linear bumpers relaxing after each of its 40:
    # most samples are taken by their own (1,083 and 1,269 of 1,558), the contact phases' and the events'
    # through the loop's steps, and the run is the loop's to the bit, with its energy ledger and without
    osc = getattr(pd_.presets, preset)()
    rec = pd_.records.el_centro().scaled(pga_g=0.4)
    for with_energy in (True, False):
        (own, ctl), (loop, ctl_loop) = both(osc, rec, with_energy)
        assert_same(own, loop)
        samples = rec.t.size - 1
        assert len(own.contacts) > 20 and ctl[CTL_OWN] > 0.5 * samples, (len(own.contacts), ctl[CTL_OWN])
        assert ctl_loop[CTL_OWN] == 0


@pytest.mark.parametrize("budget", [1, 63, 64, 65, 200, 1000, 1001, 2047])
def test_a_budget_spent_among_samples_taken_by_their_own_stops_where_the_loop_does(budget):
    # samples taken by their own one after another count as the loop's steps would, one each, and the run
    # control is looked at where the loop would look at it (every 64): a budget spent among them stops the run
    # at the same sample, the same state to the bit, as the loop's steps (the printed system under El Centro:
    # its stretches of such samples a few to some tens long, between its events)
    osc = pd_.presets.paper_printed()
    rec = pd_.records.el_centro().scaled(pga_g=0.4)
    system, forcing = assemble(osc).system, kernel_forcing(rec)
    y0 = pd_.State.at_rest(osc).vector
    runs = []
    for own in (True, False):
        ctl = new_control(budget)
        out = run_kernel(system, forcing, np.array(y0, dtype=float), rec.t[-1], 0.0, 1e-10, 10**6, False, ctl,
                         own_samples=own)
        runs.append((out, ctl))
    (own, ctl), (loop, ctl_loop) = runs
    assert own.status == int(pd_.Status.BUDGET) and 0.0 < own.state[0] < rec.t[-1]
    assert_same(own, loop)
    assert ctl[CTL_WORK] == ctl_loop[CTL_WORK]
    assert budget < 200 or ctl[CTL_OWN] > 0.3 * budget  # (a good part of a longer budget: such samples)


def test_no_sample_is_taken_by_its_own_with_a_history_uneven_steps_or_a_harmonic():
    # a history's samples fall inside the record's (the loop's samples_inside); a record of uneven steps has
    # no step of its own (its transitions would be one a sample); a harmonic has no knots
    osc = pd_.presets.paper_damped()
    rec = pd_.records.el_centro().scaled(pga_g=0.3)
    (own, ctl), (loop, _) = both(osc, rec, True, sample_dt=0.01, t_end=5.0)
    assert_same(own, loop)
    assert ctl[CTL_OWN] == 0 and own.samples.shape[0] > 400
    t = np.concatenate([[0.0], np.cumsum(0.01 * np.random.default_rng(3).uniform(0.5, 1.5, 500))])
    uneven = pd_.Record(t, np.interp(t, rec.t, rec.accel))
    (own, ctl), (loop, _) = both(osc, uneven, False)
    assert_same(own, loop)
    assert ctl[CTL_OWN] == 0 and len(own.events) > 0
    system, y0 = assemble(osc).system, pd_.State.at_rest(osc).vector
    ctl = new_control(10**9)
    harmonic = kernel_forcing(pd_.Harmonic(0.1, 1.5))
    run_kernel(system, harmonic, np.array(y0), 5.0, 0.0, 1e-10, 10**6, True, ctl)
    assert ctl[CTL_OWN] == 0 and ctl[CTL_WORK] > 0
