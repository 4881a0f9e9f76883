"""Friction bearings in plan (``Bearing`` with a ``FrictionIsolator``): the friction circle is the
bidirectional Bouc-Wen spring it says it is (that spring runs as the independent reference in
test_bouc_wen_elements.py), its steady orbit under circular shaking is the rigid-plastic closed form to the
first order of the pre-slip, one bilinear friction per axis along x is the line's friction isolator, the
building shares its weight among its bearings, a spectrum scales the pendulums' radii, and what is not
supported is refused by name."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import pounding
from pounding import Bearing, Floor, FrictionIsolator, InputError, PlanBuilding, RectangularMoat
from pounding.protocols.pounding_spectrum import bearings_at, isolated_period_s

G = 9.81


def _square(fps, c_per_bearing=0.0, mass_kg=4e5, moat=None, bidirectional=True):
    """A square floor on four equal friction bearings at its corners' quarter points, its mass centred."""
    fps = dataclasses.replace(fps, damping_n_s_m=c_per_bearing)
    return PlanBuilding([Floor(mass_kg, (20.0, 20.0))],
                        [Bearing((sx * 8.0, sy * 8.0), fps, bidirectional=bidirectional)
                         for sx in (-1, 1) for sy in (-1, 1)], moat=moat)


def test_a_bearing_carries_its_share_of_the_building_s_weight_unless_given():
    fps = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4)
    b = PlanBuilding([Floor(4e5, (20.0, 12.0)), Floor(2e5, (20.0, 12.0))],
                     [Bearing((sx * 8.0, sy * 4.0), fps) for sx in (-1, 1) for sy in (-1, 1)],
                     [pounding.Frame(1, axis, s * 3.0, 2e8) for axis in "xy" for s in (-1, 1)])
    assert [x.isolator.weight_n for x in b.bearings] == pytest.approx([G * 6e5 / 4] * 4, rel=1e-15)
    # a floor heavier: the shares follow; a weight given: kept
    heavier = dataclasses.replace(b, floors=[Floor(8e5, (20.0, 12.0)), Floor(2e5, (20.0, 12.0))])
    assert heavier.bearings[0].isolator.weight_n == pytest.approx(G * 1e6 / 4, rel=1e-15)
    given = dataclasses.replace(b, bearings=[Bearing(x.at_m, dataclasses.replace(fps, weight_n=1.5e6))
                                             for x in b.bearings])
    assert [x.isolator.weight_n for x in given.bearings] == [1.5e6] * 4
    # its initial stiffness is the pre-slip's, mu W / preslip_m + W / R, along x and y
    w = G * 6e5 / 4
    np.testing.assert_allclose(np.diag(b.stiffness_matrix(0))[:2], 4 * (0.06 * w / 5e-4 + w / 2.0),
                               rtol=1e-14)


def _balanced(b):
    """Each bearing's weight (N), and their sum and moments less the building's weight at its centre of mass:
    zero where the bearings hold the building up as it stands."""
    w = np.array([x.isolator.weight_n for x in b.bearings])
    at = np.array([x.at_m for x in b.bearings])
    floors = b.placed_floors
    mass = sum(f.mass_kg for f in floors)
    centre = sum(f.mass_kg * np.asarray(f.centre_m) for f in floors) / mass
    return w, np.array([w.sum() - G * mass, *(w @ at - G * mass * centre)]) / (G * mass)


