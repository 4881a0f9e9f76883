"""A building on friction pendulum bearings under El Centro: pounding's exact stick and slip against
OpenSeesPy's ``singleFPBearing``.

    pip install -e ".[bench]"                   # openseespy
    python benchmarks/opensees_friction.py      # about a minute
    python benchmarks/opensees_friction.py --quick

System: ``examples/friction_pendulum_moat.toml`` without its moat wall (a 30 t base on friction pendulum
bearings, R = 2.2 m, mu = 0.06, carrying the whole 90 t; three storeys of 20 t, 40 MN/m, 40 kN s/m
dashpots between floors).  Excitation: El Centro 1940 NS (``pounding.records.el_centro()``, 0.02 s) scaled
to a PGA of 0.6 g, its whole 31.16 s.

pounding: Coulomb friction ``mu W`` with a rigid stick, every stick and slip an event on the exact
trajectory.  OpenSees: a 2-D model (3 DOF a node), the bearing a zero-length ``singleFPBearing`` from the
ground to the base node (``Coulomb`` friction model, the radius R, local x vertical: its axial force is the
weight, applied as a constant load in a static step first, its axial and rotational stiffness 1e12), each
storey a zeroLength Elastic + Viscous between floors (their vertical and rotational DOFs fixed); the record
as a Path series, UniformExcitation; Newmark average acceleration, Newton to 1e-10 on the displacement
increment (KrylovNewton, then ten substeps, where it fails).  Its bearing sticks elastically: an initial
stiffness ``kInit = mu W / u_y``, the pre-slip displacement ``u_y`` the comparison shrinks.

Compared: the peak base displacement and the residual one (at the record's end), pounding's exact against
OpenSees' at its steps, over u_y and the step; the CPU time of one run; the speed ratio where OpenSees
first agrees within 1 % on both.

``--velocity``: the same models with a velocity-dependent friction (mu 0.06 at rest, 0.11 fast, 25 s/m:
OpenSees' ``VelDependent``) and, in both, the elastic pre-slip u_y (pounding's ``preslip_m``, exact between
its slips, each slip's friction at its rate): OpenSees' steps converging to pounding's run of the same
pre-slip, for u_y 1 mm and 0.1 mm.
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

import pounding as pd_
import peers  # (its load_opensees: the openseespy wheels' libraries preloaded)
from opensees_building import cpu_timed

PGA_G = 0.6
PRESLIPS_M = (1e-3, 1e-4, 1e-5, 1e-6)   # OpenSees' u_y = mu W / kInit
STEPS = (1, 10, 100)                     # OpenSees' steps: the record's step over these
QUICK_PRESLIPS_M, QUICK_STEPS = (1e-4,), (1, 10)
TARGET_ERROR, TARGET_SPEED = 0.01, 100.0
VELOCITY_MU_FAST, VELOCITY_RATE_S_M, VELOCITY_PRESLIPS_M = 0.11, 25.0, (1e-3, 1e-4)
GROUND = 1000  # the ground's node; level i is node i + 1


def the_building(path: Path | None) -> tuple[pd_.Structure, Path]:
    """The example building without its walls (the comparison is the bearing's)."""
    if path is None:
        for root in (Path(__file__).resolve().parents[1], Path(pd_.__file__).resolve().parents[2]):
            if (root / "examples" / "friction_pendulum_moat.toml").exists():
                path = root / "examples" / "friction_pendulum_moat.toml"
                break
        else:
            raise FileNotFoundError("examples/friction_pendulum_moat.toml: give --toml")
    given = pd_.Structure.from_toml(path)
    iso = given.isolator
    if not isinstance(iso, pd_.FrictionIsolator) or iso.radius_m is None or iso.preslip_m != 0.0 \
            or iso.damping_n_s_m != 0.0 or given.rayleigh is not None or any(not s.is_linear
                                                                            for s in given.storeys):
        raise SystemExit("this benchmark takes a friction pendulum without pre-slip or dashpot under linear "
                         "storeys, no Rayleigh damping")
    return pd_.Structure(given.base_mass_kg, iso, given.storeys, []), path


def opensees_model(ops, b: pd_.Structure, rec, preslip_m: float) -> None:
    """The building in OpenSees, its weight on the bearing, the record applied (see the docstring)."""
    iso = b.isolator
    weight = iso.weight_n
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(GROUND, 0.0, 0.0)
    ops.fix(GROUND, 1, 1, 1)
    for level, m in enumerate(b.masses_kg):
        ops.node(level + 1, 0.0, 0.0)
        ops.mass(level + 1, float(m), 0.0, 0.0)
        ops.fix(level + 1, 0, 0 if level == 0 else 1, 1)  # (the base free vertically: the bearing's axial)
    if iso.mu_fast is None:
        ops.frictionModel("Coulomb", 1, iso.mu)
    else:
        ops.frictionModel("VelDependent", 1, iso.mu, iso.mu_fast, iso.rate_s_m)
    ops.uniaxialMaterial("Elastic", 1, 1e12)
    ops.uniaxialMaterial("Elastic", 2, 1e12)
    k_init = iso.friction_force_n / preslip_m
    ops.element("singleFPBearing", 1, GROUND, 1, 1, iso.radius_m, k_init, "-P", 1, "-Mz", 2,
                "-orient", 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, "-iter", 100, 1e-6)
    for i, s in enumerate(b.storeys):
        mat = 10 + 3 * i
        ops.uniaxialMaterial("Elastic", mat, s.stiffness_n_m)
        ops.uniaxialMaterial("Viscous", mat + 1, s.damping_n_s_m, 1.0)
        ops.uniaxialMaterial("Parallel", mat + 2, mat, mat + 1)
        ops.element("zeroLength", 10 + i, i + 1, i + 2, "-mat", mat + 2, "-dir", 1)
    gravity(ops, 1, (0.0, -weight, 0.0), tag=2)
    ops.timeSeries("Path", 1, "-dt", rec.dt_s, "-values", *rec.accel.tolist())
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    solver(ops)
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def solver(ops, constraints: str = "Plain") -> None:
    ops.constraints(constraints)
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-10, 100)
    ops.algorithm("Newton")


