"""Run control: Ctrl-C reaches the compiled kernels, work budgets, up-front refusal, memory."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import pounding as pd_
from pounding._errors import Problem


def _sigint_after(seconds: float) -> threading.Timer:
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_stops_a_long_simulate_at_once_and_keeps_the_run():
    osc = pd_.presets.paper_damped()
    pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 1.0)  # compiled before the clock starts
    timer = _sigint_after(0.5)
    t0 = time.perf_counter()
    try:
        with pytest.raises(pd_.Interrupted) as info:
            pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 1e6, sample_rate_hz=0.0)
    finally:
        timer.cancel()
    elapsed = time.perf_counter() - t0
    run = info.value.partial
    assert elapsed < 3.0, elapsed  # 1e6 s take about 20 s
    assert run.status == pd_.Status.INTERRUPTED and "Ctrl-C" in run.message
    assert 0.0 < run.final_state.time_s < 1e6
    assert np.isfinite(run.energy.residual) and abs(run.energy.residual) < 1e-6 * run.energy.input_work
    # it continues from where it stopped
    later = pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 1.0, state=run.final_state)
    assert later.success


def test_ctrl_c_stops_a_sweep_inside_a_step_and_keeps_the_finished_steps():
    osc = pd_.presets.paper_printed()
    pd_.sweep(osc, 0.05, [1.0], steady="fixed", cycles=2, measure_cycles=1)
    timer = _sigint_after(0.5)
    try:
        with pytest.raises(pd_.Interrupted) as info:
            pd_.sweep(osc, 0.05, [2.2, 2.3], steady="fixed", cycles=10**6)  # hours
    finally:
        timer.cancel()
    partial = info.value.partial
    assert partial.steps_done == 0  # the unfinished step is dropped, not half-measured
    assert np.isnan(partial.level_metrics).all() and np.isnan(partial.contact_sums).all()


def test_budget_stops_a_run_that_then_continues_as_one_long_run():
    osc = pd_.presets.paper_damped()
    exc = pd_.Harmonic(0.1, 2.9)  # contacts: about 900 steps where the estimate says 464
    start = pd_.State.at_rest(osc, velocity_m_s=0.6)
    whole = pd_.simulate(osc, exc, 20.0, start)
    first = pd_.simulate(osc, exc, 20.0, start, max_steps=500)
    assert first.status == pd_.Status.BUDGET and "max_steps" in first.message
    assert 0.0 < first.final_state.time_s < 20.0
    rest = pd_.simulate(osc, exc, 20.0 - first.final_state.time_s, first.final_state)
    assert rest.success
    assert rest.final_state.displacement_m == pytest.approx(whole.final_state.displacement_m, abs=1e-9)
    assert len(first.contacts.dropna()) + len(rest.contacts) == len(whole.contacts)
    assert max(first.abs_acceleration_max, rest.abs_acceleration_max) == pytest.approx(
        whole.abs_acceleration_max, rel=1e-9
    )


def test_a_sweep_stops_at_its_budget_with_a_status():
    osc = pd_.presets.paper_damped()
    # the estimate (flight only) is 1060 steps; the contacts at 2.0 and 2.2 Hz need more
    res = pd_.sweep(osc, 0.05, [1.0, 1.5, 2.0, 2.2], steady="fixed", cycles=30, max_steps=1200)
    assert res.status == pd_.Status.BUDGET and 0 < res.steps_done <= 4
    assert "max_steps" in res.message


@pytest.mark.parametrize("damping, mass", [(1e12, 500.0), (1e11, 500.0), (1.0, 1e-6)])
def test_runs_that_would_take_hours_are_refused_with_the_estimate(damping, mass):
    iso = pd_.Isolator([38e3, 18e3, 2e3], [0.015, 0.04], "kinematic", damping)
    with pytest.warns(pd_.PoundingWarning) if mass < 1e-3 else _nothing():
        osc = pd_.Oscillator(mass, iso)
    with pytest.raises(pd_.InputError) as info:
        pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 100.0)
    assert info.value.problem is Problem.OVER_BUDGET and info.value.field == "duration"
    assert "integration steps" in str(info.value) and "max_steps" in str(info.value)
    with pytest.raises(pd_.InputError) as info:
        pd_.sweep(osc, 0.05)
    assert info.value.problem is Problem.OVER_BUDGET


class _nothing:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def test_sweep_counts_and_cycles_are_bounded_before_any_array_is_sized():
    osc = pd_.presets.paper_damped()
    for kwargs, field in (
        ({"max_cycles": 1e300}, "max_cycles"),
        ({"cycles": 10**13, "steady": "fixed"}, "cycles"),
        ({"freqs_hz": np.linspace(0.5, 5, 200_001)}, "freqs_hz"),
        ({"max_events_per_cycle": 2**70}, "max_events_per_cycle"),
    ):
        with pytest.raises(pd_.InputError) as info:
            pd_.sweep(osc, 0.05, **kwargs)
        assert info.value.field == field


def test_the_default_history_is_bounded_and_an_explicit_one_checked_for_memory():
    osc = pd_.presets.paper_damped()
    short = pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 2.0)
    assert short.sample_rate_hz == 1000.0 and short.t.size >= 2001
    long = pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 5000.0)
    assert long.sample_rate_hz == pytest.approx(200.0)  # a million samples at most
    with pytest.raises(pd_.InputError) as info:
        pd_.simulate(osc, pd_.Harmonic(0.05, 2.2), 1e5, sample_rate_hz=1000.0)
    assert info.value.field == "sample_rate_hz" and "GB" in str(info.value)


def test_a_1e5_s_default_simulate_stays_under_1_gb():
    # the peak of this process's own memory (VmHWM), not getrusage's ru_maxrss: that one keeps the peak of
    # the parent it was forked from (a busy test worker's, over 1 GB at times) across the exec
    code = textwrap.dedent("""
        from pathlib import Path
        import pounding as p
        osc = p.presets.paper_printed()
        run = p.simulate(osc, p.Harmonic(0.05, 2.2), 1e5, p.State.at_rest(osc, velocity_m_s=0.6))
        assert run.success and len(run.contacts) > 100_000
        hwm = [ln for ln in Path("/proc/self/status").read_text().splitlines() if ln.startswith("VmHWM:")]
        print(hwm[0].split()[1])  # KiB
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    peak_mb = int(out.stdout.split()[-1]) / 1024
    assert peak_mb < 1024, f"peak {peak_mb:.0f} MB"


def test_kernel_stops_on_a_preset_stop_flag_and_counts_its_work():
    from pounding.engine.control import new_control, request_stop
    from pounding._core import run as run_kernel
    from pounding.engine.layout import CTL_WORK
    from pounding.engine.simulate import kernel_forcing, kernel_system

    osc = pd_.presets.paper_damped()
    forcing = kernel_forcing(pd_.Harmonic(0.05, 2.2))
    state = pd_.State.at_rest(osc).vector.copy()
    ctl = new_control(10**9)
    out = run_kernel(kernel_system(osc), forcing, state, 10.0, 0.0, 1e-10, 10**6, True, ctl)
    assert out.status == 0 and ctl[CTL_WORK] > 100
    request_stop([ctl])
    out = run_kernel(kernel_system(osc), forcing, state, 10.0, 0.0, 1e-10, 10**6, True, ctl)
    assert out.status == pd_.Status.INTERRUPTED and out.state[0] == 0.0