def test_the_bearings_carry_the_building_where_it_stands():
    # the shares balance the building's weight at its centre of mass (as a rigid base on equally stiff
    # bearings shares it: linear in the bearings' places), with the accidental eccentricity; a bearing given
    # its weight keeps it, the others share what it leaves
    fps = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4)
    at = [(sx * 8.0, sy * 4.0) for sx in (-1, 1) for sy in (-1, 1)] + [(0.0, 5.0)]
    floors = [Floor(4e5, (20.0, 12.0), centre_m=(2.0, -1.0)), Floor(2e5, (20.0, 12.0), centre_m=(-1.0, 0.5))]
    frames = [pounding.Frame(1, axis, s * 3.0, 2e8) for axis in "xy" for s in (-1, 1)]
    rubber = pounding.Isolator([1e6])
    for laws, ecc in (([fps] * 5, (0.0, 0.0)), ([fps] * 4 + [rubber], (0.05, -0.05)),
                      ([dataclasses.replace(fps, weight_n=2e6)] + [fps] * 4, (0.0, 0.0))):
        b = PlanBuilding(floors, [Bearing(p, law) for p, law in zip(at, laws)], frames,
                         accidental_eccentricity=ecc)
        if isinstance(laws[-1], pounding.Isolator):  # (a rubber bearing carries its share too)
            w = np.array([x.isolator.weight_n for x in b.bearings[:4]])
            assert np.all(w > 0.0) and w.sum() < G * 6e5
            continue
        w, off = _balanced(b)
        assert np.all(w > 0.0) and np.max(np.abs(off)) < 1e-14, off
        assert w[0] == (2e6 if laws[0].weight_n else w[0])
    # a centre of mass beyond the bearings: a share would pull, refused; every weight given, far from the
    # building's: a warning (a weight in kg?)
    with pytest.raises(InputError, match="pulling") as err:
        PlanBuilding([Floor(4e5, (20.0, 12.0), centre_m=(9.5, 0.0))], [Bearing(p, fps) for p in at[:4]])
    assert err.value.field.startswith("bearings[") and err.value.field.endswith("].at_m")
    floors = [Floor(4e5, (20.0, 12.0))]
    at = at[:4]
    total = G * 4e5
    with pytest.raises(InputError, match="leave nothing"):
        PlanBuilding(floors, [Bearing(p, dataclasses.replace(fps, weight_n=total) if q < 2 else fps)
                              for q, p in enumerate(at)])
    with pytest.warns(pounding.PoundingWarning, match="weights sum to"):
        PlanBuilding(floors, [Bearing(p, dataclasses.replace(fps, weight_n=4e5 / 4)) for p in at])
    # the two on one side given 0.1 W each: the two left on the other line cannot balance the moment (they
    # carry the rest, 0.4 W each, and a warning says the building turns as if its mass were elsewhere)
    with pytest.warns(pounding.PoundingWarning, match="cannot balance"):
        b = PlanBuilding(floors, [Bearing(p, dataclasses.replace(fps, weight_n=0.1 * total) if q < 2 else fps)
                                  for q, p in enumerate(at)])
    assert [x.isolator.weight_n for x in b.bearings[2:]] == pytest.approx([0.4 * total] * 2, rel=1e-14)
    # a share whose pre-slip stiffness is beyond any isolator's: the bearing named
    with pytest.raises(InputError) as err, pytest.warns(pounding.PoundingWarning):  # (implausible numbers)
        PlanBuilding([Floor(1e9, (20.0, 12.0))],  # (mu W / preslip_m: 0.9 x 2.45e9 N / 1e-6 m > 1e15 N/m)
                     [Bearing(p, FrictionIsolator(mu=0.9, radius_m=2.0, preslip_m=1e-6)) for p in at])
    assert err.value.field == "bearings[0].isolator.preslip_m", str(err.value)


def test_a_tiny_pre_slip_warns_and_a_bad_number_in_a_file_names_its_bearing(tmp_path):
    with pytest.warns(pounding.PoundingWarning, match="preslip_m"):
        Bearing((0.0, 0.0), FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=2e-5))
    b = _square(FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4))
    text = b.to_toml_text().replace("preslip_m = 0.0005", 'preslip_m = "0.0005"', 1)
    with pytest.raises(InputError) as err:
        PlanBuilding.from_toml_text(text)
    assert err.value.field == "bearings[0].isolator.preslip_m", str(err.value)


