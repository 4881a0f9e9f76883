"""pounding.lyapunov: the exponents against closed forms (a linear isolator), against the exact
Floquet multipliers of periodic_orbit, against a two-trajectory estimate on a chaotic response,
finite differences against the exact tangent, and what users meet (bad input, Ctrl-C, files)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pounding as pd_
from pounding.engine.layout import DEF_L, DEF_R, IN_L, IN_R, D, V

# a soft impact oscillator (the literature's: a linear oscillator, zeta 0.02, striking a stop 30 times
# stiffer, here 5 mm away on one side): chaotic at a_G 0.1, 2.6 Hz
M, K, ZETA, BETA = 100.0, 4000.0, 0.02, 30.0
SOFT = pd_.Oscillator(
    mass_kg=M, isolator=pd_.Isolator(slopes_n_m=[K], damping_n_s_m=2.0 * ZETA * math.sqrt(K * M)),
    bumpers=pd_.Bumpers(gap_left_m=0.3, gap_right_m=0.005, law=pd_.KelvinVoigt(
        stiffness=BETA * K, damping=2.0 * ZETA * math.sqrt(BETA * K * M))))
CHAOS = pd_.Harmonic(0.1, 2.6)


@pytest.fixture(scope="module")
def chaotic():
    return pd_.lyapunov(SOFT, CHAOS, cycles=1000, transient_cycles=300)


@pytest.mark.parametrize("damping", [40.0, 400.0])
def test_linear_isolator_without_bumpers_has_both_exponents_minus_zeta_omega(damping):
    """x'' + 2 zeta omega x' + omega^2 x = -a(t): the flow contracts every direction at -zeta omega
    = -c / 2m; both exponents equal it to 1e-9, and so do the running estimates (the frame is
    measured in the isolator's own units, where the flow is a rotation)."""
    osc = pd_.Oscillator(mass_kg=100.0, isolator=pd_.Isolator(slopes_n_m=[4000.0], damping_n_s_m=damping))
    spec = pd_.lyapunov(osc, pd_.Harmonic(0.05, 1.3), cycles=40, transient_cycles=300)
    expected = -damping / 200.0
    assert spec.coordinates == ("x_0", "v_0") and spec.method == "exact" and spec.period == 1
    np.testing.assert_allclose(spec.exponents, [expected, expected], rtol=1e-9)
    np.testing.assert_allclose(spec.history[-1], [expected, expected], rtol=1e-9)
    assert spec.kaplan_yorke_dimension == 0.0 and not spec.chaotic


def test_impacting_periodic_orbit_largest_exponent_is_its_largest_multiplier():
    """The damped paper system at a_G 0.05, 1.5 Hz hits both bumpers every cycle: the largest
    exponent equals ln|mu_max| / T of periodic_orbit's exact multipliers to 1e-6, and the running
    estimate approaches it."""
    osc, exc = pd_.presets.paper_damped(), pd_.Harmonic(0.05, 1.5)
    orbit = pd_.periodic_orbit(osc, exc)
    assert orbit.stable and orbit.contacts_per_period == 2
    spec = pd_.lyapunov(osc, exc, cycles=300)
    expected = math.log(orbit.max_abs_multiplier) / orbit.period_s
    assert spec.period == 1 and spec.largest == pytest.approx(expected, rel=1e-6)
    assert spec.history[-1, 0] == pytest.approx(expected, rel=2e-2)
    # the touched compressions and the slip follow the mass: directions the map erases
    assert np.isneginf(spec.exponents[2:]).all() and "erased" in spec.message


def test_finite_differences_agree_with_the_exact_tangent():
    osc, exc = pd_.presets.paper_damped(), pd_.Harmonic(0.05, 1.5)
    exact = pd_.lyapunov(osc, exc, cycles=60)
    fd = pd_.lyapunov(osc, exc, cycles=60, method="finite-difference")
    assert fd.method == "finite-difference" and fd.period == 1
    assert fd.largest == pytest.approx(exact.largest, rel=1e-4)


def _two_trajectories(cycles: int, align: int, start: pd_.State) -> float:
    """Benettin's two-trajectory estimate of the largest exponent from the engine's own runs: a
    neighbour 1e-9 m/s away, its separation (in the isolator's units) measured and scaled back
    every period."""
    period = 1.0 / CHAOS.freq_hz
    wn = math.sqrt(K / M)
    wd = wn * math.sqrt(1.0 - ZETA**2)

    def advance(vec: np.ndarray) -> np.ndarray:
        run = pd_.simulate(SOFT, CHAOS, period, pd_.State(vec), sample_rate_hz=0)
        return np.array(run.final_state.vector)

    a = np.array(start.vector)
    b = a.copy()
    d0 = 1e-9
    b[V] += d0
    total = 0.0
    cont = [D, V, DEF_L, DEF_R]
    for c in range(align + cycles):
        a2, b2 = advance(a), advance(b)
        dx = b2 - a2
        dist = math.hypot(wd * dx[D], dx[V] + ZETA * wn * dx[D])
        if c >= align:
            total += math.log(dist / d0)
        assert a2[IN_L] == b2[IN_L] and a2[IN_R] == b2[IN_R]  # (the neighbour in the same mode)
        b = a2.copy()
        b[cont] = a2[cont] + d0 / dist * dx[cont]
        a = a2
    return total / (cycles * period)


def test_chaotic_response_largest_exponent_matches_two_trajectories(chaotic):
    """On the soft impact oscillator's chaotic response the largest exponent is positive and equals
    Benettin's two-trajectory estimate over the same periods within 3 % (measured: 0.03 %)."""
    assert chaotic.chaotic and chaotic.period == 0 and chaotic.largest > 0.3
    start = pd_.simulate(SOFT, CHAOS, 300 / CHAOS.freq_hz, sample_rate_hz=0).final_state
    assert chaotic.largest == pytest.approx(_two_trajectories(1000, 20, start), rel=0.03)
    # a dissipative flow: the exponents' sum is negative, the attractor between a curve and the plane
    assert chaotic.exponents[:2].sum() < 0.0 and 1.0 < chaotic.kaplan_yorke_dimension < 2.0


def test_kaplan_yorke_dimension_formula(chaotic):
    lam = chaotic.exponents
    assert chaotic.kaplan_yorke_dimension == pytest.approx(1.0 + lam[0] / abs(lam[1]), rel=1e-12)


def test_a_shorter_count_is_the_start_of_a_longer_one_and_continues_it():
    """The first 30 periods of a 60-period count are a 30-period count; the final state is where the
    count ended, and a count from it runs the long count's last 30 periods."""
    osc, exc = SOFT, CHAOS
    long = pd_.lyapunov(osc, exc, cycles=60, transient_cycles=50, align_cycles=0)
    first = pd_.lyapunov(osc, exc, cycles=30, transient_cycles=50, align_cycles=0)
    assert first.final_state.time_s == pytest.approx(80 / exc.freq_hz, rel=1e-12)
    np.testing.assert_allclose(long.history[29], first.history[-1], rtol=1e-12)
    second = pd_.lyapunov(osc, exc, cycles=30, transient_cycles=0, align_cycles=0, state=first.final_state)
    np.testing.assert_array_equal(second.final_state.vector, long.final_state.vector)


def test_bad_input_is_named():
    osc = pd_.presets.paper_damped()
    with pytest.raises(pd_.InputError, match="excitation"):
        pd_.lyapunov(osc, "1.5 Hz")
    with pytest.raises(pd_.InputError, match="cycles"):
        pd_.lyapunov(osc, pd_.Harmonic(0.05, 1.5), cycles=0)
    with pytest.raises(pd_.InputError, match="transient_cycles"):
        pd_.lyapunov(osc, pd_.Harmonic(0.05, 1.5), transient_cycles=-1)
    hertz = pd_.Oscillator(500.0, osc.isolator, pd_.Bumpers(0.015, 0.015, pd_.Hertzdamp(5e8, 0.8, 1.5)))
    with pytest.raises(pd_.InputError, match="method"):  # (a nonlinear contact law: no exact tangent)
        pd_.lyapunov(hertz, pd_.Harmonic(0.05, 1.5), method="exact")
    with pytest.raises(pd_.InputError, match="state"):
        pd_.lyapunov(osc, pd_.Harmonic(0.05, 1.5), state=[0.0, 0.0])


def _stop_at(call: int):
    calls = []

    def progress(n: int) -> None:
        calls.append(n)
        if len(calls) == call:
            raise KeyboardInterrupt

    return progress


def test_ctrl_c_keeps_the_periods_counted():
    """The progress counts the trajectory's 105 periods, then the tangent's: a Ctrl-C at the 130th
    keeps the 20 periods counted after the 5 that align the frame; one in the trajectory's pass
    stops at once, nothing counted."""
    with pytest.raises(pd_.Interrupted) as stop:
        pd_.lyapunov(SOFT, CHAOS, cycles=100, transient_cycles=20, align_cycles=5, progress=_stop_at(130))
    spec = stop.value.partial
    assert spec.status == pd_.Status.INTERRUPTED and spec.cycles == 20 and spec.history.shape == (20, 4)
    assert np.isfinite(spec.largest) and "interrupted: 20 of 100" in spec.message
    with pytest.raises(pd_.Interrupted) as stop:
        pd_.lyapunov(SOFT, CHAOS, cycles=100, transient_cycles=20, align_cycles=5, progress=_stop_at(30))
    assert stop.value.partial.cycles == 0 and np.isnan(stop.value.partial.largest)


def test_results_save_and_plot(tmp_path, chaotic):
    ds = chaotic.to_xarray()
    assert ds["exponent"].attrs["units"] == "1/s" and ds.sizes["cycle"] == 1000
    path = chaotic.to_netcdf(tmp_path / "lyap.nc")
    import xarray as xr

    with xr.open_dataset(path) as back:
        np.testing.assert_array_equal(back["exponent"].values, chaotic.exponents)
        assert back.attrs["kaplan_yorke_dimension"] == pytest.approx(chaotic.kaplan_yorke_dimension)
    artists = pd_.plots.plot_lyapunov(chaotic)
    assert len(artists) >= 2
    import matplotlib.pyplot as plt

    plt.close("all")


def test_diagram_largest_exponents_tell_chaos_from_periodic_steps():
    """On the soft impact oscillator's diagram the exponent is positive where no period is found
    (chaos at 2.6 Hz) and negative on the periodic steps; at a periodic step it is the orbit's
    ln|mu_max| / T (periodic_orbit)."""
    freqs = [2.0, 2.6]
    diagram = pd_.bifurcation_diagram(SOFT, 0.1, freqs, direction="up", transient_cycles=300,
                                      record_cycles=20)
    d = pd_.largest_exponents(diagram, cycles=300)
    lam = d.data["largest_exponent"].sel(direction="up").values
    period = d.data["period"].sel(direction="up").values
    assert period.tolist() == [1, 0] and lam[0] < 0.0 < lam[1]
    orbit = pd_.periodic_orbit(SOFT, pd_.Harmonic(0.1, 2.0), settle_cycles=300)
    assert lam[0] == pytest.approx(math.log(orbit.max_abs_multiplier) / orbit.period_s, rel=1e-6)
    assert "largest_exponent" in d.to_dataframe(cycles=False).columns
    with pytest.raises(pd_.InputError, match="diagram"):
        pd_.largest_exponents(pd_.Harmonic(0.1, 2.0))


def test_compiled_matrix_exponential_is_scipys():
    """The monodromy's compiled exponential (Padé, scaling and squaring) against scipy.linalg.expm:
    matrices of 2 to 9 rows whose 1-norm spans every degree's range (1e-3 to 40, so that 0 to 3
    squarings)."""
    from scipy.linalg import expm

    from pounding._core import expm as call

    rng = np.random.default_rng(7)
    for n in (2, 5, 9):
        for norm in (1e-3, 0.1, 0.5, 1.5, 4.0, 12.0, 40.0):
            a = rng.standard_normal((n, n))
            a *= norm / np.abs(a).sum(axis=0).max()
            want = expm(a)
            # (at norm 40 the exponential's own condition reaches 1e15: both algorithms' rounding shows)
            tol = 1e-15 if norm <= 1.5 else 2e-14 if norm <= 12.0 else 1e-12
            np.testing.assert_allclose(call(a), want, rtol=0, atol=tol * np.abs(want).max())


def test_command_line_writes_the_estimates_and_refuses_bad_input(tmp_path):
    from typer.testing import CliRunner

    from pounding.cli import app

    out, nc = tmp_path / "lyap.csv", tmp_path / "lyap.nc"
    res = CliRunner().invoke(app, ["lyapunov", "--preset", "paper-damped", "--a-g", "0.05", "--freq", "1.5",
                                   "--cycles", "50", "--out", str(out), "--netcdf", str(nc)])
    assert res.exit_code == 0, res.output
    assert "periodic (period 1)" in res.output and "lambda_1" in res.output
    import pandas as pd

    table = pd.read_csv(out)
    assert list(table.columns[:3]) == ["cycle", "lambda_1_1_s", "lambda_2_1_s"] and len(table) == 50
    assert nc.is_file()
    bad = CliRunner().invoke(app, ["lyapunov", "--preset", "paper-damped", "--a-g", "0.05", "--freq", "1.5",
                                   "--cycles", "0"])
    assert bad.exit_code == 2 and "cycles" in bad.output


def test_compiled_exponential_keeps_its_digits_on_a_stiff_contact():
    """A contact phase of a stiff bumper (k / m = 1e7 1/s^2, zeta 0.02) over 1 ms: the compiled
    exponential (balanced first) against the damped oscillator's closed form, to 1e-13."""
    from pounding._core import expm as call

    for k_m in (1e3, 1.2e5, 1e7):
        w = math.sqrt(k_m)
        zeta, tau = 0.02, 1e-3
        wd = w * math.sqrt(1.0 - zeta**2)
        a = np.array([[0.0, 1.0], [-k_m, -2.0 * zeta * w]]) * tau
        e, s, c = math.exp(-zeta * w * tau), math.sin(wd * tau), math.cos(wd * tau)
        want = e * np.array([[c + zeta * w / wd * s, s / wd], [-w * w / wd * s, c - zeta * w / wd * s]])
        np.testing.assert_allclose(call(a), want, rtol=0, atol=1e-13 * np.abs(want).max())


def test_not_chaotic_where_the_largest_exponent_is_zero():
    """An undamped linear isolator: both exponents are 0 (a rotation), estimated at the rounding's
    level; neither chaos nor a dimension."""
    osc = pd_.Oscillator(mass_kg=100.0, isolator=pd_.Isolator(slopes_n_m=[4000.0], damping_n_s_m=0.0))
    spec = pd_.lyapunov(osc, pd_.Harmonic(0.05, 1.3), cycles=200, transient_cycles=0)
    assert abs(spec.largest) < 1e-12 and not spec.chaotic


def test_the_metric_makes_each_mode_a_rotation_and_a_decay():
    """The tangent metric W: one mass's is its isolator's own units, (omega_d x, v + zeta omega_n x); a
    critically damped one's (omega_n x, v); a building's makes W A W^-1 block diagonal, each block
    [[sigma, omega], [-omega, sigma]] of one mode, scaled so that its largest displacement is 1 / omega with
    no phase (so that what LAPACK returns does not reach the estimates)."""
    from pounding.analysis.lyapunov import _modal_metric

    m, k, c = 100.0, 4000.0, 40.0
    wn = math.sqrt(k / m)
    zeta = c / (2.0 * m * wn)
    a = np.array([[0.0, 1.0], [-k / m, -c / m]])
    np.testing.assert_allclose(_modal_metric(a, 2, False), [[wn * math.sqrt(1.0 - zeta**2), 0.0],
                                                            [zeta * wn, 1.0]], rtol=1e-12, atol=1e-12)
    critical = np.array([[0.0, 1.0], [-k / m, -2.0 * wn]])
    np.testing.assert_allclose(_modal_metric(critical, 3, True), np.diag([wn, 1.0, wn * 1e-3]), rtol=1e-12)
    rng = np.random.default_rng(7)
    n = 3
    masses = rng.uniform(1e3, 3e3, n)
    springs = rng.uniform(1e6, 5e6, n)
    kk = np.diag(springs + np.append(springs[1:], 0.0)) - np.diag(springs[1:], 1) - np.diag(springs[1:], -1)
    cc = 0.02 * kk / 50.0 + 0.1 * np.diag(masses)
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-kk / masses[:, None], -cc / masses[:, None]]])
    w = _modal_metric(a, 2 * n + 1, False)
    b = w[:2 * n, :2 * n] @ a @ np.linalg.inv(w[:2 * n, :2 * n])
    t = np.linalg.inv(w[:2 * n, :2 * n])
    scale = np.abs(a).max()
    for j in range(n):
        block = b[2 * j:2 * j + 2, 2 * j:2 * j + 2]
        sigma, omega = block[0, 0], block[0, 1]
        np.testing.assert_allclose(block, [[sigma, omega], [-omega, sigma]], atol=1e-9 * scale)
        assert sigma < 0.0 < omega
        rest = np.delete(b[2 * j:2 * j + 2], [2 * j, 2 * j + 1], axis=1)
        np.testing.assert_allclose(rest, 0.0, atol=1e-9 * scale)
        v = t[:n, 2 * j] + 1j * t[:n, 2 * j + 1]
        p = int(np.argmax(np.abs(v)))
        assert v[p].real == pytest.approx(1.0 / omega, rel=1e-9) and abs(v[p].imag) <= 1e-12 * abs(v[p].real)
    assert w[-1, -1] == pytest.approx(np.abs(np.linalg.eigvals(a)).min(), rel=1e-12)
