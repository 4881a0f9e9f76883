"""A building in plan (pounding.model.plan): its checks, its matrices and modes against closed forms, its
TOML.  Its runs: tests/test_plan_run.py."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pounding
from pounding import InputError
from pounding.model.plan import PlanBuilding
from pounding.model.moats import RectangularMoat
from pounding.model.plan_parts import Bearing, Floor, Frame



def _iso(k1, k2=None, dy=0.0, c=0.0):
    if k2 is None:
        return pounding.Isolator(slopes_n_m=[k1], breakpoints_m=[], damping_n_s_m=c)
    return pounding.Isolator(slopes_n_m=[k1, k2], breakpoints_m=[dy], damping_n_s_m=c)


def _square(k=1.0e6, a=10.0, b=6.0, mass=2.0e5, ecc=(0.0, 0.0)):
    """One floor on four equal linear bearings at (+-a, +-b)."""
    bearings = [Bearing((sx * a, sy * b), _iso(k)) for sx in (-1, 1) for sy in (-1, 1)]
    return PlanBuilding([Floor(mass, (2.5 * a, 2.5 * b))], bearings, accidental_eccentricity=ecc)


# ---------------------------------------------------------------------------------------- closed forms
def test_a_symmetric_floor_s_periods_are_the_closed_form():
    k, a, b, m = 1.0e6, 10.0, 6.0, 2.0e5
    building = _square(k, a, b, m)
    j = m * ((2.5 * a) ** 2 + (2.5 * b) ** 2) / 12.0
    assert building.floors[0].inertia_kg_m2 == pytest.approx(j, rel=1e-15)
    w2 = [4 * k / m, 4 * k / m, 4 * k * (a * a + b * b) / j]
    expected = sorted((2 * math.pi / math.sqrt(v) for v in w2), reverse=True)
    np.testing.assert_allclose(building.modes().periods_s, expected, rtol=1e-12)
    np.testing.assert_allclose(building.centres_of_stiffness_m(), [[0.0, 0.0]], atol=1e-12)


@pytest.mark.parametrize("e", [0.05, -0.05, 0.1])
def test_an_eccentric_mass_couples_translation_and_rotation_as_the_closed_form(e):
    # the centre of mass moved by e of the side along x: y and rotation coupled, x alone
    k, a, b, m = 1.0e6, 10.0, 6.0, 2.0e5
    building = _square(k, a, b, m, ecc=(e, 0.0))
    ex = e * 2.5 * a
    j = m * ((2.5 * a) ** 2 + (2.5 * b) ** 2) / 12.0
    kyy, kyt, ktt = 4 * k, -4 * k * ex, 4 * k * (a * a + ex * ex + b * b)
    # det([[kyy - m w2, kyt], [kyt, ktt - j w2]]) = 0
    qa, qb, qc = m * j, -(kyy * j + ktt * m), kyy * ktt - kyt * kyt
    roots = [(-qb + s * math.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa) for s in (1, -1)]
    expected = sorted([2 * math.pi / math.sqrt(w2) for w2 in [4 * k / m, *roots]], reverse=True)
    np.testing.assert_allclose(building.modes().periods_s, expected, rtol=1e-12)
    np.testing.assert_allclose(building.eccentricities_m(), [[-ex, 0.0]], atol=1e-12)
    assert building.placed_floors[0].centre_m == pytest.approx((ex, 0.0))
    # the x mode moves x alone
    shapes = building.modes().shapes
    x_mode = np.argmin(np.abs(building.modes().periods_s - 2 * math.pi / math.sqrt(4 * k / m)))
    np.testing.assert_allclose(shapes[:, x_mode], [1.0, 0.0, 0.0], atol=1e-12)


def test_a_storey_s_centre_of_stiffness_is_its_lines_weighted_mean():
    floors = [Floor(3e5, (20.0, 10.0))] * 2
    bearings = [Bearing((sx * 8.0, sy * 4.0), _iso(2e6)) for sx in (-1, 1) for sy in (-1, 1)]
    frames = [Frame(1, "x", -5.0, 1e8), Frame(1, "x", 5.0, 3e8), Frame(1, "y", -10.0, 2e8),
              Frame(1, "y", 4.0, 2e8)]
    b = PlanBuilding(floors, bearings, frames)
    np.testing.assert_allclose(b.centres_of_stiffness_m(), [[0.0, 0.0], [-3.0, 2.5]], atol=1e-12)
    assert len(b.accidental_cases()) == 4
    assert {c.accidental_eccentricity for c in b.accidental_cases()} == {
        (sx * 0.05, sy * 0.05) for sx in (1.0, -1.0) for sy in (1.0, -1.0)}


# ---------------------------------------------------------------------------------------- checks
def _building(**changes):
    values = dict(floors=[Floor(3e5, (20.0, 10.0))] * 2,
                  bearings=[Bearing((sx * 8.0, sy * 4.0), _iso(2e6)) for sx in (-1, 1) for sy in (-1, 1)],
                  frames=([Frame(1, "x", y, 1e8) for y in (-5.0, 5.0)]
                          + [Frame(1, "y", x, 1e8) for x in (-9.0, 9.0)]),
                  moat=RectangularMoat(0.3, pounding.KelvinVoigt(1e9, 1e6)))
    values.update(changes)
    return PlanBuilding(**values)


@pytest.mark.parametrize("make, field", [
    (lambda: Floor(-1.0, (10.0, 10.0)), "floor.mass_kg"),
    (lambda: Floor(1e5, (10.0,)), "floor.size_m"),
    (lambda: Floor(1e5, (10.0, 0.0)), "floor.size_m[1]"),
    (lambda: Floor(1e5, (10.0, 10.0), centre_m=(6.0, 0.0)), "floor.centre_m[0]"),
    (lambda: Floor(1e5, (10.0, 10.0), inertia_kg_m2=float("nan")), "floor.inertia_kg_m2"),
    (lambda: Frame(0, "x", 0.0, 1e8), "frame.storey"),
    (lambda: Frame(1, "z", 0.0, 1e8), "frame.axis"),
    (lambda: Frame(1, "x", float("inf"), 1e8), "frame.at_m"),
    (lambda: Frame(1, "x", 0.0, 1e8, breakpoints_m=[0.01]), "frame.breakpoints_m"),
    (lambda: Frame(1, "x", 0.0, 1e8, height_m=0.0), "frame.height_m"),
    (lambda: Frame(1, "x", 0.0, -1e8), "frame.stiffness_n_m"),
    (lambda: Bearing((0.0, 0.0, 1.0), _iso(1e6)), "bearing.at_m"),
    (lambda: Bearing((0.0, 0.0), pounding.FrictionIsolator(mu=0.05, radius_m=2.0)),
     "bearing.isolator.preslip_m"),
    (lambda: Bearing((0.0, 0.0), pounding.TripleFrictionPendulum(
        radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08), capacities_m=(0.3, 0.05, 0.05, 0.3))),
     "bearing.isolator"),
    (lambda: RectangularMoat((0.1, 0.2), pounding.KelvinVoigt(1e9, 1e6)), "moat.gap_m"),
    (lambda: RectangularMoat(-0.1, pounding.KelvinVoigt(1e9, 1e6)), "moat.gap_m"),
    (lambda: RectangularMoat((0.1, -0.1, 0.1, 0.1), pounding.KelvinVoigt(1e9, 1e6)), "moat.gap_m[1]"),
    (lambda: _building(bearings=[Bearing((sx * 11.0, sy * 4.0), _iso(2e6)) for sx in (-1, 1)
                                 for sy in (-1, 1)]), "bearings[0].at_m"),
    (lambda: _building(frames=[Frame(1, "x", 6.0, 1e8), Frame(1, "x", -5.0, 1e8), Frame(1, "y", 9.0, 1e8)]),
     "frames[0].at_m"),
    (lambda: RectangularMoat(0.1, "steel"), "moat.law"),
    (lambda: _building(floors=[]), "floors"),
    (lambda: _building(bearings=[]), "bearings"),
    (lambda: _building(frames=[Frame(2, "x", 0.0, 1e8)]), "frames[0].storey"),
    (lambda: _building(frames=[Frame(1, "x", y, 1e8) for y in (-5.0, 5.0)]), "frames"),
    (lambda: _building(frames=[Frame(1, "x", 0.0, 1e8), Frame(1, "y", 0.0, 1e8)]), "frames"),
    (lambda: _building(frames=[Frame(1, "x", 3.0, 1e8), Frame(1, "y", 5.0, 2e8)]), "frames"),  # (off centre)
    (lambda: _building(floors=[Floor(3e5, (20.0, 10.0))], frames=[Frame(1, "x", 0.0, 1e8)]),
     "frames[0].storey"),
    (lambda: _building(floors=[Floor(3e5, (20.0, 10.0), centre_m=(9.5, 0.0))] * 2,
                       accidental_eccentricity=(0.05, 0.0)), "accidental_eccentricity"),
    (lambda: _building(bearings=[Bearing((0.0, 0.0), _iso(1e6))]), "bearings"),
    (lambda: _building(moat=RectangularMoat(0.1, pounding.KelvinVoigt(1e9, 1e6), level=2)), "moat.level"),
    (lambda: _building(accidental_eccentricity=(0.5, 0.0)), "accidental_eccentricity[0]"),
    (lambda: _building(accidental_eccentricity=(0.05,)), "accidental_eccentricity"),
    (lambda: _building(floors="floor"), "floors"),
])
def test_bad_parts_are_refused_by_name(make, field):
    with pytest.raises(InputError) as info:
        make()
    assert info.value.field == field, str(info.value)
    assert "Fix:" in str(info.value) or "fix" in str(info.value).lower()


def test_an_implausible_inertia_warns():
    with pytest.warns(UserWarning, match="floor.inertia_kg_m2"):
        Floor(1e5, (10.0, 10.0), inertia_kg_m2=1e3)


def test_a_building_in_plan_reads_back_from_toml(tmp_path):
    b = _building(frames=[Frame(1, "x", -5.0, 1e8, 2e4, slopes_after_n_m=[1e7], breakpoints_m=[0.01]),
                          Frame(1, "x", 5.0, 1e8), Frame(1, "y", -9.0, 1e8), Frame(1, "y", 9.0, 1e8)],
                  accidental_eccentricity=(0.05, -0.05))
    path = tmp_path / "plan.toml"
    b.to_toml(path)
    assert PlanBuilding.from_toml(path) == b
    text = b.to_toml_text().replace("stiffness_n_m = 100000000.0", "stiffnes_n_m = 100000000.0", 1)
    with pytest.raises(InputError, match=r"frames\[0\]\.stiffnes_n_m"):
        PlanBuilding.from_toml_text(text)


def test_a_mode_that_turns_is_scaled_by_the_motion_of_a_corner():
    # a floor on two lines along y only near its centre and stiff lines along x: its torsional mode turns
    # mostly; its shape is scaled so that its largest motion (a translation, or a corner's from the turn) is 1
    b = _square(ecc=(0.1, 0.0))
    modes = b.modes()
    reach = 0.5 * np.hypot(*b.floors[0].size_m)
    for col in range(3):
        shape = modes.shapes[:, col]
        motions = np.abs(shape) * np.array([1.0, 1.0, reach])
        assert np.max(motions) == pytest.approx(1.0, rel=1e-12)
        assert shape[np.argmax(motions)] > 0
    turning = np.argmax(np.abs(modes.shapes[2]))
    assert abs(modes.shapes[2, turning]) * reach == pytest.approx(1.0, rel=1e-12)


def test_implausible_masses_and_gaps_warn_once():
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        Floor(500.0, (40.0, 20.0))  # (tonnes given as kg)
        RectangularMoat(300.0, pounding.KelvinVoigt(1e9, 1e6))  # (mm given as m: one warning, not four)
    messages = [str(w.message) for w in caught]
    assert len(messages) == 2, messages
    assert "kg/m^2" in messages[0] and "moat.gap_m = 300.0" in messages[1]
