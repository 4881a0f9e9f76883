"""The ground's two components at the core's door: each dof moved by its own mix of them (the influence of
a system in the plane: x levels by the first, y levels by the second, rotations by neither).

* The closed form: under circularly polarised shaking a linear isotropic oscillator's steady orbit is a
  circle of radius A / sqrt((k/m - w^2)^2 + (c w/m)^2), to 1e-9.
* A linear body in plan, its stiffness off its centre of mass (x, y and the rotation coupled), under a record
  pair: the samples against scipy's exact first-order-hold response, and the energy ledger closing.
* Every nonlinear path (friction sticks, rigid stops held and chattering, a Bouc-Wen spring, stiff rings):
  a run whose dofs all move with the second component equals the run of that component alone on the first
  (the line's, plain path), to rounding; a run whose second column of influence meets no second component
  equals the line's too.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import signal

import pounding as pd_
from pounding import _control, _core
from pounding.engine.assembly import assemble
from pounding.engine.layout import L_INPUT
from pounding.engine.run_args import kernel_forcing
from pounding.engine.run_parts import EnergyLedger


def _with_influence(sy: _core.System, influence) -> _core.System:
    """``sy`` with the ground's components moving its dofs as ``influence`` (n, 2) says."""
    state = sy.__getstate__()
    state["infl"] = [float(x) for x in np.asarray(influence, dtype=float).reshape(-1)]
    out = _core.System.__new__(_core.System)
    out.__setstate__(state)
    return out


def _run(sy, forcing, state0, t_end, sample_dt=0.02):
    return _core.run(sy, forcing, np.array(state0, dtype=float), t_end, sample_dt, 1e-10, 10**6, True,
                     _control.new_control(10**10))


def _plane_oscillator(m, k, c, with_elements):
    """One mass moving in x (dof 0) and y (dof 1) on a linear isotropic spring and dashpot: as the linear
    springs of the system, or as an elastic isolator element on each axis."""
    if with_elements:
        elements = [_core.element(i=i, j=-1, c_d=c, slopes=[k], breaks=[], rule=1) for i in (0, 1)]
        k0 = c0 = np.zeros((2, 2))
    else:
        elements, k0, c0 = [], k * np.eye(2), c * np.eye(2)
    return _core.system([m, m], k0, c0, elements, False, [],
                        influence=np.eye(2))


@pytest.mark.parametrize("with_elements", [False, True])
@pytest.mark.parametrize("m, k, c, amp, w", [(2.0, 80.0, 1.5, 0.7, 4.1), (1.0e4, 4.0e5, 0.0, 1.2, 9.0),
                                             (3.0, 30.0, 4.0, 0.2, 3.0)])
def test_circular_shaking_gives_the_closed_form_circle(with_elements, m, k, c, amp, w):
    # a_x = A cos(w t), a_y = A sin(w t): z = x + i y obeys z'' + (c/m) z' + (k/m) z = -A e^(i w t), whose
    # steady orbit is z = -A e^(i w t) / (k/m - w^2 + i c w/m), a circle of the closed-form radius
    sy = _plane_oscillator(m, k, c, with_elements)
    den = complex(k / m - w * w, c * w / m)
    z0 = -amp / den
    radius = amp / abs(den)
    state0 = np.zeros(sy.state_size)
    lay = sy.layout
    state0[lay["x"]:lay["x"] + 2] = z0.real, z0.imag
    v0 = 1j * w * z0
    state0[lay["v"]:lay["v"] + 2] = v0.real, v0.imag
    forcing = _core.Forcing(kind=_core.EXCITATION["harmonic"], p=np.array([amp, w, np.pi / 2, amp, 0.0]),
                            rec_t=np.zeros(1), rec_a=np.zeros(1))
    period = 2 * np.pi / w
    out = _run(sy, forcing, state0, 6 * period, period / 50)
    x, y = out.samples[:, 1], out.samples[:, 2]
    assert out.samples.shape[0] > 250
    np.testing.assert_allclose(np.hypot(x, y), radius, rtol=1e-9, atol=0)
    # (and where on the circle: the closed form's point at every sample)
    z = -amp * np.exp(1j * w * out.samples[:, 0]) / den
    np.testing.assert_allclose(x + 1j * y, z, rtol=0, atol=1e-9 * radius)
    # the absolute accelerations are the table's and the relative ones together: k z + c z' balance them
    acc = out.samples[:, 5] + 1j * out.samples[:, 6]
    vel = out.samples[:, 3] + 1j * out.samples[:, 4]
    np.testing.assert_allclose(m * acc, -(k * (x + 1j * y) + c * vel), rtol=0, atol=1e-9 * k * radius)


