"""pounding.basins: the attractors found against continuation's stable orbits, the matching of
settled responses, the fractions and their errors, and what users meet (bad input, Ctrl-C, random
sampling, the plot, the command line)."""

from __future__ import annotations

import numpy as np
import pytest
from typer.testing import CliRunner

import pounding as pd_
from pounding.cli import app

DAMPED = pd_.presets.paper_damped()


@pytest.fixture(scope="module")
def coexisting():
    return pd_.basins(DAMPED, pd_.Harmonic(0.05, 1.8), n=(14, 14), steady_rtol=1e-10)


def test_two_attractors_where_continuation_has_two_stable_orbits(coexisting):
    """At 1.8 Hz the branch has two stable orbits (between its folds): the basins find those two,
    a free one and one in contact, each with the orbit's alpha to 1e-6."""
    branch = pd_.continuation(DAMPED, 0.05, (1.4, 2.6))
    folds = sorted(b.freq_hz for b in branch.folds())
    assert folds[0] < 1.8 < folds[1]
    att = coexisting.attractors
    assert len(att) == 2 and att["impacts"].tolist() == [False, True] and (att["period"] == 1).all()
    for row in att.itertuples():
        guess = pd_.State.at_rest(DAMPED, 0.0, row.displacement_m, row.velocity_m_s)
        orbit = pd_.periodic_orbit(DAMPED, pd_.Harmonic(0.05, 1.8), guess=guess)
        assert orbit.converged and orbit.stable
        assert row.alpha == pytest.approx(orbit.alpha, rel=1e-6)
    assert coexisting.not_settled == 0.0 and att["fraction"].sum() == pytest.approx(1.0)
    p, se = att["fraction"].to_numpy(), att["standard_error"].to_numpy()
    np.testing.assert_allclose(se, np.sqrt(p * (1 - p) / 14**2))
    # every state labelled with its attractor; both basins non-empty
    assert set(np.unique(coexisting.labels)) == {0, 1} and coexisting.labels.shape == (14, 14)


def test_one_attractor_where_there_is_one_stable_orbit():
    b = pd_.basins(DAMPED, pd_.Harmonic(0.05, 2.6), n=(5, 5))
    assert len(b.attractors) == 1 and b.fractions.tolist() == [1.0] and not b.attractors["impacts"][0]


def test_random_sampling_estimates_the_grid_fractions_within_their_errors(coexisting):
    sample = pd_.basins(DAMPED, pd_.Harmonic(0.05, 1.8), n=300, sampling="random", seed=3, steady_rtol=1e-10)
    assert sample.labels.shape == (300,) and len(sample.attractors) == 2
    grid, est = coexisting.fractions.to_numpy(), sample.fractions.to_numpy()
    se = np.hypot(coexisting.attractors["standard_error"], sample.attractors["standard_error"]).to_numpy()
    assert np.all(np.abs(grid - est) < 4 * se)
    ds = sample.to_xarray()
    assert ds["label"].dims == ("state",) and ds["attractor_alpha"].size == 2


@pytest.mark.parametrize("kwargs, field", [
    ({"displacement_m": (0.0, 0.5)}, "displacement_m"), ({"displacement_m": (0.01, -0.01)}, "displacement_m"),
    ({"velocity_m_s": 3.0}, "velocity_m_s"), ({"n": (0, 5)}, "n"), ({"n": "many"}, "n"),
    ({"sampling": "sobol"}, "sampling"), ({"max_cycles": 5}, "max_cycles"),
    ({"match_rtol": -1.0}, "match_rtol"),
    ({"scheduler": "cluster"}, "scheduler"), ({"rtol": "x"}, "rtol"), ({"rtol": 0.5}, "rtol"),
    ({"steady_rtol": 10.0}, "steady_rtol"),
])
def test_bad_arguments_are_named(kwargs, field):
    with pytest.raises(pd_.InputError, match=field):
        pd_.basins(DAMPED, pd_.Harmonic(0.05, 1.8), **kwargs)
    with pytest.raises(pd_.InputError, match="excitation"):
        pd_.basins(DAMPED, pd_.records.el_centro())


