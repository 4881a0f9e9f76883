"""The screen of a record's extrema (the core's ``screen.cpp``): inside a sub-interval of a linear phase, a
displacement's, a drift's or an absolute acceleration's extremum is looked for only where a bound from the
sub-interval's ends cannot show it within the largest and smallest so far.  What it passes over changes
nothing: every result is the same, to the last bit, as the run that finds every extremum.  And it passes over
most of them: the phase's series, which finding one takes, is made far less often."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding import _core
from pounding._control import CTL_AUDITED, CTL_ESCAPES, CTL_SERIES, CTL_WORK, new_control
from pounding._core import run as run_kernel
from pounding.engine.assembly import assemble
from pounding.engine.simulate import kernel_forcing
from strategies import LINEAR_LAWS, buildings, oscillators, records

G = 9.80665


def both(model, excitation, t_end, state=None, sample_dt=0.0):
    """The kernel's run of ``model`` screened and not, from ``state`` (a State, its vector, or at rest):
    (its outputs, its control) for each."""
    system = assemble(model).system
    forcing = kernel_forcing(excitation)
    state = pd_.State.at_rest(model) if state is None else state
    y0 = np.array(state if isinstance(state, np.ndarray) else state.vector)
    runs = []
    for screen in (True, False):
        ctl = new_control(10**9)
        runs.append((run_kernel(system, forcing, y0, t_end, sample_dt, 1e-10, 10**6, True, ctl,
                                screen_extrema=screen, whole_steps=False), ctl))
    return runs


def audited(system, forcing, y0, t_end):
    """The screened run with its audit: (the extrema it cleared, those outside the range its bound gives)."""
    ctl = new_control(10**9)
    run_kernel(system, forcing, y0, t_end, 0.0, 1e-10, 10**6, True, ctl, audit_screen=True, whole_steps=False)
    return int(ctl[CTL_AUDITED]), int(ctl[CTL_ESCAPES])


def assert_identical(screened, found):
    for name in ("state", "samples", "contacts", "events", "ledger", "extrema", "chatters"):
        np.testing.assert_array_equal(getattr(screened, name), getattr(found, name), err_msg=name)
    assert screened.status == found.status


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(building=buildings(), rec=records(duration_s=4.0), pga=st.floats(0.5, 8.0), v0=st.floats(-0.3, 0.3),
       sampled=st.booleans())
def test_a_screened_building_is_the_same_to_the_last_bit(building, rec, pga, v0, sampled):
    # random buildings (linear, bilinear and friction isolators; a wall of a linear law, a rigid stop or none)
    # under random records (even, jittered, steps shorter and longer than the phases' sub-intervals), from
    # rest or moving
    rec = pd_.Record(rec.t, rec.accel * (pga / max(np.abs(rec.accel).max(), 1e-12)))
    state = pd_.State.at_rest(building, velocity_m_s=v0)
    (screened, _), (found, _) = both(building, rec, 4.2, state, 0.01 if sampled else 0.0)
    assert_identical(screened, found)
    # every extremum it cleared, found all the same, lies within the range its bound gives
    assert audited(assemble(building).system, kernel_forcing(rec), np.array(state.vector), 4.2)[1] == 0


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(osc=st.sampled_from(LINEAR_LAWS).flatmap(lambda law: oscillators(law=law)),
       rec=records(duration_s=4.0), v0=st.floats(-0.5, 0.5))
def test_a_screened_mass_between_bumpers_is_the_same_to_the_last_bit(osc, rec, v0):
    (screened, _), (found, _) = both(osc, rec, 4.2, pd_.State.at_rest(osc, velocity_m_s=v0))
    assert_identical(screened, found)


def test_the_screen_spares_most_series_of_a_sliding_building_under_a_record():
    # a 4-level building on a friction pendulum under El Centro: each level's and each storey's extrema
    # inside its sub-intervals; the screened run makes the series in fewer than half the sub-intervals
    # the other does, and its results are the same
    iso = pd_.FrictionIsolator(mu=0.06, radius_m=2.2)
    building = pd_.Structure(4.0e5, iso, [pd_.Storey(3.0e5, 4.0e8, 8.0e5)] * 3, [])
    rec = pd_.records.el_centro().scaled(pga_g=0.6)
    (screened, ctl_s), (found, ctl_f) = both(building, rec, 20.0)
    assert_identical(screened, found)
    assert ctl_s[CTL_WORK] == ctl_f[CTL_WORK]
    assert ctl_s[CTL_SERIES] < ctl_f[CTL_SERIES] / 2, (ctl_s[CTL_SERIES], ctl_f[CTL_SERIES])


@pytest.mark.parametrize("levels", [1, 3])
def test_peaks_that_pass_the_largest_by_a_hair_are_each_found(levels):
    # a heavily damped linear building in its steady response to a sampled sine that grows by 1e-9 a second
    # (the run from 40 s on: its start's transient long gone): every cycle's peak passes the largest so far by
    # about 1e-9 of it, less than the cubic's error over a sub-interval (4e-7 of it at one level); the screen
    # clears none of them, each is found, and the largest and its time are the same to the bit (with the
    # cubic's error left out of its margin, or no margin, the largest is a cycle or more late)
    building = pd_.Structure(2.0e4, pd_.Isolator((6.0e5,), damping_n_s_m=4.4e4),
                             [pd_.Storey(1.5e4, 3.0e7, 2.0e4)] * (levels - 1), [])
    t = np.arange(0.0, 100.0 + 1e-9, 0.02)
    rec = pd_.Record(t, 2.0 * (1.0 + 1e-9 * t) * np.sin(2.0 * np.pi * 0.7 * t))
    system, forcing = assemble(building).system, kernel_forcing(rec)
    start = run_kernel(system, forcing, np.array(pd_.State.at_rest(building).vector), 40.0, 0.0, 1e-10, 10**6,
                       True, new_control(10**9)).state
    (screened, _), (found, _) = both(building, rec, 100.0, start)
    assert_identical(screened, found)


def test_a_last_part_s_transition_off_by_the_clock_s_drift_is_screened_as_such():
    # two unit masses, a 1e10 N/m spring between them and a soft one to the ground, in free vibration of their
    # soft mode (its half period the record's step) under a zero record late in time (4e6 s): each 0.02 s
    # step goes in 3602 parts, and its last one takes the parts' transition though it is longer or shorter by
    # the clock's drift over them, so that its end is the motion a few ns off; every peak falls in such a
    # part, and the screen, widened by that shift, clears none it should not (without the widening the
    # largest comes a cycle early)
    k_stiff, step, t0 = 1e10, 0.02, 4e6
    w_target = np.pi / step
    lo, hi = 0.0, 4 * w_target**2
    for _ in range(200):  # (the soft spring that puts the soft mode at w_target)
        mid = 0.5 * (lo + hi)
        stiffness = np.array([[mid + k_stiff, -k_stiff], [-k_stiff, k_stiff]])
        lo, hi = (mid, hi) if np.sqrt(np.linalg.eigvalsh(stiffness).min()) < w_target else (lo, mid)
    stiffness = np.array([[0.5 * (lo + hi) + k_stiff, -k_stiff], [-k_stiff, k_stiff]])
    values, vectors = np.linalg.eigh(stiffness)
    w, shape = np.sqrt(values[0]), vectors[:, 0] / vectors[0, 0]
    system = _core.system(np.ones(2), stiffness, np.zeros((2, 2)), [], False, [], tracked=((1, 0),))
    rec_t = t0 + step * np.arange(int(4.0 / step) + 2)
    forcing = _core.Forcing(kind=_core.EXCITATION["record"], p=np.array([step, 0.0, 0.0]), rec_t=rec_t,
                            rec_a=np.zeros(rec_t.size))
    t_peak = step - 0.4711 * step / 3602  # (the soft mode's peaks: inside each step's last part)
    layout = system.layout
    y0 = np.zeros(system.state_size)
    y0[0] = t0
    y0[layout["x"]:layout["x"] + 2] = 0.01 * shape * np.cos(-w * t_peak)
    y0[layout["v"]:layout["v"] + 2] = -0.01 * shape * w * np.sin(-w * t_peak)
    screened, found = (run_kernel(system, forcing, y0, t0 + 24.5 * step, 0.0, 1e-10, 10**7, True,
                                  new_control(10**13), screen_extrema=screen, whole_steps=False)
                        for screen in (True, False))
    assert_identical(screened, found)


@pytest.mark.parametrize("damping_n_s_m", [0.0, 2.0e3])
@pytest.mark.parametrize("shape", ["sine", "noise"])
def test_every_extremum_the_screen_clears_lies_within_its_bound(damping_n_s_m, shape):
    # a single isolated mass under a sine or white noise: the audit finds each extremum the screen cleared all
    # the same, and every one lies within the cubic's range widened by the bound on its fourth derivative
    # (that bound is within a factor of about 2 of the truth here: half of it, or Z without its growth
    # e^(alpha t) or without the jerk, lets extrema out)
    mass = pd_.Structure(2.0e4, pd_.Isolator((6.0e5,), damping_n_s_m=damping_n_s_m), [], [])
    t = np.arange(0.0, 30.0 + 1e-9, 0.01)
    noise = np.random.default_rng(3).normal(0.0, 2.0, t.size)
    accel = 2.0 * np.sin(2.0 * np.pi * 0.9 * t) if shape == "sine" else noise
    cleared, escapes = audited(assemble(mass).system, kernel_forcing(pd_.Record(t, accel)),
                               np.array(pd_.State.at_rest(mass).vector), 30.0)
    assert cleared > 20 and escapes == 0, (cleared, escapes)


def test_a_drift_s_bound_is_twice_a_level_s():
    # two unit masses in free vibration of their mode (1, -1) under a zero record: the drift's fourth
    # derivative is the two levels' accelerations' second derivatives apart, twice either's bound; every peak
    # equals the largest, so the screen clears none (with a drift's bound taken as a level's it clears some,
    # and they lie outside it)
    stiffness = np.array([[1.0 + 1e4, -1e4], [-1e4, 1e4]])
    system = _core.system(np.ones(2), stiffness, np.zeros((2, 2)), [], False, [], tracked=((1, 0),))
    t = np.arange(0.0, 2.0 + 1e-9, 0.01)
    forcing = _core.Forcing(kind=_core.EXCITATION["record"], p=np.array([0.01, 0.0, 0.0]), rec_t=t,
                            rec_a=np.zeros(t.size))
    y0 = np.zeros(system.state_size)
    y0[system.layout["x"]:system.layout["x"] + 2] = (0.01, -0.01)
    assert audited(system, forcing, y0, 2.0) == (0, 0)
