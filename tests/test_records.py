"""Earthquake records (issue 18): reading AT2 and CSV, scaling, the shipped and FEMA P695 records, and the
exact elastic response spectrum against an independent reference."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import signal

import pounding as pd_
from pounding.records import el_centro, fema_p695
from reference import reference

REFERENCE_RTOL, REFERENCE_ATOL = 1e-13, 1e-18  # (as tests/test_reference.py)
VALUES = np.array([0.0012, -0.0034, 0.0101, -0.0234, 0.05, -0.0712, 0.0333, 0.0123, -0.0045, 0.001, 0.0,
                   -0.0021])

NGA_WEST2 = """PEER NGA STRONG MOTION DATABASE RECORD
Imperial Valley-02, 5/19/1940, El Centro Array #9, 180
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=   12, DT=   .0100 SEC,
  .1200000E-02 -.3400000E-02  .1010000E-01 -.2340000E-01  .5000000E-01
 -.7120000E-01  .3330000E-01  .1230000E-01 -.4500000E-02  .1000000E-02
  .0000000E+00 -.2100000E-02
"""
NGA_WEST1 = """PEER NGA STRONG MOTION DATABASE RECORD
IMPERIAL VALLEY 05/19/40 0437, EL CENTRO ARRAY #9, 180
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=   12, DT=   .0100 SEC
 0.12000E-02-0.34000E-02 0.10100E-01-0.23400E-01 0.50000E-01
-0.71200E-01 0.33300E-01 0.12300E-01-0.45000E-02 0.10000E-02
 0.00000E+00-0.21000E-02
"""
OLD = """PACIFIC EARTHQUAKE ENGINEERING RESEARCH CENTER STRONG MOTION DATABASE
IMPERIAL VALLEY 05/19/40 0437, EL CENTRO ARRAY #9, 180
ACCELERATION TIME HISTORY IN UNITS OF G
   12    .01000    NPTS, DT
 .0012 -.0034 .0101 -.0234 .05 -.0712 .0333 .0123
 -.0045 .001 0 -.0021
