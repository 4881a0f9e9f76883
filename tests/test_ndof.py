"""The core's structures of several masses (n = 2-6), through the core's door: a shear building on a linear
isolator with Kelvin-Voigt bumpers between its masses against an independent solve_ivp reference with events
(tests/reference_ndof.py; bumpers against the ground are drawn through the public path in
tests/test_structure.py), its frequency response in closed form, and its energy ledger.  A one-mass system
goes through the same code (every other test file)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings
from hypothesis import strategies as st

from pounding import _core
from pounding._control import new_control
from pounding.engine.layout import ACT_CONTACT, L_BUMPER, L_BUMPER_LOSS, L_HYSTERETIC, L_INPUT
from pounding.engine.layout import L_ISOLATOR, L_KINETIC, L_VISCOUS
from pounding._core import EXCITATION, Forcing
from pounding.engine.layout import DOF_EXTREMA_LEN, X_D_MAX, X_D_MIN
from reference_ndof import Structure, TouchAtRest, reference

KELVIN_VOIGT = _core.LAW_IDS["kelvin_voigt"]


def shear(values: np.ndarray) -> np.ndarray:
    """The matrix of springs (or dashpots) ``values[i]`` between storey i + 1 and storey i."""
    n = values.size + 1
    k = np.zeros((n, n))
    for i, s in enumerate(values):
        k[i, i] += s
        k[i + 1, i + 1] += s
        k[i, i + 1] -= s
        k[i + 1, i] -= s
    return k


def core_system(s: Structure, bumpers: bool = True):
    params = np.zeros(_core.LAYOUT["N_LAW_PARAMS"])
    params[:2] = s.k_b, s.c_b
    contacts = [_core.contact_slot(i=s.level, j=partner, sign=sign, gap_m=gap, law=KELVIN_VOIGT,
                                   params=params)
                for partner, sign, gap in zip(s.partners, (-1.0, 1.0), s.gaps)]
    isolator = _core.element(i=0, j=-1, c_d=s.c_iso, slopes=[s.k_iso], breaks=[], rule=1)
    return _core.system(s.mass, s.k0, s.c0, [isolator], bumpers, contacts)


def core_run(s: Structure, t_end: float, y0: np.ndarray, bumpers: bool = True, sample_dt: float = 0.0):
    sy = core_system(s, bumpers)
    lay = sy.layout
    state = np.zeros(lay["size"])
    state[lay["x"]:lay["x"] + y0.size] = y0
    forcing = Forcing(kind=EXCITATION["harmonic"], p=np.array([s.a_g, s.omega, 0.0]), rec_t=np.zeros(1),
                      rec_a=np.zeros(1))
    return sy, _core.run(sy, forcing, state, t_end, sample_dt, 1e-10, 10**6, True, new_control(10**9))


@st.composite
def structures(draw, n=None, n_max=6):
    n = draw(st.integers(2, n_max)) if n is None else n
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    mass = rng.uniform(100.0, 2000.0, n)
    k_storey = rng.uniform(1e5, 5e6, n - 1)
    c_storey = rng.uniform(0.0, 2e3, n - 1)
    gap = draw(st.floats(0.002, 0.02))
    return Structure(mass=mass, k0=shear(k_storey), c0=shear(c_storey), k_iso=rng.uniform(5e3, 5e4) * n,
                     c_iso=rng.uniform(0.0, 1e3), gaps=(gap, draw(st.floats(0.002, 0.02))),
                     k_b=draw(st.floats(1e6, 2e7)), c_b=draw(st.floats(1e2, 5e3)),
                     a_g=draw(st.floats(1.0, 4.0)), omega=2 * math.pi * draw(st.floats(0.5, 3.0)))


def contact_starts(out) -> np.ndarray:
    events = out.events
    return events[events[:, 1] == ACT_CONTACT]


def last_digit_spread(s: Structure, y0: np.ndarray, starts: np.ndarray, t_end: float = 3.0) -> float:
    """How far the contact starts move, s, when every mass changes in its last digits (relative +-4e-16):
    what the problem itself makes of rounding, whatever solves it (inf: a contact more or less)."""
    spread = 0.0
    for change in (4e-16, -4e-16):
        moved = contact_starts(core_run(dataclasses.replace(s, mass=s.mass * (1.0 + change)), t_end, y0)[1])
        if moved.shape != starts.shape:
            return math.inf
        spread = max(spread, float(np.abs(moved[:, 0] - starts[:, 0]).max(initial=0.0)))
    return spread


# (A random building's Kelvin-Voigt bumpers at its base, or at any level, against the reference: drawn once,
# through the public path, in tests/test_structure.py's test_a_wall_at_any_level_matches_the_reference.)


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(s=structures(n_max=9), v0=st.floats(-0.4, 0.4), data=st.data())
def test_bumpers_between_two_masses_match_the_reference(s, v0, data):
    # the bumpers on one mass, each against another mass or the ground (a contact pair i, j): the force on
    # both, the compression of their relative motion (from 6 masses on, a shear building's phases walk their
    # rows' nonzeros only: a bumper between distant masses is what the pattern must hold)
    n = s.mass.size
    level = data.draw(st.integers(0, n - 1))
    others = [-1] + [j for j in range(n) if j != level]
    s = dataclasses.replace(s, level=level, partners=(data.draw(st.sampled_from(others)),
                                                      data.draw(st.sampled_from(others))))
    assume(s.partners != (-1, -1))
    y0 = np.zeros(2 * n)
    y0[n + level] = v0  # (the bumpers' mass pushed: the pairs move apart and back)
    _, out = core_run(s, 2.0, y0)
    assert out.status == 0, out.status
    starts = contact_starts(out)
    try:
        ref = reference(s, 2.0, y0)
    except TouchAtRest:
        assume(False)
    assume(all(depth > 1e-7 for depth in ref.depths) and all(speed > 1e-4 for speed in ref.speeds))
    assume(len(ref.contact_starts) <= 40)
    assume(last_digit_spread(s, y0, starts, 2.0) <= 1e-10)
    event(f"{'contacts' if ref.contact_starts else 'no contact'}, "
          f"{'both' if -1 not in s.partners else 'one'} against a mass")
    assert [int(c) for c in starts[:, 2]] == [c for c, _ in ref.contact_starts]
    np.testing.assert_allclose(starts[:, 0], [t for _, t in ref.contact_starts], rtol=0, atol=1e-9)
    ledger = out.ledger
    residual = ledger[L_INPUT] - ledger[L_VISCOUS] - ledger[L_HYSTERETIC] - ledger[L_BUMPER_LOSS] - (
        ledger[L_KINETIC] + ledger[L_ISOLATOR] + ledger[L_BUMPER])
    assert abs(residual) <= 1e-9 * max(abs(ledger[L_INPUT]), abs(ledger[L_VISCOUS]), abs(ledger[L_KINETIC]))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(s=structures(), v0=st.floats(-0.4, 0.4))
def test_the_ledger_closes_over_every_mass_and_contact(s, v0):
    y0 = np.zeros(2 * s.mass.size)
    y0[s.mass.size:] = v0
    _, out = core_run(s, 3.0, y0)
    ledger = out.ledger
    flows = [ledger[k]
             for k in (L_INPUT, L_VISCOUS, L_HYSTERETIC, L_BUMPER_LOSS, L_KINETIC, L_ISOLATOR, L_BUMPER)]
    residual = ledger[L_INPUT] - ledger[L_VISCOUS] - ledger[L_HYSTERETIC] - ledger[L_BUMPER_LOSS] - (
        ledger[L_KINETIC] + ledger[L_ISOLATOR] + ledger[L_BUMPER])
    assert abs(residual) <= 1e-9 * max(abs(f) for f in flows)


@pytest.mark.parametrize("n", [2, 4, 6, 7, 8, 9])
def test_a_linear_structure_reaches_its_frequency_response(n):
    # no contacts: the steady state under a_g sin(w t) is Im(X e^(i w t)) with
    # (K - w^2 M + i w C) X = -M 1 a_g, every floor (n of 1 to 8: the core's kernels sized at compile time; 9:
    # sized at run time)
    rng = np.random.default_rng(n)
    mass = rng.uniform(200.0, 1000.0, n)
    k0, c0 = shear(rng.uniform(5e5, 2e6, n - 1)), shear(rng.uniform(500.0, 2e3, n - 1))
    s = Structure(mass=mass, k0=k0, c0=c0, k_iso=2e4 * n, c_iso=300.0 * n, gaps=(0.01, 0.01), k_b=1e6,
                  c_b=1e3, a_g=1.5, omega=2 * math.pi * 1.3)
    k = k0.copy()
    k[0, 0] += s.k_iso
    c = c0.copy()
    c[0, 0] += s.c_iso
    x = np.linalg.solve(k - s.omega**2 * np.diag(mass) + 1j * s.omega * c, -mass * s.a_g)
    # from the steady state's own start: x(0) = Im X, v(0) = w Re X
    y0 = np.concatenate([x.imag, s.omega * x.real])
    _, out = core_run(s, 5.0, y0, bumpers=False, sample_dt=0.01)
    samples = out.samples
    t = samples[:, 0]
    expect = (x[None, :] * np.exp(1j * s.omega * t)[:, None]).imag
    np.testing.assert_allclose(samples[:, 1:1 + n], expect, rtol=0, atol=1e-10 * np.abs(x).max())
    # the absolute accelerations, exact: -w^2 X less the table's
    wave = np.exp(1j * s.omega * t)[:, None]
    acc = (-(s.omega**2) * x[None, :] * wave).imag + s.a_g * np.sin(s.omega * t)[:, None]
    np.testing.assert_allclose(samples[:, 1 + 2 * n:1 + 3 * n], acc, rtol=0, atol=1e-9 * np.abs(acc).max())


def test_the_outputs_have_a_column_per_dof_and_contact():
    s = Structure(mass=np.array([500.0, 300.0, 200.0]), k0=shear(np.array([1e6, 8e5])),
                  c0=shear(np.array([500.0, 400.0])), k_iso=3e4, c_iso=100.0, gaps=(0.005, 0.005), k_b=5e6,
                  c_b=1e3, a_g=3.0, omega=2 * math.pi * 1.0)
    sy, out = core_run(s, 2.0, np.zeros(6), sample_dt=0.01)
    assert out.samples.shape[1] == sy.layout["sample_cols"] == 1 + 3 * 3 + 1 + 2
    assert out.extrema.shape == (DOF_EXTREMA_LEN * 3,)  # extrema of every mass
    assert len(out.contacts) > 0  # the base pounded
    # every mass's extrema bound its sampled history
    for i in range(3):
        assert out.per_dof(3)[i, X_D_MAX] >= out.samples[:, 1 + i].max() - 1e-12
        assert out.per_dof(3)[i, X_D_MIN] <= out.samples[:, 1 + i].min() + 1e-12
