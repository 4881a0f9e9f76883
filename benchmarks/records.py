"""Earthquake records: pounding against OpenSeesPy, eqsig and sdof on the same work, in the same run (issue
18).

    pip install -e ".[bench,records]"     # the peers (openseespy, eqsig, sdof) and the FEMA P695 sets
    python benchmarks/records.py          # about 3 minutes; --quick for a smoke run, --no-write

Work:
  1. one YBs run (``presets.paper_printed()``) under a FEMA P695 far-field record of at least 40 s,
     scaled to PGA 0.3 g: pounding against OpenSeesPy (Newmark average acceleration with Newton
     iterations, the record as a Path time series, ViscoelasticGap bumpers) at the record's step and
     at a tenth of it; errors of the peak absolute acceleration and of the peak displacement
     against pounding at rtol 1e-12 (for the closed-form phases that is the same run);
  2. the elastic response spectrum of that record at 100 periods (0.05-5 s, 5 %): pounding
     (exact, peaks between samples found) against eqsig (Nigam-Jennings at the samples,
     ``true_response_spectra``) and sdof (compiled Newmark at the record's step); errors of Sa;
  3. the pounding spectrum of the whole far-field set (44 components x 100 periods x 3 gaps, with
     and without bumpers: 17,600 runs), warm, on every core.
The tables go to benchmarks/RESULTS.md between its ``records.py`` markers.
"""

from __future__ import annotations

import argparse
import math
import time
from datetime import date

import numpy as np

import pounding as pd_
import peers
from run import machine, write_section

BEGIN, END = "<!-- records.py: begin -->", "<!-- records.py: end -->"
PGA_G = 0.3
PERIODS = np.linspace(0.05, 5.0, 100)
GAPS = (0.01, 0.02, 0.05)
TARGET_SPEED, TARGET_ERROR, TARGET_SPECTRUM_RATIO, TARGET_SET_S = 100.0, 100.0, 3.0, 60.0


def long_record():
    far = pd_.records.fema_p695("far_field")
    rec = next(r for r in far if r.duration_s >= 40.0)
    return rec.scaled(pga_g=PGA_G), far


def pounding_run(osc, rec, rtol=1e-10):
    def run():
        out = pd_.simulate(osc, rec, rec.duration_s, rtol=rtol, sample_rate_hz=0)
        return out.abs_acceleration_max, max(out.displacement_max, -out.displacement_min), len(out.contacts)

    return run


def opensees_run(ops, osc, rec, dt_s):
    """The record as a Path series (linear between its samples, as pounding reads it)."""

    def run():
        peers.OpenSeesModel(ops, osc, dt_s)
        ops.timeSeries("Path", 100, "-dt", rec.dt_s, "-values", *rec.accel.tolist())
        ops.pattern("UniformExcitation", 100, 1, "-accel", 100)
        n = int(round(rec.duration_s / dt_s))
        # (ahead: the loop only steps and reads)
        ground = rec.acceleration(dt_s * np.arange(1, n + 1)).tolist()
        a_max = d_max = 0.0
        for k in range(n):
            if ops.analyze(1, dt_s) != 0:
                raise RuntimeError("OpenSees failed to converge")
            a_max = max(a_max, abs(ops.nodeAccel(2, 1) + ground[k]))
            d_max = max(d_max, abs(ops.nodeDisp(2, 1)))
        return a_max, d_max, -1

    return run