"""


@pytest.mark.parametrize("text", [NGA_WEST2, NGA_WEST1, OLD], ids=["nga-west2", "nga-west1", "old-database"])
def test_at2_in_the_peer_layouts(tmp_path, text):
    path = tmp_path / "RSN6_IMPVALL.I_I-ELC180.AT2"
    path.write_text(text)
    rec = pd_.Record.from_at2(path)
    np.testing.assert_allclose(rec.accel, VALUES * 9.81, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(rec.t, 0.01 * np.arange(12), atol=1e-15)
    assert rec.name == "RSN6_IMPVALL.I_I-ELC180" and rec.dt_s == pytest.approx(0.01) and rec.uniform
    assert rec.pga_g == pytest.approx(0.0712) and rec.duration_s == pytest.approx(0.11)
    assert rec.meta["component"] == "180" and "El Centro" in rec.meta["station"].title()
    assert rec.meta["npts"] == 12 and len(rec.meta["header"]) == 3


@pytest.mark.parametrize("change, field, words", [
    (lambda s: s.rsplit("\n", 2)[0] + "\n", "path", "has 10 values where its header says NPTS = 12"),
    (lambda s: s.replace("NPTS=   12", "NPTS=   13"), "path",
     "has 12 values where its header says NPTS = 13"),
    (lambda s: s.replace(" -.7120000E-01", " -.71x0000E-01"), "path", "line 6"),
    (lambda s: s.replace("NPTS=   12, DT=   .0100 SEC,", "12 points at .01 s"), "path", "NPTS"),
    (lambda s: s.replace("DT=   .0100", "DT=   .0000"), "path", "DT = 0 s"),
    (lambda s: s.replace("ACCELERATION", "VELOCITY"), "path", ".VT2"),
])
def test_bad_at2_files_name_the_line(tmp_path, change, field, words):
    path = tmp_path / "bad.AT2"
    path.write_text(change(NGA_WEST2))
    with pytest.raises(pd_.InputError) as info:
        pd_.Record.from_at2(path)
    assert info.value.field == field and words in str(info.value), str(info.value)


def test_at2_fortran_exponents_latin1_and_dates(tmp_path):
    text = NGA_WEST2.replace(" .1200000E-02", " .1200000-002").replace("El Centro Array", "Él Centro Array")
    path = tmp_path / "latin.AT2"
    path.write_bytes(text.encode("latin-1"))
    rec = pd_.Record.from_at2(path)
    assert rec.accel[0] == pytest.approx(0.0012 * 9.81, rel=1e-12)  # (three-digit exponent, E dropped)
    assert (rec.meta["event"], rec.meta["date"], rec.meta["station"]) == ("Imperial Valley-02", "5/19/1940",
                                                                         "Él Centro Array #9")
    old = tmp_path / "old.AT2"
    old.write_text(OLD)
    assert pd_.Record.from_at2(old).meta["date"] == "05/19/40"
    huge = tmp_path / "huge.AT2"
    huge.write_text(NGA_WEST2.replace(" .5000000E-01", " .5000000E+401"))
    with pytest.raises(pd_.InputError, match="line 5"):
        pd_.Record.from_at2(huge)


def test_csv_with_and_without_header(tmp_path):
    t = 0.02 * np.arange(12)
    two = tmp_path / "two.csv"
    two.write_text("time_s,acc_g\n" + "".join(f"{a:.3f},{b}\n" for a, b in zip(t, VALUES)))
    rec = pd_.Record.from_csv(two, time="time_s", accel="acc_g")
    np.testing.assert_allclose(rec.accel, VALUES * 9.81)
    assert rec.name == "two" and rec.dt_s == pytest.approx(0.02)
    one = tmp_path / "one.txt"
    one.write_text("".join(f"{b * 981.0}\n" for b in VALUES))  # cm/s2, no header, whitespace
    rec1 = pd_.Record.from_csv(one, accel=0, dt=0.02, units="cm/s2", name="mine")
    np.testing.assert_allclose(rec1.accel, VALUES * 9.81, rtol=1e-12)
    np.testing.assert_allclose(rec1.t, rec.t, atol=1e-12)
    assert rec1.name == "mine"
    for kwargs, field in (({"accel": "acc_g"}, "time"), ({"accel": "acc_g", "time": "time_s", "dt": 0.02},
                                                         "time"),
                          ({"accel": "nope", "time": "time_s"}, "accel"),
                          ({"accel": "acc_g", "time": "time_s", "units": "gal"}, "units")):
        with pytest.raises(pd_.InputError) as info:
            pd_.Record.from_csv(two, **kwargs)
        assert info.value.field == field, (kwargs, info.value.field)
    backwards = tmp_path / "backwards.csv"
    backwards.write_text("t,a\n0,0\n0.02,1\n0.01,2\n")
    with pytest.raises(pd_.InputError, match="line 4"):
        pd_.Record.from_csv(backwards, time="t", accel="a")
    holed = tmp_path / "holed.csv"
    holed.write_text("t,a\n0,0\n0.02,\n0.04,2\n")
    with pytest.raises(pd_.InputError, match="line 3"):
        pd_.Record.from_csv(holed, time="t", accel="a")


def test_scaling_to_a_pga_or_a_spectral_acceleration():
    rec = el_centro()
    assert rec.pga_g == pytest.approx(0.31882, rel=1e-4) and rec.dt_s == pytest.approx(0.02)
    assert rec.t.size == 1559 and rec.duration_s == pytest.approx(31.16) and rec.name
    half = rec.scaled(pga_g=0.15)
    assert half.pga_g == pytest.approx(0.15, rel=1e-12)
    assert half.meta["scale_factor"] == pytest.approx(0.15 / rec.pga_g) and half.name == rec.name
    to_sa = half.scaled(sa_g=0.5, period_s=1.0)
    psa = pd_.response_spectrum(to_sa, [1.0])["psa_g"].item()
    assert psa == pytest.approx(0.5, rel=1e-12)
    assert to_sa.meta["scale_factor"] == pytest.approx(to_sa.pga_g / rec.pga_g, rel=1e-12)
    for kwargs, field in (({}, "pga_g"), ({"pga_g": 0.2, "sa_g": 0.3}, "pga_g"), ({"sa_g": 0.3}, "period_s"),
                          ({"pga_g": -0.1}, "pga_g"), ({"pga_g": 0.2, "period_s": 1.0}, "period_s"),
                          ({"pga_g": 0.2, "damping_ratio": 0.02}, "damping_ratio"),
                          ({"sa_g": 0.3, "period_s": 1.0, "damping_ratio": 1.5}, "damping_ratio")):
        with pytest.raises(pd_.InputError) as info:
            rec.scaled(**kwargs)
        assert info.value.field == field, (kwargs, info.value.field)


def _lsim_peaks(rec: pd_.Record, period_s: float, zeta: float) -> np.ndarray:
    """The independent reference: scipy's lsim with a first-order hold (exact for a piecewise-linear
    input at its points) on the record subdivided finely, each peak refined by the parabola through
    the three points around it."""
    w = 2.0 * math.pi / period_s
    steps = np.diff(rec.t)
    subs = np.maximum(400, np.ceil(w * steps / 0.004)).astype(int)  # (each interval its own subdivision;
    # 400 at least: a peak a few thousandths of a step from a sample, where the slope has a kink, needs it)
    tf = np.concatenate([np.linspace(a, a + h, n, endpoint=False) for a, h, n in zip(rec.t[:-1], steps, subs)]
                        + [rec.t[-1:]])
    af = np.interp(tf, rec.t, rec.accel)
    system = signal.StateSpace([[0.0, 1.0], [-w * w, -2.0 * zeta * w]], [[0.0], [-1.0]],
                               [[1.0, 0.0], [0.0, 1.0], [-w * w, -2.0 * zeta * w]], [[0.0], [0.0], [0.0]])
    _, y, _ = signal.lsim(system, af, tf, interp=True)
    out = []
    for col in np.abs(y).T:
        i = int(np.argmax(col))
        if 0 < i < col.size - 1:
            y0, y1, y2 = col[i - 1:i + 2]
            den = y0 - 2.0 * y1 + y2
            out.append(y1 - 0.125 * (y0 - y2) ** 2 / den if den != 0.0 else y1)
        else:
            out.append(col[i])
    return np.array(out)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.2])
def test_response_spectrum_equals_an_independent_exact_reference(zeta):
    full = el_centro()
    rec = pd_.Record(full.t[:300], full.accel[:300], name="first 6 s")
    periods = np.array([0.0, 0.03, 0.1, 0.3, 0.7, 1.5, 4.0])
    ds = pd_.response_spectrum(rec, periods, damping_ratio=zeta)
    assert ds["sd_m"].dims == ("record", "period_s") and list(ds["record"].values) == ["first 6 s"]
    for i, period in enumerate(periods[1:], start=1):
        ref = _lsim_peaks(rec, period, zeta)
        got = np.array([ds[q].values[0, i] for q in ("sd_m", "sv_m_s", "sa_m_s2")])
        np.testing.assert_allclose(got, ref, rtol=1e-6, err_msg=f"T = {period} s")
    w = 2.0 * math.pi / periods[1:]
    np.testing.assert_allclose(ds["psa_m_s2"].values[0, 1:], w ** 2 * ds["sd_m"].values[0, 1:], rtol=1e-14)
    assert ds["sa_g"].values[0, 0] == ds["psa_g"].values[0, 0] == pytest.approx(rec.pga_g)  # (rigid: the PGA)
    if zeta == 0.0:  # undamped: the absolute acceleration is omega^2 u exactly
        np.testing.assert_allclose(ds["sa_m_s2"].values[0, 1:], ds["psa_m_s2"].values[0, 1:], rtol=1e-9)


def test_response_spectrum_finds_the_peaks_between_samples():
    # a coarse record (0.05 s) and a stiff oscillator (T = 0.12 s): the samples miss the peaks, the
    # closed form does not
    t = np.arange(0.0, 3.0, 0.05)
    rec = pd_.Record(t, 3.0 * np.sin(2.0 * math.pi * 2.3 * t) * np.exp(-0.3 * t))
    ds = pd_.response_spectrum(rec, [0.12, 0.5], damping_ratio=0.02)
    ref = np.array([_lsim_peaks(rec, T, 0.02) for T in (0.12, 0.5)])
    got = np.stack([ds[q].values[0] for q in ("sd_m", "sv_m_s", "sa_m_s2")], axis=1)
    np.testing.assert_allclose(got, ref, rtol=1e-6)


def _expm_peaks(rec: pd_.Record, period_s: float, zeta: float) -> np.ndarray:
    """A second independent reference, for uneven steps (which lsim refuses): each interval cut into
    equal sub-steps, propagated exactly by the matrix exponential of the system augmented with the
    record's value and slope; peaks refined by a parabola as in :func:`_lsim_peaks`."""
    from scipy.linalg import expm

    w = 2.0 * math.pi / period_s
    a = np.array([[0.0, 1.0, 0.0, 0.0], [-w * w, -2.0 * zeta * w, -1.0, 0.0], [0.0, 0.0, 0.0, 1.0],
                  [0.0, 0.0, 0.0, 0.0]])
    rows = []
    x = np.zeros(2)
    for k in range(rec.t.size - 1):
        h = rec.t[k + 1] - rec.t[k]
        n = max(400, math.ceil(w * h / 0.004))
        step = expm(a * (h / n))
        slope = (rec.accel[k + 1] - rec.accel[k]) / h
        z = np.array([x[0], x[1], rec.accel[k], slope])
        for _ in range(n):
            rows.append((z[0], z[1], -w * w * z[0] - 2.0 * zeta * w * z[1]))
            z = step @ z
        x = z[:2]
    rows.append((x[0], x[1], -w * w * x[0] - 2.0 * zeta * w * x[1]))
    out = []
    for col in np.abs(np.array(rows)).T:
        i = int(np.argmax(col))
        y0, y1, y2 = col[max(i - 1, 0)], col[i], col[min(i + 1, col.size - 1)]
        den = y0 - 2.0 * y1 + y2
        out.append(y1 - 0.125 * (y0 - y2) ** 2 / den if 0 < i < col.size - 1 and den != 0.0 else y1)
    return np.array(out)