def test_ctrl_c_keeps_the_states_finished():
    seen = []

    def stop_after(n):
        seen.append(n)
        if len(seen) == 20:
            raise KeyboardInterrupt

    with pytest.raises(pd_.Interrupted) as info:
        pd_.basins(DAMPED, pd_.Harmonic(0.05, 1.8), n=(10, 10), scheduler="serial", progress=stop_after)
    part = info.value.partial
    ran = int((part.labels != -2).sum())
    assert not part.complete and 0 < int((part.labels >= 0).sum()) <= ran < 100
    # (the fractions are of the states that ran)
    assert part.fractions.sum() + part.not_settled == pytest.approx(1.0)


def test_the_plot_and_the_command_line(coexisting, tmp_path):
    artists = pd_.plots.plot_basins(coexisting)
    assert coexisting.plot().__class__.__name__ == "Figure"
    assert len(artists) == 3
    out, png = tmp_path / "b.nc", tmp_path / "b.png"
    res = CliRunner().invoke(app, ["basins", "--preset", "paper-damped", "--a-g", "0.05", "--freq", "1.8",
                                   "--n", "6", "--netcdf", str(out), "--plot", str(png)])
    assert res.exit_code == 0, res.output
    assert "impacting" in res.output and out.stat().st_size > 0 and png.stat().st_size > 0
    bad = CliRunner().invoke(app, ["basins", "--preset", "paper-damped", "--a-g", "0.05", "--freq", "1.8",
                                   "--n", "0"])
    assert bad.exit_code == 2 and "n" in bad.output


def test_basin_stability_map_is_the_basins_fraction_at_each_point():
    """The map's probability at a point is basins' impacting fraction for the same random states
    (same seed): 1 where the only response pounds (1.5 Hz), 0 where it is free (2.6 Hz), between
    at 1.8 Hz, with the sampling error of that share; one impacting and one free response there."""
    m = pd_.basin_stability_map(DAMPED, [0.05], [1.5, 1.8, 2.6], samples=50, seed=4)
    ds = m.data
    p = ds["pounding_probability"].sel(a_g=0.05).values
    b = pd_.basins(DAMPED, pd_.Harmonic(0.05, 1.8), n=50, sampling="random", seed=4)
    share = float(b.attractors.loc[b.attractors["impacts"], "fraction"].sum())
    assert p[0] == 1.0 and p[2] == 0.0 and p[1] == pytest.approx(share)
    assert ds["standard_error"].sel(a_g=0.05).values[1] == pytest.approx(np.sqrt(share * (1 - share) / 50))
    assert ds["impacting_attractors"].values.tolist() == [[1, 1, 0]]
    assert ds["free_attractors"].values.tolist() == [[0, 1, 1]]
    assert m.complete and len(pd_.plots.plot_basin_stability(m)) >= 2
    # a state still settling when max_cycles ends pounds all the same if it touches the bumpers
    short = pd_.basin_stability_map(DAMPED, [0.05], [1.5], samples=10, max_cycles=11, measure_cycles=5)
    assert short.data["pounding_probability"].item() == 1.0 and short.data["not_settled"].item() > 0.5
    with pytest.raises(pd_.InputError, match="bumpers"):
        pd_.basin_stability_map(DAMPED.without_bumpers(), [0.05], [1.8])
    with pytest.raises(pd_.InputError, match="freqs_hz"):
        pd_.basin_stability_map(DAMPED, [0.05], [1.8, 1.8])
    with pytest.raises(pd_.InputError, match="a_g_levels"):
        pd_.basin_stability_map(DAMPED, [-0.05], [1.8])
    with pytest.raises(pd_.InputError, match="samples"):
        pd_.basin_stability_map(DAMPED, [0.05], [1.8], samples=0)