def best_of(run, rounds):
    best, out = math.inf, None
    for _ in range(rounds):
        t0 = time.perf_counter()
        out = run()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run: one round, 10 periods, 4 records")
    ap.add_argument("--no-write", action="store_true", help="print only; leave RESULTS.md alone")
    args = ap.parse_args()
    rounds = 1 if args.quick else 3
    rec, far = long_record()
    osc = pd_.presets.paper_printed()
    pd_.simulate(osc, rec, 1.0)  # (compiled before timing)
    lines = [BEGIN, f"## `python benchmarks/records.py` ({date.today()})", "", f"Machine: {machine()}.", ""]

    # 1. one run under a record
    ref = pounding_run(osc, rec, rtol=1e-12)()
    rows = [("pounding (rtol 1e-10)", *best_of(pounding_run(osc, rec), max(rounds, 5)))]
    ops, missing = peers.load_opensees()
    if ops is None:
        print(f"OpenSeesPy left out: {missing}")
    else:
        for dt in (rec.dt_s, rec.dt_s / 10.0):
            rows.append((f"OpenSeesPy, Newmark + Newton, dt {dt * 1e3:g} ms",
                         *best_of(opensees_run(ops, osc, rec, dt),
                                                                                       rounds)))
    lines += [f"**One YBs run (`paper_printed`) under {rec.name} ({rec.meta['event']} {rec.meta['year']}), "
              f"{rec.duration_s:g} s at {rec.dt_s:g} s, scaled to PGA {PGA_G} g: {ref[2]} impacts**", "",
              "| tool | wall s | peak a_abs error | peak D error | pounding speed / tool |",
              "| --- | ---: | ---: | ---: | ---: |"]
    wall0 = rows[0][1]
    for name, wall, out in rows:
        ea = max(abs(out[0] / ref[0] - 1.0), 1e-12)
        ed = max(abs(out[1] / ref[1] - 1.0), 1e-12)
        lines.append(f"| {name} | {wall:.4g} | {ea:.1e} | {ed:.1e} | {wall / wall0:,.0f} |")
    lines.append("")

    # 2. the elastic response spectrum
    periods = PERIODS[::10] if args.quick else PERIODS
    pd_.response_spectrum(rec, periods[:2])
    exact = pd_.response_spectrum(rec, periods)
    ref_sd, ref_sa = exact["sd_m"].values[0], exact["sa_m_s2"].values[0]
    def ours():
        ds = pd_.response_spectrum(rec, periods)
        return ds["sd_m"].values[0], ds["sa_m_s2"].values[0]

    spec_rows = [("pounding.response_spectrum (exact)", *best_of(ours, 5))]
    try:
        import eqsig.sdof as eqsdof

        def eq():
            out = eqsdof.true_response_spectra(rec.accel, rec.dt_s, periods, 0.05)
            return out[0], out[2]

        spec_rows.append(("eqsig true_response_spectra (Nigam-Jennings at the samples)",
                          *best_of(eq, rounds)))
    except ImportError:
        pass
    try:
        import sdof

        def sd():
            out = sdof.spectrum(rec.accel, rec.dt_s, 0.05, periods=periods)
            return out[0][1], out[2][1]

        sd()
        spec_rows.append(("sdof spectrum (compiled Newmark at the samples)", *best_of(sd, 5)))
    except ImportError:
        pass
    lines += [f"**Elastic response spectrum of that record: {periods.size} periods, 5 %**", "",
              "| tool | wall s | largest Sd error | largest Sa error | time / pounding's |",
              "| --- | ---: | ---: | ---: | ---: |"]
    w0 = spec_rows[0][1]
    for name, wall, (sd, sa) in spec_rows:
        e_sd = max(float(np.max(np.abs(np.abs(sd) / ref_sd - 1.0))), 1e-12)
        e_sa = max(float(np.max(np.abs(np.abs(sa) / ref_sa - 1.0))), 1e-12)
        lines.append(f"| {name} | {wall:.4g} | {e_sd:.1e} | {e_sa:.1e} | {wall / w0:.2f} |")
    fastest = min(w for _, w, _ in spec_rows)
    lines += ["", f"pounding's exact spectrum takes {w0 / fastest:.2f} times the fastest peer's time "
              f"(target: within {TARGET_SPECTRUM_RATIO:g}x). The peers' errors are their sampling: eqsig's "
              "Nigam-Jennings is exact at the samples but misses the peaks between them (and its Sa at short "
              "periods is not the absolute acceleration's peak); sdof's Newmark step lengthens short "
              "periods.", ""]

    # 3. a pounding spectrum over the far-field set
    recs = far[:4] if args.quick else far
    pd_.pounding_spectrum(recs[:1], periods[:2], gaps_m=GAPS[:1])
    t0 = time.perf_counter()
    ps = pd_.pounding_spectrum(recs, periods, gaps_m=GAPS)
    wall = time.perf_counter() - t0
    runs = len(recs) * periods.size * (len(GAPS) + 1)
    amp = ps.summary()["amplification"].sel(percentile=50.0)
    lines += [f"**Pounding spectrum of the FEMA P695 far-field set: {len(recs)} components x {periods.size} "
              f"periods x {len(GAPS)} gaps, with and without bumpers ({runs:,} runs), warm, every core**", "",
              f"{wall:.1f} s wall ({wall / runs * 1e3:.2f} ms a run; target {TARGET_SET_S:g} s); "
              f"{int(ps.data['impacts'].sum()):,} impacts; the largest median amplification by pounding "
              f"{float(amp.max()):.3g}.", "", END]
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        write_section(text, BEGIN, END)


if __name__ == "__main__":
    main()
