"""A base-isolated building pounding its moat wall under El Centro: pounding against OpenSeesPy.

    pip install -e ".[bench]"                  # openseespy
    python benchmarks/opensees_building.py     # a few minutes (OpenSeesPy at the record's step / 1000)
    python benchmarks/opensees_building.py --quick   # the record's step and a tenth of it

System: ``examples/building_moat.toml`` (a 30 t base on a bilinear kinematic isolator, 4 and 1 MN/m,
yield at 20 mm, a 20 kN s/m dashpot ground to base; three storeys of 20 t, 40 MN/m, 40 kN s/m dashpots
between floors; a moat wall at the base 0.1 m away on each side) with the wall made purely elastic
(Kelvin-Voigt 200 MN/m, no dashpot) so that OpenSees models it exactly.  Excitation: El Centro 1940 NS
(``pounding.records.el_centro()``, m/s^2 at 0.02 s) scaled to a PGA of 0.6 g, its whole 31.16 s.

OpenSees: one DOF per level, zeroLength elements to a fixed ground node: the isolator a Parallel of
Steel01 (Fy = K0 D_y, b = K1 / K0: the kinematic bilinear loop) and a Viscous dashpot; each storey a
Parallel of Elastic and Viscous between its floor and the level below; each wall side an ElasticPPGap
(compression only, behind the gap, Fy out of reach); the record as a Path series (linear between
samples, zero after), UniformExcitation; Newmark average acceleration, Newton to 1e-12 on the
displacement increment, no Rayleigh damping.  OpenSees' displacements are relative to the ground, as
pounding's; its absolute accelerations are ``nodeAccel`` plus the ground's at the step.

Compared: the peak base displacement, each level's peak absolute acceleration, the impacts (OpenSees:
the steps where the base first lies beyond a gap), against pounding's exact extrema and contacts; and
the CPU time of one run (pounding against OpenSees at the record's step).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

import pounding as pd_
import peers  # (its load_opensees: the openseespy wheels' libraries preloaded)

PGA_G = 0.6
REFINE = (1, 2, 5, 10, 20, 50, 100, 1000)   # OpenSees' steps: the record's step over these
QUICK_REFINE = (1, 10)
TARGET_ERROR, TARGET_SPEED = 0.01, 100.0
ROUND_MIN_S = 0.25            # a timing round repeats the run back to back for at least this long (CPU s)


def toml_path() -> Path:
    """``examples/building_moat.toml`` next to this script's folder, or the checkout pounding runs from."""
    for root in (Path(__file__).resolve().parents[1], Path(pd_.__file__).resolve().parents[2]):
        path = root / "examples" / "building_moat.toml"
        if path.exists():
            return path
    raise FileNotFoundError("examples/building_moat.toml: give --toml")


def elastic_walls(building: pd_.Structure) -> pd_.Structure:
    """The building with each wall's Kelvin-Voigt dashpot removed (0 N s/m: an elastic, compression-only
    spring behind the gap, as OpenSees' ElasticPPGap is)."""
    walls = []
    for w in building.walls:
        if not isinstance(w.law, pd_.KelvinVoigt) or w.law_right is not None or w.stand is not None:
            raise ValueError("this benchmark takes Kelvin-Voigt walls on the ground, the same both sides")
        walls.append(pd_.Wall(w.level, w.gap_left_m, w.gap_right_m, pd_.KelvinVoigt(w.law.stiffness, 0.0)))
    return pd_.Structure(building.base_mass_kg, building.isolator, building.storeys, tuple(walls),
                         building.rayleigh)


def check_supported(b: pd_.Structure) -> None:
    """What the OpenSees model below reproduces exactly: say so rather than compare different systems."""
    iso = b.isolator
    problems = []
    if b.fixed or b.rayleigh is not None:
        problems.append("an isolated base without Rayleigh damping")
    if iso is not None and (len(iso.slopes_n_m) != 2 or iso.hysteresis != "kinematic"
                            or iso.bouc_wen is not None):
        problems.append("a bilinear kinematic isolator")
    if any(not s.is_linear for s in b.storeys):
        problems.append("linear storeys")
    if problems:
        raise ValueError("this benchmark needs " + ", ".join(problems))


# --------------------------------------------------------------------------- timing (CPU)
def cpu_timed(run, rounds: int, min_s: float = ROUND_MIN_S):
    """``(best, median, last result)``: CPU s per run over ``rounds`` rounds, each the mean of runs
    repeated back to back for at least ``min_s`` CPU s."""
    per_run, result = [], None
    for _ in range(rounds):
        n, t0 = 0, time.process_time()
        while True:
            result = run()
            n += 1
            elapsed = time.process_time() - t0
            if elapsed >= min_s:
                break
        per_run.append(elapsed / n)
    return min(per_run), float(np.median(per_run)), result