@pytest.mark.parametrize("case", ["uneven steps", "a spike", "periods below the step", "nearly critical"])
def test_response_spectrum_on_awkward_records(case):
    rng = np.random.default_rng(3)
    t = np.cumsum(np.r_[0.0, rng.uniform(0.003, 0.08, 120)]) if case == "uneven steps" else np.arange(0.0,
                                                                                                      2.4,
                                                                                                      0.02)
    a = rng.normal(0.0, 2.0, t.size)
    if case == "a spike":
        a = np.zeros(t.size)
        a[40] = 40.0
    periods = [0.007, 0.013, 0.05, 0.4] if case == "periods below the step" else [0.05, 0.3, 1.2]
    zeta = 0.95 if case == "nearly critical" else 0.05
    rec = pd_.Record(t, a)
    ds = pd_.response_spectrum(rec, periods, damping_ratio=zeta)
    reference_peaks = _expm_peaks if case == "uneven steps" else _lsim_peaks
    ref = np.array([reference_peaks(rec, T, zeta) for T in periods])
    got = np.stack([ds[q].values[0] for q in ("sd_m", "sv_m_s", "sa_m_s2")], axis=1)
    np.testing.assert_allclose(got, ref, rtol=1e-6)


def test_response_spectrum_arguments_are_checked():
    rec = el_centro()
    with pytest.raises(pd_.InputError, match="half periods"):  # (far below the step: refused, not hours)
        pd_.response_spectrum(rec, [1e-8, 1.0])
    for kwargs, field in (({"periods_s": [1.0, 0.5]}, "periods_s"), ({"periods_s": [-0.1]}, "periods_s[0]"),
                          ({"periods_s": [1.0], "damping_ratio": -0.01}, "damping_ratio"),
                          ({"periods_s": [1.0], "damping_ratio": 1.0}, "damping_ratio"),
                          ({"periods_s": [1.0], "record": [rec, 3]}, "records[1]"),
                          ({"periods_s": [1.0], "record": "el centro"}, "record")):
        with pytest.raises(pd_.InputError) as info:
            pd_.response_spectrum(**{"record": rec, **kwargs})
        assert info.value.field == field, (kwargs, info.value.field)


