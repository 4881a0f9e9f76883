"""Property: bad input to any public entry point gets an InputError or a PoundingWarning.

Hypothesis replaces one or two arguments of a valid call with values from the classes that
broke the shell before (NaN, inf, +-huge, tiny, zero, negative, wrong type, wrong length,
non-increasing, text for numbers).  Never another exception type, never a warning other than
PoundingWarning, never a hang (each call under an alarm), never SUCCESS with a non-finite
result.
"""

from __future__ import annotations

import math
import os
import signal
import warnings
from contextlib import contextmanager

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pounding as pd_

TIMEOUT_S = 30
EXAMPLES = int(os.environ.get("POUNDING_FUZZ_EXAMPLES", "40"))  # per entry point; more for a deeper look
NAN, INF = float("nan"), float("inf")
SCALARS = [
    NAN,
    INF,
    -INF,
    1e300,
    -1e300,
    1e-300,
    -1e-300,
    0.0,
    -1.0,
    -0.0,
    2**70,
    1.5,
    True,
    None,
    "0.05",
    b"1",
    [1.0],
    {},
    (),
    object(),
    np.float32(np.nan),
    np.int64(-3),
    complex(1, 1),
]
ARRAYS = [
    [],
    [NAN],
    [INF, 1.0],
    [[1.0, 2.0], [3.0, 4.0]],
    [3.0, 2.0, 1.0],
    [1.0, 1.0],
    "abc",
    None,
    5.0,
    [1e300, 2e300],
    [-1.0, 0.0],
    [0.0],
    [1.0, "x"],
    np.zeros((0, 2)),
    [1e-300, 2e-300],
]

ISO = pd_.Isolator([38e3, 18e3, 2e3], [0.015, 0.04], "kinematic", 1000.0)
LAW = pd_.KelvinVoigt(1.46e6, 5.0)
BUMPERS = pd_.Bumpers(0.015, 0.015, LAW)
OSC = pd_.Oscillator(500.0, ISO, BUMPERS)
EXC = pd_.Harmonic(0.05, 2.2)

