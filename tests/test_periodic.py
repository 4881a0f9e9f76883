"""Periodic orbits (issue 20): Newton shooting on the engine's map, the exact monodromy against
closed forms and finite differences, the orbits against the sweeps that settle on them."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding.analysis import _hybrid as hy
from pounding.engine.simulate import kernel_system
from pounding.engine.layout import DEF_L, DEF_R, IN_L, IN_R, STATE_BASE
from pounding.engine.layout import D as I_D
from pounding.engine.layout import V as I_V
from strategies import harmonics, oscillators


def test_linear_isolator_without_bumpers_is_the_closed_form():
    m, k, c = 500.0, 38_000.0, 900.0
    osc = pd_.Oscillator(m, pd_.Isolator([k], [], "elastic", c), None)
    for f in (0.5, 1.2, 1.4, 3.0):
        exc = pd_.Harmonic(0.05, f, phase=0.3)
        orbit = pd_.periodic_orbit(osc, exc, settle_cycles=3)
        w = exc.omega_rad_s
        z = -exc.peak_m_s2 * m / (k - m * w * w + 1j * c * w)  # D = Im(z exp(i theta))
        theta = w * orbit.state.time_s + exc.phase
        d, v = (z * np.exp(1j * theta)).imag, (1j * w * z * np.exp(1j * theta)).imag
        assert orbit.converged and orbit.method == "exact"
        assert orbit.state.displacement_m == pytest.approx(d, rel=1e-9, abs=1e-12 * abs(z))
        assert orbit.state.velocity_m_s == pytest.approx(v, rel=1e-9, abs=1e-12 * abs(z) * w)
        assert orbit.excursion_m == pytest.approx(2 * abs(z), rel=1e-9)
        # multipliers exp(lambda T) of the free response, lambda = -zeta w_n +- i w_d
        lam = np.roots([m, c, k])
        expected = np.exp(lam / f)
        np.testing.assert_allclose(np.sort_complex(orbit.multipliers), np.sort_complex(expected), rtol=1e-9)
        assert orbit.stable and orbit.coordinates == ("x_0", "v_0")


def _image(osc, exc, vec, period):
    run = pd_.simulate(osc, exc, period, pd_.State(vec), sample_rate_hz=0)
    assert run.success
    return run


def _fd_jacobian(osc, exc, vec, period, free, step):
    """Central differences of the engine's map in the free coordinates (x_0, v_0, relaxing compressions,
    elastic springs' slips), the others kept on their constraints (depth in contact, slip at the
    breakpoint while slipping); written here from the state's meaning, not from the code under test."""
    n_sp = osc.isolator.n_branches - 1 if osc.isolator.hysteresis == "kinematic" else 0
    place = {"x_0": I_D, "v_0": I_V, "delta_wall0_left": DEF_L, "delta_wall0_right": DEF_R,
             **{f"u_{i}": STATE_BASE + i for i in range(n_sp)}}
    scale = {"v_0": exc.omega_rad_s}
    cols = []
    for name in free:
        ends = []
        # a compression is >= 0: forward differences of second order for it, central for the others
        steps = (0.0, 1.0, 2.0) if name.startswith("delta") else (1.0, -1.0)
        for sgn in steps:
            w = np.array(vec, dtype=float)
            w[place[name]] += sgn * step * scale.get(name, 1.0)
            gl, gr = osc.bumpers.gap_left_m, osc.bumpers.gap_right_m
            if w[IN_L]:
                w[DEF_L] = -w[I_D] - gl
            if w[IN_R]:
                w[DEF_R] = w[I_D] - gr
            for i in range(n_sp):
                s = w[STATE_BASE + n_sp + i]
                if s != 0.0:
                    w[STATE_BASE + i] = w[I_D] - s * osc.isolator.breakpoints_m[i]
            try:
                end = _image(osc, exc, w, period).final_state.vector
            except pd_.InputError as exc_info:
                # a spring within the difference's reach of its yield displacement: the moved state
                # is none the system can be in (an elastic spring past yield), and the map has a kink
                # there (a graze the check on two steps below would refuse anyway)
                assert exc_info.problem is pd_.Problem.BAD_STATE, exc_info
                assume(False)
            ends.append(np.array([end[place[q]] for q in free]))
        h = step * scale.get(name, 1.0)
        cols.append((4 * ends[1] - ends[2] - 3 * ends[0]) / (2 * h) if len(ends) == 3
                    else (ends[0] - ends[1]) / (2 * h))
    return np.array(cols).T