def gravity(ops, node: int, load: tuple, tag: int, constraints: str = "Plain") -> None:
    """The weight on ``node`` (``load``: the node's force components, N) in one static step, then held
    constant (pattern and series ``tag``) for the dynamic analysis that follows."""
    ops.timeSeries("Constant", tag)
    ops.pattern("Plain", tag, tag)
    ops.load(node, *load)
    solver(ops, constraints)
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees: the gravity step failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def opensees_run(ops, b: pd_.Structure, rec, dt_s: float, preslip_m: float):
    """One run over the record at ``dt_s``: the base's peak and residual displacement, the steps that needed
    another algorithm or substeps."""
    return stepped_run(ops, lambda: opensees_model(ops, b, rec, preslip_m), rec, dt_s)


def stepped_run(ops, build, rec, dt_s: float):
    """A run of the model ``build()`` makes (node 1 the base) over the record at ``dt_s``: the base's peak and
    residual displacement, the steps that needed another algorithm or substeps."""

    def run():
        build()
        n = int(round(rec.duration_s / dt_s))
        d_peak, hard = 0.0, 0
        for _ in range(n):
            if ops.analyze(1, dt_s) != 0:
                hard += 1
                ops.algorithm("KrylovNewton")
                if ops.analyze(1, dt_s) != 0 and ops.analyze(10, dt_s / 10.0) != 0:
                    raise RuntimeError(f"OpenSees failed to converge at t = {ops.getTime()} s")
                ops.algorithm("Newton")
            d_peak = max(d_peak, abs(ops.nodeDisp(1, 1)))
        return {"d_peak": d_peak, "d_residual": ops.nodeDisp(1, 1), "hard": hard}

    return run


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one pre-slip, two steps, one timing round")
    ap.add_argument("--toml", type=Path, default=None,
                    help="the building (default examples/friction_pendulum_moat.toml)")
    ap.add_argument("--pga", type=float, default=PGA_G, help=f"El Centro's PGA, g (default {PGA_G})")
    ap.add_argument("--velocity", action="store_true",
                    help="a velocity-dependent friction with the same pre-slip in both (see the docstring)")
    args = ap.parse_args()
    preslips, steps = (QUICK_PRESLIPS_M, QUICK_STEPS) if args.quick else (PRESLIPS_M, STEPS)
    rounds = 1 if args.quick else 3
    building, path = the_building(args.toml)
    rec = pd_.records.el_centro().scaled(pga_g=args.pga)
    ops, missing = peers.load_opensees()
    if ops is None:
        raise SystemExit(f"OpenSeesPy left out: {missing}")
    iso = building.isolator
    if args.velocity:
        velocity_dependent(ops, building, rec, steps, rounds)
        return

    pd_best, pd_median, out, ref = pounding_reference(building, rec, rounds)
    kinds = out.events["kind"].value_counts()
    print(f"pounding {pd_.__version__} against OpenSeesPy singleFPBearing: {path.name} without its wall; "
          f"R {iso.radius_m:g} m, mu {iso.mu:g}, W {iso.weight_n:.4g} N (mu W {iso.friction_force_n:.4g} N, "
          f"W / R {iso.restoring_stiffness_n_m:.4g} N/m); record {rec.name} at PGA {rec.pga_g:.3g} g, "
          f"{rec.duration_s:g} s at {rec.dt_s:g} s")
    print(f"pounding: peak base displacement {ref['d_peak']:.6f} m, residual {ref['d_residual']:+.6f} m; "
          f"{int(kinds.get('stick', 0))} sticks, {int(kinds.get('slip', 0))} slips, "
          f"{int(kinds.get('reversal', 0))} reversals; {pd_best * 1e3:.2f} CPU ms a run (median "
          f"{pd_median * 1e3:.2f})")
    print()
    rows = convergence_table(lambda dt, preslip: opensees_run(ops, building, rec, dt, preslip), rec, ref,
                             pd_best, preslips, steps, rounds)
    print()
    equal_accuracy(rows, pd_best, TARGET_ERROR, TARGET_SPEED)