def test_the_bouc_wen_friction_circle_is_its_bidirectional_bouc_wen_spring():
    # a friction pendulum bearing in plan with friction_circle="bouc_wen" (Constantinou, Mokha and Reinhorn's
    # smooth circle) is, number for number, a bearing whose law is the pendulum's W / R
    # with a bidirectional Bouc-Wen spring of stiffness mu W / preslip_m, yield displacement preslip_m, a = 1,
    # beta = gamma = 1/2, n = 2 (its force mu W z, |z| <= 1)
    fps = FrictionIsolator(mu=0.05, radius_m=2.5, preslip_m=1e-3, damping_n_s_m=2e4)
    floors = [Floor(3e5, (24.0, 16.0), centre_m=(1.0, -0.5)), Floor(2.5e5, (24.0, 16.0))]
    frames = [pounding.Frame(1, "x", -6.0, 3e8, 1e5), pounding.Frame(1, "x", 7.0, 2e8, 1e5),
              pounding.Frame(1, "y", -10.0, 3e8, 1e5), pounding.Frame(1, "y", 11.0, 2e8, 1e5)]
    at = [(sx * 10.0, sy * 6.0) for sx in (-1, 1) for sy in (-1, 1)]
    moat = RectangularMoat(0.15, pounding.KelvinVoigt(2e8, 4e5))
    sliding = PlanBuilding(floors, [Bearing(p, fps, friction_circle="bouc_wen") for p in at], frames, moat)

    def rubber(w):
        return pounding.Isolator(slopes_n_m=[w / 2.5], damping_n_s_m=2e4,
                                 bouc_wen=pounding.BoucWen(0.05 * w / 1e-3, 1e-3, 1.0, 0.5, 0.5, 2.0))

    spring = PlanBuilding(floors, [Bearing(p, rubber(x.isolator.weight_n))
                                   for p, x in zip(at, sliding.bearings)], frames, moat)
    rec = pounding.records.el_centro().scaled(pga_g=0.8)
    pair = pounding.RecordPair.of_direction(rec, 30.0)
    a, b = pounding.simulate(sliding, pair, 8.0), pounding.simulate(spring, pair, 8.0)
    assert len(a.contacts) > 0 and a.status.name == "SUCCESS"
    np.testing.assert_array_equal(a.final_state.vector, b.final_state.vector)
    np.testing.assert_array_equal(a.bearing_displacement_max_m, b.bearing_displacement_max_m)


def test_a_sliding_bearing_s_friction_stays_inside_its_circle_and_reaches_it():
    # each bearing's force less the pendulum's W / R u and the dashpot's: the friction, whose length in the
    # plane never exceeds mu W (to the rounding of the samples) and reaches it while the floor slides
    fps = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4)
    b = _square(fps, 0.0)
    rec = pounding.records.el_centro().scaled(pga_g=0.6)
    run = pounding.simulate(b, pounding.RecordPair.of_direction(rec, 25.0), 6.0, sample_rate_hz=200.0)
    w = G * 4e5 / 4
    friction = run.bearing_force - (w / 2.0) * run.bearing_displacement
    length = np.hypot(friction[..., 0], friction[..., 1])
    assert np.max(length) <= 0.06 * w * (1.0 + 1e-9)
    assert np.max(length) >= 0.06 * w * (1.0 - 1e-3)
    assert np.max(run.bearing_displacement_max_m) > 50 * 5e-4  # (it slid, far beyond the pre-slip)


