"""The event locator's first guess: inverse cubic interpolation through both ends' values and rates."""

import math

import pytest
from scipy.optimize import brentq

from pounding._core import root_guess


FUNCTIONS = {  # f, f': smooth, monotone and curved (f'' != 0) about their root in (0, 4)
    "cos": (lambda x: math.cos(x) - 0.5, lambda x: -math.sin(x)),
    "exp": (lambda x: math.exp(x) - 2.0, math.exp),
    "cubic": (lambda x: x + 0.5 * x * x + 0.3 * x**3 - 1.0, lambda x: 1.0 + x + 0.9 * x * x),
}


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_the_guess_converges_at_fourth_order_where_the_secant_does_at_second(name):
    f, df = FUNCTIONS[name]
    root = brentq(f, 0.0, 4.0, xtol=1e-15)
    errors = {"secant": [], "guess": []}
    for h in (0.4, 0.2, 0.1, 0.05):
        a = root - 0.3 * h  # the root 30 % into [a, a + h]
        fa, fb = f(a), f(a + h)
        errors["secant"].append(abs(root_guess(fa, fb, math.nan, math.nan) - 0.3) * h)
        errors["guess"].append(abs(root_guess(fa, fb, h * df(a), h * df(a + h)) - 0.3) * h)
    # halving h divides the error by 4 (secant) and by 16 (the guess), give or take
    for kind, order in (("secant", 2), ("guess", 4)):
        ratios = [e0 / e1 for e0, e1 in zip(errors[kind], errors[kind][1:])]
        assert all(0.6 * 2**order < r < 1.6 * 2**order for r in ratios), (kind, ratios)
    assert errors["guess"][-1] < 1e-3 * errors["secant"][-1]


def test_without_usable_slopes_the_guess_is_the_secants_root():
    secant = 1.0 / 3.0  # values -1 and 2
    assert root_guess(-1.0, 2.0, math.nan, 3.0) == pytest.approx(secant, rel=1e-15)
    assert root_guess(-1.0, 2.0, 3.0, -1.0) == pytest.approx(secant, rel=1e-15)  # not monotone
    assert root_guess(-1.0, 2.0, 0.0, 3.0) == pytest.approx(secant, rel=1e-15)  # flat at one end
    # a guess outside the interval: slopes that bend the inverse cubic past an end
    assert root_guess(-1.0, 2.0, 100.0, 0.05) == pytest.approx(secant, rel=1e-15)


def test_a_stationary_value_at_the_root_follows_from_the_last_evaluation():
    from pounding._core import value_at_root as at_root

    # sin(t + 0.3) is stationary at t = pi/2 - 0.3; Newton last evaluated its rate 1e-4 s away
    root = 0.5 * math.pi - 0.3
    for x in (root - 1e-4, root + 1e-4):
        value, rate, rate_of_rate = math.sin(x + 0.3), math.cos(x + 0.3), -math.sin(x + 0.3)
        assert abs(value - 1.0) > 1e-9  # the value there is off by dt^2 / 2
        assert at_root(root, x, value, rate, rate_of_rate) == pytest.approx(1.0, abs=1e-15)
