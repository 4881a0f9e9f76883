"""Rigid stops on a ring (a :class:`pounding.RigidStop` as a circular moat's law): a corner struck along the
ring's normal, held on it sliding along the curve (a constraint whose row turns with the corner, its
centripetal term in the held motion), let go where the hold would pull; two corners struck at one instant
are Moreau's impact.

Against the independent solve_ivp reference (tests/reference_plan_rigid.py, its rings checked against a
closed form in test_reference_plan_rigid.py: random eccentric buildings on linear bearings, plastic and
elastic rings), against the line's engine (a symmetric floor shaken along x is a mass between two stops),
and against invariants (the ledger, no pull, a held corner on the ring, the mirror, a continued run)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

import pounding
from pounding import _core
from pounding.cli import app
from pounding.engine.plan_assembly import assemble_plan
from pounding.engine.plan_run import _ring_depths
from pounding.engine.run_args import kernel_forcing
from pounding.model.moats import CircularMoat, RectangularMoat
from pounding.model.plan import PlanBuilding
from pounding.model.plan_parts import Bearing, Floor, Frame
from reference_plan import record_pair
from reference_plan_rigid import rigid_reference
from test_plan_rigid import (_continued_through_a_hold_equals_one_long_run, _impacts, _mirrored,
                             _moves_as_its_mirror_image, _rigid_building)
from test_plan_ring import _ringed
from test_plan_run import _pair

ROOT = Path(__file__).resolve().parents[1]


def _rigid_ringed(rng, levels, gap_m, restitution):
    """A drawn eccentric building on linear bearings (test_plan_rigid's) in a rigid ring of clearance
    ``gap_m`` at its moat's floor, and the reference's model of it."""
    b = _rigid_building(rng, levels, gap_m, restitution)
    walls = b.moat.law
    # (the ring's geometry from a compliant stand-in: the reference's rigid rings read only its place)
    b, model = _ringed(dataclasses.replace(b, moat=RectangularMoat(gap_m, pounding.KelvinVoigt(1e9, 1e6),
                                                                   b.moat.level)), gap_m)
    return dataclasses.replace(b, moat=CircularMoat(gap_m, walls, b.moat.level)), model


# (seed, levels, restitution): draws the reference follows, each with impacts; the plastic ones (but 0) with
# corners held on the ring and let go
DRAWS = [(0, 1, 0.0), (2, 1, 0.0), (3, 1, 0.0), (4, 1, 0.0), (9, 1, 0.0), (13, 1, 0.0),
         (3, 1, 0.5), (9, 1, 0.5), (11, 1, 1.0)]


@pytest.mark.parametrize("seed, levels, restitution", DRAWS)
def test_a_building_in_a_rigid_ring_runs_as_the_reference(seed, levels, restitution):
    rng = np.random.default_rng(seed)
    b, model = _rigid_ringed(rng, levels, 0.03, restitution)
    t, ax, ay = record_pair(rng, 1.5, 0.01, 6.0)
    model.record = (t, ax, ay)
    run = pounding.simulate(b, _pair(t, ax, ay), t[-1], sample_rate_hz=0.0)
    assert run.success, run.message
    ref = rigid_reference(model, restitution, t[-1], np.zeros(2 * 3 * levels))
    table = np.asarray(run.contact_table)
    struck = table[table[:, 1] == table[:, 2]]
    got = _impacts([(int(r[0]), float(r[1]), float(r[5])) for r in struck])
    want = _impacts([(c, tt, p) for c, tt, _, p in ref.impacts])
    assert len(got) == len(want) > 2
    for (t_got, p_got, _), (t_want, p_want, _) in zip(got, want):
        assert set(p_got) == set(p_want), (t_got, p_got, p_want)
        assert abs(t_got - t_want) <= 1e-9  # (measured: 1.8e-15 to 8.8e-13 s)
        for c in p_got:  # (measured: the impulses within 4.3e-10 of themselves)
            assert p_got[c] == pytest.approx(p_want[c], rel=1e-7)
    held = table[table[:, 2] > table[:, 1]]
    released = sorted((float(r[2]), int(r[0])) for r in held)
    assert [c for _, c in released] == [c for c, _ in sorted(ref.releases, key=lambda r: r[1])]
    assert np.allclose([tt for tt, _ in released], sorted(tt for _, tt in ref.releases), rtol=0, atol=1e-9)
    n = 3 * levels
    final = run.final_state.vector
    mine = np.concatenate([final[1:1 + n], final[1 + n:1 + 2 * n]])
    np.testing.assert_allclose(mine, ref.y, rtol=0, atol=1e-8 * float(np.max(np.abs(ref.y))))


def test_the_plastic_draws_hold_corners_on_the_ring_and_let_them_go():
    holds = 0
    for seed, levels, restitution in DRAWS:
        if restitution == 0.0:
            rng = np.random.default_rng(seed)
            b, _ = _rigid_ringed(rng, levels, 0.03, restitution)
            t, ax, ay = record_pair(rng, 1.5, 0.01, 6.0)
            run = pounding.simulate(b, _pair(t, ax, ay), t[-1], sample_rate_hz=0.0)
            table = np.asarray(run.contact_table)
            holds += int(np.sum(table[:, 2] > table[:, 1]))
    assert holds >= 8  # (the reference test above follows them: their releases, the motion held)


def _square_in_a_ring(restitution, centre=(0.0, 0.0), gap_m=0.04):
    """A square floor on four equal linear bearings, its mass at ``centre``, in a rigid ring ``gap_m`` clear
    of its corners."""
    iso = pounding.Isolator(slopes_n_m=[2.5e6], breakpoints_m=[], damping_n_s_m=1.5e5)
    return PlanBuilding([Floor(4e5, (20.0, 20.0), centre_m=centre)],
                        [Bearing((sx * 8.0, sy * 8.0), iso) for sx in (-1, 1) for sy in (-1, 1)],
                        moat=CircularMoat(gap_m, pounding.RigidStop(restitution)))


@pytest.mark.parametrize("restitution", [0.0, 0.6])
def test_a_symmetric_floor_shaken_along_x_in_a_ring_is_the_line_s_mass_between_two_stops(restitution):
    # two corners struck at once, their normals mirror images: no turn, and the line's motion against stops
    # at the ring's reach along x, sqrt(R^2 - b^2) - a (a, b the half sides), the line's impulse the two
    # corners' x components, 2 p (a + d) / R
    rec = pounding.records.el_centro().scaled(pga_g=0.6)
    run = pounding.simulate(_square_in_a_ring(restitution), pounding.RecordPair.of_direction(rec, 0.0), 10.0,
                            sample_rate_hz=100.0)
    half, gap = 10.0, 0.04
    radius = math.hypot(half, half) + gap
    reach = math.sqrt(radius ** 2 - half ** 2) - half
    iso = pounding.Isolator(slopes_n_m=[1e7], breakpoints_m=[], damping_n_s_m=6e5)  # (the four bearings)
    line = pounding.Structure(4e5, iso, [], [pounding.Wall(0, reach, reach, pounding.RigidStop(restitution))])
    ref = pounding.simulate(line, rec, 10.0, sample_rate_hz=100.0)
    assert run.success and ref.success
    top = float(np.max(np.abs(ref.displacement)))
    plan, one = run.final_state.vector, ref.final_state.vector  # (t, x, y, turn, their velocities; t, x, v)
    assert plan[1] == pytest.approx(one[1], abs=1e-11 * top) and plan[4] == pytest.approx(one[2], rel=1e-10)
    assert float(run.displacement_max[0, 0]) == pytest.approx(float(ref.displacement_max[0]), abs=1e-11 * top)
    assert float(np.max(np.abs(np.asarray(run.displacement)[..., 1:]))) <= 1e-12 * top  # (y, the turn: still)
    struck = run.contacts[run.contacts.t_start_s == run.contacts.t_end_s]
    line_struck = ref.contacts[ref.contacts.t_start_s == ref.contacts.t_end_s]
    assert len(line_struck) > 3
    by_instant = struck.groupby(struck.t_start_s.round(9)).impulse_n_s.sum()
    np.testing.assert_allclose(by_instant.index, line_struck.t_start_s.round(9), rtol=0, atol=1e-12)
    along_x = (half + reach) / radius  # (each normal's x component at the stop)
    np.testing.assert_allclose(by_instant.to_numpy() * along_x, line_struck.impulse_n_s, rtol=1e-10)


@pytest.mark.parametrize("restitution", [0.0, 0.5])
def test_a_rigid_ring_never_pulls_and_the_ledger_closes(restitution):
    pair = pounding.records.fema_p695_pairs("far_field")[0]
    run = pounding.simulate(_square_in_a_ring(restitution, centre=(1.0, 0.5), gap_m=0.05), pair, 20.0,
                            sample_rate_hz=100.0)
    assert run.success, run.message
    force = np.asarray(run.contact_force)
    assert restitution > 0.0 or float(np.max(force)) > 0.0  # (a plastic ring holds corners: pushing)
    assert float(np.min(force)) >= -1e-12 * max(float(np.max(force)), 1.0)
    e = run.energy
    assert abs(e.residual) <= 1e-9 * e.input_work  # (measured: 1.0e-13 plastic, 1.6e-16 at e = 0.5)
    assert len(run.contacts) > 10 and (run.contacts.wall == "ring").all()


def test_a_corner_held_on_the_ring_stays_on_it():
    # each hold of a plastic ring's, stopped halfway: its corner on the ring (its depth past it zero to the
    # rounding of the radius, 14 m), however long it has slid along it
    pair = pounding.records.fema_p695_pairs("far_field")[0]
    b = _square_in_a_ring(0.0, centre=(1.0, 0.5), gap_m=0.05)
    asm = assemble_plan(b)
    whole = pounding.simulate(b, pair, 20.0, sample_rate_hz=0.0)
    holds = whole.contacts[whole.contacts.t_end_s > whole.contacts.t_start_s]
    assert len(holds) >= 4
    for h in holds.itertuples():
        run = pounding.simulate(b, pair, 0.5 * (h.t_start_s + h.t_end_s), sample_rate_hz=0.0)
        vec, lay = run.final_state.vector, run.final_state.layout
        depths = _ring_depths(asm, vec)
        held = [c for c in depths if vec[lay["in"] + c] == 1.0]
        assert held
        for c in held:
            assert abs(depths[c]) <= 1e-13  # (measured: below 4e-15 m)


@pytest.mark.parametrize("restitution", [0.0, 0.5])
def test_the_mirrored_building_in_a_ring_moves_as_the_mirror_image(restitution):
    rng = np.random.default_rng(2)
    b, _ = _rigid_ringed(rng, 2, 0.03, restitution)
    mirrored = _mirrored(dataclasses.replace(b, moat=RectangularMoat(0.03, b.moat.law, b.moat.level)))
    _moves_as_its_mirror_image(b, dataclasses.replace(mirrored, moat=b.moat), rng)


def test_a_continued_run_through_a_hold_on_the_ring_equals_one_long_run():
    _continued_through_a_hold_equals_one_long_run(_square_in_a_ring(0.0, centre=(1.0, 0.5), gap_m=0.05))


def test_a_rigid_ring_in_a_file_round_trips(tmp_path):
    b = _square_in_a_ring(0.3)
    path = tmp_path / "ring.toml"
    b.to_toml(path)
    again = PlanBuilding.from_toml(path)
    assert again.moat == CircularMoat(0.04, pounding.RigidStop(0.3))


def test_an_elastic_ring_s_chatter_accumulates_and_holds_the_corner():
    lrb = pounding.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], damping_n_s_m=3.0e4)
    bearings = [Bearing((sx * 14.0, sy * 5.0), lrb) for sx in (-1, 1) for sy in (-1, 1)]
    frames = [Frame(s, "x", y, 4.0e8, 1.0e5) for s in (1, 2) for y in (-6.0, 6.0)]
    frames += [Frame(s, "y", x, k, 1.0e5) for s in (1, 2) for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
    b = PlanBuilding([Floor(4.0e5, (30.0, 12.0), centre_m=(3.0, 0.0))] * 3, bearings, frames,
                     CircularMoat(0.02, pounding.RigidStop(0.6)))
    quake = pounding.RecordPair.of_direction(pounding.records.el_centro().scaled(pga_g=0.5), 60.0)
    run = pounding.simulate(b, quake, 7.0, sample_rate_hz=50.0)
    assert run.success, run.message
    assert abs(run.energy.residual) <= 1e-9 * run.energy.input_work
    accumulated = run.chatters[run.chatters.accumulated]
    assert len(accumulated) >= 3 and (accumulated.impacts >= 3).all() and (accumulated.wall == "ring").all()
    held = run.contacts[run.contacts.t_end_s > run.contacts.t_start_s]
    for c in accumulated.itertuples():  # (its corner held on the ring from the chatter's last impact on)
        mine = held[held.corner == c.corner]
        assert ((mine.t_start_s >= c.t_first_s) & (mine.t_start_s <= c.t_end_s)).sum() == 1


def test_a_held_corner_s_force_rate_is_its_force_s_derivative_along_the_run():
    # the rate the held-release events take (their root finding, and whether a force may dip to zero and back
    # inside a step): a ring's hold's force turns with its row and carries its centripetal term's rate, which
    # the lines' formula lacks; against the force's central differences along the run (at 1e-5 s: measured
    # 2.5e-11 to 6e-11 of the rate; without the ring's terms, off by 1.8e-3 of it)
    pair = pounding.records.fema_p695_pairs("far_field")[0]
    b = _square_in_a_ring(0.0, centre=(1.0, 0.5), gap_m=0.05)
    system, forcing = assemble_plan(b).system, kernel_forcing(pair)
    whole = pounding.simulate(b, pair, 20.0, sample_rate_hz=0.0)
    holds = whole.contacts[whole.contacts.t_end_s > whole.contacts.t_start_s]
    assert len(holds) >= 4
    dt = 1e-5
    for h in holds.head(4).itertuples():
        at = 0.5 * (h.t_start_s + h.t_end_s)
        ends = [pounding.simulate(b, pair, t_s, sample_rate_hz=0.0).final_state
                for t_s in (at - dt, at, at + dt)]
        probes = [_core.held_force_probe(system, forcing, end.vector) for end in ends]
        assert probes[0][:, 0].tolist() == probes[1][:, 0].tolist() == probes[2][:, 0].tolist()  # (one hold)
        differences = (probes[2][:, 1] - probes[0][:, 1]) / (2.0 * dt)
        np.testing.assert_allclose(probes[1][:, 2], differences, rtol=1e-8)


def test_simulate_runs_a_rigid_ring_from_a_file_and_says_its_impacts_are_impulses(tmp_path):
    text = (ROOT / "examples" / "plan_ring_building.toml").read_text()
    law = 'law = { type = "kelvin_voigt", stiffness = 5.0e8, damping = 1.0e6 }'
    assert law in text
    path = tmp_path / "rigid_ring.toml"
    path.write_text(text.replace(law, 'law = { type = "rigid", restitution = 0.0 }'))
    args = ["simulate", str(path), "--record", str(ROOT / "examples" / "el_centro_ns.AT2"), "--scale-pga",
            "0.8", "--direction", "60", "--duration", "8", "--contacts", str(tmp_path / "contacts.csv")]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output
    out = " ".join(result.output.split())
    assert "max peak force [kN] │ inf" in out and "The run reached its end time" in out
    contacts = pd.read_csv(tmp_path / "contacts.csv")
    assert len(contacts) > 3 and (contacts.wall == "ring").all()
    held = contacts[contacts.t_end_s > contacts.t_start_s]
    assert len(held) > 0 and (held.peak_force_n > 0.0).all()  # (held on the ring, pushing)
