"""Jankowski's nonlinear viscoelastic impact law (issue 16): against the reference, the energy
ledger, no pull, the restitution it is built for, TOML and the fit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from reference import ReferenceFailed, ReferenceStalled, reference
from strategies import harmonics, oscillators
from test_reference import DURATION_S

import pounding as pd_

SETTINGS = settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _free_impact(law, v0=0.5, rtol=1e-10):
    """500 kg at v0 into the right bumper, no isolator to speak of, no table motion."""
    osc = pd_.Oscillator(500.0, pd_.Isolator((1.0,), (), "elastic", 0.0), pd_.Bumpers(0.05, 0.01, law))
    return pd_.simulate(osc, pd_.Harmonic(0.0, 1.0), 0.1, pd_.State.at_rest(osc, velocity_m_s=v0),
                        sample_rate_hz=0, rtol=rtol)


def _reference_pair(osc, exc, v0):
    """The reference at the tightest tolerance it meets, and at ten times that.

    The dashpot c0 d^((n-1)/2) has an unbounded derivative where a contact starts (d = 0):
    DOP853 cannot meet rtol 1e-13 there ("required step size is less than spacing between
    numbers", measured), mostly meets 1e-11, sometimes only 1e-10 (strong damping, n near 1).
    How far the two runs differ is what the reference itself is sure of."""
    for rtol in (1e-11, 1e-10, 1e-9):
        try:
            fine = reference(osc, exc, DURATION_S, v0=v0, rtol=rtol, atol=rtol * 1e-5)
            coarse = reference(osc, exc, DURATION_S, v0=v0, rtol=10 * rtol, atol=rtol * 1e-4)
            return fine, coarse
        except ReferenceFailed:
            continue
        except ReferenceStalled:
            break
    assume(False)  # (a degenerate graze, or no tolerance the reference meets)
    return None


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(osc=oscillators(law="jankowski"), exc=harmonics(), v0=st.floats(-0.8, 0.8))
def test_random_jankowski_systems_match_reference(osc, exc, v0):
    compare_numeric_law(osc, exc, v0)


def test_a_release_at_the_surface_and_a_return_within_one_reference_step():
    """A random draw: released at the bumper's surface at 3 mm/s, the mass comes back 6.6 ms later,
    5 um deep.  The reference's solver stepped over the dip and had one contact fewer than the
    engine; it now looks inside the step (an independent DOP853 run of the free flight from the
    release agrees: the mass is back at the surface at 0.16329 s)."""
    osc = pd_.Oscillator(100.0, pd_.Isolator((5000.0, 4476.001824612875, 11023.641121594037),
                                             (0.002, 0.050047765425710815), "elastic", 1875.658744571275),
                         pd_.Bumpers(0.005938706736575115, 0.003,
                                     pd_.Jankowski(1e7, 0.8175075145303266, 100.0, 1.2860438049393914)))
    exc = pd_.Harmonic(0.21444204511080134, 2.866669226750589, 2.862096234208599)
    fine = reference(osc, exc, 0.4, v0=0.0, rtol=1e-11, atol=1e-16)
    assert [side for side, _ in fine.contact_starts] == [1, 1, 0]
    assert fine.contact_starts[1][1] == pytest.approx(0.163294572, abs=1e-8)
    compare_numeric_law(osc, exc, 0.0, drawn=False)


def _must(condition):
    assert condition


def compare_numeric_law(osc, exc, v0, rtol=1e-12, drawn=True):
    """A system with a numerically integrated law (the engine at ``rtol``) against the reference
    at two tolerances.  A drawn system (``drawn``: hypothesis's) that the comparison does not fit is
    discarded; a given one must fit it."""
    assume_ = assume if drawn else _must
    # The engine runs at rtol 1e-12, the reference is what limits the agreement: within 1e-8 s
    # and 1e-7 of the scale, or ten times what the reference changes by between its two
    # tolerances (lightly damped systems hitting stiff bumpers amplify a 1e-13 s difference at
    # the first contact to 4e-9 s twelve contacts later, measured, the closed form of the same
    # system with a Kelvin-Voigt law agreeing with the engine's Jankowski run as closely)
    fine, coarse = _reference_pair(osc, exc, v0)
    assume_(len(fine.contact_starts) == len(coarse.contact_starts))
    run = pd_.simulate(osc, exc, DURATION_S, pd_.State.at_rest(osc, velocity_m_s=v0), sample_rate_hz=0,
                       rtol=rtol)
    assert run.success, run.message
    assume_(len(run.contacts) == 0 or run.contacts["max_compression_m"].min() > 1e-7)  # no shallow grazes
    starts = [t for _, t in fine.contact_starts]
    assert len(run.contacts) == len(starts)
    assert list(run.contacts["side"]) == ["left" if s == 0 else "right" for s, _ in fine.contact_starts]
    spread_t = np.abs(np.subtract(starts, [t for _, t in coarse.contact_starts])).max() if starts else 0.0
    np.testing.assert_allclose(run.contacts["t_start_s"], starts, rtol=0, atol=1e-8 + 10 * spread_t)
    scale_d = max(abs(run.displacement_max), abs(run.displacement_min))
    assert abs(run.final_state.displacement_m - fine.d) <= 1e-7 * scale_d + 10 * abs(fine.d - coarse.d)
    assert abs(run.final_state.velocity_m_s - fine.v) <= 1e-7 * max(abs(fine.v),
                                                                    1e-3) + 10 * abs(fine.v - coarse.v)


@SETTINGS
@given(osc=oscillators(law="jankowski"), exc=harmonics(), v0=st.floats(-0.8, 0.8))
def test_jankowski_ledger_closes_and_the_bumper_never_pulls(osc, exc, v0):
    run = check_numeric_ledger(osc, exc, v0)
    done = run.contacts.dropna()
    assert (done["impulse_n_s"] > 0).all()
    # the dashpot works on the approach only: the force never pulls, and a contact ends with
    # the compression back at zero, the bumper recovered at once
    assert (run.final_state.bumper_compression_m[0] == 0.0 or run.final_state.in_contact[0])
    assert (run.final_state.bumper_compression_m[1] == 0.0 or run.final_state.in_contact[1])


def check_numeric_ledger(osc, exc, v0):
    """A run of a numerically integrated law: the ledger closes, no dissipation is negative, no
    bumper pulls; returns the run."""
    # the ledger closes to the integration's tolerance (a free impact: 8e-9 of its energy at
    # rtol 1e-10, 8e-10 at 1e-11, measured), hence rtol 1e-11 here, relative to the energy that
    # went through the bumpers too: each contact stores and returns its impact's kinetic energy
    # (an elastic bumper hit 30 times at 0.5 m/s: 1.3e-8 J against net flows of 0.95 J)
    run = pd_.simulate(osc, exc, 3.0, pd_.State.at_rest(osc, velocity_m_s=v0), sample_rate_hz=2000,
                       rtol=1e-11)
    e = run.energy
    through = 0.5 * osc.mass_kg * float(np.sum(run.contacts["v_in_m_s"].to_numpy() ** 2))
    flows = max(abs(e.input_work), abs(e.kinetic), e.viscous + abs(e.hysteretic) + e.contact_dissipation,
                through)
    assert abs(e.residual) <= 1e-8 * flows
    assert e.contact_dissipation >= -1e-12 * flows
    assert run.bumper_force_left.min() >= 0.0 and run.bumper_force_right.min() >= 0.0
    return run


@pytest.mark.parametrize("restitution", [0.5, 0.7, 0.9, 1.0])
def test_from_restitution_gives_that_restitution(restitution):
    # Jankowski (2006) derived the damping ratio for a free impact: measured 0.4946, 0.6977,
    # 0.8997 and 1 for 0.5, 0.7, 0.9 and 1
    run = _free_impact(pd_.Jankowski.from_restitution(1e9, restitution, 500.0))
    impact = run.impacts.iloc[0]
    assert impact["restitution"] == pytest.approx(restitution, rel=0.015)
    dissipated = 0.5 * 500.0 * 0.25 * (1.0 - impact["restitution"] ** 2)
    # (to the integration tolerance of the impact energy, 62.5 J: v_out is good to 1e-9 of itself)
    assert run.energy.contact_dissipation == pytest.approx(dissipated, rel=1e-6, abs=1e-8 * 62.5)


def test_without_damping_it_is_hertz():
    # xi = 0: the same force as Hunt-Crossley without its dashpot; both elastic, restitution 1
    jank = _free_impact(pd_.Jankowski(1e9, 0.0, 500.0, 1.5))
    hertz = _free_impact(pd_.HuntCrossley(1e9, 1.5, 0.0))
    for col in ("t_start_s", "t_end_s", "v_out_m_s", "impulse_n_s", "peak_force_n", "max_compression_m"):
        assert jank.contacts[col].iloc[0] == pytest.approx(hertz.contacts[col].iloc[0], rel=1e-9)
    # contact time of a Hertz impact (energy conservation): 2 (d_max / v) int_0^1 dx / sqrt(1 - x^2.5)
    # with d_max = (5 m v^2 / (4 k))^(2/5); the 1 N/m isolator changes it by 1e-9
    from scipy.integrate import quad

    d_max = (5 * 500.0 * 0.25 / (4 * 1e9)) ** 0.4
    t_c = 2 * d_max / 0.5 * quad(lambda x: 1 / math.sqrt(1 - x**2.5), 0, 1, epsabs=1e-14)[0]
    assert jank.contacts["t_end_s"].iloc[0] - jank.contacts["t_start_s"].iloc[0] == pytest.approx(t_c,
                                                                                                  rel=1e-7)


def test_toml_round_trip_and_bad_values(tmp_path):
    law = pd_.Jankowski.from_restitution(5e8, 0.8, 500.0, exponent=1.6)
    osc = pd_.Oscillator(500.0, pd_.Isolator((38e3, 18e3), (0.015,)), pd_.Bumpers(0.015, 0.015, law))
    path = tmp_path / "j.toml"
    path.write_text(osc.to_toml_text())
    back = pd_.Oscillator.from_toml(path)
    assert back.bumpers.law == law
    for kwargs, field in (({"damping_ratio": -0.1}, "law.damping_ratio"),
                          ({"effective_mass": 0.0}, "law.effective_mass"),
                          ({"exponent": 0.5}, "law.exponent"),
                          ({"stiffness": math.inf}, "law.stiffness")):
        args = {"stiffness": 1e9, "damping_ratio": 0.2, "effective_mass": 500.0, **kwargs}
        with pytest.raises(pd_.InputError) as info:
            pd_.Jankowski(**args)
        assert info.value.field == field
    with pytest.raises(pd_.InputError) as info:
        pd_.Jankowski.from_restitution(1e9, 1.2, 500.0)
    assert info.value.field == "restitution"
    text = path.read_text().replace('effective_mass = 500.0\n', '')
    path.write_text(text)
    with pytest.raises(pd_.InputError) as info:
        pd_.Oscillator.from_toml(path)
    assert info.value.field == "bumpers.law.effective_mass"


def test_fit_contact_law_recovers_a_jankowski_law():
    truth = pd_.Jankowski(2e8, 0.35, 500.0, 1.4)
    t = np.linspace(0.0, 4.0, 4001)
    d = 0.01 + 0.008 * np.sin(2 * np.pi * 1.0 * t)  # +-8 mm about 10 mm, 1 Hz (as the paper's Fig. 3)
    v = 0.008 * 2 * np.pi * np.cos(2 * np.pi * t)
    from pounding.engine.kernels import law_forces

    force = law_forces(truth.LAW_ID, truth.params(), d, v)
    fit = pd_.fit_contact_law(d, force, velocity_m_s=v, law="jankowski", effective_mass_kg=500.0)
    for name in ("stiffness", "damping_ratio", "exponent"):
        assert getattr(fit.law, name) == pytest.approx(getattr(truth, name), rel=1e-6), name
    assert fit.rms_n < 1e-6 * np.abs(force).max()
    with pytest.raises(pd_.InputError) as info:
        pd_.fit_contact_law(d, force, velocity_m_s=v, law="jankowski")
    assert info.value.field == "effective_mass_kg"
