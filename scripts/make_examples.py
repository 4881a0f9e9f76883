"""Make the example input files the README's shell commands read (deterministic):

- ``examples/lab_test.csv``: a short synthetic shaking-table recording, as a data-acquisition
  system writes one (time in ms, accelerations in g, the laser in mm; two accelerometers on the
  mass): the damped paper system at a_G = 0.05, steps of 1.5 and 1.7 Hz, 8 cycles each, sampled at
  1 kHz through a 200 Hz anti-alias filter with 1 % noise, gains 1.02 and 0.98 and a 10 um laser.
  It is not a measurement.
- ``examples/el_centro_ns.AT2``: the El Centro 1940 N-S record shipped with the package (a US
  Government work in the public domain), written in the PEER NGA ``.AT2`` layout.

Run: ``python scripts/make_examples.py``.
"""

from pathlib import Path


import pounding
from pounding.lab import synthetic_test

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def lab_test() -> Path:
    rec = synthetic_test(pounding.presets.paper_damped(), 0.05, [1.5, 1.7], cycles=8, sample_rate_hz=1000.0,
                         noise=0.01, anti_alias_hz=200.0, gains=(1.02, 0.98), laser_resolution_m=1e-5, seed=1)
    g = pounding.Harmonic(0.05, 1.0).g  # (the g the recording is in: standard gravity)
    columns = {"t_ms": rec.time_s * 1e3, "a_table": rec.table_acc_m_s2 / g, "a1": rec.mass_acc_m_s2[:, 0] / g,
               "a2": rec.mass_acc_m_s2[:, 1] / g, "laser_mm": rec.displacement_m * 1e3}
    path = EXAMPLES / "lab_test.csv"
    with path.open("w", encoding="utf-8", newline="\n") as fh:
        fh.write(",".join(columns) + "\n")
        for row in zip(*columns.values()):
            fh.write(f"{row[0]:.1f}," + ",".join(f"{x:.5g}" for x in row[1:]) + "\n")
    return path


def el_centro_at2() -> Path:
    quake = pounding.records.el_centro()
    acc_g = quake.accel / quake.g
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD (layout only: written by pounding's "
             "scripts/make_examples.py)",
             "Imperial Valley 1940-05-19, El Centro Terminal Substation, N-S (180)",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {acc_g.size:6d}, DT= {quake.dt_s:.4f} SEC"]
    lines += ["".join(f"{x:16.7E}" for x in acc_g[i:i + 5]) for i in range(0, acc_g.size, 5)]
    path = EXAMPLES / "el_centro_ns.AT2"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


if __name__ == "__main__":
    for made in (lab_test(), el_centro_at2()):
        print(made, f"{made.stat().st_size / 1e3:.0f} kB")
