"""Periodic orbits of structures of several masses: Newton shooting with the exact n-dof monodromy.

- Closed form: a linear structure without contacts under a sine is on its frequency response (every
  level, 1e-10) and its Floquet multipliers are exp(lambda T) of the state matrix's eigenvalues (1e-10).
- The monodromy composed from state-transition and saltation matrices equals finite differences of the
  engine's map (random structures of 2-5 masses, Kelvin-Voigt walls at any level or a link between two
  structures, multi-linear kinematic or elastic isolators and storeys), where the map is differentiable at
  the differences' scale.
- N = 1: a one-level structure is the oscillator, orbit for orbit (the same numbers to 1e-12).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding.analysis._shooter import _Shooter as _StructureShooter
from strategies import oscillators


def _linear(rng: np.random.Generator, n: int, rayleigh: bool) -> pd_.Structure:
    mass = rng.uniform(300.0, 3000.0, n)
    k = rng.uniform(5e5, 5e6, n - 1)
    c = rng.uniform(0.0, 3e3, n - 1)
    iso = pd_.Isolator([rng.uniform(2e4, 1e5) * n], [], damping_n_s_m=rng.uniform(1e2, 3e3))
    if rayleigh and n > 2:
        return pd_.Structure(mass[0], iso, [pd_.Storey(m, kk) for m, kk in zip(mass[1:], k)],
                             rayleigh=(0.02, 0.05))
    return pd_.Structure(mass[0], iso, [pd_.Storey(*v) for v in zip(mass[1:], k, c)])


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 5), rayleigh=st.booleans(),
       a_g=st.floats(0.05, 0.5), freq=st.floats(0.3, 4.0), phase=st.floats(0.0, 6.0))
def test_a_linear_structure_is_on_its_frequency_response_with_multipliers_exp_lambda_t(seed, n, rayleigh, a_g,
                                                                                       freq, phase):
    rng = np.random.default_rng(seed)
    b = _linear(rng, n, rayleigh)
    exc = pd_.Harmonic(a_g, freq, phase=phase)
    guess = pd_.State.at_rest(b)
    orbit = pd_.periodic_orbit(b, exc, guess=guess)
    assert orbit.converged and orbit.method == "exact", orbit.message
    # the frequency response: M x'' + C x' + K x = -M 1 A sin(w t + phase)
    m = np.diag(b.masses_kg)
    k = b.stiffness_matrix.copy()
    c = b.damping_matrix.copy()
    k[0, 0] += b.isolator.slopes_n_m[0]
    c[0, 0] += b.isolator.damping_n_s_m
    w, amp = exc.omega_rad_s, exc.peak_m_s2
    h = np.linalg.solve(k - w**2 * m + 1j * w * c, -m @ np.ones(n) * amp)  # x = Im(h e^(i(w t + phase)))
    t0 = orbit.state.time_s
    z = h * np.exp(1j * (w * t0 + phase))
    scale = np.abs(h).max()
    assert np.abs(orbit.state.displacements_m - z.imag).max() <= 1e-10 * scale
    assert np.abs(orbit.state.velocities_m_s - (1j * w * z).imag).max() <= 1e-10 * scale * w
    # the multipliers: exp(lambda T), lambda the state matrix's eigenvalues
    a = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(m, k), -np.linalg.solve(m, c)]])
    expected = np.linalg.eigvals(scipy.linalg.expm(a * orbit.period_s))
    got = orbit.multipliers
    assert got.size == 2 * n, orbit.coordinates
    for mu in expected:
        assert np.abs(got - mu).min() <= 1e-10 * max(1.0, abs(mu)), (got, expected)
    assert orbit.stable


def _isolator(rng: np.random.Generator, rule: str, scale: float) -> pd_.Isolator:
    k1 = rng.uniform(3e4, 1e5) * scale
    return pd_.Isolator([k1, k1 * rng.uniform(0.1, 0.5)], [rng.uniform(0.002, 0.01)], hysteresis=rule,
                        damping_n_s_m=rng.uniform(1e2, 1e3))


@st.composite
def impacting(draw, where: str, rule: str):
    """A structure of 2-5 masses on a bilinear isolator (and a bilinear storey) with a Kelvin-Voigt wall at a
    level, or an isolated building linked to a fixed-base one; a sine strong enough to reach the contacts."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    n = draw(st.integers(2, 5))
    mass = rng.uniform(300.0, 2000.0, n)
    law = pd_.KelvinVoigt(rng.uniform(1e6, 2e7), rng.uniform(1e2, 3e3))
    k, c = rng.uniform(3e5, 3e6, n - 1), rng.uniform(1e2, 2e3, n - 1)
    exc = pd_.Harmonic(draw(st.floats(0.1, 0.5)), draw(st.floats(0.5, 2.5)))
    if where == "wall":
        storeys = [pd_.Storey(*v) for v in zip(mass[1:], k, c)]
        if draw(st.booleans()):  # a storey of its own hysteresis
            s = storeys[0]
            storeys[0] = pd_.Storey(s.mass_kg, s.stiffness_n_m, s.damping_n_s_m,
                                    slopes_after_n_m=(0.3 * s.stiffness_n_m,), breakpoints_m=(0.002,),
                                    hysteresis=rule)
        gap = draw(st.floats(0.005, 0.03))
        stand = (pd_.Stand(rng.uniform(5.0, 50.0), rng.uniform(1e6, 1e7), rng.uniform(10.0, 500.0))
                 if draw(st.booleans()) else None)  # (the bumpers on stands of their own: two more masses)
        model = pd_.Structure(mass[0], _isolator(rng, rule, n), storeys,
                              [pd_.Wall(draw(st.integers(0, n - 1)), gap, gap, law, stand=stand)])
        return model, exc
    if where == "fixed":  # a fixed base whose first storey yields, a stop at a floor
        storeys = [pd_.Storey(*v) for v in zip(mass[1:], k * 3, c)]
        s = storeys[0]
        storeys[0] = pd_.Storey(s.mass_kg, s.stiffness_n_m, s.damping_n_s_m, hysteresis=rule,
                                slopes_after_n_m=(0.3 * s.stiffness_n_m,), breakpoints_m=(0.002,))
        gap = draw(st.floats(0.003, 0.02))
        model = pd_.Structure.fixed_base(storeys, [pd_.Wall(draw(st.integers(1, n - 1)), gap, gap, law)])
        return model, exc
    n1 = draw(st.integers(1, n - 1))
    first = pd_.Structure(mass[0], _isolator(rng, rule, n1),
                          [pd_.Storey(*v) for v in zip(mass[1:n1], k[:n1 - 1], c[:n1 - 1])])
    second = pd_.Structure.fixed_base([pd_.Storey(*v) for v in zip(mass[n1:], k[n1 - 1:] * 3, c[n1 - 1:])]
                                      + ([pd_.Storey(1000.0, 3e6, 500.0)] if n - n1 == 0 else []))
    link = pd_.Link(draw(st.integers(0, n1 - 1)), draw(st.integers(1, second.n_levels - 1)),
                    draw(st.floats(0.003, 0.02)), law)
    return pd_.Adjacent(first, second, [link]), exc


