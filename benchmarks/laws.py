"""What a contact law costs: the paper's campaign with each law, against Kelvin-Voigt (issue 16).

    python benchmarks/laws.py          # about a minute; --repeats N (default 5)

Work: the whole campaign of the paper (NBs and YBs, 7 sweeps each, 46 steps of 30 cycles, fixed
mode) on one core, warm, best of N, on the first calibrated isolator (v1) with each bumper law:

- Kelvin-Voigt, that preset's;
- a multi-linear law of one slope (the same system: what the multi-linear code path costs);
- the D-shaped multi-linear bumper (stiff, a plateau, steep; its contacts cross breakpoints), elastic
  and with kinematic hysteresis (its springs slip and hold: more events per contact);
- an elastic-plastic law (contacts that yield and turn: two or three branch events each);
- Hertzdamp and Hunt-Crossley (integrated numerically during contact);
- Kelvin-Voigt bumpers on the isolator with a Bouc-Wen spring added (every phase numerical).

Prints wall seconds and the ratio to Kelvin-Voigt (a law whose contacts are fewer, longer or
with more events does different work: compare the ratios with that in mind).
The issue's targets: the multi-linear campaign within 1.5 x of Kelvin-Voigt's; with Bouc-Wen, state the cost.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

import pounding as pd_

TARGET_RATIO = 1.5


def systems() -> dict[str, pd_.Oscillator]:
    base = pd_.presets.paper_calibrated_v1()  # (its Kelvin-Voigt law is the reference)
    kv = base.bumpers.law
    laws = {
        "kelvin_voigt": kv,
        "multilinear, 1 slope": pd_.MultilinearBumper((kv.stiffness,), (), kv.damping),
        "multilinear, D-shaped": pd_.MultilinearBumper((kv.stiffness, 0.1 * kv.stiffness, 4.0 * kv.stiffness),
                                                       (0.002, 0.006), kv.damping),
        "multilinear, D-shaped, kinematic": pd_.MultilinearBumper(
            (kv.stiffness, 0.1 * kv.stiffness, 4.0 * kv.stiffness), (0.002, 0.006), kv.damping, "kinematic"),
        "elastic_plastic": pd_.ElasticPlastic(4.0 * kv.stiffness, 0.1 * kv.stiffness, 0.002),
        "hertzdamp": pd_.Hertzdamp.from_restitution(3e8, 0.85),
        "hunt_crossley": pd_.HuntCrossley(3e8, 1.5, 1e8),
    }
    out = {name: pd_.Oscillator(base.mass_kg, base.isolator, pd_.Bumpers(0.015, 0.015, law)) for name,
           law in laws.items()}
    # the isolator with a Bouc-Wen spring (every phase integrated numerically), Kelvin-Voigt bumpers
    rubber = replace(base.isolator, bouc_wen=pd_.BoucWen(10e3, 0.005))
    out["kelvin_voigt, Bouc-Wen isolator"] = pd_.Oscillator(base.mass_kg, rubber,
                                                            pd_.Bumpers(0.015, 0.015, kv))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    kw = dict(steady="fixed", cycles=30, measure_cycles=5, workers=1)
    rows = []
    for name, ybs in systems().items():
        nbs = ybs.without_bumpers()
        pd_.campaign(nbs, ybs, **kw)  # (a first run, not timed)
        best = float("inf")
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            pd_.campaign(nbs, ybs, **kw)
            best = min(best, time.perf_counter() - t0)
        rows.append((name, best))
        print(f"{name:24s} {best:7.3f} s", flush=True)
    kv = rows[0][1]
    print(f"\n| law | campaign, 1 core, warm (best of {args.repeats}) s | / Kelvin-Voigt |")
    print("| --- | ---: | ---: |")
    for name, best in rows:
        print(f"| {name} | {best:.3f} | {best / kv:.2f} |")
    worst_ml = max(best for name, best in rows if name.startswith("multilinear"))
    print(f"\nmulti-linear within {TARGET_RATIO} x of Kelvin-Voigt: "
          f"{'met' if worst_ml <= TARGET_RATIO * kv else 'MISSED'} ({worst_ml / kv:.2f} x)")


if __name__ == "__main__":
    main()