@pytest.mark.parametrize("rule, events", [("kinematic", (hy.ACT_CONTACT, hy.ACT_YIELD, hy.ACT_REVERSAL)),
                                          ("elastic", (hy.ACT_CONTACT, hy.ACT_RELEASE, hy.ACT_REGION))])
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                 HealthCheck.filter_too_much])
@given(data=st.data(), settle=st.integers(2, 20))
def test_exact_monodromy_equals_finite_differences_of_the_engine(rule, events, data, settle):
    """On random systems whose period holds contacts and the isolator's events (yields and
    reversals; changes of branch): the monodromy composed from state-transition and saltation
    matrices equals a finite-difference Jacobian of the engine's map to 1e-5 (where the map is
    differentiable at the differences' scale: two steps agree)."""
    osc, exc = data.draw(oscillators(hysteresis=rule)), data.draw(harmonics())
    assume(osc.isolator.n_branches > 1)
    period = 1.0 / exc.freq_hz
    state = pd_.simulate(osc, exc, settle * period, sample_rate_hz=0).final_state
    vec = np.array(state.vector)
    run = _image(osc, exc, vec, period)
    actions = set(run.event_table[:, 1].astype(int).tolist())
    assume({int(e) for e in events} <= actions)
    from pounding.analysis._shooter import _Shooter

    shooter = _Shooter(osc, exc, period, exact=True)
    free = shooter.names(vec)
    exact = shooter.jacobian(vec, run, ())
    size = max(abs(run.displacement_max), abs(run.displacement_min))
    fd1 = _fd_jacobian(osc, exc, vec, period, free, 1e-6 * size)
    fd2 = _fd_jacobian(osc, exc, vec, period, free, 5e-7 * size)
    norm = np.abs(fd1).max()
    assume(np.abs(fd1 - fd2).max() <= 1e-7 * norm)  # (no grazing within the differences' reach)
    assert np.abs(exact - fd1).max() <= 1e-5 * norm, (free, exact, fd1)
    # and the propagation by the modes' exponentials ends where the engine ends
    _, x_end = hy.monodromy(kernel_system(osc), vec, run.event_table, vec[0] + period, exc.omega_rad_s,
                            exc.peak_m_s2, exc.phase)
    n_sp = osc.isolator.n_branches - 1 if osc.isolator.hysteresis == "kinematic" else 0
    fs = run.final_state.vector  # (D, V, the compressions, the slips: read by the state's layout)
    end = np.array([fs[I_D], fs[I_V], fs[DEF_L], fs[DEF_R], *fs[STATE_BASE:STATE_BASE + n_sp]])
    x_end = x_end[:end.size]  # (an elastic isolator's unused slips come last)
    # each coordinate to 1e-8 of its own scale: lengths (D, compressions, slips) of the orbit's size,
    # the velocity (the second) of that size times the forcing's rate or of itself
    scale = np.full(end.size, size)
    scale[1] = max(size * exc.omega_rad_s, abs(end[1]))
    assert (np.abs(x_end - end) <= 1e-8 * scale).all(), (x_end - end, scale)


def _sweep_orbits(osc, a_g, freqs, direction):
    s = pd_.sweep(osc, a_g, freqs, direction, steady="fixed", cycles=60, measure_cycles=5)
    df = s.to_dataframe()
    for i, f in enumerate(s.freqs_hz):
        exc = pd_.Harmonic(a_g, f, phase=-(2 * math.pi * f * s.step_start_s[i]))
        yield df.iloc[i], pd_.periodic_orbit(osc, exc, guess=pd_.State(s.window_states[i]))


