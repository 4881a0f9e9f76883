"""The exact monodromy through friction: single friction isolators and triple friction pendulums (every
surface's slip, rigid and stiff rings, sticks and reversals), against the map's own finite differences at
random states, and periodic orbits whose section falls in a stick."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding.analysis._shooter import _Shooter
from pounding.analysis._shooting import _Failed
from pounding.engine.simulate import short_run

TFP = dict(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08), capacities_m=(0.35, 0.05, 0.05, 0.35))


@st.composite
def friction_systems(draw):
    """A random structure of 1 to 3 levels on a friction pendulum or a triple friction pendulum (symmetric
    or not; rigid rings, a short outer travel whose rigid ring is reached, or stiff rings), under a random
    harmonic from sticking most of each period to reaching the rings."""
    kind = draw(st.sampled_from(["single", "triple", "short outer travel", "stiff rings"]))
    if kind == "single":
        iso = pd_.FrictionIsolator(mu=draw(st.floats(0.03, 0.1)), radius_m=draw(st.floats(1.5, 4.0)),
                                   damping_n_s_m=draw(st.sampled_from([0.0, 2e4])))
    else:
        r_in, r_out, m_in = draw(st.floats(0.2, 0.6)), draw(st.floats(1.5, 3.0)), draw(st.floats(0.01, 0.02))
        if draw(st.booleans()):  # (the usual symmetric bearing: surfaces that slip as one)
            m_out = m_in * draw(st.floats(1.5, 3.0))
            radii, mu = (r_out, r_in, r_in, r_out), (m_out, m_in, m_in, m_out)
        else:
            radii = (r_out, r_in, r_in * draw(st.floats(0.8, 1.2)), r_out * draw(st.floats(0.8, 1.2)))
            mu = (m_in * draw(st.floats(2.0, 3.0)), m_in, m_in * draw(st.floats(0.8, 1.2)),
                  m_in * draw(st.floats(3.5, 5.0)))
        outer = draw(st.floats(0.02, 0.06)) if kind == "short outer travel" else draw(st.floats(0.2, 0.5))
        caps = (outer, draw(st.floats(0.03, 0.08)), draw(st.floats(0.03, 0.08)), draw(st.floats(0.5, 0.8)))
        iso = pd_.TripleFrictionPendulum(radii_m=radii, mu=mu, capacities_m=caps,
                                         damping_n_s_m=draw(st.sampled_from([0.0, 2e4])),
                                         ring_stiffness_n_m=draw(st.floats(2e5, 5e7)) if kind == "stiff rings"
                                         else None)
    storeys = [pd_.Storey(draw(st.floats(5e3, 3e4)), draw(st.floats(1e7, 8e7)), draw(st.floats(0.0, 2e5)))
               for _ in range(draw(st.integers(0, 2)))]
    base_kg = draw(st.floats(5e3, 4e4))
    system = pd_.Structure(base_kg, iso, storeys, []) if storeys else pd_.Oscillator(base_kg, iso)
    table = pd_.Harmonic(draw(st.floats(0.02, 0.8)), draw(st.floats(0.3, 1.5)),
                         phase=draw(st.floats(0.0, 6.2)))
    return system, table, draw(st.integers(3, 10))


def _exact_against_differences(system, table, periods: float) -> float:
    """From the state ``system`` reaches after ``periods`` periods of ``table``: the largest difference
    between the map's exact Jacobian over a period and its central finite differences, relative to the
    latter's largest entry (at least 1); NaN where there is no such map to compare (the settling run stopped,
    an event within a finite difference's step of either end, a differenced run that the engine stops)."""
    period = 1.0 / table.freq_hz
    settled = pd_.simulate(system, table, periods * period, sample_rate_hz=0)
    if not settled.success:  # (a rigid ring's travel used up: no map)
        return math.nan
    vec = np.array(settled.final_state.vector)
    shooter = _Shooter(system, table, period, True)
    run = short_run(system, table, period, vec, shooter.asm)
    events = run.event_table
    # (an event within a finite-difference step of either end moves across it: a map not smooth there)
    if not run.success or np.any(np.abs(events[:, 0] - vec[0]) < 1e-4 * period) or np.any(
            np.abs(events[:, 0] - vec[0] - period) < 1e-4 * period):
        return math.nan
    shooter.scale_d = max(1e-3, float(np.abs(vec[1:1 + shooter.n]).max()))
    frozen = shooter.frozen(vec, run)
    free, emb = shooter._layout(vec, frozen)
    full, x_end = shooter._propagate(vec, run)
    # (it ends where the engine does, to 1e-9 of the size: the orbit solvers' scales, the size times the
    # forcing's rate for a velocity; measured: a structure on an elastic-plastic bumper ends 1.6e-12 m/s off
    # a velocity of 7.5e-3 m/s after twenty stiff contacts, 2e-10 of it, which the size in metres refused)
    scale = np.full(x_end.size, shooter.scale_d)
    scale[shooter.n:2 * shooter.n] *= table.omega_rad_s
    assert np.all(np.abs(x_end - shooter.coords(run.final_state.vector)) <= 1e-9 * scale)
    exact = full[free] @ emb
    errors = []
    # (central differences at 1e-6 of the scale, and where they are off, at 1e-7: their own error grows with
    # the step squared where an event is within the step's reach, a draw's 1e-3, 1.05e-5 and 8.9e-8 at 1e-5,
    # 1e-6 and 1e-7: the exact map differs from the converged ones, not from the coarse)
    for step_rel in (1e-6, 1e-7):
        try:
            differenced = shooter.differences(vec, free, emb, step_rel)[free]
        except _Failed:  # (a table whose peak only touches a threshold: a differenced run's slips accumulate)
            break
        errors.append(float(np.abs(exact - differenced).max() / max(1.0, np.abs(differenced).max())))
        if errors[-1] <= 1e-5:
            break
    return min(errors) if errors else math.nan