def _plan_body():
    """A rigid floor in plan (x, y, rotation) on four springs off its centre of mass, with Rayleigh damping:
    its stiffness couples the rotation with both translations."""
    m, j = 2.0e4, 2.0e4 * (12.0**2 + 8.0**2) / 12.0
    springs = [((1.0, 0.0), (2.0, 4.0), 6.0e6), ((1.0, 0.0), (-1.5, -4.0), 4.0e6),
               ((0.0, 1.0), (6.0, 0.5), 5.0e6), ((0.0, 1.0), (-6.0, -1.0), 3.5e6)]
    k = np.zeros((3, 3))
    for (cx, cy), (px, py), ks in springs:
        d = np.array([cx, cy, cy * px - cx * py])  # (the spring's stretch per unit x, y and rotation)
        k += ks * np.outer(d, d)
    mass = np.array([m, m, j])
    c = 0.04 * np.diag(mass) + 0.002 * k
    return mass, k, c


def test_a_linear_body_in_plan_matches_the_exact_first_order_hold():
    mass, k, c = _plan_body()
    sy = _core.system(mass, k, c, [], False, [],
                      influence=np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]))
    rng = np.random.default_rng(12)
    dt = 0.01
    t = np.arange(0.0, 6.0 + dt / 2, dt)
    ax, ay = (np.convolve(rng.normal(0.0, 3.0, t.size), np.ones(5) / 5, "same") for _ in range(2))
    forcing = _core.Forcing(kind=_core.EXCITATION["record"], p=np.array([dt, 0.0, 0.0]), rec_t=t, rec_a=ax,
                            rec_b=ay)
    out = _run(sy, forcing, np.zeros(sy.state_size), t[-1], dt)
    # the same system as a state space, its input the pair linear between samples (scipy's lsim: exact)
    minv = np.diag(1.0 / mass)
    a = np.block([[np.zeros((3, 3)), np.eye(3)], [-minv @ k, -minv @ c]])
    b = np.vstack([np.zeros((3, 2)), -np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]])])
    _, _, states = signal.lsim((a, b, np.eye(6), np.zeros((6, 2))), np.column_stack([ax, ay]), t,
                               interp=True)
    got = out.samples[:, 1:7]
    assert np.allclose(out.samples[:, 0], t, rtol=0, atol=1e-12)
    scale = np.max(np.abs(states), axis=0)
    assert scale[2] > 1e-3 * scale[0]  # (the rotation is no bystander)
    np.testing.assert_allclose(got, states, rtol=0, atol=1e-8 * scale.max())
    for q in range(6):
        np.testing.assert_allclose(got[:, q], states[:, q], rtol=0, atol=1e-7 * scale[q])
    e = EnergyLedger.of(out.ledger)
    assert out.ledger[L_INPUT] != 0.0
    assert abs(e.residual) <= 1e-9 * max(abs(e.input_work), e.viscous, e.kinetic)


def _swap_forcing(forcing: _core.Forcing, rng) -> _core.Forcing:
    """``forcing`` as the second component of a pair, beside an unrelated first."""
    if forcing.kind == _core.EXCITATION["harmonic"]:
        amp, w, phase = forcing.p[:3]
        return _core.Forcing(kind=forcing.kind, p=np.array([3.0 * amp, w, 1.1, amp, phase]),
                             rec_t=forcing.rec_t, rec_a=forcing.rec_a)
    other = rng.normal(0.0, 2.0 * np.std(forcing.rec_a), forcing.rec_a.size)
    return _core.Forcing(kind=forcing.kind, p=forcing.p, rec_t=forcing.rec_t, rec_a=other,
                         rec_b=forcing.rec_a)


def _systems():
    rigid = pd_.RigidStop(0.6)
    kv = pd_.KelvinVoigt(2.0e8, 1.0e5)
    bilinear = pd_.Isolator(slopes_n_m=[4.0e6, 1.0e6], breakpoints_m=[0.02], damping_n_s_m=2.0e4)
    storeys = [pd_.Storey(2.0e4, 4.0e7, 4.0e4)] * 2
    bw = pd_.Isolator([1.0e6], [], damping_n_s_m=1.0e4, bouc_wen=pd_.BoucWen(3.0e6, 0.01))
    return {
        "rigid moat": pd_.Structure(3.0e4, bilinear, storeys, walls=[pd_.Wall(0, 0.03, 0.025, rigid)]),
        "friction": pd_.Structure(3.0e4, pd_.FrictionIsolator(0.06, radius_m=2.2), storeys,
                                  walls=[pd_.Wall(0, 0.05, 0.05, kv)]),
        "bouc-wen": pd_.Structure(3.0e4, bw, storeys, walls=[pd_.Wall(0, 0.02, 0.02, pd_.HuntCrossley(
            5.0e8, 1.5, 0.4))]),
        "triple pendulum": pd_.Structure(3.0e4, pd_.TripleFrictionPendulum(
            radii_m=(2.1, 0.3, 0.3, 2.1), mu=(0.05, 0.02, 0.02, 0.08), capacities_m=(0.35, 0.05, 0.05, 0.35)),
            storeys),
        "single mass": pd_.presets.paper_damped(),
    }


