"""The issue's reproducers of bad input: each gets an InputError naming the field, or a warning."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import pounding as pd_
from pounding.engine.layout import DEF_R, IN_R, REGION, STATE_BASE, Z_L, Z_R, ZETA
from pounding._errors import Problem

ISO = pd_.Isolator([38e3, 18e3, 2e3], [0.015, 0.04], "kinematic", 1000.0)
OSC = pd_.Oscillator(500.0, ISO, pd_.Bumpers(0.015, 0.015, pd_.KelvinVoigt(1.46e6, 5.0)))


def _raises(call, field: str, problem: Problem | None = None) -> pd_.InputError:
    with pytest.raises(pd_.InputError) as info:
        call()
    assert info.value.field == field, str(info.value)
    if problem is not None:
        assert info.value.problem is problem, str(info.value)
    assert "Fix:" in str(info.value)
    return info.value


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"velocity_m_s": np.nan}, "velocity_m_s"),
        ({"velocity_m_s": np.inf}, "velocity_m_s"),
        ({"displacement_m": -1.0}, "displacement_m"),  # far inside the left bumper
        ({"displacement_m": 0.0151}, "displacement_m"),
        ({"time_s": "0"}, "time_s"),
        ({"velocity_m_s": 1e300}, "velocity_m_s"),
    ],
)
def test_at_rest_refuses_bad_motion(kwargs, field):
    _raises(lambda: pd_.State.at_rest(OSC, **kwargs), field)


def test_at_rest_puts_a_displaced_isolator_on_its_backbone():
    for rule in ("kinematic", "elastic"):
        osc = pd_.Oscillator(500.0, pd_.Isolator(ISO.slopes_n_m, ISO.breakpoints_m, rule, 1000.0))
        state = pd_.State.at_rest(osc, displacement_m=0.05)
        run = pd_.simulate(osc, pd_.Harmonic(0.0, 1.0), 1e-6, state)  # the force is the backbone's
        assert run.isolator_force[0] == pytest.approx(ISO.backbone(0.05), rel=1e-12)


@pytest.mark.parametrize(
    "index, value, field",
    [
        (2, np.nan, "state.vector[2]"),  # velocity NaN
        (6, 7.5, "state.in_contact[1]"),  # a contact flag of 7.5
        (3, -1e-3, "state.bumper_compression_m[0]"),
    ],
)
def test_raw_states_are_checked(index, value, field):
    vec = pd_.State.at_rest(OSC).vector.copy()
    vec[index] = value
    _raises(lambda: pd_.State(vec), field)


def test_a_state_must_fit_the_system():
    vec = pd_.State.at_rest(OSC).vector.copy()
    vec[1] = -1.0  # inside the left bumper, not in contact
    state = pd_.State(vec)
    _raises(lambda: pd_.simulate(OSC, pd_.Harmonic(0.05, 2.2), 1.0, state), "state.displacement_m")
    vec = pd_.State.at_rest(OSC).vector.copy()
    vec[6] = 1.0  # in contact on the right, but the mass is at 0
    _raises(
        lambda: pd_.simulate(OSC, pd_.Harmonic(0.05, 2.2), 1.0, pd_.State(vec)),
        "state.bumper_compression_m[1]",
    )
    vec = pd_.State.at_rest(OSC).vector.copy()
    vec[4] = 1e-3  # a compressed bumper on a system without bumpers
    _raises(
        lambda: pd_.simulate(OSC.without_bumpers(), pd_.Harmonic(0.05, 2.2), 1.0, pd_.State(vec)),
        "state.in_contact",
    )
    vec = pd_.State.at_rest(OSC, displacement_m=0.01).vector.copy()
    vec[STATE_BASE] = -0.02  # a slip that leaves spring 0 strained beyond its yield displacement
    _raises(
        lambda: pd_.simulate(OSC, pd_.Harmonic(0.05, 2.2), 1.0, pd_.State(vec)), "state.plastic_slips_m[0]"
    )
    vec = pd_.State.at_rest(OSC).vector.copy()
    vec[Z_L] = 1e-3  # a law state for a Kelvin-Voigt bumper, which has none
    _raises(lambda: pd_.simulate(OSC, pd_.Harmonic(0.05, 2.2), 1.0, pd_.State(vec)), f"state.vector[{Z_L}]")
    ep = pd_.Oscillator(500.0, OSC.isolator, pd_.Bumpers(0.015, 0.015, pd_.ElasticPlastic(2e6, 2e5, 0.002)))
    vec = pd_.State.at_rest(ep, displacement_m=0.015).vector.copy()
    vec[IN_R], vec[DEF_R], vec[Z_R] = 1.0, 0.0, 0.01  # an offset whose elastic branch starts deeper
    _raises(lambda: pd_.simulate(ep, pd_.Harmonic(0.05, 2.2), 1.0, pd_.State(vec)), f"state.vector[{Z_R}]")
    vec[Z_R] = -1.0  # on the yield line at no compression
    _raises(lambda: pd_.simulate(ep, pd_.Harmonic(0.05, 2.2), 1.0, pd_.State(vec)), f"state.vector[{Z_R}]")


def test_final_states_of_runs_always_fit():
    run = pd_.simulate(OSC, pd_.Harmonic(0.1, 2.9), 7.3, pd_.State.at_rest(OSC, velocity_m_s=0.6))
    assert len(run.contacts) > 5
    for t_end in (2.0, 3.1, 4.77):  # wherever a run stops: in contact, sliding, in flight
        part = pd_.simulate(OSC, pd_.Harmonic(0.1, 2.9), t_end, pd_.State.at_rest(OSC, velocity_m_s=0.6))
        pd_.simulate(OSC, pd_.Harmonic(0.1, 2.9), 0.1, part.final_state)


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda: pd_.Harmonic(1e300, 2.2), "a_g"),
        (lambda: pd_.Harmonic(0.05, 2.2, g=1e300), "g"),
        (lambda: pd_.Harmonic(0.05, 1e300), "freq_hz"),
        (lambda: pd_.Record([0.0, 1.0], [0.0, 1e300]), "record.accel[1]"),
        (lambda: pd_.Isolator([1e300], []), "isolator.slopes_n_m[0]"),
        (lambda: pd_.Isolator([38e3], [], damping_n_s_m=1e300), "isolator.damping_n_s_m"),
        (lambda: pd_.KelvinVoigt(1e300, 5.0), "law.stiffness"),
        (lambda: pd_.HuntCrossley(1e8, 1e300, 1.0), "law.exponent"),
        (lambda: pd_.Bumpers(1e300, 0.015, pd_.KelvinVoigt(1e6)), "bumpers.gap_left_m"),
        (lambda: pd_.Oscillator(1e300, ISO), "mass_kg"),
        (lambda: pd_.sweep(OSC, 1e300), "a_g"),
    ],
)
def test_magnitudes_that_would_overflow_are_refused(make, field):
    _raises(make, field)


@pytest.mark.parametrize(
    "make, words",
    [
        (lambda: pd_.Bumpers(15.0, 15.0, pd_.KelvinVoigt(1e6)), "15 mm is 0.015"),
        (lambda: pd_.Oscillator(1e-6, ISO), "kg"),
        (lambda: pd_.Harmonic(10.0, 2.2), "in g"),
        (lambda: pd_.Harmonic(0.05, 5e3), "Hz"),
        (lambda: pd_.Harmonic(0.05, 2.2, g=981.0), "9.81 on Earth"),
    ],
)
def test_implausible_values_warn_with_what_was_meant(make, words):
    with pytest.warns(pd_.PoundingWarning, match=words):
        make()


def test_wrong_lengths_and_orders_get_their_own_fix():
    err = _raises(lambda: pd_.Record([0.0, 1.0, 2.0], [0.0, 1.0]), "record.accel", Problem.LENGTH_MISMATCH)
    assert "breakpoint" not in str(err)
    err = _raises(
        lambda: pd_.Record([0.0, 1.0, 1.0], [0.0, 1.0, 2.0]), "record.t[1:3]", Problem.NOT_INCREASING
    )
    assert "0.015" not in str(err)
    err = _raises(lambda: pd_.Isolator([1.0, 2.0], []), "isolator.breakpoints_m", Problem.BREAKPOINT_COUNT)
    assert "one breakpoint fewer" in str(err)
    vec = pd_.State.at_rest(OSC).vector
    err = _raises(
        lambda: pd_.simulate(
            OSC.without_bumpers(), pd_.Harmonic(0.05, 2.2), 1.0, pd_.State(np.append(vec, [0.0, 0.0]))
        ),
        "state",
    )
    assert "breakpoint" not in str(err)


def test_a_law_table_must_give_every_field(tmp_path):
    text = (
        pd_.presets.paper_printed().to_toml_text().replace('type = "kelvin_voigt"', 'type = "hunt_crossley"')
    )
    err = _raises(lambda: pd_.Oscillator.from_toml_text(text), "bumpers.law.exponent", Problem.MISSING_KEY)
    assert "hunt_crossley" in str(err)


def test_files_that_are_not_utf8_text_or_not_files(tmp_path):
    latin = tmp_path / "latin.toml"
    latin.write_bytes("mass = 500.0 # masse \xe9\n".encode("latin-1"))
    _raises(lambda: pd_.Oscillator.from_toml(latin), "path", Problem.BAD_ENCODING)
    binary = tmp_path / "binary.toml"
    binary.write_bytes(bytes(range(256)))
    _raises(lambda: pd_.Oscillator.from_toml(binary), "path", Problem.BAD_ENCODING)
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path), "path", Problem.NOT_A_FILE)
    _raises(lambda: pd_.Oscillator.from_toml(None), "path", Problem.WRONG_TYPE)
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path / "missing.toml"), "path", Problem.NO_FILE)


def test_tolerance_ranges_say_the_range():
    err = _raises(
        lambda: pd_.simulate(OSC, pd_.Harmonic(0.05, 2.2), 1.0, rtol=0.5), "rtol", Problem.OUT_OF_RANGE
    )
    assert "[1e-14, 1e-3]" in str(err)
    _raises(lambda: pd_.sweep(OSC, 0.05, steady_rtol=1.0), "steady_rtol", Problem.OUT_OF_RANGE)


def test_measured_names_the_tables_it_has():
    with pytest.raises(pd_.InputError, match="table") as info:
        pd_.data.measured("5")
    assert "'2', '3', '4'" in str(info.value)
    assert pd_.data.measured(str(3)).shape[0] == 4


def test_the_energy_ledger_holds_python_floats():
    """Fields annotated float are floats (NumPy 2 prints its scalars as np.float64(...))."""
    import dataclasses

    osc = pd_.presets.paper_damped()
    run = pd_.simulate(osc, pd_.Harmonic(0.05, 2.0), 2.0, state=pd_.State.at_rest(osc, velocity_m_s=0.6))
    for field in dataclasses.fields(run.energy):
        assert type(getattr(run.energy, field.name)) is float, field.name


_T = np.linspace(0.0, 2.0, 401)
_D = 0.002 * (1.0 - np.cos(2.0 * np.pi * _T))  # m: two cycles of a 0-4 mm compression test
_F = 3e7 * _D**1.5


def _fit(**changes):
    kwargs = {"displacement_m": _D, "force_n": _F, "time_s": _T, "law": "hunt_crossley", **changes}
    return lambda: pd_.fit_contact_law(kwargs.pop("displacement_m"), kwargs.pop("force_n"), **kwargs)


@pytest.mark.parametrize(
    "call, field, problem",
    [
        (_fit(exponent_bounds=None), "exponent_bounds", Problem.WRONG_TYPE),
        (_fit(exponent_bounds=2.0), "exponent_bounds", Problem.WRONG_TYPE),
        (_fit(exponent_bounds=(1.5,)), "exponent_bounds", Problem.LENGTH_MISMATCH),
        (_fit(exponent_bounds=(1.0, 2.0, 3.0)), "exponent_bounds", Problem.LENGTH_MISMATCH),
        (_fit(exponent_bounds=(1.0, 11.0)), "exponent_bounds[1]", Problem.TOO_LARGE),
        (_fit(exponent_bounds=(1.0, float("nan"))), "exponent_bounds[1]", None),
        # time steps so small the compression rate overflows (it was a raw "array must not contain infs")
        (_fit(time_s=_T * 1e-310, law="kelvin_voigt"), "time_s", Problem.TOO_LARGE),
        (_fit(time_s=_T * 1e-300), "time_s", Problem.TOO_LARGE),
        # compressions in the wrong units (1e300 overflowed; 1e-300 gave a law of 1e304 N/m)
        (_fit(displacement_m=_D * 1e302, law="kelvin_voigt"), "displacement_m[100]", Problem.TOO_LARGE),
        (_fit(displacement_m=_D * 1e302), "displacement_m[100]", Problem.TOO_LARGE),
        (_fit(displacement_m=_D * 1e-298, law="elastic_plastic"), "displacement_m[100]", Problem.TOO_SMALL),
        (_fit(displacement_m=_D * 1e-298, law="multilinear"), "displacement_m[100]", Problem.TOO_SMALL),
        (_fit(force_n=_F * 1e300), "force_n[100]", Problem.TOO_LARGE),
        # forces all negative (a stiffness of 2.2e-308 came back)
        (_fit(force_n=-_F, law="kelvin_voigt"), "force_n", Problem.NO_FIT),
        (_fit(force_n=-_F), "force_n", Problem.NO_FIT),
        (_fit(force_n=-_F, law="multilinear"), "force_n", Problem.NO_FIT),
        (_fit(force_n=-_F, law="jankowski", effective_mass_kg=500.0), "force_n", Problem.NO_FIT),
    ],
)
def test_contact_law_fits_refuse_data_no_bumper_test_has(call, field, problem):
    _raises(call, field, problem)


@pytest.mark.parametrize(
    "call, field",
    [
        # e = E / D_tmax and nu = f / f_R overflowed or divided by zero
        (lambda: pd_.sweep(OSC, 0.05, [1.0], omega_min_rad_s=1e300), "omega_min_rad_s"),
        (lambda: pd_.sweep(OSC, 0.05, [1.0], omega_min_rad_s=1e-300), "omega_min_rad_s"),
        (lambda: pd_.sweep(OSC, 0.05, [1.0], f_ref_hz=1e-300), "f_ref_hz"),
        (lambda: pd_.sweep(OSC, 0.05, [1.0], f_ref_hz=1e300), "f_ref_hz"),
        # a mass whose phases' rates overflow
        (lambda: pd_.Oscillator(1e-300, ISO), "mass_kg"),
        (lambda: pd_.campaign(None, OSC, ybs_a_g=[]), "ybs_a_g"),
        # record steps below what a run can resolve
        (lambda: pd_.Record(np.arange(5) * 1e-300, [0.0, 1.0, 0.0, -1.0, 0.0]), "record.t[4] - record.t[3]"),
        # (steps of 10 ns at t = 1000 s are 1e5 times the times' rounding: not resolved either)
        (lambda: pd_.Record(1e3 + np.array([0.0, 1e-8, 3e-8, 6e-8]), [0.0, 1.0, 0.0, -1.0]),
         "record.t[1] - record.t[0]"),
    ],
)
def test_scales_that_overflowed_are_named(call, field):
    _raises(call, field)


def test_a_tiny_mass_in_toml_is_named(tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text(OSC.to_toml_text().replace("mass_kg = 500.0", "mass_kg = 1e-300"))
    assert "1e-300" in path.read_text()
    _raises(lambda: pd_.Oscillator.from_toml(path), "mass_kg", Problem.TOO_SMALL)


def test_a_mass_without_bumpers_is_the_one_level_structure_without_walls():
    bare = OSC.without_bumpers()
    exc = pd_.Harmonic(0.3, 1.2)
    run = pd_.simulate(bare, exc, 3.0, pd_.State.at_rest(bare, velocity_m_s=0.2))
    end = run.final_state
    assert end.n_contacts == 0 and end.in_contact == () and end.layout is not None
    assert not run.bumper_force_left.any() and not run.bumper_force_right.any()
    assert run.contact_table.size == 0
    assert np.any(end.plastic_slips_m != 0.0)  # (the isolator yielded: its springs' state is carried)
    one = pd_.Structure.from_oscillator(bare)
    assert not one.walls
    np.testing.assert_array_equal(pd_.simulate(one, exc, 3.0, pd_.State.at_rest(one, velocity_m_s=0.2))
                                  .final_state.vector, end.vector)
    # 0.1's vector of it (two unused contact slots) continues the run as its own state does, with a warning
    lay, old = end.layout, np.zeros(STATE_BASE + end.plastic_slips_m.size * 2)
    old[:3] = end.vector[:3]  # (t, D, V)
    old[REGION] = end.vector[lay["region"]]
    old[ZETA:] = end.vector[lay["zeta"]:]  # (z, then the slips and their directions)
    with pytest.warns(FutureWarning, match="0.1's"):
        legacy = pd_.simulate(bare, exc, 1.0, pd_.State(old))
    again = pd_.simulate(bare, exc, 1.0, end)
    np.testing.assert_array_equal(legacy.final_state.vector, again.final_state.vector)
    # and a state with its bumpers' numbers is refused for it, as a bumperless state is for a mass with them
    _raises(lambda: pd_.simulate(OSC, exc, 1.0, end), "state")


def test_every_protocol_runs_a_mass_without_bumpers_from_a_state_laid_out_with_two_slots():
    """A state with two bumpers' slots (0.1's layout, or a run's with bumpers) given to a mass without
    bumpers: taken in its own layout, with a warning, by every protocol that takes a state."""
    bare = pd_.Oscillator(500.0, pd_.Isolator([3.8e4, 2e3], [0.015], "kinematic", 1500.0))
    with_them = pd_.Oscillator(500.0, bare.isolator, pd_.Bumpers(0.05, 0.05, pd_.KelvinVoigt(1.46e6, 50.0)))
    exc = pd_.Harmonic(0.1, 1.5)
    hit = pd_.simulate(with_them, pd_.Harmonic(0.4, 1.5), 4.0)  # (it pounds: its contacts' totals stay)
    assert len(hit.contacts) and not any(hit.final_state.in_contact)
    two_slots = pd_.State._of(hit.final_state.vector, hit.final_state.dofs, None)
    assert two_slots.vector[STATE_BASE - 30:STATE_BASE - 2].any()  # (a finished contact's totals)
    own = pd_.simulate(bare, exc, 1.0)  # (from rest: its own layout)
    assert own.final_state.n_contacts == 0
    with pytest.warns(FutureWarning, match="two bumpers' contact slots") as said:
        run = pd_.simulate(bare, exc, 1.0, two_slots)
    assert said[0].filename == __file__  # (the warning names the caller's line)
    assert run.final_state.vector.size == own.final_state.vector.size
    with pytest.warns(FutureWarning, match="two bumpers' contact slots"):
        swept = pd_.sweep(bare, 0.1, [1.0, 1.5], cycles=6, measure_cycles=2, steady="fixed",
                          state=two_slots)
    assert swept.success
    rest = pd_.State._of(pd_.State.at_rest(with_them).vector, ((0,),), None)
    with pytest.warns(FutureWarning, match="two bumpers' contact slots"):
        orbit = pd_.periodic_orbit(bare, exc, guess=rest)
    assert orbit.converged and orbit.coordinates[:2] == ("x_0", "v_0")
    assert "delta_wall0_left" not in orbit.coordinates
    with pytest.warns(FutureWarning, match="two bumpers' contact slots"):
        branch = pd_.continuation(bare, 0.1, (1.4, 1.6), guess=rest)
    again = branch.orbit(0)
    assert again.converged and again.state.n_contacts == 0
    diagram = pd_.bifurcation_diagram(bare, 0.1, [1.4, 1.6], direction="up", transient_cycles=20,
                                      record_cycles=4, max_period=2)
    exponents = pd_.largest_exponents(diagram, cycles=20, align_cycles=4)
    assert np.isfinite(exponents.data["largest_exponent"].values).all()
    # 0.1's layout was a single mass's alone: a structure of one level without walls refuses it
    level = pd_.Structure.from_oscillator(bare)
    for run_it in (lambda: pd_.simulate(level, exc, 1.0, two_slots),
                   lambda: pd_.periodic_orbit(level, exc, guess=rest, max_iter=2)):
        with warnings.catch_warnings():
            warnings.simplefilter("error", FutureWarning)
            with pytest.raises(pd_.InputError, match="contact slots"):
                run_it()


def test_a_shooter_s_advance_is_none_from_a_vector_that_is_no_state():
    """The solvers' raw vectors: one that is none of the system's states gives no state on (None), as a
    run that stopped does, not an exception out of the follower."""
    from pounding.analysis._shooter import _Shooter

    stop = pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(1.0e8, 2.0e4))
    b = pd_.Structure(2.0e3, pd_.Isolator([2.0e5], [], "elastic", 4.0e3), [pd_.Storey(1.0e3, 2.0e6, 2.0e3)],
                      [stop])
    exc = pd_.Harmonic(0.1, 1.5)
    sh = _Shooter(b, exc, 1 / 1.5, True)
    vec = np.array(pd_.State.at_rest(b).vector)
    assert sh.advance(exc, 0.3, vec) is not None
    vec[sh.lay["x"]] = 0.5  # (the base 0.5 m into a wall 0.02 m away, flagged apart)
    assert sh.advance(exc, 0.3, vec) is None
