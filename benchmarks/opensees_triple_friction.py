"""A triple friction pendulum: pounding's series model with exact stick, slip and rings against OpenSeesPy's
``TripleFrictionPendulum`` element (Dao et al. 2013), on the parameter set of its verification example.

    pip install -e ".[bench]"                          # openseespy
    python benchmarks/opensees_triple_friction.py      # about two minutes
    python benchmarks/opensees_triple_friction.py --quick

The bearing: the OpenSees wiki's verification set for the element (Nhan Dao's static cyclic pushover):
inner slider L1 = 0.36 m, mu 0.012, d 0.1 m; outer plates L2 = L3 = 1.25 m, mu 0.052 (bottom) and 0.14 (top),
d 0.2 m.  In pounding's terms ``TripleFrictionPendulum(radii_m=(1.25, 0.36, 0.36, 1.25), mu=(0.052, 0.012,
0.012, 0.14), capacities_m=(0.2, 0.1, 0.1, 0.2))``: travel 0.6 m, its five stages from rest at 0.029, 0.170,
0.350, 0.492 and 0.6 m.

1. The law.  A 100 t mass on the bearing shaken at 0.09 g, 0.4 Hz for 10 s slides through all five stages
   (its rings reached six times); OpenSees' element is then driven through the very displacement history
   pounding's run gives (a zero-length element between a fixed node and one whose horizontal displacement
   is imposed, the weight on it), and the bearing forces are compared sample by sample, as its ``uy`` (the
   elastic displacement before sliding) shrinks.
2. A building.  A 40 t base under three storeys of 30 t (60 MN/m, 100 kN s/m) on the bearing, under El Centro
   1940 NS scaled to a PGA of 1.0 g (stages I to V: its rings reached four times).  OpenSees: a 3-D model (6
   DOF a node, all at one point), the bearing from the ground to the base (the weight applied in a static
   step first), the storeys zeroLength Elastic + Viscous along x, every other DOF fixed but the base's
   vertical; Newmark average acceleration, Newton to 1e-10 (KrylovNewton, then ten substeps, where it fails).
   The peak and residual base displacements over ``uy`` and the step, and the CPU time at equal accuracy.
"""

from __future__ import annotations

import argparse

import numpy as np

import peers  # (its load_opensees: the openseespy wheels' libraries preloaded)
import pounding as pd_
from opensees_friction import (convergence_table, equal_accuracy, gravity, pounding_reference, solver,
                               stepped_run)

RADII_M, MU, CAPACITIES_M = (1.25, 0.36, 0.36, 1.25), (0.052, 0.012, 0.012, 0.14), (0.2, 0.1, 0.1, 0.2)
UYS_M = (1e-3, 3e-4, 1e-4)     # OpenSees' uy
STEPS = (1, 10, 100)           # OpenSees' steps: the record's step over these
QUICK_UYS_M, QUICK_STEPS = (1e-4,), (1, 10)
TARGET_ERROR = 0.02            # the agreement on a published set
LAW_STEP_M = 1e-4              # the law's imposed path: its samples at least this far apart
GROUND = 1000


def the_bearing() -> pd_.TripleFrictionPendulum:
    return pd_.TripleFrictionPendulum(radii_m=RADII_M, mu=MU, capacities_m=CAPACITIES_M)


def _tfp_element(ops, weight_n: float, uy_m: float, i_node: int, j_node: int) -> None:
    """The bearing as OpenSees' element: its pendulums inner (L1), bottom (L2), top (L3)."""
    (r1, r2, _, r4), (m1, m2, _, m4), (d1, d2, _, d4) = RADII_M, MU, CAPACITIES_M
    ops.frictionModel("Coulomb", 1, m2)
    ops.frictionModel("Coulomb", 2, m1)
    ops.frictionModel("Coulomb", 3, m4)
    ops.uniaxialMaterial("Elastic", 1, 1e12)  # (vertical compression)
    ops.uniaxialMaterial("Elastic", 2, 10.0)  # (rotations)
    ops.element("TripleFrictionPendulum", 1, i_node, j_node, 1, 2, 3, 1, 2, 2, 2, r2, r1, r4, d2, d1, d4,
                weight_n, uy_m, 1.0, 0.1, 1e-10)


def _gravity(ops, node: int, weight_n: float) -> None:
    gravity(ops, node, (0.0, 0.0, -weight_n, 0.0, 0.0, 0.0), tag=100, constraints="Transformation")


def opensees_law(ops, weight_n: float, uy_m: float, path_m: np.ndarray) -> np.ndarray:
    """OpenSees' bearing force (N) along the imposed displacement path (m)."""
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(GROUND, 0.0, 0.0, 0.0)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.fix(GROUND, 1, 1, 1, 1, 1, 1)
    ops.fix(1, 0, 1, 0, 1, 1, 1)
    _tfp_element(ops, weight_n, uy_m, GROUND, 1)
    _gravity(ops, 1, weight_n)
    ops.timeSeries("Linear", 2)
    ops.pattern("Plain", 2, 2)
    ops.sp(1, 1, 1.0)
    solver(ops, "Transformation")
    ops.integrator("LoadControl", 0.0)
    ops.analysis("Static")
    forces, last = np.empty(path_m.size), 0.0
    for k, u in enumerate(path_m):
        ops.integrator("LoadControl", float(u) - last)
        if ops.analyze(1) != 0:
            raise RuntimeError(f"OpenSees: the imposed displacement {u} m failed")
        last = float(u)
        ops.reactions()
        forces[k] = -ops.nodeReaction(GROUND, 1)
    return forces


