"""Model updating by the paths of a system's numbers (pounding.identify with a SystemFamily): a single mass,
or a rig of several masses, fitted by the dotted names of its numbers, on its base's targets.

- A one-level structure's targets are the oscillator's (its base's paper quantities, to rounding).
- The same fit of a one-level structure, of the oscillator by its paths and of the oscillator's ModelFamily
  find the same number.
"""

from __future__ import annotations

import numpy as np
import pytest

import pounding as pd_


def test_a_one_level_structure_s_targets_are_the_oscillators():
    osc = pd_.presets.paper_calibrated()
    targets = pd_.paper_targets()
    freqs = np.arange(0.5, 3.51, 0.1)
    one = pd_.identification.evaluate(osc, targets, freqs_hz=freqs)
    many = pd_.identification.evaluate(pd_.Structure.from_oscillator(osc), targets, freqs_hz=freqs)
    assert list(one["quantity"]) == list(many["quantity"])
    a, b = one["model"].to_numpy(float), many["model"].to_numpy(float)
    assert (np.isnan(a) == np.isnan(b)).all()
    np.testing.assert_allclose(b[np.isfinite(a)], a[np.isfinite(a)], rtol=1e-9)
    assert list(one["within"]) == list(many["within"])


def test_the_same_fit_finds_the_same_number():
    damped = pd_.presets.paper_damped()
    targets = pd_.Targets.from_records([{"configuration": "NBs", "a_g": 0.05, "quantity": "alpha",
                                         "value": 2.99}])
    options = dict(freqs_hz=[0.9, 1.0, 1.1, 1.2, 1.3], popsize=4, maxiter=3, workers=1)
    fixed = pd_.ModelFamily(500.0).values_of(damped)
    del fixed["isolator_damping"]
    one = pd_.identify(targets, pd_.ModelFamily(500.0, fixed=fixed), {"isolator_damping": (100.0, 5000.0)},
                       **options)
    family = pd_.SystemFamily(pd_.Structure.from_oscillator(damped))
    many = pd_.identify(targets, family, {"isolator.damping_n_s_m": (100.0, 5000.0)}, **options)
    assert many.parameters["isolator.damping_n_s_m"] == pytest.approx(one.parameters["isolator_damping"],
                                                                      rel=1e-9)
    assert isinstance(many.oscillator, pd_.Structure) and many.n_within == one.n_within == 1
    # the single mass itself, its number named by its path: the ModelFamily's fit, number for number
    mass = pd_.identify(targets, pd_.SystemFamily(damped), {"isolator.damping_n_s_m": (100.0, 5000.0)},
                        **options)
    assert mass.parameters["isolator.damping_n_s_m"] == one.parameters["isolator_damping"]
    assert isinstance(mass.oscillator, pd_.Oscillator) and mass.oscillator == one.oscillator


def test_a_system_family_names_what_it_refuses():
    rig = pd_.Structure.from_oscillator(pd_.presets.paper_calibrated())
    with pytest.raises(pd_.InputError, match="names no number"):
        pd_.SystemFamily(rig).free_names({"walls[0].stand.mass_kg": (1.0, 50.0)})
    with pytest.raises(pd_.InputError, match="names no number"):
        pd_.SystemFamily(pd_.presets.paper_calibrated()).free_names({"walls[0].law.stiffness": (1e5, 1e7)})
    with pytest.raises(pd_.InputError, match="isolated"):
        pd_.SystemFamily(pd_.Structure.fixed_base([pd_.Storey(1e3, 1e6)]))
    with pytest.raises(pd_.InputError, match="Oscillator or pounding.Structure"):
        pd_.SystemFamily(pd_.Adjacent(rig, rig, [pd_.Link(0, 0, 0.05, pd_.KelvinVoigt(1e7, 1e3))]))
    with pytest.raises(pd_.InputError) as err:  # (its metrics are exact: no chain to fit)
        pd_.identify(pd_.paper_targets(), pd_.SystemFamily(rig),
                     {"isolator.damping_n_s_m": (100.0, 5000.0), "measurement_cutoff_hz": (10.0, 100.0)})
    assert err.value.field == "bounds.measurement_cutoff_hz"
    with pytest.warns(FutureWarning, match="SystemFamily"):  # (its name before)
        assert pd_.StructureFamily is pd_.SystemFamily


def test_a_system_family_file_on_the_command_line(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    pd_.Structure.from_oscillator(pd_.presets.paper_damped()).to_toml(tmp_path / "rig.toml")
    (tmp_path / "family.toml").write_text('system = "rig.toml"\n'
                                          '[bounds]\n"isolator.damping_n_s_m" = [100.0, 5000.0]\n')
    (tmp_path / "targets.toml").write_text('[[target]]\nconfiguration = "NBs"\na_g = 0.05\n'
                                           'quantity = "alpha"\nvalue = 2.99\n')
    result = CliRunner().invoke(app, ["identify", str(tmp_path / "targets.toml"), "--family",
                                      str(tmp_path / "family.toml"), "--out", str(tmp_path / "fit.toml"),
                                      "--fmin", "0.9", "--fmax", "1.3", "--fstep", "0.1", "--maxiter", "2",
                                      "--popsize", "3", "--workers", "1"])
    assert result.exit_code == 0, result.output
    fitted = pd_.Structure.from_toml(tmp_path / "fit.toml")
    assert 100.0 <= fitted.isolator.damping_n_s_m <= 5000.0
    (tmp_path / "bad.toml").write_text('system = "rig.toml"\n[bounds]\n"walls[3].gap_m" = [0.01, 0.02]\n')
    bad = CliRunner().invoke(app, ["identify", str(tmp_path / "targets.toml"), "--family",
                                   str(tmp_path / "bad.toml")])
    assert bad.exit_code == 2 and "names no number" in bad.output
    # a single mass's file, and the family's key as it was named before (with a warning)
    pd_.presets.paper_damped().to_toml(tmp_path / "mass.toml")
    (tmp_path / "mass_family.toml").write_text('structure = "mass.toml"\n'
                                               '[bounds]\n"bumpers.law.damping" = [0.0, 5000.0]\n')
    with pytest.warns(FutureWarning, match="'system'"):
        family, bounds = pd_.SystemFamily.from_toml(tmp_path / "mass_family.toml")
    assert isinstance(family.base, pd_.Oscillator) and bounds == {"bumpers.law.damping": (0.0, 5000.0)}