def velocity_dependent(ops, building: pd_.Structure, rec, steps, rounds: int) -> None:
    """The building's bearing with a velocity-dependent friction and the same pre-slip u_y in both codes,
    for u_y 1 mm and 0.1 mm: OpenSees' runs over its step against pounding's of that pre-slip."""
    fast = dataclasses.replace(building.isolator, mu_fast=VELOCITY_MU_FAST, rate_s_m=VELOCITY_RATE_S_M)
    print(f"pounding {pd_.__version__} against OpenSeesPy singleFPBearing, VelDependent friction: mu "
          f"{fast.mu:g} at rest, {fast.mu_fast:g} fast, {fast.rate_s_m:g} s/m; record {rec.name} at PGA "
          f"{rec.pga_g:.3g} g; both with the pre-slip u_y")
    for uy in VELOCITY_PRESLIPS_M:
        b = dataclasses.replace(building, isolator=dataclasses.replace(fast, preslip_m=uy))
        pd_best, _, out, ref = pounding_reference(b, rec, rounds)
        print(f"\nu_y {uy:g} m: pounding's peak base displacement {ref['d_peak']:.6f} m, residual "
              f"{ref['d_residual']:+.6f} m, {pd_best * 1e3:.2f} CPU ms a run")
        rows = convergence_table(lambda dt, u: opensees_run(ops, b, rec, dt, u), rec, ref, pd_best, (uy,),
                                 steps, rounds)
        equal_accuracy(rows, pd_best, TARGET_ERROR)


def pounding_reference(building: pd_.Structure, rec, rounds: int):
    """pounding's run of the building over the record, timed: ``(best, median CPU s, the run, its base's peak
    and residual displacement)``."""

    def run_pd():
        out = pd_.simulate(building, rec, rec.duration_s, sample_rate_hz=0)
        if not out.success:
            raise RuntimeError(out.message)
        return out

    run_pd()
    best, median, out = cpu_timed(run_pd, max(rounds, 3))
    ref = {"d_peak": max(abs(out.displacement_max[0]), abs(out.displacement_min[0])),
           "d_residual": float(out.final_state.displacements_m[0])}
    return best, median, out, ref


def convergence_table(make_run, rec, ref: dict, pd_best: float, stiffnesses, steps, rounds: int) -> list:
    """OpenSees' runs (``make_run(dt, u_y)``) over its elastic displacement ``u_y`` and the record's step over
    ``steps``, each printed against pounding's ``ref``: rows ``(u_y, dt, CPU s, peak error, residual
    error)``."""
    print("OpenSees u_y m | dt s | CPU s | peak m | peak err | residual m | residual err | steps re-solved | "
          "x pounding's time")
    rows = []
    for uy in stiffnesses:
        for r in steps:
            dt = rec.dt_s / r
            if r == 1:
                best, _, res = cpu_timed(make_run(dt, uy), rounds)
            else:  # (one run: seconds at the finest steps)
                t0 = time.process_time()
                res = make_run(dt, uy)()
                best = time.process_time() - t0
            e_peak = res["d_peak"] / ref["d_peak"] - 1.0
            e_res = res["d_residual"] / ref["d_residual"] - 1.0
            rows.append((uy, dt, best, e_peak, e_res))
            print(f"{uy:.0e} | {dt:.3g} | {best:.4g} | {res['d_peak']:.6f} | {e_peak:+.2e} | "
                  f"{res['d_residual']:+.6f} | {e_res:+.2e} | {res['hard']} | {best / pd_best:,.0f}x",
                  flush=True)
    return rows


def equal_accuracy(rows: list, pd_best: float, target_error: float,
                   target_speed: float | None = None) -> None:
    """The cheapest OpenSees run within ``target_error`` on both the peak and the residual, and its time
    against pounding's (against ``target_speed`` where there is one)."""
    within = [row for row in rows if abs(row[3]) <= target_error and abs(row[4]) <= target_error]
    if not within:
        print(f"equal accuracy: no OpenSees run here within {target_error:.0%} of pounding on both the peak "
              "and the residual")
        return
    uy, dt, cpu, _, _ = min(within, key=lambda row: row[2])
    speed = cpu / pd_best
    verdict = "" if target_speed is None else \
        f" (target >= {target_speed:g}x: {'met' if speed >= target_speed else 'MISSED'})"
    print(f"equal accuracy: the cheapest OpenSees run within {target_error:.0%} of pounding on the peak and "
          f"the residual, u_y {uy:.0e} m at dt {dt:.3g} s, {cpu:.3g} CPU s: {speed:,.0f}x pounding's "
          f"time{verdict}")


if __name__ == "__main__":
    main()