def test_stable_orbits_are_what_the_sweeps_settle_on():
    """Both responses where up and down sweeps differ (1.7-2.0 Hz), and around: the orbit from the
    sweep's window state is stable, and its metrics are the sweep's steady ones to 1e-6."""
    osc = pd_.presets.paper_damped()
    seen = set()
    for direction, freqs in (("up", np.round(np.arange(1.0, 2.01, 0.1), 2)),
                             ("down", np.round(np.arange(2.3, 1.69, -0.1), 2))):
        for row, orbit in _sweep_orbits(osc, 0.05, freqs, direction):
            if not (row["steady"] and row["period_multiple"] == 1):
                continue  # (1.1 Hz up: no period-1 response settles; test_an_unstable_orbit_...)
            assert orbit.converged and orbit.stable and orbit.method == "exact", orbit.message
            assert orbit.alpha == pytest.approx(row["alpha"], rel=1e-6)
            assert orbit.excursion_m == pytest.approx(row["excursion_m"], rel=1e-6)
            assert orbit.contacts_per_period == pytest.approx(row["contacts_per_cycle"], abs=1e-12)
            seen.add((row["freq_hz"], orbit.contacts_per_period > 0))
    assert (1.8, True) in seen and (1.8, False) in seen  # (the two coexisting responses)


def test_an_unstable_orbit_returns_over_one_period_and_departs_over_many():
    """Sweeping up to 1.1 Hz no period-1 response settles: Newton from the sweep's state finds the
    unstable period-1 orbit there; simulated, it returns after a period and leaves it after many."""
    osc = pd_.presets.paper_damped()
    (row, orbit), = list(_sweep_orbits(osc, 0.05, [1.1], "up"))[-1:]
    assert not row["steady"]
    assert orbit.converged and not orbit.stable and orbit.max_abs_multiplier > 2.0
    exc = orbit.run.excitation
    size = orbit.excursion_m
    one = pd_.simulate(osc, exc, orbit.period_s, orbit.state, sample_rate_hz=0).final_state
    assert abs(one.displacement_m - orbit.state.displacement_m) < 1e-8 * size
    assert abs(one.velocity_m_s - orbit.state.velocity_m_s) < 1e-8 * size * exc.omega_rad_s
    # at the section times of periods 30 to 60 (the rounding of 1e-11 grown by 2.3^k)
    state, gone = orbit.state, []
    for k in range(1, 61):
        state = pd_.simulate(osc, exc, orbit.period_s, state, sample_rate_hz=0).final_state
        if k >= 30:
            gone.append(math.hypot((state.displacement_m - orbit.state.displacement_m) / size,
                                   (state.velocity_m_s - orbit.state.velocity_m_s)
                                   / (size * exc.omega_rad_s)))
    assert max(gone) > 1e-3  # (from 1e-11: it settles about 1e-2 away, on the motion that does settle)


def test_an_orbit_returns_to_its_state():
    osc = pd_.presets.paper_damped()
    orbit = pd_.periodic_orbit(osc, pd_.Harmonic(0.05, 1.5), settle_cycles=4)
    assert orbit.converged and orbit.iterations >= 1 and orbit.contacts_per_period == 2
    end = orbit.run.final_state.vector
    size = orbit.excursion_m
    assert abs(end[I_D] - orbit.state.displacement_m) < 1e-8 * size
    assert abs(end[I_V] - orbit.state.velocity_m_s) < 1e-8 * size * 2 * math.pi * 1.5
    assert orbit.residual <= 1e-10
    np.testing.assert_allclose(orbit.impact_velocities_m_s.size, 2)
    assert orbit.eta == pytest.approx(orbit.excursion_m / 0.03)


def test_systems_with_nonlinear_laws_use_finite_differences():
    b = pd_.Bumpers(0.015, 0.015, pd_.Hertzdamp(5e8, 0.8, 1.5))
    osc = pd_.Oscillator(500.0, pd_.Isolator([38e3, 18e3, 2e3], [0.015, 0.04], "kinematic", 1000.0), b)
    orbit = pd_.periodic_orbit(osc, pd_.Harmonic(0.05, 1.5), settle_cycles=10, tol=1e-8)
    assert orbit.method == "finite-difference" and orbit.converged, orbit.message
    assert orbit.contacts_per_period > 0 and orbit.stable
    with pytest.raises(pd_.InputError, match="Hertzdamp"):
        pd_.periodic_orbit(osc, pd_.Harmonic(0.05, 1.5), method="exact")


