"""The event locator's first guess: the root of the cubic through both ends' values and rates."""

import math

import numba
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pounding.engine._trajectory import _cubic_root


@numba.njit
def cubic_root(fa, fb, sa, sb):
    return _cubic_root(fa, fb, sa, sb)  # (compiled-only functions have no Python wrapper)


@settings(max_examples=200, deadline=None)
@given(root=st.floats(0.05, 0.95), c2=st.floats(-0.5, 0.5), c3=st.floats(-0.3, 0.3))
def test_the_guess_for_a_cubic_is_its_root(root, c2, c3):
    # p(t) = (t - root)(1 + c2 t + c3 t^2): one root in (0, 1), the quadratic factor stays positive
    def p(t):
        return (t - root) * (1.0 + c2 * t + c3 * t * t)

    def dp(t):
        return (1.0 + c2 * t + c3 * t * t) + (t - root) * (c2 + 2.0 * c3 * t)

    # three Newton steps from the secant's root: far closer than the guess needs to be (the
    # locator's Newton iterations finish the job), and than the secant's
    guess = cubic_root(p(0.0), p(1.0), dp(0.0), dp(1.0))
    assert guess == pytest.approx(root, abs=1e-9)
    assert abs(guess - root) <= abs(cubic_root(p(0.0), p(1.0), math.nan, math.nan) - root)


@pytest.mark.parametrize("h", [0.4, 0.2, 0.1])
def test_the_cubic_guess_converges_at_fourth_order_where_the_secant_does_at_second(h):
    # sin on [pi - 0.3 h, pi + 0.7 h]: the guess's error relative to the interval length
    a = math.pi - 0.3 * h
    fa, fb = math.sin(a), math.sin(a + h)
    secant = cubic_root(fa, fb, math.nan, math.nan)
    cubic = cubic_root(fa, fb, h * math.cos(a), h * math.cos(a + h))
    exact = 0.3
    assert secant == pytest.approx(fa / (fa - fb), abs=0.0)
    assert abs(secant - exact) > 1e-2 * h**2
    assert abs(cubic - exact) < 1e-2 * h**4