def _same_run(a, b, n, scale_x, chatters):
    """Two runs the same to rounding: their end states, extrema and energies; their events too, but where a
    rigid stop chatters (the count of a chatter's impacts, and whether a yield at one of them is met first,
    go by rounding)."""
    assert a.status == b.status == 0
    if not chatters:
        assert a.events.shape == b.events.shape
        np.testing.assert_array_equal(a.events[:, 1:], b.events[:, 1:])
        np.testing.assert_allclose(a.events[:, 0], b.events[:, 0], rtol=0, atol=1e-9)
        assert a.contacts.shape == b.contacts.shape
        np.testing.assert_allclose(a.contacts[:, 1:3], b.contacts[:, 1:3], rtol=0, atol=1e-9)
        # the history: displacements, velocities and absolute accelerations (the table's and the relative)
        assert a.samples.shape == b.samples.shape
        for q, size in ((1, scale_x), (1 + n, None), (1 + 2 * n, None)):
            got, want = a.samples[:, q:q + n], b.samples[:, q:q + n]
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * (size or np.max(np.abs(want))))
    assert a.chatters.shape == b.chatters.shape
    # (a chatter's first impact and its accumulation, from the local model of the push's rates in time: the
    # same to 4e-15 s here, 2e-11 s off with the second component's rates left out of that model)
    np.testing.assert_allclose(a.chatters[:, 1:3], b.chatters[:, 1:3], rtol=0, atol=1e-12)
    # (x and v at the end)
    np.testing.assert_allclose(a.state[1:1 + n], b.state[1:1 + n], rtol=0, atol=1e-9 * scale_x)
    np.testing.assert_allclose(a.state[1 + n:1 + 2 * n], b.state[1 + n:1 + 2 * n], rtol=1e-7,
                               atol=1e-9 * scale_x)  # (v, m/s: scale_x over 1 s is far below any here)
    pa, pb = a.per_dof(n), b.per_dof(n)
    for col in (0, 2):  # (the displacements' extrema)
        np.testing.assert_allclose(pa[:, col], pb[:, col], rtol=0, atol=1e-9 * scale_x)
    np.testing.assert_allclose(pa[:, 4], pb[:, 4], rtol=1e-7)  # (the absolute accelerations' largest)
    for name in ("input_work", "viscous", "hysteretic", "contact_dissipation"):
        ea, eb = getattr(EnergyLedger.of(a.ledger), name), getattr(EnergyLedger.of(b.ledger), name)
        assert abs(ea - eb) <= 1e-7 * max(abs(ea), abs(eb), 1e-30), name


@pytest.mark.parametrize("name", list(_systems()))
@pytest.mark.parametrize("excitation", ["harmonic", "record"])
def test_a_second_component_on_every_dof_is_the_line_under_it(name, excitation):
    model = _systems()[name]
    rng = np.random.default_rng(5)
    if excitation == "harmonic":
        exc = pd_.Harmonic(a_g=0.35, freq_hz=1.3)
    else:
        t = np.arange(0.0, 4.0, 0.01)
        exc = pd_.Record(t, np.convolve(rng.normal(0.0, 4.0, t.size), np.ones(4) / 4, "same"))
    sy = assemble(model).system
    assert sy.plain
    n = sy.n
    line = kernel_forcing(exc)
    state0 = pd_.State.at_rest(model).vector
    plain = _run(sy, line, state0, 4.0)
    assert plain.events.shape[0] > 3  # (something happens: the nonlinear paths are taken)
    scale_x = np.max(np.abs(plain.per_dof(n)[:, [0, 2]]))
    chatters = len(plain.chatters) > 0
    # every dof moved by the second component alone, the first an unrelated motion
    swapped = _run(_with_influence(sy, np.tile([0.0, 1.0], (n, 1))), _swap_forcing(line, rng), state0, 4.0)
    assert not _with_influence(sy, np.tile([0.0, 1.0], (n, 1))).plain
    _same_run(plain, swapped, n, scale_x, chatters)
    # a second column of influence with no second component: the line's motion, by the general path
    alone = _run(_with_influence(sy, np.tile([1.0, 0.7], (n, 1))), line, state0, 4.0)
    _same_run(plain, alone, n, scale_x, chatters)


