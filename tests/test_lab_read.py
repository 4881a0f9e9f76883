"""Reading shaking-table recordings (issue 17): pounding.lab.read_test and LabRecord."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import pounding as pd_
from pounding.lab import LabRecord, read_test

N = 200
FS = 1000.0
T = np.arange(N) / FS
TABLE = 0.05 * np.sin(2 * np.pi * 2.0 * T)  # g
ACC1 = 0.5 * np.sin(2 * np.pi * 2.0 * T + 0.3)  # g
ACC2 = ACC1 * 1.02
DISP = 18.0 * np.sin(2 * np.pi * 2.0 * T - 0.5)  # mm
UNITS = {"time": "ms", "table_acc": "g", "mass_acc": "g", "displacement": "mm"}


def _write(path, delimiter=",", header=True, rows=None, comment=True):
    lines = ["# shaking-table test, 1 kHz"] if comment else []
    if header:
        lines.append(delimiter.join(["t_ms", "a_table", "a1", "a2", "laser_mm"]))
    data = rows if rows is not None else [
        delimiter.join(f"{v:.12g}" for v in row) for row in zip(T * 1e3, TABLE, ACC1, ACC2, DISP)]
    lines += data
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("delimiter", [",", "\t", ";", " "])
def test_every_delimiter_by_name_and_units_to_si(tmp_path, delimiter):
    path = _write(tmp_path / "test.txt", delimiter)
    rec = read_test(path, time="t_ms", table_acc="a_table", mass_acc=["a1", "a2"], displacement="laser_mm",
                    units=UNITS)
    np.testing.assert_allclose(rec.time_s, T, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(rec.table_acc_m_s2, TABLE * 9.81, rtol=1e-11)
    np.testing.assert_allclose(rec.mass_acc_m_s2, np.column_stack([ACC1, ACC2]) * 9.81, rtol=1e-11)
    np.testing.assert_allclose(rec.displacement_m, DISP * 1e-3, rtol=1e-11)
    assert rec.mass_channels == ("a1", "a2") and rec.sample_rate_hz == pytest.approx(FS)
    np.testing.assert_allclose(rec.mass_acc_mean_m_s2, (ACC1 + ACC2) / 2 * 9.81, rtol=1e-11)
    assert rec.gaps.empty and rec.nan_runs.empty and rec.source == str(path)
    assert list(rec.to_dataframe().columns) == ["time_s", "table_acc_m_s2", "a1", "a2", "displacement_m"]


def test_columns_by_index_without_a_header(tmp_path):
    path = _write(tmp_path / "test.csv", ",", header=False, comment=False)
    rec = read_test(path, time=0, table_acc=1, mass_acc=2, displacement=4, units=UNITS)
    assert rec.mass_channels == ("column 2",) and rec.mass_acc_m_s2.shape == (N, 1)
    np.testing.assert_allclose(rec.displacement_m, DISP * 1e-3, rtol=1e-11)


def test_gaps_and_missing_values_are_reported(tmp_path):
    rows = [",".join(f"{v:.12g}" for v in row) for row in zip(T * 1e3, TABLE, ACC1, ACC2, DISP)]
    del rows[50:60]  # 10 samples never recorded
    rows[100] = rows[100].replace(rows[100].split(",")[2], "", 1)  # an empty accelerometer field
    rows[101] = ",".join(rows[101].split(",")[:2] + ["nan"] + rows[101].split(",")[3:])
    path = _write(tmp_path / "test.csv", rows=rows)
    with pytest.warns(pd_.PoundingWarning, match="gap.*missing values"):
        rec = read_test(path, time="t_ms", table_acc="a_table", mass_acc=["a1", "a2"],
                        displacement="laser_mm", units=UNITS)
    gap = rec.gaps.iloc[0]
    assert len(rec.gaps) == 1 and gap.missing_samples == 10 and gap.start_s == pytest.approx(0.049)
    run = rec.nan_runs.iloc[0]
    assert len(rec.nan_runs) == 1 and run.channel == "a1" and run.samples == 2


@pytest.mark.parametrize("change, field, words", [
    (lambda rows: rows[:7] + ["0.007,0.01,0.02"] + rows[8:], "path", ["line 10", "3 fields", "laser_mm"]),
    (lambda rows: rows[:5] + ["0.005,0.01,abc,0.02,1.0"] + rows[6:], "path", ["line 8", "a1", "'abc'"]),
    (lambda rows: rows[:5] + ["5,0,01,0.01,0.02,1.0"] + rows[6:], "path",
     ["line 8", "6 fields", "header has 5"]),
    (lambda rows: rows[:5] + [rows[3]] + rows[6:], "t_ms", ["line 8", "does not increase", "sort"]),
])
def test_bad_files_name_the_line_and_the_column(tmp_path, change, field, words):
    rows = [",".join(f"{v:.12g}" for v in row) for row in zip(T * 1e3, TABLE, ACC1, ACC2, DISP)]
    path = _write(tmp_path / "bad.csv", rows=change(rows))
    with pytest.raises(pd_.InputError) as info:
        read_test(path, time="t_ms", table_acc="a_table", mass_acc=["a1", "a2"], displacement="laser_mm",
                  units=UNITS)
    assert info.value.field == field
    for w in words:
        assert w in str(info.value), (w, str(info.value))


def test_bad_arguments_are_named(tmp_path):
    path = _write(tmp_path / "test.csv")
    good = dict(time="t_ms", table_acc="a_table", mass_acc=["a1", "a2"], displacement="laser_mm", units=UNITS)
    for change, field in (({"time": "time"}, "time"), ({"mass_acc": ["a1", 9]}, "mass_acc[1]"),
                          ({"mass_acc": []}, "mass_acc"), ({"displacement": 2.5}, "displacement"),
                          ({"units": {"time": "min"}}, "units.time"),
                          ({"units": {"speed": "m/s"}}, "units key"),
                          ({"units": "SI"}, "units"), ({"g": -9.81}, "g")):
        with pytest.raises(pd_.InputError) as info:
            read_test(path, **{**good, **change})
        assert info.value.field == field, (change, info.value.field)
        assert "Fix:" in str(info.value)
    with pytest.raises(pd_.InputError) as info:
        read_test(tmp_path / "nowhere.csv", **good)
    assert info.value.field == "path"
    (tmp_path / "empty.csv").write_text("# nothing\n\n")
    with pytest.raises(pd_.InputError):
        read_test(tmp_path / "empty.csv", **good)


def test_displacement_in_mm_read_as_m_warns(tmp_path):
    path = _write(tmp_path / "test.csv")
    with pytest.warns(pd_.PoundingWarning, match="mm"):
        read_test(path, time="t_ms", table_acc="a_table", mass_acc="a1", displacement="laser_mm",
                  units={"time": "ms", "table_acc": "g", "mass_acc": "g"})


def test_labrecord_from_arrays_is_checked():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rec = LabRecord(T, TABLE, ACC1, DISP * 1e-3, ("a1",))
    assert rec.mass_acc_m_s2.shape == (N, 1) and not rec.time_s.flags.writeable
    for kwargs, field in (({"time_s": T[::-1]}, "time_s"), ({"time_s": T[:5]}, "time_s"),
                          ({"table_acc_m_s2": TABLE[:-1]}, "table_acc_m_s2"),
                          ({"mass_channels": ("a1", "a2")}, "mass_channels"),
                          ({"mass_acc_m_s2": ACC1[:-2]}, "mass_acc_m_s2")):
        args = {"time_s": T, "table_acc_m_s2": TABLE, "mass_acc_m_s2": ACC1, "displacement_m": DISP * 1e-3,
                "mass_channels": ("a1",), **kwargs}
        with pytest.raises(pd_.InputError) as info:
            LabRecord(**args)
        assert info.value.field == field


def test_cli_lab_writes_tables_figure_and_targets(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    osc = pd_.presets.paper_damped()
    freqs = [1.4, 1.6, 1.8]
    rec = pd_.lab.synthetic_test(osc, 0.05, freqs, cycles=20, noise=0.005, gains=(1.0, 1.0), seed=2)
    df = rec.to_dataframe()
    df["time_ms"] = df["time_s"] * 1e3
    df["laser_mm"] = df["displacement_m"] * 1e3
    path = tmp_path / "test.csv"
    df[["time_ms", "table_acc_m_s2", "accelerometer_1", "accelerometer_2", "laser_mm"]].to_csv(path,
                                                                                               index=False)
    out = tmp_path / "lab"
    runner = CliRunner()
    args = ["lab", str(path), "--time", "time_ms", "--table-acc", "table_acc_m_s2", "--mass-acc",
            "accelerometer_1,accelerometer_2", "--displacement", "laser_mm", "--units",
            "time=ms,displacement=mm",
            "--mass", "500", "--gap", "0.03", "--freqs", "1.4,1.6,1.8", "--out", str(out)]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    for name in ("steps.csv", "impacts.csv", "lab_sweep.png", "targets.toml"):
        assert (out / name).is_file(), name
    targets = pd_.Targets.from_toml(out / "targets.toml")
    assert targets.eta_gap_total_m == 0.03 and "alpha" in set(targets.data["quantity"])
    bad = runner.invoke(app, args[:-2] + ["--out", str(tmp_path / "x"), "--units", "time=minutes"])
    assert bad.exit_code == 2 and "units.time" in bad.output
    assert not (tmp_path / "x").exists()
    bad_freqs = [a if a != "1.4,1.6,1.8" else "1.4,x" for a in args[:-2]] + ["--out", str(tmp_path / "y")]
    bad = runner.invoke(app, bad_freqs)
    assert bad.exit_code == 2 and "'x' is not a number" in bad.output and "Traceback" not in bad.output
    # a header written with quotes (spreadsheets, pandas quoting) reads as the names
    quoted = tmp_path / "quoted.csv"
    quoted.write_text('"time_s","table","a1","d"\n' + "".join(f"{k * 0.001},{k},{k},{k * 1e-4}\n"
                                                              for k in range(40)))
    read = pd_.lab.read_test(quoted, time="time_s", table_acc="table", mass_acc="a1", displacement="d")
    assert read.time_s.size == 40