# --------------------------------------------------------------------------- pounding
def pounding_run(building, rec):
    def run():
        out = pd_.simulate(building, rec, rec.duration_s, sample_rate_hz=0)
        if not out.success:
            raise RuntimeError(out.message)
        return out

    return run


def pounding_figures(out) -> dict:
    return {"d_base": max(abs(out.displacement_max[0]), abs(out.displacement_min[0])),
            "a_abs": np.asarray(out.abs_acceleration_max, dtype=float),
            "impacts": len(out.contacts)}


# --------------------------------------------------------------------------- OpenSees
GROUND = 1000  # the ground's node; level i is node i + 1


def check_materials(ops, b: pd_.Structure) -> None:
    """A static check of the two nonlinear materials, strain by strain: the wall's ElasticPPGap pushes
    only once the gap is closed (compression: negative strain) and is elastic both ways; Steel01 follows
    the kinematic bilinear loop (an elastic spring K1 in parallel with an elastic-perfectly-plastic
    K0 - K1 that slips at D_y), the isolator of pounding."""
    ops.wipe()
    w = b.walls[0]
    k_w, gap = w.law.stiffness, w.gap_right_m
    ops.uniaxialMaterial("ElasticPPGap", 1, k_w, -1e20, -gap)
    ops.testUniaxialMaterial(1)
    for strain in (0.05, 0.0, -0.5 * gap, -gap, -gap - 1e-3, -gap - 1e-2, -gap - 1e-3, -0.5 * gap, 0.1,
                   -gap - 2e-2):
        ops.setStrain(strain)
        want = k_w * min(0.0, strain + gap)
        if abs(ops.getStress() - want) > 1e-9 * k_w * gap:
            raise AssertionError(f"ElasticPPGap at strain {strain}: {ops.getStress()} N, expected {want} N")
    k0, k1 = b.isolator.slopes_n_m
    dy = b.isolator.breakpoints_m[0]
    ops.uniaxialMaterial("Steel01", 2, k0 * dy, k0, k1 / k0)
    ops.testUniaxialMaterial(2)
    slip = 0.0  # the plastic spring's slip
    for strain in np.concatenate([np.linspace(0, 0.05, 11), np.linspace(0.05, -0.08, 27),
                                  np.linspace(-0.08, 0.01, 19)]):
        ops.setStrain(float(strain))
        slip = min(max(slip, strain - dy), strain + dy)
        want = k1 * strain + (k0 - k1) * (strain - slip)
        if abs(ops.getStress() - want) > 1e-9 * k0 * dy:
            raise AssertionError(f"Steel01 at strain {strain}: {ops.getStress()} N, expected {want} N")
    ops.wipe()


def opensees_model(ops, b: pd_.Structure, rec, dt_s: float) -> None:
    """The building in OpenSees, the record applied, the transient analysis set (see the docstring)."""
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(GROUND, 0.0)
    ops.fix(GROUND, 1)
    for level, m in enumerate(b.masses_kg):
        ops.node(level + 1, 0.0)
        ops.mass(level + 1, float(m))
    iso = b.isolator
    k0, k1 = iso.slopes_n_m
    ops.uniaxialMaterial("Steel01", 1, k0 * iso.breakpoints_m[0], k0, k1 / k0)
    ops.uniaxialMaterial("Viscous", 2, iso.damping_n_s_m, 1.0)
    ops.uniaxialMaterial("Parallel", 3, 1, 2)
    ops.element("zeroLength", 1, GROUND, 1, "-mat", 3, "-dir", 1)
    for i, s in enumerate(b.storeys):  # storey i + 1: level i + 1 on level i
        mat = 10 + 3 * i
        ops.uniaxialMaterial("Elastic", mat, s.stiffness_n_m)
        ops.uniaxialMaterial("Viscous", mat + 1, s.damping_n_s_m, 1.0)
        ops.uniaxialMaterial("Parallel", mat + 2, mat, mat + 1)
        ops.element("zeroLength", 10 + i, i + 1, i + 2, "-mat", mat + 2, "-dir", 1)
    for j, w in enumerate(b.walls):
        node, mat = w.level + 1, 100 + 2 * j
        ops.uniaxialMaterial("ElasticPPGap", mat, w.right.stiffness, -1e20, -w.gap_right_m)
        ops.uniaxialMaterial("ElasticPPGap", mat + 1, w.left.stiffness, -1e20, -w.gap_left_m)
        ops.element("zeroLength", 100 + 2 * j, node, GROUND, "-mat", mat, "-dir", 1)       # strain -D: right
        ops.element("zeroLength", 101 + 2 * j, GROUND, node, "-mat", mat + 1, "-dir", 1)   # strain +D: left
    ops.timeSeries("Path", 1, "-dt", rec.dt_s, "-values", *rec.accel.tolist())
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def opensees_run(ops, b: pd_.Structure, rec, dt_s: float):
    """One run over the record at ``dt_s``: the peaks at the steps and the impacts."""
    n_levels = b.n_levels
    wall = b.walls[0]
    base = wall.level + 1
    nodes = list(range(1, n_levels + 1))

    def run():
        opensees_model(ops, b, rec, dt_s)
        n = int(round(rec.duration_s / dt_s))
        ground = rec.acceleration(dt_s * np.arange(1, n + 1)).tolist()  # (ahead: the loop steps and reads)
        a_max = [0.0] * n_levels
        d_max, d_min, impacts, outside, retries = 0.0, 0.0, 0, False, 0
        for k in range(n):
            if ops.analyze(1, dt_s) != 0:
                retries += 1  # (never needed so far: the step in ten, then give up)
                if ops.analyze(10, dt_s / 10.0) != 0:
                    raise RuntimeError(f"OpenSees failed to converge at t = {ops.getTime()} s")
            g = ground[k]
            for i, node in enumerate(nodes):
                a = abs(ops.nodeAccel(node, 1) + g)
                if a > a_max[i]:
                    a_max[i] = a
            d = ops.nodeDisp(base, 1)
            d_max, d_min = max(d_max, d), min(d_min, d)
            now = d > wall.gap_right_m or d < -wall.gap_left_m
            impacts += now and not outside
            outside = now
        return {"d_base": max(d_max, -d_min), "a_abs": np.array(a_max), "impacts": impacts,
                "retries": retries}

    return run