def test_a_bouc_wen_isolator_returns_its_z_too():
    iso = pd_.Isolator([20e3], [], "elastic", 300.0, bouc_wen=pd_.BoucWen(2e4, 0.005))
    osc = pd_.Oscillator(500.0, iso, pd_.Bumpers(0.03, 0.03, pd_.KelvinVoigt(1.4e6, 500.0)))
    exc = pd_.Harmonic(0.1, 1.2)
    orbit = pd_.periodic_orbit(osc, exc, settle_cycles=3, tol=1e-8)
    assert orbit.converged and orbit.method == "finite-difference" and "z" in orbit.coordinates, orbit.message
    end = orbit.run.final_state
    assert abs(end.bouc_wen_z - orbit.state.bouc_wen_z) < 1e-7
    settled = pd_.periodic_orbit(osc, exc, settle_cycles=300, tol=1e-8)
    assert orbit.alpha == pytest.approx(settled.alpha, rel=1e-6)


def test_a_branch_change_at_rest_and_steps_across_breakpoints():
    """The elastic rule: a guess at rest on a breakpoint (the engine changes branch at V = 0, toward
    the acceleration) and Newton steps that cross breakpoints (the branch follows D)."""
    osc = pd_.presets.paper_damped(bumpers=False, hysteresis="elastic")
    for d, phase in ((-0.015, math.pi / 2), (0.015, -math.pi / 2)):
        orbit = pd_.periodic_orbit(osc, pd_.Harmonic(-0.3, 1.0, phase=phase),
                                   guess=pd_.State.at_rest(osc, 0.0, d, 0.0))
        assert orbit.converged and orbit.method == "exact", orbit.message


def test_a_section_inside_a_contact_reports_the_orbit_s_own_contacts():
    osc = pd_.presets.paper_damped()
    exc = pd_.Harmonic(0.05, 1.5)
    run = pd_.simulate(osc, exc, 60.0 / 1.5, sample_rate_hz=0)
    t_mid = 0.5 * (run.contact_table[-1, 1] + run.contact_table[-1, 2])  # (the middle of a contact)
    guess = pd_.simulate(osc, exc, t_mid, sample_rate_hz=0).final_state
    assert any(guess.in_contact)
    orbit = pd_.periodic_orbit(osc, exc, guess=guess)
    assert orbit.converged and orbit.contacts_per_period == 2
    v = orbit.impact_velocities_m_s
    assert v[0] == pytest.approx(-v[1], rel=1e-6)  # (mirror symmetry of the paper's system)


@pytest.mark.parametrize("kwargs, words", [
    ({"samples_per_period": 10**9}, "samples_per_period"),
    ({"method": np.array(["exact"])}, "method"),
    ({"tol": float("nan")}, "tol"),
    ({"guess": pd_.State.at_rest(pd_.Oscillator(500.0, pd_.Isolator([1e4], [], "elastic", 1.0), None))},
     "guess"),
    ({"excitation": "harmonic"}, "excitation"),
    ({"period_multiple": 0}, "period_multiple"),
    ({"tol": -1.0}, "tol"),
    ({"method": "newton"}, "method"),
    ({"guess": (0.0, 0.0)}, "guess"),
    ({"max_iter": 2.5}, "max_iter"),
])
def test_bad_arguments_are_named(kwargs, words):
    args = {"system": pd_.presets.paper_damped(), "excitation": pd_.Harmonic(0.05, 1.5)}
    args.update(kwargs)
    with pytest.raises(pd_.InputError, match=words):
        pd_.periodic_orbit(args.pop("system"), args.pop("excitation"), **args)


def test_an_orbit_plots():
    import matplotlib

    matplotlib.use("Agg")
    orbit = pd_.periodic_orbit(pd_.presets.paper_damped(), pd_.Harmonic(0.05, 1.5))
    artists = pd_.plots.plot_orbit(orbit, c="k", ls=":")
    assert artists[0].get_linestyle() == ":" and artists[0].get_color() == "k"
    assert len(artists[2].get_xdata()) == 2  # (the two contacts' starts)
    assert math.isnan(pd_.periodic_orbit(pd_.presets.paper_damped(), pd_.Harmonic(0.0, 1.5)).alpha)