def test_a_building_on_pendulums_turns_only_as_its_masses_make_it():
    # a rigid floor on friction pendulums whose centre of mass is 3 m off the bearings' middle: each
    # bearing's load, and so its W / R and mu W, follows where the mass stands, the bearings' centre of
    # stiffness is the centre of mass, and shaking across the offset turns it not at all (with equal
    # shares it turned by 3 mrad and its bearings moved 87 and 173 mm)
    fps = FrictionIsolator(mu=0.06, radius_m=2.5, preslip_m=5e-4)
    b = PlanBuilding([Floor(1.2e6, (30.0, 12.0), centre_m=(3.0, 0.0))],
                     [Bearing((sx * 14.0, sy * 5.0), fps) for sx in (-1, 1) for sy in (-1, 1)])
    rec = pounding.records.el_centro().scaled(pga_g=0.5)
    run = pounding.simulate(b, pounding.RecordPair.of_direction(rec, 90.0), 8.0)
    assert np.max(run.bearing_displacement_max_m) > 0.05
    assert np.max(np.abs(run.displacement[:, 0, 2])) < 1e-15
    np.testing.assert_allclose(run.bearing_displacement_max_m, run.bearing_displacement_max_m[0], rtol=1e-12)


def steady_orbit_radius(fps, c_per_bearing, freq_hz, a_g):
    """The steady orbit's radius (half its width, about its own centre) of the square floor on ``fps``
    under circular shaking, at each sample of its last period."""
    b = _square(fps, c_per_bearing)
    table = pounding.HarmonicPair.circular(a_g, freq_hz)
    steady = pounding.simulate(b, table, 12.0, sample_rate_hz=0.0).final_state
    run = pounding.simulate(b, table, 1.0 / freq_hz, state=steady, sample_rate_hz=400.0)
    x, y = run.displacement[:, 0, 0], run.displacement[:, 0, 1]
    # (the circle through the samples, x^2 + y^2 + d x + e y + f = 0 by least squares: a flat slider's orbit
    # is centred where its transient left it)
    d, e, _ = np.linalg.lstsq(np.column_stack([x, y, np.ones_like(x)]), -(x * x + y * y), rcond=None)[0]
    centre = (-0.5 * d, -0.5 * e)
    assert np.max(np.abs(run.displacement[:, 0, 2])) < 1e-15  # (a symmetric floor never turns)
    return np.hypot(x - centre[0], y - centre[1])


def _steady_radius(fps, c_per_bearing, freq_hz, a_g):
    """The steady orbit's radius (:func:`steady_orbit_radius`) and the closed form of the rigid-plastic
    friction circle: |(k - m w^2) r + i (c w r + mu W)| = m A."""
    got = steady_orbit_radius(fps, c_per_bearing, freq_hz, a_g)
    w = 2.0 * math.pi * freq_hz
    k_m = 0.0 if fps.radius_m is None else G / fps.radius_m
    c_m, mu_g, acc = 4 * c_per_bearing / 4e5, fps.mu * G, a_g * G
    a2, b1, c0 = (k_m - w * w) ** 2 + (c_m * w) ** 2, 2.0 * c_m * w * mu_g, mu_g**2 - acc**2
    closed = (-b1 + math.sqrt(b1 * b1 - 4.0 * a2 * c0)) / (2.0 * a2)
    return got, closed


@pytest.mark.parametrize("radius_m, freq_hz, a_g", [(2.0, 0.7, 0.3), (None, 0.7, 0.3), (2.0, 0.3, 0.2)])
def test_circular_shaking_drives_the_closed_form_orbit_of_the_friction_circle(radius_m, freq_hz, a_g):
    # a rigid floor on sliding bearings under circularly polarised shaking settles on a circle whose
    # friction, mu W along the velocity, turns with it: the rigid-plastic circle's closed form.  The elastic
    # pre-slip lags the force behind the velocity: the radius differs to the first order of preslip / r, so
    # five times less pre-slip gives five times less difference
    errors = []
    for preslip in (1e-3, 2e-4):
        fps = FrictionIsolator(mu=0.06, radius_m=radius_m, preslip_m=preslip)
        got, closed = _steady_radius(fps, 3e5, freq_hz, a_g)
        assert np.ptp(got) < 1e-6 * closed  # (a circle)
        error = abs(float(np.mean(got)) / closed - 1.0)
        assert error < preslip / closed, (preslip, error)
        errors.append(error)
    assert 3.5 < errors[0] / errors[1] < 6.5