def _fd(sh: _StructureShooter, vec: np.ndarray, step: float) -> np.ndarray:
    free, emb = sh._layout(vec)
    sh.scale_d = step / 1e-6
    return sh.differences(vec, free, emb)[free]


@pytest.mark.parametrize("where", ["wall", "link", "fixed"])
@pytest.mark.parametrize("rule", ["kinematic", "elastic"])
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                 HealthCheck.filter_too_much])
@given(data=st.data(), settle=st.integers(3, 15))
def test_exact_monodromy_equals_finite_differences_of_the_engine(where, rule, data, settle):
    model, exc = data.draw(impacting(where, rule))
    period = 1.0 / exc.freq_hz
    vec = np.array(pd_.simulate(model, exc, settle * period, sample_rate_hz=0).final_state.vector)
    sh = _StructureShooter(model, exc, period, exact=True)
    end, run = sh._image(vec)
    actions = set(run.event_table[:, 1].astype(int).tolist())
    assume(pd_.analysis._hybrid.ACT_CONTACT in actions)
    size = sh._size_of(run)
    sh.scale_d = size
    exact = sh.jacobian(vec, run, ())
    assert sh.exact, sh.fell_back
    fd1, fd2 = _fd(sh, vec, 1e-6 * size), _fd(sh, vec, 5e-7 * size)
    norm = np.abs(fd1).max()
    assume(np.abs(fd1 - fd2).max() <= 1e-7 * norm)  # (no grazing within the differences' reach)
    assert np.abs(exact - fd1).max() <= 1e-5 * norm, (sh.names(vec), exact, fd1)
    # the modes' propagation ends where the engine ends (each coordinate to 1e-8 of the orbit's size)
    _, x_end = sh._propagate(vec, run)
    tail = sh.coords(end)
    scale = np.full(tail.size, size)
    scale[sh.n:2 * sh.n] = np.maximum(size * exc.omega_rad_s, np.abs(tail[sh.n:2 * sh.n]))
    assert (np.abs(x_end - tail) <= 1e-8 * scale).all(), (x_end - tail, scale)


