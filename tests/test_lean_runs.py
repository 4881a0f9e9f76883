"""What a system's many runs share, and what a run read for its peaks leaves out, change no number.

A system's assembly and its rates are built once for its many runs (``assemble``'s kept assemblies): an
equal model gets the one kept, a run from it is the run from a fresh assembly number for number, a model
that differs gets its own, and what is kept cannot be changed in place.  A run read for its peaks
(``peaks``: a study's point, a pounding spectrum's run, an orientation's) skips the energy integrals and
gives ``simulate``'s quantities number for number, on every kind of system and phase."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pandas
import pytest

import pounding as pd_
from pounding.engine import assembly, control
from pounding.engine.simulate import peaks


def _building(stiffness_n_m: float = 4.0e7) -> pd_.Structure:
    iso = pd_.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02], damping_n_s_m=2.0e4)
    storeys = [pd_.Storey(2.0e4, stiffness_n_m, 4.0e4)] * 2
    moat = pd_.Wall(0, 0.02, 0.02, pd_.KelvinVoigt(stiffness=2.0e8, damping=1.0e5))
    return pd_.Structure(3.0e4, iso, storeys, [moat])


def _same_run(a, b) -> None:
    for name in ("t", "event_table", "contacts"):
        x, y = getattr(a, name), getattr(b, name)
        if isinstance(x, pandas.DataFrame):
            pandas.testing.assert_frame_equal(x, y, check_exact=True)
        else:
            assert np.array_equal(np.asarray(x), np.asarray(y), equal_nan=True), name
    assert np.array_equal(a.final_state.vector, b.final_state.vector)
    assert a.summary().equals(b.summary())


@pytest.mark.parametrize("make", [_building, pd_.presets.paper_calibrated], ids=["building", "mass"])
def test_an_equal_model_runs_from_the_kept_assembly_as_from_a_fresh_one(make):
    quake = pd_.records.el_centro().scaled(pga_g=0.4)
    first, again = make(), make()
    assert first is not again and first == again
    assembly._kept.cache_clear()
    control._kept_rates.cache_clear()
    fresh = pd_.simulate(first, quake, 8.0, sample_rate_hz=200)
    hits = assembly._kept.cache_info().hits
    kept = pd_.simulate(again, quake, 8.0, sample_rate_hz=200)
    assert assembly._kept.cache_info().hits > hits  # (the second run's assembly was the kept one)
    assert assembly.assemble(again) is assembly.assemble(first)
    assert len(fresh.contacts) > 0
    _same_run(fresh, kept)
    # the assembly made anew, outside the cache, runs the same
    assert assembly._assemble(first).system.n == assembly.assemble(first).system.n
    assert control.model_rates(first, assembly._assemble(first)) == control.fastest_rates(
        assembly._assemble(first))


def test_a_model_that_differs_gets_its_own_assembly_and_its_own_run():
    quake = pd_.records.el_centro().scaled(pga_g=0.4)
    soft, stiff = _building(4.0e7), _building(8.0e7)
    assert assembly.assemble(soft) is not assembly.assemble(stiff)
    rates = [control.model_rates(m, assembly.assemble(m))[0] for m in (soft, stiff)]
    assert rates[0] < rates[1]
    a, b = (pd_.simulate(m, quake, 4.0, sample_rate_hz=0) for m in (soft, stiff))
    assert not np.array_equal(a.final_state.vector, b.final_state.vector)


def test_what_is_kept_cannot_be_changed_in_place():
    asm = assembly.assemble(_building())
    for array in (asm.masses, asm.k_fast, asm.c_all, asm.bouc_wen.numbers):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 1.0


def test_a_model_that_cannot_be_hashed_is_assembled_anew_each_time():
    model = _building()
    odd = dataclasses.replace(model)
    object.__setattr__(odd, "walls", list(odd.walls))  # (a list where a tuple was: no hash)
    with pytest.raises(TypeError):
        hash(odd)
    a, b = assembly.assemble(odd), assembly.assemble(odd)
    assert a is not b and np.array_equal(a.k_fast, b.k_fast) and a.k_fast.flags.writeable
    assert control.model_rates(odd, a) == control.fastest_rates(a)
    assert assembly._kept.cache_info().maxsize == assembly.ASSEMBLIES_KEPT


def _same_quantities(a: dict, b: dict) -> bool:
    return a.keys() == b.keys() and all(a[k] == b[k] or (np.isnan(a[k]) and np.isnan(b[k])) for k in a)


def _systems() -> dict:
    tfp = pd_.TripleFrictionPendulum(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08),
                                     capacities_m=(0.3, 0.05, 0.05, 0.3))
    bouc_wen = pd_.Isolator((2.0e4,), (), "kinematic", 300.0, pd_.BoucWen(8.0e4, 0.004))
    bilinear = pd_.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02], damping_n_s_m=2.0e4)
    linear = pd_.Isolator((2.0e4,), (), damping_n_s_m=300.0)
    stops = pd_.Bumpers(0.01, 0.01, pd_.RigidStop(0.7))
    rigid = pd_.Structure(3.0e4, bilinear, [pd_.Storey(2.0e4, 4.0e7, 4.0e4)] * 2,
                          [pd_.Wall(0, 0.015, 0.015, pd_.RigidStop(0.6))])
    return {
        "printed (multi-linear bumpers)": pd_.presets.paper_printed(),
        "calibrated (kinematic bumpers)": pd_.presets.paper_calibrated(),
        "building in a Kelvin-Voigt moat": _building(),
        "building, rigid moat": rigid,
        "friction pendulum building": pd_.Structure(8.0e3, pd_.FrictionIsolator(mu=0.06, radius_m=2.0),
                                                    [pd_.Storey(1.2e4, 2.0e7, 4.0e4)],
                                                    [pd_.Wall(0, 0.03, 0.03, pd_.KelvinVoigt(5.0e7, 1.0e4))]),
        "triple friction pendulum": pd_.Oscillator(1.0e4, tfp),
        "Bouc-Wen isolator (numerical phases)": pd_.Oscillator(500.0, bouc_wen,
                                                               pd_.presets.paper_damped().bumpers),
        "fixed-base building (its ground a level)": pd_.Structure.fixed_base(
            [pd_.Storey(2.0e4, 4.0e7, 4.0e4)] * 3, [pd_.Wall(2, 0.01, 0.01, pd_.KelvinVoigt(5.0e7, 1.0e4))]),
        "single mass between rigid stops": pd_.Oscillator(500.0, linear, stops),
        "two adjacent buildings": pd_.Adjacent.from_toml(
            Path(__file__).parents[1] / "examples" / "adjacent_buildings.toml"),
    }


@pytest.mark.parametrize("name", list(_systems()))
def test_a_run_read_for_its_peaks_gives_simulate_s_quantities_number_for_number(name):
    system = _systems()[name]
    quake = pd_.records.el_centro().scaled(pga_g=0.5)
    for excitation, duration in ((quake, 10.0), (pd_.Harmonic(a_g=0.3, freq_hz=1.2), 6.0)):
        full = pd_.simulate(system, excitation, duration, sample_rate_hz=0)
        assert full.status == pd_.Status.SUCCESS and np.isfinite(full.energy.input_work)
        assert _same_quantities(full.quantities(), peaks(system, excitation, duration)), (name, excitation)
    state = full.final_state  # (from a state: a continued run's peaks too)
    assert _same_quantities(pd_.simulate(system, quake, 3.0, state, sample_rate_hz=0).quantities(),
                            peaks(system, quake, 3.0, state))


def test_a_run_read_for_its_peaks_refuses_and_stops_as_simulate_does():
    system, quake = _building(), pd_.records.el_centro()
    with pytest.raises(pd_.InputError) as full:
        pd_.simulate(system, quake, 10.0, max_steps=50)
    with pytest.raises(pd_.InputError) as lean:
        peaks(system, quake, 10.0, max_steps=50)
    assert str(full.value) == str(lean.value)
    with pytest.raises(pd_.InputError, match="duration"):
        peaks(system, quake, -1.0)
