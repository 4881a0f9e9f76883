"""Lyapunov exponents of structures of several masses, from the exact n-dof tangent dynamics.

- Closed form: a linear structure's exponents are the real parts of its state matrix's eigenvalues, from the
  first period on (the frame measured in its real modal coordinates).
- Exact against finite differences of the engine's map, on a chaotic impacting response.
- N = 1: a one-level structure on a periodic response has the oscillator's exponents (its Floquet values).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pounding as pd_


@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 5), a_g=st.floats(0.05, 0.5),
       freq=st.floats(0.3, 4.0))
def test_a_linear_structure_has_the_real_parts_of_its_eigenvalues(seed, n, a_g, freq):
    rng = np.random.default_rng(seed)
    mass = rng.uniform(300.0, 3000.0, n)
    iso = pd_.Isolator([rng.uniform(2e4, 1e5) * n], [], damping_n_s_m=rng.uniform(1e2, 3e3))
    k, c = rng.uniform(5e5, 5e6, n - 1), rng.uniform(1e2, 3e3, n - 1)
    b = pd_.Structure(mass[0], iso, [pd_.Storey(*v) for v in zip(mass[1:], k, c)])
    spec = pd_.lyapunov(b, pd_.Harmonic(a_g, freq), cycles=5, transient_cycles=0, align_cycles=0)
    m = b.masses_kg
    k = b.stiffness_matrix.copy()
    c = b.damping_matrix.copy()
    k[0, 0] += iso.slopes_n_m[0]
    c[0, 0] += iso.damping_n_s_m
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-k / m[:, None], -c / m[:, None]]])
    expected = np.sort(np.linalg.eigvals(a).real)[::-1]
    assert spec.method == "exact" and spec.coordinates[:2] == ("x_0", "x_1")
    scale = np.abs(expected).max()
    for row in spec.history:  # every period's estimate, the first included
        np.testing.assert_allclose(np.sort(row)[::-1], expected, rtol=0, atol=1e-9 * scale)


def _chaotic() -> pd_.Structure:
    stop = pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(1.0e8, 2.0e4))
    iso = pd_.Isolator(slopes_n_m=[2e5, 5e4], breakpoints_m=[0.005], damping_n_s_m=4e3)
    return pd_.Structure(2.0e3, iso, [pd_.Storey(1.0e3, 2.0e6, 2.0e3)], [stop])


def test_a_chaotic_impacting_building_exact_against_finite_differences():
    exc = pd_.Harmonic(0.2, 1.5)
    exact = pd_.lyapunov(_chaotic(), exc, cycles=60)
    fd = pd_.lyapunov(_chaotic(), exc, cycles=60, method="finite-difference")
    assert exact.method == "exact" and fd.method == "finite-difference"
    assert exact.period == 0 and exact.largest > 1.0  # (chaos: a positive exponent)
    finite = np.isfinite(exact.exponents)
    assert (finite == np.isfinite(fd.exponents)).all()
    np.testing.assert_allclose(exact.exponents[finite], fd.exponents[finite], rtol=0,
                               atol=1e-5 * np.abs(exact.exponents[finite]).max())
    # where the count ended: the structure's state after the transient, the alignment and the count
    assert isinstance(exact.final_state, pd_.State)
    assert exact.final_state.time_s == pytest.approx((200 + 20 + 60) / 1.5, abs=1e-9)


def test_one_level_on_a_periodic_response_has_the_oscillators_exponents():
    osc = pd_.presets.paper_damped()
    exc = pd_.Harmonic(0.05, 1.5)
    one = pd_.lyapunov(osc, exc, cycles=60)
    many = pd_.lyapunov(pd_.Structure.from_oscillator(osc), exc, cycles=60)
    assert one.period == many.period == 1
    np.testing.assert_allclose(many.exponents, one.exponents, rtol=1e-9)
    assert len(many.coordinates) == len(one.coordinates)


def test_a_state_of_one_mass_is_refused_for_a_structure():
    with pytest.raises(pd_.InputError, match="state"):
        pd_.lyapunov(_chaotic(), pd_.Harmonic(0.2, 1.5), state=pd_.State.at_rest(pd_.presets.paper_damped()))