_CURVED = (pd_.Oscillator(31599.0, pd_.TripleFrictionPendulum(
    radii_m=(2.25, 0.25, 0.25, 2.25), mu=(0.017578125, 0.01171875, 0.01171875, 0.017578125),
    capacities_m=(0.484375, 0.03125, 0.03125, 0.7421875), weight_n=309986.19, ring_stiffness_n_m=35156688.0)),
    pd_.Harmonic(a_g=0.46484375, freq_hz=0.5078125), 3)  # (a draw whose differences at 1e-6 are off: above)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(friction_systems())
@example(_CURVED)
def test_the_exact_jacobian_through_friction_is_the_map_s_finite_differences(case):
    """From the state a random system reaches after a few periods (its section anywhere: in a stick, a slip,
    on a ring), the map over a period composed exactly (every stick, slip, reversal, surface's slip, rigid
    or stiff ring on the way: saltations, the slipping surfaces where the force puts them, a stuck pair's
    velocity perturbation slid off) equals its central finite differences in the orbit solvers' coordinates,
    to 1e-5 of its largest entry (their own error is about 1e-7, or they are taken at a tenth of the step)."""
    error = _exact_against_differences(*case)
    assume(not math.isnan(error))
    assert error <= 1e-5


def _triple(radii=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08), caps=(0.35, 0.05, 0.05, 0.35)):
    return pd_.TripleFrictionPendulum(radii_m=radii, mu=mu, capacities_m=caps)


@pytest.mark.parametrize("system", [
    pd_.Oscillator(1e4, _triple(caps=(0.02, 0.003, 0.003, 0.35))),
    pd_.Oscillator(1e4, _triple(radii=(2.1, 0.3, 0.45, 2.1), mu=(0.05, 0.02, 0.025, 0.08),
                                caps=(0.02, 0.003, 0.004, 0.35))),
    pd_.Structure(1e4, _triple(caps=(0.02, 0.003, 0.003, 0.35)), [pd_.Storey(8e3, 2e7, 2e4)], [])])
def test_the_exact_jacobian_through_rigid_inner_rings(system):
    """Inner surfaces that reach their rigid rings while the outer ones are held: the series turns rigid
    and its force jumps to the next surface's threshold, the one event whose guard's saltation the field's
    jump makes count (the others' only move the slipping surfaces, which are put where the force puts
    them).  Its exact Jacobian is the finite differences' to 1e-5 at sections over several periods."""
    errors = [_exact_against_differences(system, pd_.Harmonic(0.15, 0.7), p) for p in (5, 5.37, 8.81)]
    assert sum(not math.isnan(e) for e in errors) >= 2, errors
    assert max(e for e in errors if not math.isnan(e)) <= 1e-5, errors


@pytest.mark.parametrize("system, table", [
    (pd_.Oscillator(1e4, pd_.TripleFrictionPendulum(**TFP)), pd_.Harmonic(0.025, 1.5)),
    (pd_.Structure(4000.0, pd_.FrictionIsolator(mu=0.1, radius_m=2.0), [pd_.Storey(3000.0, 4e6, 4e3)], []),
     pd_.Harmonic(0.12, 0.7, phase=0.5)),
    (pd_.Structure(4000.0, pd_.TripleFrictionPendulum(**TFP), [pd_.Storey(3000.0, 4e6, 4e3)], []),
     pd_.Harmonic(0.025, 1.5))])
def test_an_orbit_whose_section_sticks_has_exact_multipliers(system, table):
    """Periodic orbits of a friction pendulum and a triple friction pendulum whose section falls in a stick
    (the last two: a building's): composed exactly, their multipliers are the finite differences' to 1e-6
    (a stuck pair's velocity perturbation slides it by its square: the exact map's start forgets it)."""
    exact = pd_.periodic_orbit(system, table, settle_cycles=60)
    fd = pd_.periodic_orbit(system, table, settle_cycles=60, method="finite-difference")
    assert exact.converged and fd.converged and exact.method == "exact", exact.message
    assert "gave way" not in exact.message
    lay = exact.state.layout
    assert exact.state.vector[lay["region"]] == 0.0  # (the section in a stick)
    np.testing.assert_allclose(np.sort_complex(exact.multipliers), np.sort_complex(fd.multipliers), rtol=0.0,
                               atol=1e-6)
