"""The rigid moat's reference (tests/reference_plan_rigid.py) on a ring, against closed forms and invariants:
a point struck and held on a ring slides along it at its speed; elastic impacts on a ring keep an undamped,
unshaken building's energy.  (The engine's rigid rings are tested against it in test_plan_rigid_ring.py.)"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import pounding
from reference_plan import PlanModel
from reference_plan_rigid import rigid_reference
from test_plan_rigid import _rigid_building
from test_plan_ring import _ringed


def _point_in_a_ring(mass, radius):
    """A free floor of ``mass`` (its inertia 50 m, no springs) whose centre of mass is a ring's point."""
    still = (np.array([0.0, 1.0]), np.zeros(2), np.zeros(2))
    e = np.eye(3)
    return PlanModel(mass=np.array([mass, mass, 50.0 * mass]), k=np.zeros((3, 3)), c=np.zeros((3, 3)),
                     influence=e[:, :2], record=still, rings=[(e[0], e[1], 0.0, 0.0, radius, 0.0, 0.0)])


@pytest.mark.parametrize("inwards, speed", [(0.3, 2.0), (1.5, 0.7), (0.05, 5.0)])
def test_a_point_struck_and_held_on_a_ring_slides_along_it_at_its_speed(inwards, speed):
    # from (R - d, 0) at (u, V): a straight flight to the ring, a plastic impact that takes the normal
    # speed away, then a uniform circular motion at the tangential speed s (without the held motion's
    # centripetal term the point leaves the ring tangentially and is struck again and again)
    m, radius, d, t_end = 1000.0, 0.5, 0.1, 0.9
    model = _point_in_a_ring(m, radius)
    y0 = np.array([radius - d, 0.0, 0.0, inwards, speed, 0.0])
    ref = rigid_reference(model, 0.0, t_end, y0)
    a, b, c = inwards ** 2 + speed ** 2, 2.0 * (radius - d) * inwards, (radius - d) ** 2 - radius ** 2
    t_hit = (-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)
    x, y = radius - d + inwards * t_hit, speed * t_hit
    normal = (inwards * x + speed * y) / radius
    s = (speed * x - inwards * y) / radius  # (the tangential speed, anticlockwise)
    angle = math.atan2(y, x) + s * (t_end - t_hit) / radius
    assert [(k, pytest.approx(t, abs=1e-12)) for k, t in ref.holds] == [(0, t_hit)]
    assert ref.releases == []
    (k, t, u, p), = ref.impacts
    assert (k, t) == (0, pytest.approx(t_hit, abs=1e-12))
    assert u == pytest.approx(normal, rel=1e-12) and p == pytest.approx(m * normal, rel=1e-12)
    want = [radius * math.cos(angle), radius * math.sin(angle), 0.0,
            -s * math.sin(angle), s * math.cos(angle), 0.0]
    np.testing.assert_allclose(ref.y, want, rtol=0, atol=1e-9 * radius)


def _ringed_building(seed):
    """A drawn eccentric one-floor building on linear bearings (test_plan_rigid's), in a ring 3 cm wide."""
    rng = np.random.default_rng(seed)
    b = _rigid_building(rng, 1, 0.03, 0.0)
    b = dataclasses.replace(b, moat=pounding.RectangularMoat(0.03, pounding.KelvinVoigt(1e9, 1e6)))
    return _ringed(b, 0.03)[1]


@pytest.mark.parametrize("seed", [2, 3, 4])
def test_elastic_impacts_on_a_ring_keep_an_undamped_building_s_energy(seed):
    model = _ringed_building(seed)
    model.c = np.zeros_like(model.c)
    model.record = (np.array([0.0, 1.0]), np.zeros(2), np.zeros(2))
    n = model.mass.size
    y0 = np.zeros(2 * n)
    y0[n:] = (0.4, 0.15, 0.004)

    def energy(y):
        return 0.5 * y[n:] @ (model.mass * y[n:]) + 0.5 * y[:n] @ model.k @ y[:n]

    ref = rigid_reference(model, 1.0, 3.0, y0)
    assert len(ref.impacts) >= 5 and not ref.holds
    assert energy(ref.y) == pytest.approx(energy(y0), rel=1e-12)  # (measured: 2.3e-15)