def opensees_bare(ops, b: pd_.Structure, rec, dt_s: float):
    """The same run as one ``analyze`` call, nothing read: OpenSees' own cost, without the Python loop."""

    def run():
        opensees_model(ops, b, rec, dt_s)
        if ops.analyze(int(round(rec.duration_s / dt_s)), dt_s) != 0:
            raise RuntimeError("OpenSees failed to converge")
        return ops.nodeDisp(1, 1)

    return run


# --------------------------------------------------------------------------- the table
def rel(x: float, ref: float) -> str:
    return f"{x / ref - 1.0:+.2e}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help=f"OpenSees at the record's step / {QUICK_REFINE} only, one timing round")
    ap.add_argument("--toml", type=Path, default=None,
                    help="the building (default examples/building_moat.toml)")
    ap.add_argument("--pga", type=float, default=PGA_G, help=f"El Centro's PGA, g (default {PGA_G})")
    args = ap.parse_args()
    rounds = 1 if args.quick else 5
    refine = QUICK_REFINE if args.quick else REFINE

    path = args.toml or toml_path()
    given = pd_.Structure.from_toml(path)
    check_supported(given)
    building = elastic_walls(given)
    rec = pd_.records.el_centro().scaled(pga_g=args.pga)
    ops, missing = peers.load_opensees()
    if ops is None:
        raise SystemExit(f"OpenSeesPy left out: {missing}")
    check_materials(ops, building)

    print(f"pounding {pd_.__version__} against OpenSeesPy: {path.name}, wall dashpot removed "
          f"(Kelvin-Voigt {building.walls[0].law.stiffness:.3g} N/m, 0 N s/m)")
    print(f"isolated periods {building.modes().periods_s.round(3).tolist()} s; record {rec.name}, "
          f"{rec.duration_s:g} s at {rec.dt_s:.3g} s, scaled x{rec.meta['scale_factor']:.4g} to PGA "
          f"{rec.pga_g:.3g} g; wall at level {building.walls[0].level}, gaps "
          f"{building.walls[0].gap_left_m:g} / {building.walls[0].gap_right_m:g} m")
    print("static check: ElasticPPGap compression-only behind the gap, Steel01 = kinematic bilinear: ok")

    # pounding: warm, then timed
    run_pd = pounding_run(building, rec)
    run_pd()
    pd_best, pd_median, out = cpu_timed(run_pd, max(rounds, 3))
    ref = pounding_figures(out)
    n_levels = building.n_levels
    given_out = pounding_run(given, rec)()  # (the example as given, with its wall dashpot: for context)

    rows = []
    for r in refine:
        dt = rec.dt_s / r
        if r == 1:
            best, median, res = cpu_timed(opensees_run(ops, building, rec, dt), rounds)
        else:  # one run (minutes at the finest steps)
            t0 = time.process_time()
            res = opensees_run(ops, building, rec, dt)()
            best = median = time.process_time() - t0
        rows.append((dt, best, median, res))
        print(f"  OpenSees dt {dt:.3g} s: {best:.3g} CPU s, {res['impacts']} impacts", flush=True)

    # the table
    acc_names = [f"a{i} m/s2" for i in range(n_levels)]
    head = ["run", "CPU s", "D_base m", *acc_names, "impacts"]
    print()
    print("Peaks over the run (pounding: exact extrema; OpenSees: at its steps). Impacts: pounding's "
          "contacts; OpenSees' entries of the base beyond a gap.")
    print(" | ".join(head))

    def line(name, cpu, fig):
        return " | ".join([name, f"{cpu:.4g}", f"{fig['d_base']:.6f}", *(f"{a:.4f}" for a in fig["a_abs"]),
                           str(fig["impacts"])])

    print(line("pounding (elastic wall)", pd_best, ref))
    for dt, best, _, res in rows:
        print(line(f"OpenSees dt {dt:.3g} s", best, res))
    print()
    print("Relative differences to pounding (OpenSees / pounding - 1)")
    print(" | ".join(["OpenSees dt", "D_base", *[f"a{i}" for i in range(n_levels)], "max |diff|", "impacts"]))
    worst_at = {}
    for dt, _, _, res in rows:
        diffs = [res["d_base"] / ref["d_base"] - 1.0, *(res["a_abs"] / ref["a_abs"] - 1.0)]
        worst = max(abs(x) for x in diffs)
        worst_at[dt] = (worst, res["impacts"] == ref["impacts"])
        print(" | ".join([f"{dt:.3g} s", *(f"{x:+.2e}" for x in diffs), f"{worst:.2e}",
                          f"{res['impacts']} vs {ref['impacts']}"]))
    retries = {dt: res["retries"] for dt, _, _, res in rows if res["retries"]}
    if retries:
        print(f"steps OpenSees had to split (Newton failed at the step): {retries}")

    bare_best, _, _ = cpu_timed(opensees_bare(ops, building, rec, rec.dt_s), rounds)
    print()
    os_best, os_median = rows[0][1], rows[0][2]
    speed = os_best / pd_best
    print(f"CPU time of one run (best of {max(rounds, 3)} rounds for pounding, {rounds} for OpenSees at the "
          f"record's step; each round >= {ROUND_MIN_S} s of back-to-back runs):")
    print(f"  pounding {pd_best * 1e3:.3f} ms (median {pd_median * 1e3:.3f} ms); OpenSees at dt "
          f"{rows[0][0]:.3g} s {os_best * 1e3:.1f} ms (median {os_median * 1e3:.1f} ms)")
    print(f"  speed ratio OpenSees / pounding at the record's step: {speed:.0f}x (target >= "
          f"{TARGET_SPEED:g}x): {'met' if speed >= TARGET_SPEED else 'MISSED'}")
    print(f"  OpenSees at dt {rows[0][0]:.3g} s as one analyze call, nothing read per step: "
          f"{bare_best * 1e3:.1f} ms, {bare_best / pd_best:.1f}x")
    # what a call costs whatever its length (checks, assembly, the result's tables), and the core's per
    # sample: the ratio's ceiling with an infinitely fast core is OpenSees' time over the first
    one_step = lambda: pd_.simulate(building, rec, rec.dt_s, sample_rate_hz=0)  # noqa: E731
    fixed, _, _ = cpu_timed(one_step, max(rounds, 3))
    per_sample = (pd_best - fixed) / rec.t.size
    print(f"  pounding's cost of a call of one record step: {fixed * 1e3:.3f} ms (ceiling of the ratio with "
          f"a core that took no time: {os_best / fixed:.0f}x); the rest, {per_sample * 1e6:.2f} us a record "
          f"sample ({TARGET_SPEED:g}x would need the whole run in {os_best / TARGET_SPEED * 1e3:.3f} ms)")
    for dt, best, _, _ in rows[1:]:
        print(f"  at dt {dt:.3g} s: {best / pd_best:,.0f}x")
    met = [dt for dt, (worst, same) in worst_at.items() if worst <= TARGET_ERROR and same]
    if met:
        at = max(met)
        cpu = next(best for dt, best, _, _ in rows if dt == at)
        print(f"agreement within {TARGET_ERROR:.0%} on every peak, same impact count: from OpenSees dt "
              f"{at:.3g} s (the largest step run where it holds; {cpu:.3g} CPU s, {cpu / pd_best:,.0f}x "
              f"pounding's time)")
    else:
        print(f"agreement within {TARGET_ERROR:.0%}: not reached at the steps run")
    print()
    g = pounding_figures(given_out)
    print(f"For context, the example as given (wall dashpot {given.walls[0].law.damping:g} N s/m, pounding "
          f"only): D_base {g['d_base']:.6f} m, accelerations {np.round(g['a_abs'], 3).tolist()} m/s2, "
          f"{g['impacts']} impacts.")


if __name__ == "__main__":
    main()
