"""Start-up guards: every compiled function of the package is specialised only once.

Numba compiles a function again for each new argument type, and a Python-int constant
argument (or a counter initialised from one) is a literal type of its own, as is a
read-only array.  Each extra specialisation costs a compilation on first use (cold start
is an issue 5 target), so a typical session, run in a fresh process, must leave exactly
one signature per dispatcher.  ``pounding.warm_up`` compiles ahead of time: it must cover every
kernel Python calls, with the same types, and a new process must then load them all.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

SESSION = textwrap.dedent("""
    import gc, json
    import numpy as np
    from numba.core.registry import CPUDispatcher
    import pounding as p

    # first, in this process (in workers the kernels would be loaded here, their callees unseen):
    # what it compiles must serve the session below as it is
    warm = p.warm_up(workers=1)
    osc = p.presets.paper_printed()
    p.simulate(osc, p.Harmonic(0.05, 2.2), 1.0, sample_rate_hz=100.0)
    run = p.simulate(osc, p.Harmonic(0.05, 2.2), 3.0, p.State.at_rest(osc, velocity_m_s=0.6))
    run.impacts
    hc = p.Oscillator(500.0, osc.isolator, p.Bumpers(0.015, 0.015, p.HuntCrossley(1e8, 1.5, 1e5)))
    p.simulate(hc, p.Harmonic(0.05, 2.2), 2.0, p.State.at_rest(hc, velocity_m_s=0.6))
    el = p.Oscillator(500.0, p.Isolator(osc.isolator.slopes, osc.isolator.breakpoints, "elastic", 10.0),
                      osc.bumpers)
    t = np.linspace(0.0, 2.0, 201)
    p.simulate(el, p.Record(t, np.sin(7.0 * t)), 2.0)
    p.sweep(osc, 0.05, [1.0, 1.1], steady="fixed", cycles=3, measure_cycles=1)
    p.sweep(osc, 0.05, [1.0, 1.1], max_cycles=40)
    p.response_spectrum(p.Record(t, np.sin(7.0 * t)), [0.0, 0.2, 1.0])
    p.periodic_orbit(p.presets.paper_damped(), p.Harmonic(0.05, 1.5))  # (the exact monodromy)
    p.periodic_orbit(p.presets.paper_damped(hysteresis="elastic"), p.Harmonic(0.05, 1.5))
    p.continuation(osc.without_bumpers(), 0.05, (1.0, 1.2))
    many = {}
    entries = []  # the kernels Python calls (with a Python wrapper)
    for obj in gc.get_objects():
        if isinstance(obj, CPUDispatcher) and obj.py_func.__module__.startswith("pounding"):
            if len(obj.signatures) > 1:
                many[obj.py_func.__qualname__] = [str(s) for s in obj.signatures]
            if not obj.targetoptions.get("no_cpython_wrapper", False):
                entries.append(obj.py_func.__name__)
    print(json.dumps({"many": many, "entries": sorted(entries), "compiled": warm.compiled,
                      "loaded": warm.loaded}))
""")
KERNELS = ["run_kernel", "step_kernel", "impact_row", "law_force_many", "spectrum_kernel", "monodromy_kernel"]


def test_each_compiled_function_has_one_specialisation(tmp_path):
    # an empty cache: with a filled one, a kernel loads its callees' code with its own and
    # their dispatchers never see (nor count) the types they are called with
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    out = subprocess.run([sys.executable, "-c", SESSION], capture_output=True, text=True, check=True, env=env)
    report = json.loads(out.stdout.strip().splitlines()[-1])
    many = report["many"]
    assert many == {}, f"compiled more than once (pass typed ints, writable arrays): {many}"
    # warm_up compiled every kernel Python calls, with the types the session then used
    assert report["entries"] == sorted(KERNELS)
    assert report["compiled"] == KERNELS and report["loaded"] == []
    # and a new process loads them all from the cache it filled
    again = subprocess.run([sys.executable, "-c", "import json, pounding as p; w = p.warm_up(); "
                            "print(json.dumps([w.compiled, w.loaded, w.message]))"],
                           capture_output=True, text=True, check=True, env=env)
    compiled, loaded, message = json.loads(again.stdout.strip().splitlines()[-1])
    assert compiled == [] and loaded == KERNELS, message
    assert message.startswith("6 kernels loaded from Numba's cache ("), message


def test_warm_up_compiles_in_two_processes_at_once(tmp_path):
    # from an empty cache the two groups of kernels compile in worker processes, and this one
    # loads what they cached; from a script read from standard input too (a worker of
    # multiprocessing's would import that script again, and fail)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    code = ("import json, pounding as p; w = p.warm_up(workers=2); "
            "print(json.dumps([w.compiled, w.loaded, w.in_memory, w.workers]))")
    out = subprocess.run([sys.executable, "-"], input=code, capture_output=True, text=True, check=True,
                         env=env, cwd=tmp_path)
    compiled, loaded, in_memory, workers = json.loads(out.stdout.strip().splitlines()[-1])
    assert compiled == KERNELS and loaded == [] and in_memory == [] and workers == 2
    # a cache file per kernel, written by the workers
    assert all(any(tmp_path.rglob(f"*{name}*.nbc")) for name in KERNELS)


def test_warm_up_arguments_are_checked():
    import pytest

    import pounding as p

    for bad in (0, -1, 2.5, "2", True):
        with pytest.raises(p.InputError, match="workers"):
            p.warm_up(workers=bad)


def test_import_leaves_the_optimizers_for_model_updating():
    # scipy.optimize is 0.3 s of a 0.8 s `import pounding` (a warm start is import + 0.3 s):
    # only identify and fit_contact_law need it, and import it when called
    code = "import sys, pounding; print('scipy.optimize' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_caches_of_changed_sources_are_cleared(tmp_path, monkeypatch):
    # Numba keys a cache to its own file: a kernel cached before a callee in another file (or
    # engine/_layout.py's indices) changed would load stale code, so _jit clears the caches
    # when any compiled source's size or time changed since they were written
    from pounding._jit import clear_stale_caches

    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    (tmp_path / "engine" / "__pycache__").mkdir(parents=True)
    source = tmp_path / "engine" / "_layout.py"
    source.write_text("P_X = 1\n")
    cache = tmp_path / "engine" / "__pycache__" / "_kernel.run_kernel-1.py311.nbi"
    cache.write_bytes(b"index")
    assert clear_stale_caches(tmp_path) and not cache.exists()  # no stamp yet: cleared
    cache.write_bytes(b"index")
    assert not clear_stale_caches(tmp_path) and cache.exists()  # nothing changed: kept
    source.write_text("P_X = 2\n")
    os.utime(source, ns=(source.stat().st_atime_ns, source.stat().st_mtime_ns + 10**9))
    assert clear_stale_caches(tmp_path) and not cache.exists()  # a source changed: cleared
    (tmp_path / "cli.py").write_text("x = 1\n")  # not compiled code: the caches stay
    cache.write_bytes(b"index")
    assert not clear_stale_caches(tmp_path) and cache.exists()