def test_fema_p695_sets():
    far = fema_p695("far_field")
    assert len(far) == 44 and far[0].name == "953 NORTHR/MUL009"
    m = far[0].meta
    assert (m["event"], m["year"], m["magnitude"], m["rsn"]) == ("Northridge", 1994, 6.7, 953)
    assert m["station"].startswith("Beverly Hills") and m["scale_factor"] == 1.0
    assert 0.3 < far[0].pga_g < 0.6 and far[0].dt_s == pytest.approx(0.01)
    normalized = fema_p695("far_field", normalized=True)
    assert normalized[0].pga_g == pytest.approx(far[0].pga_g * m["normalization_factor"], rel=1e-3)
    near = fema_p695("near_field")
    pulse, no_pulse = fema_p695("near_field_pulse"), fema_p695("near_field_no_pulse")
    assert len(near) == 56 == len(pulse) + len(no_pulse)
    with pytest.raises(pd_.InputError) as info:
        fema_p695("farfield")
    assert info.value.field == "record_set" and "far_field" in str(info.value)


def test_a_record_run_with_bumpers_matches_the_reference():
    # El Centro's first 6 s at 0.4 g on the paper's damped system: the same contacts as the slow
    # solve_ivp reference, starting within 1e-8 s
    full = el_centro().scaled(pga_g=0.4)
    rec = pd_.Record(full.t[:300], full.accel[:300], name="El Centro, 6 s")
    osc = pd_.presets.paper_damped()
    run = pd_.simulate(osc, rec, 6.0, sample_rate_hz=0)
    ref = reference(osc, rec, 6.0, rtol=REFERENCE_RTOL, atol=REFERENCE_ATOL)
    assert len(run.contacts) == len(ref.contact_starts) >= 4
    np.testing.assert_allclose(run.contacts["t_start_s"], [t for _, t in ref.contact_starts], atol=1e-8)
    assert list(run.contacts["side"]) == [("left", "right")[side] for side, _ in ref.contact_starts]


