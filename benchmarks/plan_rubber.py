"""What rubber bearings' Bouc-Wen springs, sliding bearings' friction circle, a circular moat and rigid walls
cost a building in plan: CPU time of one run.

The building of ``opensees_plan.py`` (5 storeys above its base, 18 dofs) under the far-field set's first
pair x2, its whole record, events only, on its four bilinear lead-rubber bearings (exact phases), then on
high-damping rubber bearings of about the same initial and post-yield stiffness: each a linear spring
beside a Bouc-Wen spring, one bidirectional spring per bearing (Park, Wen and Ang: yielding under the
resultant), and the same springs uncoupled (one along each axis).  Every phase with a Bouc-Wen spring is
integrated numerically (Dormand-Prince 5(4) at the run's rtol), so the ratio is that integration's cost.
Then on friction pendulums of the bilinear law's post-yield stiffness (W / R = k2) and characteristic
strength (mu W = (k1 - k2) d_y), an elastic pre-slip of 0.5 mm: the plastic friction circle (the default:
its sticks and slips located as events, integrated numerically between them), the Bouc-Wen circle (a
bidirectional Bouc-Wen spring of that yield displacement, n = 2), and one bilinear friction per axis (exact
phases).  Last, the
bilinear bearings with a ring for a moat instead of four walls, the same clearance at the corners: its
contacts' starts located on the exact phases, each contact integrated numerically; and with four rigid walls
(plastic, ``RigidStop(0)``): impulses at the corners, corners held on their walls (constraints) on exact
phases; and with a rigid ring (plastic): its corners held on the ring (a constraint whose row turns with
the corner) integrated numerically.  The two circles also with a velocity-dependent friction
(``mu_fast = 1.8 mu``, 25 s/m): their slips' force at the slip's rate.

    python benchmarks/plan_rubber.py [--storeys 5] [--rounds 3]
"""

from __future__ import annotations

import argparse
import dataclasses

from opensees_building import cpu_timed
from opensees_plan import SCALE, building

import pounding as pd_


def rubber(b: pd_.PlanBuilding, bidirectional: bool) -> pd_.PlanBuilding:
    """``b`` on high-damping rubber bearings: the bilinear law's post-yield slope as the linear spring, a
    Bouc-Wen spring of the rest of its initial stiffness yielding at its breakpoint (n = 1)."""
    lrb = b.bearings[0].isolator
    k1, k2 = lrb.slopes_n_m
    bw = pd_.BoucWen(stiffness_n_m=k1 - k2, yield_displacement_m=lrb.breakpoints_m[0])
    hdr = pd_.Isolator(slopes_n_m=[k2], breakpoints_m=[], damping_n_s_m=lrb.damping_n_s_m, bouc_wen=bw)
    bearings = tuple(dataclasses.replace(x, isolator=hdr, bidirectional=bidirectional) for x in b.bearings)
    return dataclasses.replace(b, bearings=bearings)


def sliding(b: pd_.PlanBuilding, bidirectional: bool, circle: str = "plastic",
            fast: float = 0.0) -> pd_.PlanBuilding:
    """``b`` on friction pendulums: the bilinear law's post-yield stiffness as W / R and its characteristic
    strength ``Q = (k1 - k2) d_y`` as mu W (W an equal share of the weight), a pre-slip of 0.5 mm; with
    ``fast`` > 0 its friction velocity-dependent, ``fast`` times mu fast (a rate of 25 s/m)."""
    lrb = b.bearings[0].isolator
    k1, k2 = lrb.slopes_n_m
    weight = 9.81 * sum(f.mass_kg for f in b.floors) / len(b.bearings)
    mu = (k1 - k2) * lrb.breakpoints_m[0] / weight
    speed = {"mu_fast": fast * mu, "rate_s_m": 25.0} if fast > 0.0 else {}
    fps = pd_.FrictionIsolator(mu=mu, radius_m=weight / k2, preslip_m=5e-4, damping_n_s_m=lrb.damping_n_s_m,
                               **speed)
    bearings = tuple(dataclasses.replace(x, isolator=fps, bidirectional=bidirectional, friction_circle=circle)
                     for x in b.bearings)
    return dataclasses.replace(b, bearings=bearings)


def ringed(b: pd_.PlanBuilding) -> pd_.PlanBuilding:
    """``b`` with a ring for a moat, its smallest gap clear of the base's corners, the walls' law."""
    return dataclasses.replace(b, moat=pd_.CircularMoat(b.moat.smallest_gap_m, b.moat.law, b.moat.level))


def rigid(b: pd_.PlanBuilding) -> pd_.PlanBuilding:
    """``b`` with its four walls rigid and plastic (restitution 0)."""
    return dataclasses.replace(b, moat=dataclasses.replace(b.moat, law=pd_.RigidStop(0.0)))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--storeys", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    base = building(args.storeys)
    pair = pd_.records.fema_p695_pairs("far_field")[0].scaled(SCALE)
    print(f"pounding {pd_.__version__}: a building in plan of {args.storeys} storeys ({base.n_dofs} dofs) "
          f"under {pair.name} x{SCALE:g}, {pair.duration_s:g} s, events only; CPU time of one run (best of "
          f"{args.rounds})")
    rows = []
    for label, b in (("bilinear bearings (exact phases)", base),
                     ("Bouc-Wen bearings, bidirectional", rubber(base, True)),
                     ("Bouc-Wen bearings, one spring per axis", rubber(base, False)),
                     ("friction pendulums, the plastic circle", sliding(base, True)),
                     ("friction pendulums, the Bouc-Wen circle", sliding(base, True, "bouc_wen")),
                     ("friction pendulums, one friction per axis", sliding(base, False)),
                     ("the plastic circle, mu_fast = 1.8 mu", sliding(base, True, fast=1.8)),
                     ("the Bouc-Wen circle, mu_fast = 1.8 mu", sliding(base, True, "bouc_wen", 1.8)),
                     ("bilinear bearings, a ring for a moat", ringed(base)),
                     ("bilinear bearings, four rigid walls", rigid(base)),
                     ("bilinear bearings, a rigid ring", ringed(rigid(base)))):
        def run(b=b):
            out = pd_.simulate(b, pair, pair.duration_s, sample_rate_hz=0)
            if not out.success:
                raise RuntimeError(out.message)
            return out
        run()
        best, _, out = cpu_timed(run, args.rounds)
        rows.append((label, best, out))
    first = rows[0][1]
    for label, best, out in rows:
        print(f"  {label:42s} {best * 1e3:8.1f} ms  ({best / first:5.1f}x)  largest bearing displacement "
              f"{out.bearing_displacement_max_m.max() * 1e3:6.1f} mm, {len(out.contacts)} contacts")


if __name__ == "__main__":
    main()