@settings(max_examples=15, deadline=None)
@given(osc=oscillators(hysteresis="kinematic"), a_g=st.floats(0.05, 0.4), freq=st.floats(0.8, 3.0))
def test_one_level_structure_is_the_oscillator_orbit_for_orbit(osc, a_g, freq):
    exc = pd_.Harmonic(a_g, freq)
    one = pd_.periodic_orbit(osc, exc, settle_cycles=20)
    b = pd_.Structure.from_oscillator(osc)
    state = pd_.State._of(np.array(pd_.simulate(osc, exc, 20 / freq, sample_rate_hz=0).final_state.vector),
                          ((0,),), pd_.State.at_rest(b).layout)
    many = pd_.periodic_orbit(b, exc, guess=state)
    assert one.method == many.method and one.iterations == many.iterations
    assert one.converged == many.converged
    np.testing.assert_allclose(many.state.vector, one.state.vector, rtol=0, atol=1e-12)
    assert many.monodromy.shape == one.monodromy.shape
    np.testing.assert_allclose(many.monodromy, one.monodromy, rtol=0,
                               atol=1e-12 * max(1.0, np.abs(one.monodromy).max()))
    assert many.coordinates == one.coordinates  # (one vocabulary: a single mass is a one-level structure)
    # what an orbit says of its motion, per level (one here)
    assert many.contacts_per_period == one.contacts_per_period
    np.testing.assert_allclose(many.impact_velocities_m_s, one.impact_velocities_m_s, rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(many.alpha, [one.alpha], rtol=1e-8)
    np.testing.assert_allclose(many.excursion_m, [one.excursion_m], rtol=1e-8, atol=1e-14)


def _moat() -> pd_.Structure:
    iso = pd_.Isolator(slopes_n_m=[2.0e5], breakpoints_m=[], damping_n_s_m=4.0e3)
    stop = pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(1.0e8, 2.0e4))
    return pd_.Structure(2.0e3, iso, [pd_.Storey(1.0e3, 2.0e6, 2.0e3)], [stop])


def test_an_impacting_orbit_of_a_building_and_of_a_pair():
    orbit = pd_.periodic_orbit(_moat(), pd_.Harmonic(0.1, 1.5))
    assert orbit.converged and orbit.method == "exact" and orbit.contacts_per_period == 2
    assert orbit.coordinates == ("x_0", "x_1", "v_0", "v_1", "delta_wall0_left", "delta_wall0_right")
    # a period on from the orbit's state is the orbit's state
    again = pd_.simulate(_moat(), pd_.Harmonic(0.1, 1.5), orbit.period_s, orbit.state, sample_rate_hz=0)
    assert np.abs(again.final_state.displacements_m - orbit.state.displacements_m).max() <= 1e-9 * 0.02
    fd = pd_.periodic_orbit(_moat(), pd_.Harmonic(0.1, 1.5), method="finite-difference")
    assert fd.method == "finite-difference"
    assert np.abs(fd.monodromy - orbit.monodromy).max() <= 1e-6 * np.abs(orbit.monodromy).max()
    iso = pd_.Isolator(slopes_n_m=[4.0e5, 1.0e5], breakpoints_m=[0.01], damping_n_s_m=2.0e3)
    first = pd_.Structure(3.0e3, iso, [pd_.Storey(2.0e3, 4.0e6, 2.0e3)])
    second = pd_.Structure.fixed_base([pd_.Storey(2.0e3, 6.0e6, 3.0e3)] * 2)
    pair = pd_.Adjacent(first, second, [pd_.Link(1, 1, 0.01, pd_.KelvinVoigt(5.0e7, 1.0e4))])
    orbit = pd_.periodic_orbit(pair, pd_.Harmonic(0.3, 1.2))
    assert orbit.converged and orbit.method == "exact", orbit.message
    # (the link's compression relaxes between contacts: a coordinate; the isolator's spring slips and
    # sticks over the period: its slip one too)
    assert orbit.coordinates == ("x_first.0", "x_first.1", "x_second.1", "x_second.2", "v_first.0",
                                 "v_first.1", "v_second.1", "v_second.2", "delta_link0", "u_0")
    assert orbit.contacts_per_period == 3 and len(orbit.run.link_table) > 0
    # per level, the first's then the second's; the contacts at walls and links, in the order they began
    assert orbit.alpha.shape == orbit.excursion_m.shape == (5,)
    np.testing.assert_array_equal(orbit.excursion_m[2:], orbit.run.second.displacement_max
                                  - orbit.run.second.displacement_min)
    assert orbit.impact_velocities_m_s.shape == (3,)


