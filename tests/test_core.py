"""The compiled core's door (pounding._core): what Python and C++ declare side by side agrees, a system
travels to other processes, and a run releases the GIL and stops when asked."""

from __future__ import annotations

import pickle
import threading

import numpy as np
import pytest

import pounding as pd_
from pounding import _control, _core
from pounding._errors import Status
from pounding.engine import layout
from pounding.engine.simulate import kernel_forcing, kernel_system
from pounding.model import contact_laws


def test_every_law_has_the_id_the_core_gives_it():
    laws = {
        "kelvin_voigt": pd_.KelvinVoigt(1e5, 10.0),
        "hunt_crossley": pd_.HuntCrossley(1e6, 1.5, 0.3),
        "jankowski": pd_.Jankowski(1e6, 0.1, 100.0),
        "multilinear": pd_.MultilinearBumper((1e5, 1e4), (0.01,)),
        "elastic_plastic": pd_.ElasticPlastic(1e5, 1e4, 0.01),
        "hertzdamp": pd_.Hertzdamp(1e6, 0.5),
        "multilinear_kinematic": pd_.MultilinearBumper((1e5, 1e4), (0.01,), hysteresis="kinematic"),
        "rigid": pd_.RigidStop(0.7),
    }
    assert set(laws) == set(_core.LAW_IDS)  # (every law the core knows is checked here)
    for name, law in laws.items():
        assert law.LAW_ID == _core.LAW_IDS[name], name
    assert len(set(_core.LAW_IDS.values())) == len(_core.LAW_IDS)
    assert contact_laws.N_LAW_PARAMS == _core.LAYOUT["N_LAW_PARAMS"]
    for law in laws.values():
        assert law.params().shape == (contact_laws.N_LAW_PARAMS,)


def test_statuses_actions_and_the_control_array_agree_with_the_core():
    assert {s.name: int(s) for s in Status} == _core.STATUS
    assert [layout.EVENT_NAMES.index(k) for k in _core.ACTIONS] == list(_core.ACTIONS.values())
    assert sorted(_core.ACTIONS.values()) == list(range(len(_core.ACTIONS)))
    assert _control.CTL_LEN == _core.LAYOUT["CTL_LEN"]
    assert _control.CTL_SERIES == _core.LAYOUT["CTL_SERIES"]
    assert _control.CTL_AUDITED == _core.LAYOUT["CTL_AUDITED"]
    assert _control.CTL_ESCAPES == _core.LAYOUT["CTL_ESCAPES"]
    assert _control.CTL_WHOLE == _core.LAYOUT["CTL_WHOLE"]
    assert _control.CTL_OWN == _core.LAYOUT["CTL_OWN"]
    assert layout.LEDGER_LEN == layout.L_BUMPER + 1


def test_the_core_s_door_refuses_a_run_control_it_would_write_past():
    # the kernels write every slot of the control: one made for an older core (4 slots), of another type or
    # read-only is refused before the call, naming the control and its maker
    from pounding._control import new_control

    osc = pd_.presets.paper_damped()
    sy, forcing = kernel_system(osc), kernel_forcing(pd_.Harmonic(0.1, 1.0))
    y0 = np.array(pd_.State.at_rest(osc).vector)
    read_only = new_control(10**6)
    read_only.setflags(write=False)
    for ctl in (np.zeros(4, dtype=np.int64), new_control(10**6).astype(np.int32), read_only):
        with pytest.raises(ValueError, match="ctl: the run control.*new_control"):
            _core.run(sy, forcing, y0, 1.0, 0.0, 1e-10, 10**5, True, ctl)
    assert _core.run(sy, forcing, y0, 1.0, 0.0, 1e-10, 10**5, True, new_control(10**6)).status == 0


def test_a_system_pickles_and_runs_the_same_after():
    osc = pd_.presets.paper_damped()
    sy = kernel_system(osc)
    back = pickle.loads(pickle.dumps(sy))
    fo = kernel_forcing(pd_.Harmonic(0.1, 2.0))
    state = pd_.State.at_rest(osc).vector
    runs = [_core.run(s, fo, state.copy(), 3.0, 0.01, 1e-10, 10**6, True, _control.new_control(10**9))
            for s in (sy, back)]
    for name in ("state", "samples", "contacts", "events", "ledger", "extrema", "chatters"):
        np.testing.assert_array_equal(getattr(runs[0], name), getattr(runs[1], name))
    assert runs[0].status == runs[1].status == Status.SUCCESS