def assert_along_x_is_the_line(run, ref):
    """A plan building's run along x (``run``) against its line's (``ref``): every floor's extremes along x
    to 1e-9, the input work to 1e-9 and the hysteretic work to 1e-8."""
    np.testing.assert_allclose(run.displacement_max[:, 0], ref.displacement_max, rtol=1e-9)
    np.testing.assert_allclose(run.displacement_min[:, 0], ref.displacement_min, rtol=1e-9)
    assert run.energy.input_work == pytest.approx(ref.energy.input_work, rel=1e-9)
    assert run.energy.hysteretic == pytest.approx(ref.energy.hysteretic, rel=1e-8)


def along_x_and_its_line(bidirectional):
    """A symmetric two-floor building on four friction pendulums (``bidirectional``: their circle, or one
    friction per axis), the line's structure it is along x (one isolator carrying the whole weight), and
    El Centro at 0.5 g: ``(building, line, record)``."""
    fps = FrictionIsolator(mu=0.07, radius_m=2.2, preslip_m=1e-3, damping_n_s_m=1e4)
    floors = [Floor(3e5, (24.0, 16.0))] * 2
    frames = [pounding.Frame(1, axis, s * at, 1.5e8, 1e5) for axis, at in (("x", 7.0), ("y", 11.0))
              for s in (-1.0, 1.0)]
    b = PlanBuilding(floors, [Bearing((sx * 10.0, sy * 6.0), fps, bidirectional=bidirectional)
                              for sx in (-1, 1) for sy in (-1, 1)], frames)
    line = pounding.Structure(3e5, dataclasses.replace(fps, damping_n_s_m=4e4),
                              [pounding.Storey(3e5, 3e8, 2e5)], [])
    return b, line, pounding.records.el_centro().scaled(pga_g=0.5)


def test_one_friction_per_axis_along_x_is_the_line_s_friction_isolator():
    # bidirectional=False: each axis a bilinear friction (the line's law with its pre-slip); a symmetric
    # building shaken along x is the line's structure on one isolator carrying the whole weight
    b, line, rec = along_x_and_its_line(False)
    run, ref = pounding.simulate(b, rec, 10.0), pounding.simulate(line, rec, 10.0)
    assert ref.displacement_max[0] > 0.05  # (it slid)
    np.testing.assert_allclose(run.displacement_max[:, 0], ref.displacement_max, rtol=1e-9)
    np.testing.assert_allclose(run.displacement_min[:, 0], ref.displacement_min, rtol=1e-9)
    assert run.energy.input_work == pytest.approx(ref.energy.input_work, rel=1e-9)


def test_a_spectrum_scales_the_pendulums_radii():
    fps = FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4, damping_n_s_m=1e4)
    b = _square(fps, 1e4)
    assert isolated_period_s(b) == pytest.approx(2.0 * math.pi * math.sqrt(2.0 / G), rel=1e-14)
    at = bearings_at(b, 4.0)
    assert isolated_period_s(at) == pytest.approx(4.0, rel=1e-14)
    iso = at.bearings[0].isolator
    assert iso.radius_m == pytest.approx(G * (4.0 / (2.0 * math.pi)) ** 2, rel=1e-14)
    assert (iso.mu, iso.preslip_m) == (0.06, 5e-4)
    assert iso.damping_n_s_m == pytest.approx(1e4 * isolated_period_s(b) / 4.0, rel=1e-14)  # (its ratio kept)
    assert iso.weight_n == pytest.approx(G * 4e5 / 4, rel=1e-15)
    flat = _square(FrictionIsolator(mu=0.06, preslip_m=5e-4))
    with pytest.raises(InputError, match="flat slider"):
        isolated_period_s(flat)
    for period in (0.0, -3.0, float("inf"), "3", None, 1000.0):  # (1000 s: a radius beyond any pendulum's)
        with pytest.raises(InputError) as err:
            bearings_at(b, period)
        assert err.value.field == "period_s", str(err.value)
    with pytest.raises(InputError, match="building"):
        isolated_period_s(None)


