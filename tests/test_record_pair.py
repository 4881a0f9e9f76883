"""Pairs of ground-motion components (RecordPair) and their RotD spectra: each direction's peak against
the one-component exact spectrum of the motion along it, closed forms, invariance to a rotation of the pair,
the inputs refused, the FEMA P695 pairs and the command line."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

import pounding as pd_

ROOT = Path(__file__).parents[1]
PERIODS = [0.0, 0.05, 0.2, 0.5, 1.0, 2.0, 4.0]


def _pair(seed: int = 0, n: int = 800) -> pd_.RecordPair:
    """Two random components (a few hundredths of g to about 0.4 g), 0.01 s apart."""
    rng = np.random.default_rng(seed)
    t = 0.01 * np.arange(n)
    envelope = np.sin(np.pi * t / t[-1]) ** 2
    x = envelope * np.convolve(rng.normal(0.0, 0.15, n), np.ones(5) / 5, mode="same")
    y = envelope * np.convolve(rng.normal(0.0, 0.10, n), np.ones(3) / 3, mode="same")
    return pd_.RecordPair(pd_.Record.from_g(t, x, name="a"), pd_.Record.from_g(t, y, name="b"))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10_000), zeta=st.sampled_from([0.0, 0.02, 0.05, 0.2]),
       step=st.sampled_from([1.0, 7.5, 15.0, 90.0]))
def test_each_direction_s_peak_is_the_exact_spectrum_of_the_motion_along_it(seed, zeta, step):
    """Along every direction, the pair kernel's peak displacement equals response_spectrum's (the one-
    component exact kernel, peaks between samples found) of pair.along(angle), to 1e-12 relative or 1e-13
    of the quasi-static displacement a_max / omega^2 (the closed form's particular solution, from which
    both subtract as much: the pair kernel combines the components' coefficients, the other the combined
    record's); the rigid period's the peak acceleration along it."""
    pair = _pair(seed)
    spec = pd_.rotd_spectrum(pair, PERIODS, zeta, angle_step_deg=step)
    periods = np.array(PERIODS)
    omega = 2.0 * np.pi / np.where(periods > 0.0, periods, 1.0)
    quasi_static = np.where(periods > 0.0, max(np.abs(pair.x.accel).max(), np.abs(pair.y.accel).max())
                            / omega ** 2, 0.0)
    for angle in spec["angle_deg"].values:
        one = pd_.response_spectrum(pair.along(float(angle)), PERIODS, zeta)
        mine, theirs = spec["sd_m"].sel(angle_deg=angle).values[0], one["sd_m"].values[0]
        assert np.all(np.abs(mine - theirs) <= 1e-12 * theirs + 1e-13 * quasi_static), (angle, mine - theirs)
        assert spec["psa_g"].sel(angle_deg=angle).values[0, 0] == pytest.approx(one["psa_g"].values[0, 0],
                                                                                 rel=1e-12)


def test_closed_forms_one_component_and_twin_components():
    """y = 0: each direction's peak is |cos a| times the x spectrum (RotD100 the x spectrum at 0 degrees,
    RotD50 the median of |cos a| times it); y = x: RotD100 is sqrt(2) times x's, at 45 degrees, RotD50 x's
    own (the median of sqrt(2) |sin(a + 45)|)."""
    quake = pd_.records.el_centro()
    still = quake._derived(np.zeros_like(quake.accel), {})
    one = pd_.response_spectrum(quake, PERIODS)
    alone = pd_.rotd_spectrum(pd_.RecordPair(quake, still), PERIODS)
    cosines = np.abs(np.cos(np.radians(alone["angle_deg"].values)))
    np.testing.assert_allclose(alone["sd_m"].values[0], np.outer(one["sd_m"].values[0], cosines), rtol=1e-12,
                               atol=1e-18)
    np.testing.assert_allclose(alone["rotd100_psa_g"].values[0], one["psa_g"].values[0], rtol=1e-12)
    np.testing.assert_allclose(alone["rotd50_psa_g"].values[0], np.median(cosines) * one["psa_g"].values[0],
                               rtol=1e-12)
    assert (alone["rotd100_angle_deg"].values == 0.0).all()
    twins = pd_.rotd_spectrum(pd_.RecordPair(quake, quake), PERIODS)
    np.testing.assert_allclose(twins["rotd100_psa_g"].values[0], math.sqrt(2.0) * one["psa_g"].values[0],
                               rtol=1e-12)
    assert (twins["rotd100_angle_deg"].values == 45.0).all()
    sines = math.sqrt(2.0) * np.abs(np.sin(np.radians(twins["angle_deg"].values + 45.0)))
    np.testing.assert_allclose(twins["rotd50_psa_g"].values[0], np.median(sines) * one["psa_g"].values[0],
                               rtol=1e-12)
    assert twins["peak_vector_g"].values[0] == pytest.approx(math.sqrt(2.0) * quake.pga_g, rel=1e-12)


def test_rotd_does_not_depend_on_how_the_pair_is_turned():
    """The pair turned by 30 degrees: each direction's peak is the original's 30 degrees on (a direction
    and its opposite have one peak), so RotD50 and RotD100 are the same, to 1e-12."""
    pair = _pair(3)
    spec = pd_.rotd_spectrum(pair, PERIODS)
    turned = pd_.rotd_spectrum(pair.rotated(30.0), PERIODS)
    np.testing.assert_allclose(turned["sd_m"].values[0], np.roll(spec["sd_m"].values[0], -30, axis=1),
                               rtol=1e-12, atol=1e-18)
    for name in ("rotd50_psa_g", "rotd100_psa_g"):
        np.testing.assert_allclose(turned[name].values, spec[name].values, rtol=1e-12)


def test_a_pair_turns_projects_and_scales():
    pair = _pair(1)
    np.testing.assert_array_equal(pair.along(0.0).accel, pair.x.accel)
    np.testing.assert_allclose(pair.along(90.0).accel, pair.y.accel, atol=1e-15)
    np.testing.assert_allclose(pair.rotated(90.0).x.accel, pair.y.accel, atol=1e-15)
    np.testing.assert_allclose(pair.rotated(90.0).y.accel, -pair.x.accel, atol=1e-15)
    twice = pair.rotated(20.0).rotated(25.0)
    np.testing.assert_allclose(twice.x.accel, pair.rotated(45.0).x.accel, atol=1e-15)
    assert twice.meta["rotation_deg"] == 45.0
    double = pair.scaled(2.0)
    np.testing.assert_array_equal(double.y.accel, 2.0 * pair.y.accel)
    assert double.meta["scale_factor"] == 2.0 and double.pga_g == pytest.approx(
        (2 * pair.pga_g[0], 2 * pair.pga_g[1]))
    assert repr(pair).startswith("RecordPair('a / b', n=800")
    frame = pair.to_dataframe()
    assert list(frame.columns) == ["time_s", "accel_x_m_s2", "accel_y_m_s2"] and len(frame) == 800
    assert pair.to_xarray().sizes["sample"] == 800


def test_a_shorter_component_is_at_rest_after_its_end():
    x = pd_.Record.from_g(0.01 * np.arange(6), [0.0, 0.1, -0.1, 0.2, 0.0, 0.1])
    y = pd_.Record.from_g(0.01 * np.arange(4), [0.0, 0.05, 0.1, 0.0])
    pair = pd_.RecordPair(x, y)
    assert pair.y.t.size == 6 and np.array_equal(pair.y.t, pair.x.t)
    np.testing.assert_array_equal(pair.y.accel[4:], 0.0)


def test_a_pair_that_is_none_is_refused_by_name():
    quake = pd_.records.el_centro()
    with pytest.raises(pd_.InputError) as err:
        pd_.RecordPair(quake, "north")
    assert err.value.field == "pair.y"
    other_g = pd_.Record(quake.t, quake.accel, g=9.80665)
    with pytest.raises(pd_.InputError, match="one g") as err:
        pd_.RecordPair(quake, other_g)
    slower = pd_.Record(2 * quake.t, quake.accel)
    with pytest.raises(pd_.InputError, match="resample") as err:
        pd_.RecordPair(quake, slower)
    assert err.value.field == "pair.y.t"
    pair = pd_.RecordPair(quake, quake)
    for bad in (0.0, 7.0, 120.0, math.nan):
        with pytest.raises(pd_.InputError) as err:
            pd_.rotd_spectrum(pair, [1.0], angle_step_deg=bad)
        assert err.value.field == "angle_step_deg"
    with pytest.raises(pd_.InputError) as err:
        pd_.rotd_spectrum([pair, quake], [1.0])
    assert err.value.field == "pairs[1]"
    with pytest.raises(pd_.InputError, match="more than the most allowed"):
        pd_.rotd_spectrum(pair, np.linspace(0.01, 10.0, 100_000))
    with pytest.raises(pd_.InputError):
        pair.rotated(math.inf)
    with pytest.raises(pd_.InputError):
        pair.scaled(-1.0)


def test_a_pair_from_two_at2_files_and_from_two_columns(tmp_path):
    at2 = ROOT / "examples" / "el_centro_ns.AT2"
    pair = pd_.RecordPair.from_at2(at2, at2)
    assert pair.x.t.size == pair.y.t.size and pair.pga_g[0] == pytest.approx(0.319, abs=1e-3)
    path = tmp_path / "pair.csv"
    path.write_text("time,north,east\n0,0.0,0.0\n0.01,0.1,-0.05\n0.02,-0.2,0.1\n0.03,0.0,0.0\n")
    two = pd_.RecordPair.from_csv(path, x="north", y="east", time="time")
    assert two.pga_g == pytest.approx((0.2, 0.1)) and two.name == "pair"
    with pytest.raises(pd_.InputError) as err:
        pd_.RecordPair.from_csv(path, x="north", time="time")
    assert err.value.field == "y"


def test_the_fema_p695_pairs_are_each_event_s_two_components():
    pairs = pd_.records.fema_p695_pairs("far_field")
    records = pd_.records.fema_p695("far_field")
    assert len(pairs) == 22 and len(records) == 44
    padded = 0
    for pair, (a, b) in zip(pairs, zip(records[::2], records[1::2])):
        for mine, read in ((pair.x, a), (pair.y, b)):  # (a shorter component at rest after its end)
            assert np.array_equal(mine.accel[:read.t.size], read.accel)
            assert not mine.accel[read.t.size:].any()
            padded += mine.t.size > read.t.size
        assert pair.meta["components"] == [a.meta["component"], b.meta["component"]]
    assert padded >= 1  # (Manjil's components: 53.5 s and 46 s)
    normalized = pd_.records.fema_p695_pairs("far_field", normalized=True)
    factor = normalized[0].meta["normalization_factor"]
    np.testing.assert_allclose(normalized[0].y.accel, factor * pairs[0].y.accel, rtol=1e-12)


def test_the_command_line_writes_rotd_spectra(tmp_path):
    from pounding.cli import app

    at2 = str(ROOT / "examples" / "el_centro_ns.AT2")
    done = CliRunner().invoke(app, ["rotd", "--record-x", at2, "--record-y", at2, "--periods", "0:2:0.5",
                                    "--out", str(tmp_path / "out")])
    assert done.exit_code == 0, done.output
    assert "RotD100 / RotD50 from 1.414 to 1.414" in done.output
    for name in ("rotd_spectrum.nc", "rotd_spectrum.csv", "rotd_spectrum.png"):
        assert (tmp_path / "out" / name).stat().st_size > 0
    bad = CliRunner().invoke(app, ["rotd", "--record-x", at2, "--out", str(tmp_path / "x")])
    assert bad.exit_code == 2 and "both --record-x and --record-y" in bad.output


def _linear() -> pd_.Oscillator:
    """A mass on a linear isolator, no bumpers: its response scales with the motion."""
    return pd_.Oscillator(500.0, pd_.Isolator(slopes_n_m=[2.0e4], breakpoints_m=[], damping_n_s_m=300.0))


def test_orientations_run_the_motion_along_each_angle():
    """Each angle's peaks are simulate's under pair.along(angle), bit for bit, on threads as in series."""
    pair, system = _pair(5), pd_.presets.paper_damped()
    found = pd_.orientations(system, pair, [0.0, 30.0, 200.0], duration_s=4.0, scheduler="serial")
    threads = pd_.orientations(system, pair, [0.0, 30.0, 200.0], duration_s=4.0, workers=2)
    for angle in (0.0, 30.0, 200.0):
        alone = pd_.simulate(system, pair.along(angle), 4.0, sample_rate_hz=0).quantities()
        assert found.data.loc[angle].to_dict() == pytest.approx(alone, rel=0.0, abs=0.0, nan_ok=True)
    assert found.data.equals(threads.data)
    angle, value = found.critical("disp_max_m")
    assert value == found.data["disp_max_m"].max() and found.data.loc[angle, "disp_max_m"] == value
    frame, data = found.to_dataframe(), found.to_xarray()
    assert list(frame.index) == [0.0, 30.0, 200.0] and data.sizes["angle_deg"] == 3
    assert data.attrs["duration_s"] == 4.0


def test_the_critical_orientation_of_twin_components_is_45_degrees():
    """A linear system under a pair whose components are one motion: the motion along a is
    (cos a + sin a) times it, largest at 45 degrees (sqrt(2) times the motion along x) and none at 135."""
    quake = pd_.records.el_centro()
    found = pd_.orientations(_linear(), pd_.RecordPair(quake, quake), [0.0, 45.0, 135.0, 225.0],
                             duration_s=10.0)
    peaks = found.data["disp_max_m"]
    assert found.critical("disp_max_m")[0] in (45.0, 225.0)
    assert peaks[45.0] == pytest.approx(math.sqrt(2.0) * peaks[0.0], rel=1e-9)
    assert peaks[225.0] == pytest.approx(peaks[45.0], rel=1e-9)  # (a linear system: mirror symmetric)
    assert peaks[135.0] < 1e-12 * peaks[0.0]


def test_orientations_refuse_bad_input_by_name():
    pair = _pair(2)
    system = pd_.presets.paper_damped()
    for angles, field in (([0.0, 360.0], "angles_deg[1]"), ([-1.0], "angles_deg[0]"),
                          ([90.0, 45.0], "angles_deg"), ([math.nan], "angles_deg[0]")):
        with pytest.raises(pd_.InputError) as err:
            pd_.orientations(system, pair, angles)
        assert err.value.field == field
    with pytest.raises(pd_.InputError) as err:
        pd_.orientations(system, pair.x, [0.0])
    assert err.value.field == "pair"
    with pytest.raises(pd_.InputError) as err:
        pd_.orientations(system, pair, [0.0], duration_s=-1.0)
    assert err.value.field == "duration_s"
    with pytest.raises(pd_.InputError) as err:
        pd_.orientations("a building", pair, [0.0])
    found = pd_.orientations(system, pair, [0.0, 90.0], duration_s=1.0)
    with pytest.raises(pd_.InputError) as err:
        found.critical("peak")
    assert err.value.field == "quantity"


def test_the_command_line_finds_the_critical_orientation(tmp_path):
    from pounding.cli import app

    at2 = str(ROOT / "examples" / "el_centro_ns.AT2")
    done = CliRunner().invoke(app, ["orientations", "--preset", "paper-damped", "--record-x", at2,
                                    "--record-y", at2, "--angles", "0,45,90", "--duration", "5",
                                    "--out", str(tmp_path / "o")])
    assert done.exit_code == 0, done.output
    assert "at 45 deg" in done.output
    for name in ("orientations.csv", "orientations.png"):
        assert (tmp_path / "o" / name).stat().st_size > 0
    bad = CliRunner().invoke(app, ["orientations", "--preset", "paper-damped", "--record-x", at2,
                                   "--record-y", at2, "--pair", "3", "--out", str(tmp_path / "x")])
    assert bad.exit_code == 2 and "--pair 3" in bad.output


def test_a_study_turns_a_pair_and_scales_its_largest_direction(tmp_path):
    """A study's points under a FEMA P695 pair ('fema-p695-pair:<set>:<index>') turned by angle_deg: each
    simulate's under the pair scaled by one factor (its RotD100 PGA, the peak vector, to scale_pga_g) along
    that angle, bit for bit; sa_g scales its RotD100 pseudo-acceleration; a single component refuses
    angle_deg, and an index past the set is named."""
    spec = pd_.StudySpec(pd_.presets.paper_damped(),
                         {"kind": "record", "record": "fema-p695-pair:far_field:0", "scale_pga_g": 0.3,
                          "duration_s": 3.0}, {"angle_deg": [0.0, 90.0, 200.0]})
    data = pd_.study(spec, tmp_path / "pair.zarr", scheduler="serial", progress=False)
    pair = pd_.records.fema_p695_pairs("far_field")[0]
    scaled = pair.scaled(0.3 / pair.peak_vector_g)
    assert scaled.peak_vector_g == pytest.approx(0.3, rel=1e-12)
    for angle in (0.0, 90.0, 200.0):
        alone = pd_.simulate(pd_.presets.paper_damped(), scaled.along(angle), 3.0, sample_rate_hz=0)
        assert float(data["disp_max_m"].sel(angle_deg=angle)) == alone.quantities()["disp_max_m"]
    from pounding.studies.points import excitation_of

    at_sa = excitation_of({"kind": "record", "record": "fema-p695-pair:far_field:1", "sa_g": 0.5,
                           "sa_period_s": 1.0, "angle_deg": 30.0})
    second = pd_.records.fema_p695_pairs("far_field")[1]
    factor = at_sa.accel[np.argmax(np.abs(at_sa.accel))] / second.along(30.0).accel[
        np.argmax(np.abs(at_sa.accel))]
    rotd = pd_.rotd_spectrum(second.scaled(factor), [1.0])
    assert float(rotd["rotd100_psa_g"].values[0, 0]) == pytest.approx(0.5, rel=1e-9)
    with pytest.raises(pd_.InputError) as err:
        excitation_of({"kind": "record", "record": "el-centro", "angle_deg": 30.0})
    assert err.value.field == "angle_deg"
    with pytest.raises(pd_.InputError, match="22 pairs"):
        excitation_of({"kind": "record", "record": "fema-p695-pair:far_field:22"})
    with pytest.raises(pd_.InputError) as err:
        excitation_of({"kind": "record", "record": "fema-p695-pair:far_field:0", "scale_pga_g": -0.3})
    assert err.value.field == "scale_pga_g"


def test_rotd_at_the_edges_of_its_inputs():
    """A pair a hundred orders of magnitude weak has its spectrum scaled exactly (the kernel's squares
    neither under- nor overflow); periods beyond 1000 s, steps finer than 0.05 degrees and periods far below
    the record's step (too much work: each direction's half periods counted) are refused by name; a step
    over 15 degrees warns."""
    pair = _pair(4)
    spec = pd_.rotd_spectrum(pair, PERIODS)
    tiny = pd_.RecordPair(pd_.Record(pair.t, pair.x.accel * 2.0 ** -600),
                          pd_.Record(pair.t, pair.y.accel * 2.0 ** -600))
    weak = pd_.rotd_spectrum(tiny, PERIODS)
    np.testing.assert_array_equal(weak["sd_m"].values * 2.0 ** 600, spec["sd_m"].values)
    for periods, field in (([1.0, 1001.0], "periods_s[1]"), ([1e-6], "periods_s")):
        with pytest.raises(pd_.InputError) as err:
            pd_.rotd_spectrum(pair, periods)
        assert err.value.field == field
    with pytest.raises(pd_.InputError) as err:
        pd_.response_spectrum(pair.x, [2000.0])
    assert err.value.field == "periods_s[0]"
    with pytest.raises(pd_.InputError) as err:
        pd_.rotd_spectrum(pair, [1.0], angle_step_deg=0.01)
    assert err.value.field == "angle_step_deg"
    with pytest.warns(pd_.PoundingWarning, match="angle_step_deg"):
        pd_.rotd_spectrum(pair, [1.0], angle_step_deg=30.0)
    figure = pair.plot()
    assert len(figure.axes) == 1 and len(figure.axes[0].lines) == 2
