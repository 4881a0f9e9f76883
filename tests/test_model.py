"""Construction, validation (errors that name field, value and fix) and TOML round trips."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

import pounding as pd_
from pounding import InputError


def _raises(fn, *fragments):
    with pytest.raises(InputError) as info:
        fn()
    msg = str(info.value)
    for frag in fragments:
        assert frag in msg, msg
    assert "Fix:" in msg
    return info.value


def test_paper_printed_values_exactly():
    osc = pd_.presets.paper_printed()
    assert osc.mass_kg == 500.0
    assert osc.isolator.slopes_n_m == (38e3, 18e3, 2e3)
    assert osc.isolator.breakpoints_m == (0.015, 0.04)
    assert osc.isolator.damping_n_s_m == 1.0
    assert osc.bumpers.gap_left_m == osc.bumpers.gap_right_m == 0.015
    assert osc.bumpers.law == pd_.KelvinVoigt(1.46e6, 5.0)
    assert osc.bumpers.total_gap == pytest.approx(0.03)
    assert pd_.presets.paper_printed(bumpers=False).bumpers is None
    np.testing.assert_allclose(osc.isolator.yield_forces, [570.0, 1020.0])


def test_backbone_is_odd_and_piecewise_linear():
    iso = pd_.Isolator((10.0, 5.0, 20.0), (1.0, 2.0))
    d = np.array([-3.0, -1.5, 0.0, 0.5, 1.0, 1.5, 2.0, 3.0])
    np.testing.assert_allclose(iso.backbone(d), [-35.0, -12.5, 0.0, 5.0, 10.0, 12.5, 15.0, 35.0])


@pytest.mark.parametrize("mass", [0.0, -1.0])
def test_non_positive_mass(mass):
    iso = pd_.Isolator((1e4,))
    _raises(lambda: pd_.Oscillator(mass, iso), "mass_kg", repr(mass), "> 0")


def test_breakpoints_not_increasing():
    _raises(lambda: pd_.Isolator((3.0, 2.0, 1.0), (0.04, 0.015)), "isolator.breakpoints_m", "increasing")


def test_slopes_and_breakpoints_mismatch():
    _raises(lambda: pd_.Isolator((3.0, 2.0, 1.0), (0.01,)), "isolator.breakpoints_m", "2 are needed")


def test_negative_gap_and_stiffness():
    law = pd_.KelvinVoigt(1e6, 5.0)
    _raises(lambda: pd_.Bumpers(-0.01, 0.01, law), "bumpers.gap_left_m", "-0.01", ">= 0")
    _raises(lambda: pd_.KelvinVoigt(-1.0, 5.0), "law.stiffness", "> 0")
    _raises(lambda: pd_.Isolator((1e4, -1.0), (0.01,)), "isolator.slopes_n_m[1]", ">= 0")


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_nan_and_inf_anywhere(bad):
    law = pd_.KelvinVoigt(1e6, 5.0)
    _raises(lambda: pd_.Oscillator(bad, pd_.Isolator((1e4,))), "mass_kg", "finite")
    _raises(lambda: pd_.Isolator((1e4, bad), (0.01,)), "isolator.slopes_n_m[1]", "finite")
    _raises(lambda: pd_.Isolator((1e4, 1e3), (bad,)), "isolator.breakpoints_m[0]", "finite")
    _raises(lambda: pd_.Isolator((1e4,), damping_n_s_m=bad), "isolator.damping_n_s_m", "finite")
    _raises(lambda: pd_.Bumpers(0.01, bad, law), "bumpers.gap_right_m", "finite")
    _raises(lambda: pd_.KelvinVoigt(1e6, bad), "law.damping", "finite")
    _raises(lambda: pd_.Harmonic(bad, 2.0), "a_g", "finite")
    _raises(lambda: pd_.Harmonic(0.05, bad), "freq_hz", "finite")
    _raises(lambda: pd_.Record([0.0, 1.0], [0.0, bad]), "record.accel[1]", "finite")
    osc = pd_.presets.paper_printed()
    _raises(lambda: pd_.simulate(osc, pd_.Harmonic(0.05, 2.0), bad), "duration", "finite")


def test_record_time_must_increase():
    _raises(lambda: pd_.Record([0.0, 0.1, 0.1, 0.2], [0, 1, 2, 3]), "record.t[1:3]", "increasing")
    _raises(lambda: pd_.Record([0.0, 1.0], [0.0]), "record.accel")
    _raises(lambda: pd_.Record([0.0], [0.0]), "record.t", "at least 2")


def test_bad_simulate_arguments():
    osc = pd_.presets.paper_printed()
    exc = pd_.Harmonic(0.05, 2.0)
    _raises(lambda: pd_.simulate(osc, exc, -1.0), "duration", "> 0")
    _raises(lambda: pd_.simulate(osc, exc, 1.0, sample_rate_hz=-5), "sample_rate_hz")
    _raises(lambda: pd_.simulate(osc, exc, 1.0, rtol=0.5), "rtol")
    _raises(lambda: pd_.simulate("system.toml", exc, 1.0), "system", "Oscillator")
    _raises(lambda: pd_.simulate(osc, 0.05, 1.0), "excitation", "Harmonic")
    other = pd_.Oscillator(500.0, pd_.Isolator((1e4,)))
    _raises(lambda: pd_.simulate(osc, exc, 1.0, pd_.State.at_rest(other)), "state")


def test_toml_round_trip(tmp_path):
    for osc in (pd_.presets.paper_printed(), pd_.presets.paper_printed(bumpers=False),
                pd_.Oscillator(300.0, pd_.Isolator((1e4, 3e4), (0.02,), "elastic", 50.0),
                               pd_.Bumpers(0.01, 0.02, pd_.HuntCrossley(1e8, 1.5, 1e7),
                                           pd_.KelvinVoigt(2e6, 10.0)))):
        path = osc.to_toml(tmp_path / "system.toml")
        assert pd_.Oscillator.from_toml(path) == osc


def test_toml_unknown_key(tmp_path):
    text = pd_.presets.paper_printed().to_toml(tmp_path / "a.toml").read_text()
    (tmp_path / "b.toml").write_text(text.replace("damping_n_s_m = 1.0", "dampnig = 1.0"))
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path / "b.toml"), "isolator.dampnig", "not a known key")
    (tmp_path / "c.toml").write_text("colour = 'red'\n" + text)
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path / "c.toml"), "colour")
    (tmp_path / "d.toml").write_text(text.replace("kelvin_voigt", "maxwell"))
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path / "d.toml"), "bumpers.law.type", "kelvin_voigt")
    (tmp_path / "e.toml").write_text(text.replace("stiffness = 1460000.0", "stiffness = -1.0"))
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path / "e.toml"), "bumpers.law.stiffness", "> 0")
    (tmp_path / "f.toml").write_text(text.replace("stiffness = 1460000.0", "stiffness = nan"))
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path / "f.toml"), "bumpers.law.stiffness", "finite")
    _raises(lambda: pd_.Oscillator.from_toml(tmp_path / "missing.toml"), "does not exist")


def test_example_file_is_the_printed_preset():
    from pathlib import Path

    path = Path(__file__).parents[1] / "examples" / "paper_printed_ybs.toml"
    assert pd_.Oscillator.from_toml(path) == pd_.presets.paper_printed()


def test_the_gaps_names_before_still_work_with_a_warning_naming_the_new_one():
    law = pd_.KelvinVoigt(1.46e6, 5.0)
    new = pd_.Bumpers(gap_left_m=0.015, gap_right_m=0.02, law=law)
    with pytest.warns(FutureWarning, match="'gap_left' is now 'gap_left_m'"):
        old = pd_.Bumpers(gap_left=0.015, gap_right_m=0.02, law=law)
    assert old == new
    with pytest.warns(FutureWarning, match="'gap_right' is now 'gap_right_m'"):
        assert new.gap_right == 0.02
    with pytest.raises(TypeError, match="gap_middle"):
        pd_.Bumpers(0.01, 0.01, law, gap_middle=0.01)
    with pytest.raises(InputError, match="bumpers.gap_right_m"):
        pd_.Bumpers(gap_left_m=0.01, law=law)
    # a TOML file of 0.1: the same system, a warning per old key; both spellings of one key: an error
    text = pd_.presets.paper_printed().to_toml_text()
    assert "gap_left_m = 0.015" in text
    with pytest.warns(FutureWarning, match="'bumpers.gap_left' is now 'bumpers.gap_left_m'"):
        before = pd_.Oscillator.from_toml_text(text.replace("gap_left_m =", "gap_left ="))
    assert before == pd_.presets.paper_printed()
    with pytest.raises(InputError, match="bumpers.gap_left") as info:
        both = text.replace("gap_left_m = 0.015", "gap_left_m = 0.015\ngap_left = 0.015")
        pd_.Oscillator.from_toml_text(both)
    assert "its new name" in str(info.value)
    # the dotted names a study or a continuation varies
    from pounding.model.dotted import get_value, set_value

    table = pd_.presets.paper_printed().to_dict()
    with pytest.warns(FutureWarning, match="'bumpers.gap' is now 'bumpers.gap_m'"):
        set_value(table, "bumpers.gap", 0.02)
    assert get_value(table, "bumpers.gap_left_m") == get_value(table, "bumpers.gap_right_m") == 0.02


def test_the_mass_is_mass_kg_and_its_name_before_still_works_with_a_warning():
    iso = pd_.presets.paper_printed().isolator
    new = pd_.Oscillator(mass_kg=500.0, isolator=iso)
    assert new == pd_.Oscillator(500.0, iso) and new.mass_kg == 500.0
    with pytest.warns(FutureWarning, match="'mass' is now 'mass_kg'"):
        assert pd_.Oscillator(mass=500.0, isolator=iso) == new
    with pytest.warns(FutureWarning, match="'mass' is now 'mass_kg'"):
        assert new.mass == 500.0
    with pytest.raises(TypeError, match="both 'mass_kg' and 'mass'"):
        pd_.Oscillator(mass_kg=500.0, mass=500.0, isolator=iso)
    with pytest.raises(TypeError, match="weight"):
        pd_.Oscillator(weight=500.0, isolator=iso)
    with pytest.raises(TypeError, match="mass_kg"):
        pd_.Oscillator(isolator=iso)
    # a TOML file of 0.1 (its key "mass"), and the dotted name a study varies
    text = pd_.presets.paper_printed().to_toml_text()
    assert text.startswith("mass_kg = 500.0")
    with pytest.warns(FutureWarning, match="'mass' is now 'mass_kg'"):
        before = pd_.Oscillator.from_toml_text(text.replace("mass_kg =", "mass ="))
    assert before == pd_.presets.paper_printed()
    with pytest.raises(InputError, match="mass"):
        pd_.Oscillator.from_toml_text(text.replace("mass_kg = 500.0", "mass_kg = 500.0\nmass = 500.0"))
    from pounding.model.dotted import get_value, set_value

    table = pd_.presets.paper_printed().to_dict()
    with pytest.warns(FutureWarning, match="'mass' is now 'mass_kg'"):
        set_value(table, "mass", 600.0)
    assert get_value(table, "mass_kg") == 600.0 and pd_.Oscillator.from_dict(table).mass_kg == 600.0
    # replace() and pickling keep working (frozen, with its own __init__)
    import pickle

    assert dataclasses.replace(new, mass_kg=600.0).mass_kg == 600.0
    assert pickle.loads(pickle.dumps(new)) == new


def test_the_isolator_s_numbers_carry_their_units_and_their_names_before_still_work():
    new = pd_.Isolator(slopes_n_m=[38e3, 18e3], breakpoints_m=[0.015], damping_n_s_m=600.0)
    assert new == pd_.Isolator((38e3, 18e3), (0.015,), "kinematic", 600.0)
    with pytest.warns(FutureWarning) as caught:
        before = pd_.Isolator(slopes=[38e3, 18e3], breakpoints=[0.015], damping=600.0)
    assert before == new
    assert sorted(str(w.message).split("'")[1] for w in caught) == ["breakpoints", "damping", "slopes"]
    with pytest.warns(FutureWarning, match="'damping' is now 'damping_n_s_m'"):
        assert new.damping == 600.0
    with pytest.warns(FutureWarning, match="'slopes' is now 'slopes_n_m'"):
        assert new.slopes == (38e3, 18e3)
    with pytest.raises(TypeError, match="both 'damping_n_s_m' and 'damping'"):
        pd_.Isolator([38e3], damping=1.0, damping_n_s_m=1.0)
    with pytest.raises(InputError) as err:
        pd_.Isolator([38e3, -1.0], [0.015])
    assert err.value.field == "isolator.slopes_n_m[1]"
    # a TOML file of 0.1 (a one-mass system's and a building's), and the dotted names a study varies
    text = pd_.presets.paper_printed().to_toml_text()
    assert "slopes_n_m = [" in text and "damping_n_s_m = " in text
    old = text.replace("slopes_n_m =", "slopes =").replace("breakpoints_m =", "breakpoints =")
    with pytest.warns(FutureWarning) as caught:
        assert pd_.Oscillator.from_toml_text(old) == pd_.presets.paper_printed()
    assert sorted(str(w.message).split("'")[1] for w in caught) == ["isolator.breakpoints", "isolator.slopes"]
    building = pd_.Structure(3e4, new, [pd_.Storey(2e4, 4e7)])
    old = building.to_toml_text().replace("damping_n_s_m = 600.0", "damping = 600.0")
    with pytest.warns(FutureWarning, match="'isolator.damping' is now 'isolator.damping_n_s_m'"):
        assert pd_.Structure.from_toml_text(old) == building
    from pounding.model.dotted import get_value, set_value

    table = pd_.presets.paper_printed().to_dict()
    with pytest.warns(FutureWarning, match=r"'isolator.slopes\[1\]' is now 'isolator.slopes_n_m\[1\]'"):
        set_value(table, "isolator.slopes[1]", 20e3)
    assert get_value(table, "isolator.slopes_n_m[1]") == 20e3
    pair = pd_.Adjacent(building, pd_.Structure.fixed_base([pd_.Storey(2e4, 4e7)]),
                        [pd_.Link(1, 1, 0.1, pd_.KelvinVoigt(1e8, 1e5))]).to_dict()
    with pytest.warns(FutureWarning, match="'first.isolator.damping' is now 'first.isolator.damping_n_s_m'"):
        set_value(pair, "first.isolator.damping", 700.0)
    assert get_value(pair, "first.isolator.damping_n_s_m") == 700.0
    # its Bouc-Wen spring's too
    bw = pd_.BoucWen(stiffness_n_m=2e4, yield_displacement_m=0.005)
    with pytest.warns(FutureWarning) as caught:
        assert pd_.BoucWen(stiffness=2e4, yield_displacement=0.005) == bw
    assert sorted(str(w.message).split("'")[1] for w in caught) == ["stiffness", "yield_displacement"]
    with pytest.warns(FutureWarning, match="'yield_displacement' is now 'yield_displacement_m'"):
        assert bw.yield_displacement == 0.005
    rubber = pd_.Oscillator(500.0, pd_.Isolator([1.8e4], damping_n_s_m=500.0, bouc_wen=bw))
    text = rubber.to_toml_text()
    assert "stiffness_n_m = 20000.0" in text
    before = text.replace("stiffness_n_m = 2", "stiffness = 2")
    with pytest.warns(FutureWarning, match="'isolator.bouc_wen.stiffness' is now 'isolator.bouc_wen.stiff"):
        assert pd_.Oscillator.from_toml_text(before) == rubber
    table = rubber.to_dict()
    with pytest.warns(FutureWarning, match="'isolator.bouc_wen.stiffness' is now"):
        set_value(table, "isolator.bouc_wen.stiffness", 3e4)
    assert get_value(table, "isolator.bouc_wen.stiffness_n_m") == 3e4


def test_a_system_is_given_as_system_and_the_name_before_still_works():
    osc, exc = pd_.presets.paper_damped(), pd_.Harmonic(0.05, 2.0)
    with pytest.warns(FutureWarning, match="'oscillator' is now 'system'"):
        before = pd_.simulate(oscillator=osc, excitation=exc, duration=1.0)
    now = pd_.simulate(system=osc, excitation=exc, duration=1.0)
    np.testing.assert_array_equal(before.displacement, now.displacement)
    with pytest.raises(TypeError, match="both 'system' and 'oscillator'"):
        pd_.sweep(system=osc, oscillator=osc, a_g=0.05, freqs_hz=[1.0])


def test_a_single_mass_s_bumpers_are_its_wall_checked_and_warned_about_once():
    # (its Bumpers checked the numbers; the one-level structure it is assembled as does not say it again)
    law = pd_.KelvinVoigt(1e8, 1e3)
    other = pd_.KelvinVoigt(2e8, 0.0)
    for bumpers in (pd_.Bumpers(0.015, 0.02, law), pd_.Bumpers(0.0, 0.01, law, law_right=other)):
        wall = pd_.Structure.from_oscillator(pd_.Oscillator(500.0, pd_.presets.paper_damped().isolator,
                                                            bumpers)).walls[0]
        assert wall == pd_.Wall(0, bumpers.gap_left_m, bumpers.gap_right_m, bumpers.left,
                                None if bumpers.right is bumpers.left else bumpers.right)
        assert wall.left is bumpers.left and wall.right is bumpers.right
    with pytest.warns(pd_.PoundingWarning) as seen:
        far = pd_.Oscillator(500.0, pd_.presets.paper_damped().isolator, pd_.Bumpers(3.0, 3.0, law))
    assert [str(w.message).split(" = ")[0] for w in seen] == ["bumpers.gap_left_m", "bumpers.gap_right_m"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # (a second warning, the wall's, would raise here)
        run = pd_.simulate(far, pd_.Harmonic(0.05, 2.0), 1.0)
    assert run.status == pd_.Status.SUCCESS and len(run.contacts) == 0


def test_the_module_of_bumpers_before_answers_for_one_release():
    import importlib
    import pickle

    before = importlib.import_module("pounding.model.bumpers")
    with pytest.warns(FutureWarning, match="pounding.model.structure_parts.Bumpers"):
        assert before.Bumpers is pd_.Bumpers
    with pytest.raises(AttributeError):
        before.Wall  # noqa: B018  (only its own names answer)
    # a pickle made before names the old module: it still loads
    old = pickle.dumps(pd_.Bumpers(0.01, 0.02, pd_.KelvinVoigt(1e6, 5.0)), protocol=0).replace(
        b"pounding.model.structure_parts", b"pounding.model.bumpers")
    with pytest.warns(FutureWarning):
        assert pickle.loads(old) == pd_.Bumpers(0.01, 0.02, pd_.KelvinVoigt(1e6, 5.0))
