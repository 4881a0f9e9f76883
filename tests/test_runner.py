"""The shared task runner: every scheduler gives the same values; errors, Ctrl-C and progress
behave the same whatever runs the tasks."""

from __future__ import annotations

import os
import signal
import threading
import time

import numpy as np
import pytest

import pounding as pd_
from pounding._errors import Interrupted
from pounding._runner import run_tasks, scheduler_kind


def square(task, ctx):
    """A task: its number squared, one step reported."""
    ctx.advance(1)
    return task * task


def fails_on_three(task, ctx):
    if task == 3:
        raise ValueError("three is not allowed")
    ctx.advance(1)
    return task


def counts_until_stopped(task, ctx):
    """Counts in small steps until the run is stopped, then keeps what it counted."""
    n = 0
    while n < 400:  # (4 s at most: a test that never stops fails, it does not hang)
        if ctx.stopped():
            raise Interrupted(n, n, 400, "steps")
        time.sleep(0.01)
        n += 1
    return n


@pytest.mark.parametrize("scheduler", ["serial", "threads", "processes", "local"])
def test_every_scheduler_gives_the_same_values(scheduler):
    seen = []
    out = run_tasks(square, list(range(7)), scheduler=scheduler, workers=2, progress=seen.append)
    assert out.values == [i * i for i in range(7)] and out.complete and not out.interrupted
    assert sum(seen) == 7  # (one step a task: reported by the task in this process, or as it ends)


def test_a_tasks_error_stops_the_others_or_lets_them_finish():
    stopped = run_tasks(fails_on_three, list(range(8)), scheduler="serial", on_error="stop")
    assert list(stopped.errors) == [3] and stopped.values[:3] == [0, 1, 2]
    assert stopped.values[4:] == [None] * 4
    finished = run_tasks(fails_on_three, list(range(8)), scheduler="threads", workers=2, on_error="finish")
    assert list(finished.errors) == [3]
    assert [v for v in finished.values if v is not None] == [0, 1, 2, 4, 5, 6, 7]
    with pytest.raises(ValueError, match="three"):
        finished.raise_first_error()
    procs = run_tasks(fails_on_three, list(range(8)), scheduler="processes", workers=2, on_error="finish")
    assert list(procs.errors) == [3] and isinstance(procs.errors[3], ValueError)


def test_ctrl_c_on_threads_stops_every_task_and_keeps_what_they_did():
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    out = run_tasks(counts_until_stopped, [0, 1], scheduler="threads", workers=2)
    assert time.monotonic() - t0 < 2.0
    assert out.interrupted and out.partial == {0, 1} and all(10 < v < 200 for v in out.values)
    assert not out.complete


def sleeps(task, ctx):
    """A task that takes ``task`` seconds (in a worker process, where nothing can stop it but its end)."""
    time.sleep(task)
    ctx.advance(1)
    return task


@pytest.mark.parametrize("scheduler", ["processes", "local"])
def test_ctrl_c_on_worker_processes_keeps_what_finished_and_stops_the_rest(scheduler):
    """On processes and Dask a task in flight cannot be asked to stop: Ctrl-C stops the workers at
    once, what had finished is kept, the tasks in flight and not started are None."""
    done, timer = [], threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))

    def progress(n):
        done.append(n)
        if len(done) == 3:
            timer.start()  # (the quick tasks have ended; the slow ones run)

    t0 = time.monotonic()
    out = run_tasks(sleeps, [0.0, 0.01, 0.02, 60.0, 60.0], scheduler=scheduler, workers=2, progress=progress)
    assert time.monotonic() - t0 < 40.0  # (not the slow tasks' 60 s)
    assert out.interrupted and not out.complete and not out.errors
    assert out.values == [0.0, 0.01, 0.02, None, None] and out.ended == {0, 1, 2}


def test_bad_arguments_are_named():
    with pytest.raises(pd_.InputError, match="scheduler") as info:
        scheduler_kind("cluster")
    assert "tcp://host:8786" in str(info.value)
    with pytest.raises(pd_.InputError, match="on_error"):
        run_tasks(square, [1], on_error="ignore")
    with pytest.raises(pd_.InputError, match="workers"):
        run_tasks(square, [1], workers=0)