@pytest.mark.parametrize("iso, field, fix", [
    (FrictionIsolator(mu=0.06, radius_m=2.0), "preslip_m", "give preslip_m > 0"),
    (FrictionIsolator(mu=0.06, radius_m=2.0, mu_fast=0.1, rate_s_m=20.0), "preslip_m", "give preslip_m > 0"),
    (pounding.TripleFrictionPendulum(radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08),
                                     capacities_m=(0.3, 0.05, 0.05, 0.3)), "triple friction pendulum",
     "give a pounding.Isolator or pounding.FrictionIsolator"),
])
def test_what_a_friction_bearing_in_plan_cannot_be_is_refused_by_name(iso, field, fix):
    with pytest.raises(InputError, match=field) as err:
        Bearing((0.0, 0.0), iso)
    assert fix in str(err.value).split("Fix:")[1], str(err.value)
    for x, y in ((FrictionIsolator(mu=0.06, preslip_m=1e-3), pounding.Isolator([1e6])),
                 (pounding.Isolator([1e6]), FrictionIsolator(mu=0.06, preslip_m=1e-3))):
        with pytest.raises(InputError, match="isolator_y"):
            Bearing((0.0, 0.0), x, y)


def test_a_friction_bearing_reads_back_from_toml(tmp_path):
    b = _square(FrictionIsolator(mu=0.06, radius_m=2.0, preslip_m=5e-4), 1e4, bidirectional=False)
    path = tmp_path / "b.toml"
    b.to_toml(path)
    back = PlanBuilding.from_toml(path)
    assert back == b
    assert not back.bearings[0].coupled


def test_the_code_s_displacement_on_friction_pendulums_is_their_effective_stiffness_and_damping():
    # ASCE 7's D_M on friction pendulums: k_eff = W / R + mu W / D and beta = 2 mu / (pi (mu + D / R)) at
    # the D it finds, the loop's area 4 mu W (D - preslip) with the pre-slip
    from pounding import design

    b = _square(FrictionIsolator(mu=0.06, radius_m=2.5, preslip_m=5e-4))
    out = design.asce7_bearings_displacement(b, s_m1_g=0.6, rtol=1e-12)
    d, weight = out["d_m_x_m"], G * 4e5
    assert out["k_m_x_n_m"] == pytest.approx(weight / 2.5 + 0.06 * weight / d, rel=1e-12)
    assert out["beta_m_x"] == pytest.approx(2 * 0.06 / (math.pi * (0.06 + d / 2.5)) * (1.0 - 5e-4 / d),
                                            rel=1e-12)
    assert out["d_m_y_m"] == d
    # flat sliders: no post-yield stiffness to start from (it divided by zero); k_eff = mu W / D, beta =
    # 2 / pi (1 - preslip / D), capped at the code's 0.5 in B
    with pytest.warns(pounding.PoundingWarning, match="17.2.4.4"):  # (the code asks a restoring force)
        flat = design.asce7_bearings_displacement(_square(FrictionIsolator(mu=0.06, preslip_m=5e-4)),
                                                  s_m1_g=0.6, rtol=1e-12)
    d = flat["d_m_x_m"]
    assert flat["k_m_x_n_m"] == pytest.approx(0.06 * weight / d, rel=1e-12)
    assert flat["beta_m_x"] == pytest.approx(2.0 / math.pi * (1.0 - 5e-4 / d), rel=1e-12)


def test_a_unitless_number_s_fix_names_no_unit():
    with pytest.raises(InputError) as err:
        FrictionIsolator(mu=0.0)
    assert str(err.value).endswith("Fix: give a positive value."), str(err.value)