# entry point -> (call, valid keyword arguments, which of them take arrays)
ENTRIES = {
    "Isolator": (
        pd_.Isolator,
        {
            "slopes_n_m": [38e3, 18e3, 2e3],
            "breakpoints_m": [0.015, 0.04],
            "hysteresis": "kinematic",
            "damping_n_s_m": 1000.0,
        },
        {"slopes_n_m", "breakpoints_m"},
    ),
    "KelvinVoigt": (pd_.KelvinVoigt, {"stiffness": 1.46e6, "damping": 5.0}, set()),
    "HuntCrossley": (pd_.HuntCrossley, {"stiffness": 1e8, "exponent": 1.5, "damping": 1e5}, set()),
    "Jankowski": (pd_.Jankowski, {"stiffness": 1e8, "damping_ratio": 0.3, "effective_mass": 500.0,
                                  "exponent": 1.5},
                  set()),
    "MultilinearBumper": (pd_.MultilinearBumper,
                          {"slopes": [1.46e6, 1e5, 5e6], "breakpoints": [0.001, 0.004], "damping": 500.0},
                          {"slopes", "breakpoints"}),
    "Jankowski.from_restitution": (pd_.Jankowski.from_restitution,
                                   {"stiffness": 1e8, "restitution": 0.8, "effective_mass": 500.0,
                                    "exponent": 1.5},
                                   set()),
    "Bumpers": (pd_.Bumpers, {"gap_left_m": 0.015, "gap_right_m": 0.015, "law": LAW, "law_right": None},
                set()),
    "Oscillator": (pd_.Oscillator, {"mass_kg": 500.0, "isolator": ISO, "bumpers": BUMPERS}, set()),
    "Harmonic": (pd_.Harmonic, {"a_g": 0.05, "freq_hz": 2.2, "phase": 0.0, "g": 9.81}, set()),
    "Record": (pd_.Record, {"t": [0.0, 0.5, 1.0], "accel": [0.0, 1.0, 0.0]}, {"t", "accel"}),
    "State.at_rest": (
        pd_.State.at_rest,
        {"system": OSC, "time_s": 0.0, "displacement_m": 0.0, "velocity_m_s": 0.6},
        set(),
    ),
    "State": (pd_.State, {"vector": pd_.State.at_rest(OSC).vector}, {"vector"}),
    "simulate": (
        pd_.simulate,
        {
            "system": OSC,
            "excitation": EXC,
            "duration": 2.0,
            "state": None,
            "rtol": 1e-10,
            "sample_rate_hz": 100.0,
            "max_events": 10**6,
            "max_steps": 10**7,
        },
        set(),
    ),
    "sweep": (
        pd_.sweep,
        {
            "system": OSC,
            "a_g": 0.05,
            "freqs_hz": [2.0, 2.2],
            "direction": "up",
            "steady": "fixed",
            "cycles": 4,
            "measure_cycles": 2,
            "steady_rtol": 1e-6,
            "max_period": 4,
            "omega_min_rad_s": 3.77,
            "f_ref_hz": 1.0,
            "rtol": 1e-10,
            "max_events_per_cycle": 10**5,
            "max_steps": 10**7,
        },
        {"freqs_hz"},
    ),
    "campaign": (
        pd_.campaign,
        {
            "nbs_system": OSC.without_bumpers(),
            "ybs_system": OSC,
            "nbs_a_g": [0.05],
            "ybs_a_g": [0.05],
            "freqs_hz": [2.0],
            "directions": ["up"],
            "workers": 1,
            "steady": "fixed",
            "cycles": 3,
            "measure_cycles": 1,
        },
        {"nbs_a_g", "ybs_a_g", "freqs_hz", "directions"},
    ),
    "fit_contact_law": (
        pd_.fit_contact_law,
        {
            "displacement_m": [0.0, 1e-3, 2e-3, 1e-3, 0.0],
            "force_n": [0.0, 1.5e3, 3e3, 1.4e3, 0.0],
            "time_s": [0.0, 0.1, 0.2, 0.3, 0.4],
            "law": "kelvin_voigt",
        },
        {"displacement_m", "force_n", "time_s"},
    ),
    "fit_contact_law multilinear": (
        pd_.fit_contact_law,
        {
            "displacement_m": [0.0, 1e-3, 2e-3, 3e-3, 2e-3, 1e-3, 0.0],
            "force_n": [0.0, 1.5e3, 3e3, 6e3, 2.9e3, 1.4e3, 0.0],
            "time_s": [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
            "law": "multilinear",
            "breakpoints": [1.5e-3],
            "n_branches": 2,
        },
        {"displacement_m", "force_n", "time_s", "breakpoints"},
    ),
    "rank_contact_laws": (
        pd_.rank_contact_laws,
        {
            "displacement_m": [0.0, 1e-3, 2e-3, 3e-3, 2e-3, 1e-3, 0.0],
            "force_n": [0.0, 1.5e3, 3e3, 6e3, 2.9e3, 1.4e3, 0.0],
            "time_s": [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
            "effective_mass_kg": 500.0,
            "n_branches": 2,
        },
        {"displacement_m", "force_n", "time_s"},
    ),
    "Targets.from_records": (
        pd_.Targets.from_records,
        {
            "records": [{"configuration": "YBs", "a_g": 0.05, "quantity": "alpha", "value": 16.8}],
            "defaults": None,
            "tolerances": None,
            "eta_gap_total_m": 0.03,
        },
        set(),
    ),
    "Oscillator.from_toml_text": (pd_.Oscillator.from_toml_text, {"text": OSC.to_toml_text()}, set()),
    "paper_targets": (pd_.paper_targets, {"direction": "up", "quantities": ("alpha", "nu_r")},
                      {"quantities"}),
    "Targets.check_consistency": (
        pd_.paper_targets().check_consistency,
        {"mass_kg": 500.0, "gap_total_m": 0.03, "g": 9.81, "f_ref_hz": 1.0, "omega_min_rad_s": 3.77},
        set(),
    ),
}


@contextmanager
def _alarm(seconds: int):
    def hang(signum, frame):
        raise TimeoutError(f"no answer within {seconds} s")

    previous = signal.signal(signal.SIGALRM, hang)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def _finite_if_success(result) -> None:
    if isinstance(result, pd_.Run) and result.success:
        values = [
            result.displacement_max,
            result.displacement_min,
            result.abs_acceleration_max,
            *vars(result.energy).values(),
            *result.final_state.vector,
        ]
        assert all(math.isfinite(v) for v in values), result
    if isinstance(result, pd_.SweepResult) and result.success:
        done = slice(0, result.steps_done)
        assert np.isfinite(result.level_metrics[done]).all(), result
        assert np.isfinite(result.contact_sums[done]).all(), result
    if isinstance(result, pd_.CampaignResult):
        for sw in result.sweeps.values():
            _finite_if_success(sw)


def _call_with(entry: str, replaced: dict):
    call, kwargs, _ = ENTRIES[entry]
    kwargs = {**kwargs, **replaced}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning but the documented one fails
        warnings.simplefilter("ignore", pd_.PoundingWarning)
        with _alarm(TIMEOUT_S):
            try:
                result = call(**kwargs)
            except pd_.InputError as exc:
                assert "Fix:" in str(exc)
                return
    _finite_if_success(result)


@st.composite
def _bad_arguments(draw, entry: str) -> dict:
    _, kwargs, arrays = ENTRIES[entry]
    names = draw(st.lists(st.sampled_from(sorted(kwargs)), min_size=1, max_size=2, unique=True))
    return {
        name: draw(st.sampled_from(ARRAYS + SCALARS[:8] if name in arrays else SCALARS + ARRAYS[:4]))
        for name in names
    }


@pytest.mark.parametrize("entry", sorted(ENTRIES))
def test_bad_arguments_get_an_input_error_or_a_documented_warning(entry):
    @settings(
        max_examples=EXAMPLES,
        deadline=None,
        derandomize=True,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    )
    @given(_bad_arguments(entry))
    def check(replaced):
        _call_with(entry, replaced)

    check()


def test_bad_toml_values_in_every_field(tmp_path):
    # each number of a system file replaced by text, a table, NaN or a huge value
    text = OSC.to_toml_text()
    numbers = ["500.0", "38000.0", "0.015", "1000.0", "1460000.0", "5.0"]
    for number in numbers:
        for bad in ('"1"', "{ a = 1 }", "nan", "1e300", "-1.0", "[]", "true"):
            changed = text.replace(number, bad, 1)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", pd_.PoundingWarning)
                with pytest.raises(pd_.InputError):
                    pd_.Oscillator.from_toml_text(changed)