def test_a_run_releases_the_gil_and_stops_when_asked():
    # a run of a million simulated seconds on a helper thread: this thread sees its work counter grow
    # while it runs (impossible with the GIL held), then asks it to stop; it returns INTERRUPTED
    osc = pd_.presets.paper_damped()
    sy, fo = kernel_system(osc), kernel_forcing(pd_.Harmonic(0.1, 2.0))
    ctl = _control.new_control(10**12)
    box = {}

    def target():
        box["out"] = _core.run(sy, fo, pd_.State.at_rest(osc).vector, 1e6, -1.0, 1e-10, 10**12, False, ctl)

    worker = threading.Thread(target=target, daemon=True)
    worker.start()
    seen = 0
    while seen < 10_000 and worker.is_alive():  # (the run would take minutes: it is still going)
        seen = int(ctl[_control.CTL_WORK])
    assert seen >= 10_000, "the run held the GIL: its progress could not be watched"
    _control.request_stop([ctl])
    worker.join()
    assert box["out"].status == Status.INTERRUPTED
    assert 0 < box["out"].state[layout.T] < 1e6


def test_a_budget_stops_a_run_with_its_status():
    osc = pd_.presets.paper_damped()
    ctl = _control.new_control(500)
    out = _core.run(kernel_system(osc), kernel_forcing(pd_.Harmonic(0.1, 2.0)), pd_.State.at_rest(osc).vector,
                    1e3, -1.0, 1e-10, 10**9, False, ctl)
    assert out.status == Status.BUDGET and ctl[_control.CTL_WORK] <= 500


@pytest.mark.parametrize("n", [1, 2, 4, 9])
def test_the_core_matrix_exponential_matches_scipy(n):
    from scipy.linalg import expm

    rng = np.random.default_rng(n)
    for scale in (1e-3, 1.0, 30.0):
        a = scale * rng.standard_normal((n, n))
        np.testing.assert_allclose(_core.expm(a), expm(a), rtol=1e-12, atol=1e-14 * np.abs(expm(a)).max())


def test_the_door_names_what_a_run_returns_and_every_index_is_the_core_s():
    osc = pd_.presets.paper_damped()
    out = _core.run(kernel_system(osc), kernel_forcing(pd_.Harmonic(0.1, 2.0)), pd_.State.at_rest(osc).vector,
                    5.0, 0.0, 1e-10, 10**6, True, _control.new_control(10**9))
    with pytest.raises(TypeError):
        out[0]  # (fields, never positions)
    fields = {"state", "samples", "contacts", "events", "ledger", "extrema", "status", "chatters", "norms"}
    assert set(type(out).__slots__) == fields
    # every column and slot named once, each name on its own index
    for names, size in ((_core.CONTACT_COLUMNS, "CONTACT_COLS"), (_core.LEDGER, "LEDGER_LEN"),
                        (_core.DOF_EXTREMA, "DOF_EXTREMA"), (_core.PAIR_EXTREMA, "PAIR_EXTREMA"),
                        (_core.NORM_EXTREMA, "NORM_EXTREMA")):
        assert sorted(names.values()) == list(range(_core.LAYOUT[size])), (size, names)
    assert out.contacts.shape[1] == _core.LAYOUT["CONTACT_COLS"] and len(out.contacts) > 0
    # the named places are where the public run reads them
    run = pd_.simulate(osc, pd_.Harmonic(0.1, 2.0), 5.0)
    ex = out.per_dof(1)[0]
    assert (ex[_core.DOF_EXTREMA["d_max"]], ex[_core.DOF_EXTREMA["a_abs_max"]]) == (
        run.displacement_max, run.abs_acceleration_max)
    assert out.ledger[_core.LEDGER["input"]] == run.energy.input_work
    assert out.contacts[0, _core.CONTACT_COLUMNS["v_in_m_s"]] == run.contacts["v_in_m_s"].iloc[0]
    assert set(_core.EXCITATION) == {"harmonic", "record"}


def test_a_run_s_outputs_keep_their_shapes_with_and_without_rows():
    # (the core returns the fixed-size outputs as one array and a table without rows as None: the door
    # gives each its own array, a table without rows empty with its columns)
    osc = pd_.presets.paper_damped()
    sy, fo = kernel_system(osc), kernel_forcing(pd_.Harmonic(0.1, 2.0))
    rest = pd_.State.at_rest(osc).vector
    quiet = _core.run(sy, fo, rest, 0.01, -1.0, 1e-10, 10**6, True, _control.new_control(10**9))
    busy = _core.run(sy, fo, rest, 5.0, 0.01, 1e-10, 10**6, True, _control.new_control(10**9))
    cols = {"samples": sy.sample_cols, "contacts": _core.LAYOUT["CONTACT_COLS"],
            "events": _core.LAYOUT["EVENT_COLS"], "chatters": 5}
    for name, k in cols.items():
        assert getattr(quiet, name).shape == ((2, k) if name == "samples" else (0, k)), name  # (its ends)
        assert getattr(busy, name).shape[1] == k and getattr(busy, name).dtype == np.float64, name
    assert len(busy.samples) > 400 and len(busy.contacts) > 0 and len(busy.events) > 0
    for out in (quiet, busy):
        assert out.state.shape == (sy.state_size,) and out.ledger.shape == (_core.LAYOUT["LEDGER_LEN"],)
        assert out.extrema.shape == (sy.norm_extrema_at,) and out.norms.shape == (0, len(_core.NORM_EXTREMA))
    # (each part of the one array in its place: the public run's state, ledger and extrema, read apart)
    run = pd_.simulate(osc, pd_.Harmonic(0.1, 2.0), 5.0, sample_rate_hz=100.0)
    assert np.array_equal(busy.state, run.final_state.vector)
    assert busy.ledger[_core.LEDGER["input"]] == run.energy.input_work
    ex, at = busy.per_dof(1)[0], _core.DOF_EXTREMA
    assert (ex[at["d_max"]], ex[at["d_min"]], ex[at["a_abs_max"]]) == (
        run.displacement_max, run.displacement_min, run.abs_acceleration_max)