def test_refusals_name_the_field_and_the_fix():
    b = _moat()
    with pytest.raises(pd_.InputError, match="excitation"):
        pd_.periodic_orbit(b, pd_.Record(np.array([0.0, 0.01, 0.02]), np.array([0.0, 1.0, 0.0])))
    with pytest.raises(pd_.InputError, match="state"):
        pd_.periodic_orbit(b, pd_.Harmonic(0.1, 1.5), guess=pd_.State.at_rest(pd_.presets.paper_damped()))
    hc = pd_.Structure(2.0e3, b.isolator, b.storeys,
                       [pd_.Wall(1, 0.02, 0.02, pd_.HuntCrossley(1e9, 1.5, 1e9))])
    with pytest.raises(pd_.InputError, match="wall 0's left law: HuntCrossley"):
        pd_.periodic_orbit(hc, pd_.Harmonic(0.1, 1.5), method="exact")
    orbit = pd_.periodic_orbit(hc, pd_.Harmonic(0.1, 1.5), settle_cycles=30)
    assert orbit.method == "finite-difference" and orbit.converged, orbit.message
    with pytest.raises(pd_.InputError, match="period_multiple"):
        pd_.periodic_orbit(b, pd_.Harmonic(0.1, 1.5), period_multiple=0)


def test_the_orbit_plots_each_level_in_its_phase_plane():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    orbit = pd_.periodic_orbit(_moat(), pd_.Harmonic(0.1, 1.5))
    assert orbit.plot().__class__.__name__ == "Figure"
    artists = pd_.plots.plot_orbit(orbit)
    ax = artists[0].axes
    assert len(artists) == len(ax.get_lines()) == 4
    assert "2 contacts per period" in ax.get_title()
    assert math.isclose(ax.get_lines()[0].get_xdata()[0], orbit.state.displacements_m[0] * 1e3)
    with pytest.warns(FutureWarning, match="plot_orbit"):  # (its name before, returning the Axes)
        assert len(pd_.plots.plot_structure_orbit(orbit).get_lines()) == 4


def test_one_orbit_class_for_every_system():
    """A structure's orbit is a PeriodicOrbit, its alpha, excursion and eta per level (eta over the gap of
    the wall at that level, NaN without one); a one-level structure's numbers are its oscillator's to the
    bit, as floats for the single mass; the old class name answers with a FutureWarning."""
    osc = pd_.presets.paper_damped()
    h = pd_.Harmonic(0.05, 1.5)
    one, level = pd_.periodic_orbit(osc, h), pd_.periodic_orbit(pd_.Structure.from_oscillator(osc), h)
    assert isinstance(one.alpha, float) and isinstance(one.eta, float)
    assert level.alpha.shape == level.eta.shape == level.excursion_m.shape == (1,)
    assert (one.alpha, one.excursion_m, one.eta) == (level.alpha[0], level.excursion_m[0], level.eta[0])
    assert one.eta == one.excursion_m / osc.bumpers.total_gap
    orbit = pd_.periodic_orbit(_moat(), pd_.Harmonic(0.1, 1.5))
    walls = {w.level: w.gap_left_m + w.gap_right_m for w in _moat().walls}
    expected = [orbit.excursion_m[lv] / walls[lv] if lv in walls else math.nan
                for lv in range(orbit.excursion_m.size)]
    np.testing.assert_array_equal(orbit.eta, expected)
    with pytest.warns(FutureWarning, match="PeriodicOrbit"):
        assert pd_.StructurePeriodicOrbit is pd_.PeriodicOrbit
    with pytest.warns(FutureWarning, match="PeriodicOrbit"):
        assert pd_.analysis.StructurePeriodicOrbit is pd_.PeriodicOrbit
