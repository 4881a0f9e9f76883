"""The chain's cutoff as a free number of identify: recovered from targets measured through a known
chain, and bad bounds named."""

from __future__ import annotations

import pytest

import pounding
from pounding.identification.identify import evaluate
from pounding.identification.measured import CUTOFF

FREQS = [1.3, 1.5, 1.7]


def test_identify_recovers_the_cutoff_the_targets_were_measured_through():
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
    assert "zero-phase Butterworth" in fit.to_toml("fit.toml").read_text()


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