def test_a_system_goes_in_by_name_and_comes_back_from_a_pickle_by_name():
    slot = _core.contact_slot(i=0, j=-1, sign=1.0, gap_m=0.03, law=_core.LAW_IDS["hunt_crossley"],
                              params=[5e8, 1.5, 2e8])
    assert (slot.i, slot.j, slot.sign, slot.gap_m) == (0, -1, 1.0, 0.03)
    assert slot.params[:3] == [5e8, 1.5, 2e8] and len(slot.params) == _core.LAYOUT["N_LAW_PARAMS"]
    with pytest.raises(TypeError):  # (keywords only: never positions)
        _core.ContactSlot(0, -1, 1.0, 0.03, 1, [5e8])
    with pytest.raises(ValueError, match="at most"):  # (more parameters than a slot holds: refused, not cut)
        _core.contact_slot(i=0, j=-1, sign=1.0, gap_m=0.03, law=1, params=[1.0] * 11)
    iso = _core.element(i=0, j=-1, c_d=1000.0, slopes=[38e3, 2e3], breaks=[0.015], rule=0)
    sy = _core.system([500.0], np.zeros((1, 1)), np.zeros((1, 1)), [iso], True, [slot])
    back = pickle.loads(pickle.dumps(sy))
    assert back.__getstate__() == sy.__getstate__()
    named = {"n", "mass", "k0", "c0", "elements", "has_b", "contacts", "tracked", "infl", "norm_p", "norm_q",
             "norm_at"}
    assert set(sy.__getstate__()) == named
    before = {k: v for k, v in sy.__getstate__().items() if k != "norm_at"}  # (a pickle from before offsets)
    again = _core.System.__new__(_core.System)
    again.__setstate__(before)
    assert again.__getstate__() == sy.__getstate__()
    assert pickle.loads(pickle.dumps(slot)).gap_m == 0.03
    assert pickle.loads(pickle.dumps(iso)).breaks == [0.015]
    # a Bouc-Wen spring is an element's, and travels with it; a pickle from before (the system's, element
    # 0's) comes back as element 0's
    bw = [900.0, 0.004, 1.0, 0.5, 0.5, 1.0]
    with_bw = _core.element(i=0, j=-1, c_d=0.0, slopes=[1e3], breaks=[], rule=1, bw=bw)
    assert pickle.loads(pickle.dumps(with_bw)).bw == bw and iso.bw == [0.0] * 6
    old = sy.__getstate__() | {"bw": bw}
    again = _core.System.__new__(_core.System)
    again.__setstate__(old)
    assert again.__getstate__()["elements"][0]["bw"] == bw and again.layout["n_bouc_wen"] == 1
    with pytest.raises(ValueError, match="bw"):
        _core.element(i=0, j=-1, c_d=0.0, slopes=[1e3], breaks=[], rule=1, bw=[1.0, 0.0, 1.0, 0.5, 0.5, 1.0])
    # a bidirectional spring: two elements, each the other's mate, the same numbers; anything else refused
    def pair(mate_x, mate_y, bw_y=bw):
        return [_core.element(i=0, j=-1, c_d=0.0, slopes=[1e3], breaks=[], rule=1, bw=bw, bw_mate=mate_x),
                _core.element(i=1, j=-1, c_d=0.0, slopes=[1e3], breaks=[], rule=1, bw=bw_y, bw_mate=mate_y)]
    two = _core.system([500.0, 500.0], np.zeros((2, 2)), np.zeros((2, 2)), pair(1, 0), False, [])
    assert [e["bw_mate"] for e in pickle.loads(pickle.dumps(two)).__getstate__()["elements"]] == [1, 0]
    for bad in (pair(1, -1), pair(0, 1), pair(1, 0, [1.1e3, 0.004, 1.0, 0.5, 0.5, 1.0]), pair(2, 0)):
        with pytest.raises(ValueError, match="mate"):
            _core.system([500.0, 500.0], np.zeros((2, 2)), np.zeros((2, 2)), bad, False, [])
    with pytest.raises(ValueError, match="ContactSlot"):
        _core.system([500.0], np.zeros((1, 1)), np.zeros((1, 1)), [iso], True,
                     [(0, -1, 1.0, 0.03, 1, [5e8])])
