"""The exact monodromy through piecewise linear contact laws with branches and memory: the elastic and the
kinematic multi-linear bumpers and the elastic-plastic one (their branch changes and turns, a kinematic
bumper's springs' slips, the elastic-plastic offset, a damped bumper's recovery piece by piece apart),
against the map's own finite differences at random states, and the orbits and branches the solvers find
with it."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import pounding as pd_
from pounding.analysis._hybrid import NoExactMonodromy
from pounding.analysis._shooter import _Shooter
from pounding.engine.layout import ACT_LAW_BRANCH, C_MAX_COMPRESSION, C_T_END, E_ACTION
from pounding.engine.simulate import short_run
from test_friction_monodromy import _exact_against_differences

_ISOLATOR = pd_.Isolator([40e3, 18.8e3, 14.9e3], [0.0101, 0.066], "kinematic", 305.0)


@st.composite
def law_systems(draw):
    """A mass (or a base-isolated storey) between two bumpers of a random piecewise linear law, elastic or
    with memory, its recovery apart from fast (a tenth of a millisecond) to slow (5 ms), under a random
    harmonic that brings it from light touches to deep ones; the section anywhere (in a contact, in a
    recovery, apart)."""
    kind = draw(st.sampled_from(["elastic", "kinematic", "kinematic softening", "elastic-plastic"]))
    k1 = draw(st.floats(5e6, 2e7))
    c = k1 * draw(st.floats(1e-4, 5e-3))
    b1 = draw(st.floats(2e-4, 1e-3))
    b2 = b1 * draw(st.floats(2.0, 6.0))
    if kind == "elastic-plastic":
        law = pd_.ElasticPlastic(k1, k1 * draw(st.floats(0.02, 0.3)), b1)
    elif kind == "kinematic softening":  # (two springs that slip)
        law = pd_.MultilinearBumper([k1, k1 * draw(st.floats(0.3, 0.6)), k1 * draw(st.floats(0.0, 0.2))],
                                    [b1, b2], c, "kinematic")
    else:  # (a soft branch, then a hardening one)
        law = pd_.MultilinearBumper([k1, k1 * draw(st.floats(0.1, 0.5)), k1 * draw(st.floats(0.5, 1.5))],
                                    [b1, b2], c, kind)
    gap = draw(st.floats(0.003, 0.02))
    bumpers = pd_.Bumpers(gap, gap * draw(st.floats(0.7, 1.3)), law)
    if draw(st.booleans()):
        system = pd_.Oscillator(500.0, _ISOLATOR, bumpers)
    else:
        system = pd_.Structure(400.0, _ISOLATOR, [pd_.Storey(150.0, 3e5, 500.0)],
                               [pd_.Wall(0, bumpers.gap_left_m, bumpers.gap_right_m, law)])
    table = pd_.Harmonic(draw(st.floats(0.03, 0.15)), draw(st.floats(0.8, 3.0)),
                         phase=draw(st.floats(0.0, 6.2)))
    return system, table, draw(st.floats(3.0, 12.0))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(law_systems())
def test_the_exact_jacobian_through_bumper_branches_is_the_map_s_finite_differences(case):
    """From the state a random system reaches after a few periods, the map over a period composed exactly
    (its bumpers' branch changes and turns with their saltations, a kinematic bumper's springs slipping
    with the compression or held, the elastic-plastic offset, a recovery apart across its pieces' edges)
    ends where the engine does, to 1e-9 of the size (checked inside), and equals its central finite
    differences in the orbit solvers' coordinates to 1e-5 of its largest entry (measured: 1.6e-6 at most
    over 200 draws of the same kind; their own error is about 1e-7)."""
    error = _exact_against_differences(*case)
    assume(not math.isnan(error))
    assert error <= 1e-5


def test_a_recovery_across_its_pieces_is_followed():
    """A kinematic bumper slow to recover (5 ms) whose spring starts to slip back on the way (a piece's
    edge inside a phase, no event of the run): the propagation ends where the engine does and its Jacobian
    is the differences' (without the edge, the end's compression is off by 7e-4 m)."""
    law = pd_.MultilinearBumper([11641292.4, 4024968.7, 6150855.7], [0.00023240857, 0.00114531519], 54351.8,
                                "kinematic")
    system = pd_.Oscillator(500.0, pd_.presets.paper_calibrated().isolator, pd_.Bumpers(0.0105, 0.0094, law))
    errors = [_exact_against_differences(system, pd_.Harmonic(0.121, 1.928, phase=5.83), p)
              for p in (3.3, 3.6, 4.2)]
    assert sum(not math.isnan(e) for e in errors) >= 2, errors
    assert max(e for e in errors if not math.isnan(e)) <= 1e-5, errors


def test_the_calibrated_preset_s_orbits_are_exact_and_their_multipliers_the_differences():
    """The calibrated preset (kinematic multi-linear bumpers) is shot with its exact monodromy; its
    multipliers equal those the finite-difference solver finds, at an impacting and a quiet frequency."""
    osc = pd_.presets.paper_calibrated()
    for f in (1.3, 2.2):
        exc = pd_.Harmonic(0.1, f)
        exact = pd_.periodic_orbit(osc, exc, settle_cycles=20)
        fd = pd_.periodic_orbit(osc, exc, settle_cycles=20, method="finite-difference")
        assert exact.method == "exact" and exact.converged and fd.converged, exact.message
        assert exact.contacts_per_period > 0
        assert exact.state.displacement_m == pytest.approx(fd.state.displacement_m, abs=1e-10)
        assert exact.state.velocity_m_s == pytest.approx(fd.state.velocity_m_s, abs=1e-9)
        big = np.sort(np.abs(exact.multipliers))[::-1]
        np.testing.assert_allclose(big, np.sort(np.abs(fd.multipliers))[::-1], rtol=1e-5, atol=1e-7)


def test_an_undamped_kinematic_bumper_is_refused_by_name():
    """A kinematic multi-linear bumper without a dashpot rests at its set once a contact ends, a depth that
    moves with the state: the exact monodromy is refused by name, and "auto" takes finite differences."""
    law = pd_.MultilinearBumper([1.2e7, 4e6], [4e-4], 0.0, "kinematic")
    osc = pd_.Oscillator(500.0, _ISOLATOR, pd_.Bumpers(0.016, 0.016, law))
    with pytest.raises(pd_.InputError, match="no damping"):
        pd_.periodic_orbit(osc, pd_.Harmonic(0.1, 1.3), method="exact")
    orbit = pd_.periodic_orbit(osc, pd_.Harmonic(0.1, 1.3), settle_cycles=20)
    assert orbit.method == "finite-difference"


def test_a_turn_a_hair_below_the_next_edge_is_refused_not_taken_for_the_edge():
    """A kinematic bumper's slipping spring turns (the compression's rate through zero) at a depth 1e-8 of it
    below the next breakpoint: the same run, event for event, as with that breakpoint far off. The event is
    told by its rate (still: a turn), not by its depth (at the edge to 1e-7): met still at an edge, it is
    refused (a grazing of the edge). Taken for the edge, as it was when told by depth, its saltation divides
    by a rate of rounding and the Jacobian is off the differences by a third of its largest entry. With the
    breakpoint 1 % farther the event is a plain turn, and exact."""
    k1, b1, table = 1e7, 4e-4, pd_.Harmonic(0.1, 2.0, phase=1.0)

    def period(b2):
        law = pd_.MultilinearBumper([k1, 0.3 * k1, 0.8 * k1], [b1, b2], 0.002 * k1, "kinematic")
        system = pd_.Oscillator(500.0, _ISOLATOR, pd_.Bumpers(0.006, 0.006, law))
        vec = np.array(pd_.simulate(system, table, 3.0, sample_rate_hz=0).final_state.vector)
        shooter = _Shooter(system, table, table.period_s, True)
        shooter.scale_d = 1e-3
        return shooter, vec, short_run(system, table, table.period_s, vec, shooter.asm)

    _, vec, run = period(20 * b1)
    assert np.count_nonzero(run.event_table[:, E_ACTION] == ACT_LAW_BRANCH) >= 2
    done = run.contact_table[np.isfinite(run.contact_table[:, C_T_END])]
    deepest = float(done[:, C_MAX_COMPRESSION].max())
    assert b1 < deepest < 20 * b1  # (its spring slips, and turns there)
    for rel, refused in ((1e-8, True), (1e-2, False)):
        shooter, vec_b, run_b = period(deepest * (1.0 + rel))
        # (the same motion, to the bit: the far breakpoint is never reached)
        np.testing.assert_array_equal(run_b.event_table, run.event_table)
        np.testing.assert_array_equal(vec_b, vec)
        if refused:
            with pytest.raises(NoExactMonodromy, match="bumper_branch event .* grazing of an edge"):
                shooter._propagate(vec_b, run_b)
            continue
        free, emb = shooter._layout(vec_b, shooter.frozen(vec_b, run_b))
        exact = shooter._propagate(vec_b, run_b)[0][free] @ emb
        differenced = shooter.differences(vec_b, free, emb, 1e-7)[free]
        assert np.abs(exact - differenced).max() <= 1e-5 * np.abs(differenced).max()