def _resampled(path_m: np.ndarray, step_m: float) -> np.ndarray:
    """The samples at least ``step_m`` from the last one kept (OpenSees' element fails on increments of a
    few nm, as a run's samples near a reversal have: forces of 4e8 N seen)."""
    keep, last = [0], path_m[0]
    for k in range(1, path_m.size):
        if abs(path_m[k] - last) >= step_m:
            keep.append(k)
            last = path_m[k]
    return np.array(keep)


def the_law(ops, uys) -> None:
    osc = pd_.Oscillator(100_000.0, the_bearing())
    run = pd_.simulate(osc, pd_.Harmonic(a_g=0.09, freq_hz=0.4), 10.0, sample_rate_hz=1000)
    kinds = run.events["kind"].value_counts()
    keep = _resampled(np.asarray(run.displacement, dtype=float), LAW_STEP_M)
    path = np.asarray(run.displacement, dtype=float)[keep]
    force = np.asarray(run.levels.isolator_force, dtype=float)[keep]
    print(f"1. the law: a 100 t mass shaken at 0.09 g, 0.4 Hz, 10 s: peak {np.abs(path).max():.4f} m of "
          f"{osc.isolator.travel_m:g} m; {int(kinds.get('surface_slip', 0))} surface slips, "
          f"{int(kinds.get('ring', 0))} rings, {int(kinds.get('reversal', 0))} reversals; OpenSees driven "
          f"through {path.size} of its samples ({LAW_STEP_M:g} m apart at least)")
    near = np.zeros(path.size, bool)  # (within 2 mm of travel after a reversal: OpenSees' elastic uy there)
    heading, u_turn = 0.0, path[0]
    for k in range(1, path.size):
        way = np.sign(path[k] - path[k - 1])
        if way != 0.0 and way != heading:
            heading, u_turn = way, path[k - 1]
        near[k] = abs(path[k] - u_turn) < 2e-3
    peak = np.abs(force).max()
    print("OpenSees uy m | force err / peak force: max | 99th percentile | max beyond 2 mm after a reversal")
    for uy in uys:
        try:
            f_os = opensees_law(ops, osc.isolator.weight_n, uy, path)
        except RuntimeError as err:
            print(f"{uy:.0e} | OpenSees failed: {err}")
            continue
        err = np.abs(f_os - force) / peak
        print(f"{uy:.0e} | {err.max():.2e} | {np.percentile(err, 99):.2e} | {err[~near].max():.2e}",
              flush=True)


def the_building() -> pd_.Structure:
    return pd_.Structure(40_000.0, the_bearing(), [pd_.Storey(30_000.0, 6.0e7, 1.0e5)] * 3, [])


def opensees_building(ops, b: pd_.Structure, rec, uy_m: float) -> None:
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(GROUND, 0.0, 0.0, 0.0)
    ops.fix(GROUND, 1, 1, 1, 1, 1, 1)
    for level, m in enumerate(b.masses_kg):
        ops.node(level + 1, 0.0, 0.0, 0.0)
        ops.mass(level + 1, float(m), 0.0, 0.0, 0.0, 0.0, 0.0)
        ops.fix(level + 1, 0, 1, 0 if level == 0 else 1, 1, 1, 1)  # (the base free vertically: the bearing)
    weight = b.isolator.weight_n
    _tfp_element(ops, weight, uy_m, GROUND, 1)
    for i, s in enumerate(b.storeys):
        mat = 10 + 3 * i
        ops.uniaxialMaterial("Elastic", mat, s.stiffness_n_m)
        ops.uniaxialMaterial("Viscous", mat + 1, s.damping_n_s_m, 1.0)
        ops.uniaxialMaterial("Parallel", mat + 2, mat, mat + 1)
        ops.element("zeroLength", 10 + i, i + 1, i + 2, "-mat", mat + 2, "-dir", 1)
    _gravity(ops, 1, weight)
    ops.timeSeries("Path", 1, "-dt", rec.dt_s, "-values", *rec.accel.tolist())
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    solver(ops, "Transformation")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def building_runs(ops, uys, steps, rounds: int) -> None:
    b = the_building()
    rec = pd_.records.el_centro().scaled(pga_g=1.0)
    pd_best, pd_median, out, ref = pounding_reference(b, rec, rounds)
    kinds = out.events["kind"].value_counts()
    print(f"\n2. a building (40 t base, three 30 t storeys) under {rec.name} at PGA {rec.pga_g:.3g} g, "
          f"{rec.duration_s:g} s at {rec.dt_s:g} s")
    print(f"pounding: peak base displacement {ref['d_peak']:.6f} m, residual {ref['d_residual']:+.6f} m; "
          f"{int(kinds.get('surface_slip', 0))} surface slips, {int(kinds.get('ring', 0))} rings, "
          f"{int(kinds.get('stick', 0))} sticks; {pd_best * 1e3:.2f} CPU ms a run (median "
          f"{pd_median * 1e3:.2f})")
    def make_run(dt: float, uy: float):
        return stepped_run(ops, lambda: opensees_building(ops, b, rec, uy), rec, dt)

    rows = convergence_table(make_run, rec, ref, pd_best, uys, steps, rounds)
    equal_accuracy(rows, pd_best, TARGET_ERROR)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one uy, two steps, one timing round")
    args = ap.parse_args()
    ops, missing = peers.load_opensees()
    if ops is None:
        raise SystemExit(f"OpenSeesPy left out: {missing}")
    uys, steps = (QUICK_UYS_M, QUICK_STEPS) if args.quick else (UYS_M, STEPS)
    print(f"pounding {pd_.__version__} against OpenSeesPy TripleFrictionPendulum, the verification set: "
          f"radii {RADII_M} m, mu {MU}, capacities {CAPACITIES_M} m")
    the_law(ops, uys)
    building_runs(ops, uys, steps, 1 if args.quick else 3)


if __name__ == "__main__":
    main()
