"""The chain's cutoff as a free number of identify: recovered from targets measured through a known
chain, and bad bounds named."""

from __future__ import annotations

from dataclasses import replace

import pytest

import pounding
from pounding.identification.identify import evaluate
from pounding.identification.measured import CUTOFF

FREQS = [1.3, 1.5, 1.7]


def test_identify_recovers_the_cutoff_the_targets_were_measured_through(tmp_path):
    system = pounding.presets.paper_damped()
    truth = pounding.MeasurementChain.lowpass(20.0)
    seen = pounding.sweep(system, 0.05, FREQS, steady="fixed", cycles=30, measure_cycles=5, measurement=truth)
    targets = pounding.Targets.from_records(
        [
            {
                "configuration": "YBs",
                "a_g": 0.05,
                "quantity": "alpha",
                "value": seen.alpha_max,
                "tolerance": 0.01,
            }
        ]
    )
    family = pounding.ModelFamily(500.0, fixed=pounding.ModelFamily(500.0).values_of(system))
    fit = pounding.identify(
        targets, family, {CUTOFF: (5.0, 100.0)}, freqs_hz=FREQS, popsize=4, maxiter=3, workers=1
    )
    assert fit.parameters[CUTOFF] == pytest.approx(20.0, rel=0.01)
    assert fit.measurement.mass.lowpass_hz == fit.parameters[CUTOFF] and fit.measurement.mass.zero_phase
    assert fit.n_within == 1
    # the exact alpha is far from it: the fit needed the filter
    exact = evaluate(system, targets, freqs_hz=FREQS)
    assert not bool(exact["within"].iloc[0])
    assert "zero-phase Butterworth" in fit.to_toml(tmp_path / "fit.toml").read_text()


@pytest.mark.parametrize(
    "pair, match",
    [((0.5, 50.0), "1, 500"), ((50.0, 20.0), "increasing"), ((5.0, 600.0), "500"), ("5-100", "pair")],
)
def test_bad_cutoff_bounds_are_named(pair, match):
    system = pounding.presets.paper_damped()
    family = pounding.ModelFamily(500.0, fixed=pounding.ModelFamily(500.0).values_of(system))
    targets = pounding.Targets.from_records(
        [{"configuration": "YBs", "a_g": 0.05, "quantity": "alpha", "value": 10.0}]
    )
    with pytest.raises(pounding.InputError, match=match) as err:
        pounding.identify(targets, family, {CUTOFF: pair}, freqs_hz=FREQS, popsize=2, maxiter=1)
    assert err.value.field.startswith(f"bounds.{CUTOFF}")


def test_a_cutoff_beyond_the_plausible_warns():
    system = pounding.presets.paper_damped()
    family = pounding.ModelFamily(500.0, fixed=pounding.ModelFamily(500.0).values_of(system))
    targets = pounding.Targets.from_records(
        [{"configuration": "YBs", "a_g": 0.05, "quantity": "alpha", "value": 10.0}]
    )
    with pytest.warns(pounding.PoundingWarning, match="plausibly"):
        pounding.identify(
            targets,
            family,
            {CUTOFF: (2.0, 30.0)},
            freqs_hz=[1.5],
            popsize=2,
            maxiter=0,
            refine=False,
            workers=1,
        )


def test_the_measured_preset_reproduces_its_stored_residuals_through_its_chain():
    import numpy as np

    ybs, chain = pounding.presets.paper_calibrated_measured()
    stored = pounding.presets.residuals("paper-calibrated-measured")
    now = evaluate(ybs, pounding.paper_targets(), measurement=chain)
    assert list(now["quantity"]) == list(stored["quantity"])
    # (the measured metrics pass through splines, filters and least squares: 1e-6, not rounding)
    np.testing.assert_allclose(now["model"], stored["model"], rtol=1e-6, atol=1e-9, equal_nan=True)
    assert list(now["within"]) == list(stored["within"])
    profile = pounding.presets.measurement_profile()
    free = profile[profile["shipped"]].iloc[0]
    assert bool(free["cutoff_free"]) and int(profile["shipped"].sum()) == 1
    assert free["cutoff_hz"] == pytest.approx(chain.mass.lowpass_hz) and int(free["met"]) == int(
        now["within"].sum()
    )
    assert 5.0 <= chain.mass.lowpass_hz <= 100.0
    assert pounding.presets.by_name("paper-calibrated-measured").bumpers.law == ybs.bumpers.law
    # the exact preset is kept, and is not this one
    assert pounding.presets.paper_calibrated().bumpers.law != ybs.bumpers.law


def test_the_laser_preset_reproduces_its_stored_residuals_through_its_chain():
    import numpy as np

    ybs, chain = pounding.presets.paper_calibrated_laser()
    assert chain.contact_timing == "laser" and 5.0 <= chain.mass.lowpass_hz <= 100.0
    stored = pounding.presets.residuals("paper-calibrated-laser")
    now = evaluate(ybs, pounding.paper_targets(), measurement=chain)
    assert list(now["quantity"]) == list(stored["quantity"])
    np.testing.assert_allclose(now["model"], stored["model"], rtol=1e-6, atol=1e-9, equal_nan=True)
    assert list(now["within"]) == list(stored["within"])
    profile = pounding.presets.measurement_profile("laser")
    shipped = profile[profile["shipped"]].iloc[0]
    assert int(profile["shipped"].sum()) == 1 and bool(shipped["cutoff_free"])
    assert (profile["timing"] == "laser").all() and set(profile["start_from"]) == {"calibrated", "measured"}
    assert shipped["cutoff_hz"] == pytest.approx(chain.mass.lowpass_hz)
    assert int(shipped["met"]) == int(now["within"].sum()) == int(profile["met"].max())
    assert pounding.presets.by_name("paper-calibrated-laser").bumpers.law == ybs.bumpers.law
    # timed by the force pulses instead, the same system meets fewer: the laser's reading is the count
    pulse = evaluate(ybs, pounding.paper_targets(), measurement=replace(chain, contact_timing="pulse"))
    assert int(pulse["within"].sum()) < int(now["within"].sum())
    with pytest.raises(pounding.InputError, match="contact_timing"):
        pounding.presets.measurement_profile("force")