def test_a_record_plots():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rec = el_centro()
    artists = pd_.plots.plot_record(rec)
    assert rec.plot().__class__.__name__ == "Figure"
    assert artists[0].get_label() == rec.name and len(artists) == 3
    spectrum = pd_.response_spectrum([rec, rec.scaled(pga_g=0.1)], np.linspace(0.05, 3.0, 30))
    lines = pd_.plots.plot_response_spectrum(spectrum)
    assert len(lines) == 2
    plt.close("all")


def test_cli_simulate_with_a_record(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    at2 = tmp_path / "elc.AT2"
    rec = el_centro()
    rows = [rec.accel[i:i + 5] / rec.g for i in range(0, 300, 5)]
    at2.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nIMPERIAL VALLEY 05/19/40 0437, EL CENTRO, 180\n"
                   "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   300, DT=   .0200 SEC\n"
                   + "".join("".join(f"{v:15.7E}" for v in row) + "\n" for row in rows))
    runner = CliRunner()
    contacts = tmp_path / "contacts.csv"
    result = runner.invoke(app, ["simulate", "--preset", "paper-damped", "--record", str(at2), "--scale-pga",
                                 "0.4", "--contacts", str(contacts)])
    assert result.exit_code == 0, result.output
    assert "record elc (PGA 0.4 g, 5.98 s)" in result.output and contacts.is_file()
    # the same as the Python API
    run = pd_.simulate(pd_.presets.paper_damped(), pd_.Record.from_at2(at2).scaled(pga_g=0.4), 5.98,
                       sample_rate_hz=0)
    import pandas as pd

    assert len(run.contacts) == len(pd.read_csv(contacts)) > 0
    one = tmp_path / "one.txt"
    one.write_text("".join(f"{a}\n" for a in rec.accel[:300] / rec.g))
    same = runner.invoke(app, ["simulate", "--preset", "paper-damped", "--record", str(one), "--record-dt",
                               "0.02", "--scale-pga", "0.4"])
    assert same.exit_code == 0 and "record one (PGA 0.4 g, 5.98 s)" in same.output, same.output
    two = tmp_path / "two.csv"
    two.write_text("".join(f"{t},{a}\n" for t, a in zip(rec.t[:50], rec.accel[:50] / rec.g)))
    for args, words in ((["--record", str(at2), "--a-g", "0.1"], "not both"), ([], "--a-g and --freq"),
                        (["--a-g", "0.1", "--freq", "1", "--scale-pga", "0.3"],
                         "--scale-pga is for --record"),
                        (["--record", str(two), "--record-dt", "0.02"], "has 2 columns"),
                        (["--record", str(one)], "has 1 column(s)"),
                        (["--record", str(at2), "--record-dt", "0.02"], "an .AT2 file gives its DT")):
        bad = runner.invoke(app, ["simulate", "--preset", "paper-damped", *args])
        assert bad.exit_code == 2 and words in bad.output, bad.output


def test_a_pickled_record_leaves_its_kernel_arrays_behind():
    import pickle

    rec = el_centro()
    before = len(pickle.dumps(rec))
    rec.kernel_arrays()  # cached on the record
    assert "_kernel_arrays" in rec.__dict__
    data = pickle.dumps(rec)
    assert len(data) == before  # the samples once, not three times
    back = pickle.loads(data)
    assert "_kernel_arrays" not in back.__dict__
    assert np.array_equal(back.accel, rec.accel) and back.name == rec.name
    for a, b in zip(back.kernel_arrays()[1:], rec.kernel_arrays()[1:]):
        assert np.array_equal(a, b)
