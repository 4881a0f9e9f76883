"""A soft-impact oscillator of the literature: the Aberdeen rig of Ing, Pavlovskaia, Wiercigroch &
Banerjee (Phil. Trans. R. Soc. A 366, 2008, 679-705), as nondimensionalised there and in
Kundu, Banerjee, Ing, Pavlovskaia & Wiercigroch, "Singularities in soft-impacting systems",
Physica D 241 (2012) 553-565:

    x'' + 2 zeta x' + x + beta (x - 1) H(x - 1) = f cos(omega t),  zeta = 0.01, beta = 29

(the values as in github.com/Tudesz/PWSDDE-cont, bld_osc_demo.m, with its delayed feedback off).
In pounding: mass 1 kg, natural frequency 10 Hz, gap e = 1.26 mm on the right (the left stop out of
reach), a Kelvin-Voigt stop of stiffness beta k1 without damper (relaxed at contact), base
acceleration of amplitude f e omega_n^2.  docs/periodic.md gives the mapping.

Kundu et al. report (abstract): the period-1 orbit persists across grazing when m = 2 omega_0 /
omega is an integer, and changes abruptly (to a high-period or chaotic orbit) otherwise; and the
determinant of the map's Jacobian varies continuously across grazing.  Both are reproduced here,
with the grazing amplitude against its closed form.  No numeric period-doubling value of this
model could be found in a readable source (the check against an independent piecewise closed-form
solver is the last test).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import pounding as pd_

M, FN = 1.0, 10.0
WN = 2 * math.pi * FN
ZETA, BETA, E = 0.01, 29.0, 0.00126


def rig() -> pd_.Oscillator:
    iso = pd_.Isolator(slopes_n_m=[M * WN**2], breakpoints_m=[], hysteresis="elastic",
                       damping_n_s_m=2 * ZETA * M * WN)
    stop = pd_.KelvinVoigt(stiffness=BETA * M * WN**2, damping=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pd_.PoundingWarning)  # (the left gap is implausibly wide on purpose)
        return pd_.Oscillator(M, iso, pd_.Bumpers(gap_left_m=0.4, gap_right_m=E, law=stop))


def a_g_of(f: float) -> float:
    return f * E * WN**2 / pd_.Harmonic(1.0, 1.0).peak_m_s2


def f_of(a_g: float) -> float:
    return a_g / a_g_of(1.0)


def branch(omega: float, f_range: tuple[float, float]) -> pd_.Branch:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pd_.PoundingWarning)
        return pd_.continuation(rig(), (a_g_of(f_range[0]), a_g_of(f_range[1])), omega * FN, parameter="a_g",
                                max_step=0.01)


@pytest.fixture(scope="module")
def m_half_integer() -> pd_.Branch:  # omega = 0.8: m = 2.5
    return branch(0.8, (0.3, 0.7))


@pytest.fixture(scope="module")
def m_integer() -> pd_.Branch:  # omega = 0.5: m = 4
    return branch(0.5, (0.6, 1.2))


def grazing_f(omega: float) -> float:
    """The forcing at which the non-impacting orbit's amplitude is the gap (closed form)."""
    return math.hypot(1.0 - omega**2, 2.0 * ZETA * omega)


@pytest.mark.parametrize("name, omega", [("m_half_integer", 0.8), ("m_integer", 0.5)])
def test_grazing_amplitude_is_the_closed_form(name: str, omega: float,
                                              request: pytest.FixtureRequest) -> None:
    br = request.getfixturevalue(name)
    graze = [b for b in br.bifurcations if b.kind == "grazing"]
    assert br.success and len(graze) == 1 and graze[0].side == "wall0_right"
    assert f_of(graze[0].a_g) == pytest.approx(grazing_f(omega), rel=2e-6)


def test_non_integer_m_changes_abruptly_at_grazing(m_half_integer: pd_.Branch) -> None:
    """m = 2.5: the period-1 orbit period-doubles within 0.1 % above grazing."""
    f_g = grazing_f(0.8)
    pds = [f_of(b.a_g) for b in m_half_integer.bifurcations if b.kind == "period-doubling"]
    assert pds and f_g < pds[0] < 1.001 * f_g
    df = m_half_integer.to_dataframe()
    after = df[(df.a_g > a_g_of(1.001 * f_g)) & (df.a_g < a_g_of(0.6))]
    assert len(after) and not after.stable.any()


def test_integer_m_keeps_the_period_one_orbit_across_grazing(m_integer: pd_.Branch) -> None:
    """m = 4: the period-1 orbit stays stable well beyond grazing (to 1.08, 44 % above it)."""
    f_g = grazing_f(0.5)
    df = m_integer.to_dataframe()
    across = df[(df.a_g > a_g_of(0.9 * f_g)) & (df.a_g < a_g_of(1.4 * f_g))]
    assert across.contacts_per_period.max() == 1 and across.contacts_per_period.min() == 0
    assert across.stable.all()
    first = min(f_of(b.a_g) for b in m_integer.bifurcations if b.kind != "grazing")
    assert first > 1.4 * f_g


@pytest.mark.parametrize("name, omega", [("m_half_integer", 0.8), ("m_integer", 0.5)])
def test_the_determinant_is_continuous_across_grazing(name: str, omega: float,
                                                      request: pytest.FixtureRequest) -> None:
    """Without a damper in the stop the map's Jacobian keeps det = exp(-2 zeta T), contacts or not."""
    br = request.getfixturevalue(name)
    det = np.prod(br.multipliers[:, :2], axis=1).real
    assert np.allclose(det, math.exp(-2.0 * ZETA * 2.0 * math.pi / omega), rtol=1e-7, atol=0)


@pytest.mark.parametrize("name, independent", [("m_integer", (1.081078, 1.091370)),
                                               ("m_half_integer", (0.360605, 0.616715))])
def test_period_doublings_are_located_where_a_multiplier_is_minus_one(name: str, independent: tuple,
                                                                      request: pytest.FixtureRequest) -> None:
    """The period-doublings as an independent solver finds them (the regimes' closed forms, the
    switching at x = 1 by root finding, Newton on the map, 1 + tr J + det J = 0 by Brent; its values
    printed to 6 decimals): at omega = 0.5 the orbit loses stability at f = 1.081078 and regains it at
    1.091370; at omega = 0.8 it loses it 0.07 % above grazing and regains it at 0.616715.  (The
    regaining ones were once reported at a branch point past them, and the one next to grazing
    where the steps across grazing failed.)"""
    pds = [b for b in request.getfixturevalue(name).bifurcations if b.kind == "period-doubling"]
    assert len(pds) == 2 and all(b.located for b in pds)
    for b, f_independent in zip(pds, independent):
        assert f_of(b.a_g) == pytest.approx(f_independent, abs=1e-6)
        assert np.min(np.abs(b.multipliers + 1.0)) < 1e-6