@pytest.mark.parametrize("scheduler", ["serial", "processes", "local"])
def test_a_pounding_spectrum_is_the_same_on_every_scheduler(scheduler):
    quake = pd_.records.el_centro().scaled(pga_g=0.3)
    short = pd_.Record(quake.t[:400], quake.accel[:400])
    args = ([quake, short], [1.0, 2.0])
    kw = dict(gaps_m=[0.02, 0.05], workers=2)
    ref = pd_.pounding_spectrum(*args, **kw)
    other = pd_.pounding_spectrum(*args, scheduler=scheduler, **kw)
    for name in ref.data.data_vars:
        np.testing.assert_array_equal(other.data[name].values, ref.data[name].values)


@pytest.mark.parametrize("scheduler", ["serial", "processes", "local"])
def test_a_campaign_is_the_same_on_every_scheduler(scheduler):
    ybs = pd_.presets.paper_damped()
    kw = dict(nbs_a_g=[0.05], ybs_a_g=[0.05, 0.1], freqs_hz=[1.5, 2.0, 2.5], directions=["up", "down"],
              steady="fixed", cycles=6, workers=2)
    ref = pd_.campaign(ybs.without_bumpers(), ybs, **kw)
    other = pd_.campaign(ybs.without_bumpers(), ybs, scheduler=scheduler, **kw)
    assert other.complete and list(other.sweeps) == list(ref.sweeps)
    for name in ref.data.data_vars:
        np.testing.assert_array_equal(other.data[name].values, ref.data[name].values)


@pytest.mark.parametrize("scheduler", ["serial", "processes", "local"])
def test_an_identification_is_the_same_on_every_scheduler(scheduler):
    fixed = {"slope_1": 38e3, "slope_2": 18e3, "slope_3": 2e3, "breakpoint_1": 0.015, "breakpoint_2": 0.04,
             "gap": 0.015, "bumper_stiffness": 1.46e6, "bumper_damping": 400.0}
    family = pd_.ModelFamily(500.0, 3, "kinematic", "kelvin_voigt", fixed=fixed)
    targets = pd_.Targets.from_records([dict(configuration="NBs", a_g=0.05, quantity="alpha", value=2.5),
                                        dict(configuration="YBs", a_g=0.05, quantity="alpha", value=8.0)])
    kw = dict(seed=3, maxiter=2, popsize=4, refine=True, workers=2, freqs_hz=np.arange(1.0, 3.01, 0.5),
              cycles=10)
    ref = pd_.identify(targets, family, {"isolator_damping": (200.0, 3000.0)}, **kw)
    other = pd_.identify(targets, family, {"isolator_damping": (200.0, 3000.0)}, scheduler=scheduler, **kw)
    same = ("parameters", "cost", "n_evaluations")
    assert [getattr(other, a) for a in same] == [getattr(ref, a) for a in same]


def test_a_tasks_error_is_raised_as_it_was_naming_the_task():
    out = run_tasks(fails_on_three, list(range(8)), scheduler="threads", workers=2, on_error="finish")
    with pytest.raises(ValueError, match="three") as info:
        out.raise_first_error(lambda i: f"task number {i}")
    assert info.value.__notes__ == ["(in task number 3)"]
    # through a caller: a record the engine refuses mid-spectrum names the record
    quake = pd_.records.el_centro().scaled(pga_g=0.3)
    bad = pd_.Record(quake.t[:50], quake.accel[:50], name="short one")
    with pytest.MonkeyPatch.context() as mp:
        import importlib

        ps = importlib.import_module("pounding.protocols.pounding_spectrum")

        def refuse(task, ctx):
            if task[0].name == "short one":
                raise RuntimeError("refused")
            return original(task, ctx)

        original = ps._one_record
        mp.setattr(ps, "_one_record", refuse)
        with pytest.raises(RuntimeError, match="refused") as info:
            pd_.pounding_spectrum([quake, bad], [1.0], gaps_m=[0.05], scheduler="serial")
    assert info.value.__notes__ == ["(in record 1 (short one))"]


def returns_none(task, ctx):
    return None


def test_a_task_that_returns_none_is_counted_once():
    seen = []
    out = run_tasks(returns_none, list(range(5)), scheduler="threads", workers=2, progress=seen.append)
    assert sum(seen) == 5 and out.values == [None] * 5 and out.complete