@pytest.mark.parametrize("influence, p", [
    ([[1.0, 0.0], [-0.5, 0.0]], [2.0, 4.4, np.pi + 0.3]),
    ([[1.0, 0.0], [0.0, 1.0]], [2.0, 4.4, np.pi + 0.3, 1.0, 0.3]),
    ([[1.0, 0.2], [0.1, 1.0]], [2.0, 4.4, np.pi + 0.3, 1.0, 0.3])])
def test_a_held_pair_moved_by_different_tables_has_each_dof_s_own_acceleration_extrema(influence, p):
    # two masses held together by a rigid stop between them (a group not on the ground), each moved by its
    # own mix of the components: while held, each dof's absolute acceleration is the group's relative one
    # plus its own table, and the exact extrema are the crests of that (a review found them the group's mean
    # table's: up to 5 % below the finely sampled peak)
    stop = _core.contact_slot(i=0, j=1, sign=1.0, gap_m=1e-9, law=_core.LAW_IDS["rigid"], params=[0.0] * 10)
    sy = _core.system([1.0, 3.0], np.diag([4.0, 2.0]), np.diag([0.05, 0.05]), [], True, [stop],
                      influence=np.array(influence))
    forcing = _core.Forcing(kind=_core.EXCITATION["harmonic"], p=np.array(p), rec_t=np.zeros(1),
                            rec_a=np.zeros(1))
    out = _run(sy, forcing, np.zeros(sy.state_size), 3.0, 1e-4)
    held = np.abs(out.samples[:, 1] - out.samples[:, 2] - 1e-9) < 1e-12
    assert held.mean() > 0.1
    sampled = np.max(np.abs(out.samples[:, 5:7]), axis=0)
    crest = np.argmax(np.abs(out.samples[:, 5:7]), axis=0)
    assert held[crest].all()  # (the peaks fall while held)
    exact = out.per_dof(2)[:, 4]
    assert np.all(exact >= sampled * (1 - 1e-12))
    np.testing.assert_allclose(exact, sampled, rtol=1e-6)  # (samples 0.1 ms apart round a crest by ~1e-8)


def test_the_door_refuses_a_second_component_it_cannot_place():
    sy = _plane_oscillator(2.0, 80.0, 1.5, False)
    state0 = np.zeros(sy.state_size)
    harmonic, record = _core.EXCITATION["harmonic"], _core.EXCITATION["record"]
    t = np.linspace(0.0, 1.0, 11)
    none = {"rec_t": np.zeros(1), "rec_a": np.zeros(1)}
    bad = [dict(kind=harmonic, p=np.array([1.0, 2.0, 0.0, 1.0]), **none),
           dict(kind=harmonic, p=np.array([1.0, 2.0, 0.0]), rec_b=np.zeros(1), **none),
           dict(kind=record, p=np.array([0.1, 0.0, 0.0]), rec_t=t, rec_a=np.zeros(11), rec_b=np.zeros(10)),
           dict(kind=record, p=np.array([0.1, 0.0, 0.0, 1.0, 0.0]), rec_t=t, rec_a=np.zeros(11)),
           dict(kind=7, p=np.array([1.0, 2.0, 0.0]), **none)]
    for numbers in bad:  # (refused as the forcing is made, once for every run that takes it)
        with pytest.raises(ValueError, match="rec_b"):
            _core.Forcing(**numbers)
    good = _core.Forcing(kind=harmonic, p=[1.0, 2.0, 0.0], **none)  # (its arrays made contiguous float64)
    assert good.p.dtype == np.float64 and good.p.flags.c_contiguous and good.rec_b.size == 0
    assert _run(sy, good, state0, 1.0).status == _core.STATUS["SUCCESS"]
    with pytest.raises(ValueError, match="influence"):
        _core.system([1.0, 1.0], np.eye(2), np.zeros((2, 2)), [], False,
                     [], influence=np.ones((2, 3)))
    state = sy.__getstate__()
    state["infl"] = [1.0, 0.0, 0.0]  # (not 2 n values: refused, not read as a line's table)
    with pytest.raises(ValueError, match="infl"):
        _core.System.__new__(_core.System).__setstate__(state)
    with pytest.raises(ValueError, match="second"):  # (a harmonic of one component: the monodromy, a step)
        _core.monodromy(sy, state0, np.zeros((0, 3)), 1.0, 2.0, 1.0, 0.0)
