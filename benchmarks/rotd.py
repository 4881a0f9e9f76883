"""RotD50 and RotD100 spectra of the FEMA P695 far-field pairs: pounding's exact kernel against pyrotd
(Kottke's, the field's Python tool: the oscillators' responses in the frequency domain, at the samples,
the record upsampled where an oscillator is fast), on the same work in the same run (issue 65).

    pip install -e ".[bench,records]"     # pyrotd, and the FEMA P695 pairs
    python benchmarks/rotd.py             # about a minute; --quick for a smoke run, --no-write

Work: the 22 far-field pairs (as recorded), 100 periods 0.05-5 s, 5 % damping, the 180 directions 0-179
degrees; CPU time of each tool for the whole set, and pyrotd's RotD50 and RotD100 against pounding's
(exact along each direction, peaks between samples found).  The table goes to benchmarks/RESULTS.md
between its ``rotd.py`` markers.
"""

from __future__ import annotations

import argparse
import time
from datetime import date

import numpy as np

import pounding as pd_
from run import machine, write_section

BEGIN, END = "<!-- rotd.py: begin -->", "<!-- rotd.py: end -->"
PERIODS = np.linspace(0.05, 5.0, 100)


def pounding_rotd(pairs, periods):
    t0 = time.process_time()
    spec = pd_.rotd_spectrum(pairs, periods)
    return time.process_time() - t0, spec["rotd50_psa_g"].values, spec["rotd100_psa_g"].values


def pyrotd_rotd(pairs, periods):
    import pyrotd

    out50, out100 = np.zeros((len(pairs), periods.size)), np.zeros((len(pairs), periods.size))
    t0 = time.process_time()
    for i, p in enumerate(pairs):
        res = pyrotd.calc_rotated_spec_accels(p.dt_s, p.x.accel / p.g, p.y.accel / p.g, 1.0 / periods,
                                              0.05, percentiles=[50, 100])
        out50[i] = res.spec_accel[res.percentile == 50]
        out100[i] = res.spec_accel[res.percentile == 100]
    return time.process_time() - t0, out50, out100


def lsim_rotd100(pair, period_s: float, damping: float = 0.05, finer: int = 20) -> float:
    """An independent RotD100 (g): scipy's lsim of each component, the record linear between its samples (as
    pounding and OpenSees' Path series read it) on a grid ``finer`` times its step, peaks at those points."""
    from scipy import signal

    w = 2.0 * np.pi / period_s
    oscillator = signal.lti([[0.0, 1.0], [-w * w, -2.0 * damping * w]], [[0.0], [-1.0]], [[1.0, 0.0]],
                            [[0.0]])
    t = np.linspace(pair.t[0], pair.t[-1], (pair.t.size - 1) * finer + 1)
    ux = signal.lsim(oscillator, np.interp(t, pair.t, pair.x.accel), t, interp=True)[1]
    uy = signal.lsim(oscillator, np.interp(t, pair.t, pair.y.accel), t, interp=True)[1]
    angles = np.radians(np.arange(180.0))
    return float(np.abs(np.outer(np.cos(angles), ux) + np.outer(np.sin(angles), uy)).max()) * w * w / pair.g


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="4 pairs, 20 periods")
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args()
    pairs = pd_.records.fema_p695_pairs("far_field")
    periods = PERIODS
    if args.quick:
        pairs, periods = pairs[:4], np.linspace(0.05, 5.0, 20)
    samples = sum(p.t.size for p in pairs)
    mine_s, p50, p100 = pounding_rotd(pairs, periods)
    theirs_s, q50, q100 = pyrotd_rotd(pairs, periods)
    d50, d100 = q50 / p50 - 1.0, q100 / p100 - 1.0
    short = periods < 0.5

    def largest(d: np.ndarray) -> float:
        return float(d.flat[np.abs(d).argmax()])

    checks = []  # (pair, period): the largest differences at short and long periods, checked independently
    for part in (short, ~short):
        i, j = np.unravel_index(np.abs(np.where(part[None, :], d100, 0.0)).argmax(), d100.shape)
        checks.append((pairs[i], float(periods[j]), p100[i, j], q100[i, j],
                       lsim_rotd100(pairs[i], periods[j])))
    lines = [BEGIN, f"## `python benchmarks/rotd.py` (issue 65), {date.today()}", "",
             f"Machine: {machine()}.", "",
             f"RotD50 and RotD100 of the {len(pairs)} FEMA P695 far-field pairs ({samples} samples a "
             f"component in all), {periods.size} periods {periods[0]:g}-{periods[-1]:g} s, 5 %, 180 "
             "directions; CPU s for the whole set, and pyrotd's spectra relative to pounding's:", "",
             "| tool | CPU s | RotD50: median, largest | RotD100: median, largest | largest below 0.5 s "
             "(RotD50, RotD100) |",
             "| --- | ---: | ---: | ---: | ---: |",
             f"| pounding (exact, the record linear between samples) | {mine_s:.2f} | | | |",
             f"| pyrotd {__import__('pyrotd').__version__} (frequency domain) | {theirs_s:.2f} | "
             f"{np.median(d50):+.1e}, {largest(d50):+.1e} | {np.median(d100):+.1e}, {largest(d100):+.1e} | "
             f"{largest(d50[:, short]):+.1e}, {largest(d100[:, short]):+.1e} |", "",
             f"CPU time: pyrotd / pounding = {theirs_s / mine_s:.2f}.  The largest differences, checked by "
             "scipy's lsim (the record linear between its samples, on a grid 20 times finer, peaks at its "
             "points):", "",
             "| pair | period s | step s | RotD100 pounding g | pyrotd g | lsim g |",
             "| --- | ---: | ---: | ---: | ---: | ---: |"]
    lines += [f"| {p.name} | {t:g} | {p.dt_s:.3g} | {a:.5f} | {b:.5f} | {c:.5f} |"
              for p, t, a, b, c in checks]
    lines += ["", "pyrotd takes the record band-limited (its spectrum, upsampled in the frequency domain) "
              "where pounding, lsim and OpenSees' Path series take it linear between samples: near the "
              "record's step the two readings part.  Its response is periodic (an FFT's), so a long "
              "oscillator's on a short record wraps around.  Where the record is well sampled and long "
              "enough, the two agree to about 1e-3 (the medians).", END]
    text = "\n".join(lines)
    print(text)
    if not args.no_write and not args.quick:
        write_section(text, BEGIN, END)


if __name__ == "__main__":
    main()
