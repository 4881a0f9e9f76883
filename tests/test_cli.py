"""The command line, as a user runs it."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
from typer.testing import CliRunner

from pounding.cli import app

EXAMPLE = Path(__file__).parents[1] / "examples" / "paper_printed_ybs.toml"
runner = CliRunner()


def test_simulate_writes_contacts_and_history(tmp_path):
    contacts, history = tmp_path / "contacts.csv", tmp_path / "history.csv"
    result = runner.invoke(app, ["simulate", str(EXAMPLE), "--a-g", "0.05", "--freq", "2.2", "--duration",
                                 "5",
                                 "--velocity", "0.6", "--contacts", str(contacts), "--history", str(history)])
    assert result.exit_code == 0, result.output
    assert "D max / min [mm]" in result.output
    df = pd.read_csv(contacts)
    assert list(df.columns) == ["wall", "level", "side", "t_start_s", "t_end_s", "v_in_m_s", "v_out_m_s",
                                "impulse_n_s", "peak_force_n", "max_compression_m", "bumper_dissipation_j"]
    assert len(df) > 10
    hist = pd.read_csv(history, keep_default_na=False)
    assert list(hist.columns) == ["t_s", "displacement_m", "velocity_m_s", "abs_acceleration_m_s2",
                                  "isolator_force_n", "bumper_force_left_n", "bumper_force_right_n", "event"]
    assert hist["t_s"].iloc[-1] == 5.0
    # repeated time stamps are events (the state just after the jump), and say which
    repeated = hist["t_s"].duplicated(keep="first")
    assert repeated.any() and (hist.loc[repeated, "event"] != "").all()
    assert (hist["event"] == "contact_start").sum() == len(df)


def test_simulate_preset_and_errors():
    assert runner.invoke(app, ["simulate", "--preset", "paper-printed", "--a-g", "0.05", "--freq", "1.5",
                               "--duration", "2"]).exit_code == 0
    bad = runner.invoke(app, ["simulate", str(EXAMPLE), "--a-g", "0.05", "--freq", "-1"])
    assert bad.exit_code == 2 and "freq_hz" in bad.output and "Fix" in bad.output
    missing = runner.invoke(app, ["simulate", "nope.toml", "--a-g", "0.05", "--freq", "1"])
    assert missing.exit_code == 2 and "does not exist" in missing.output


def test_sweep_writes_the_issue_columns(tmp_path):
    out, nc, png = tmp_path / "sweep.csv", tmp_path / "sweep.nc", tmp_path / "sweep.png"
    result = runner.invoke(app, ["sweep", str(EXAMPLE), "--a-g", "0.05", "--direction", "down", "--fmin",
                                 "1.0",
                                 "--fmax", "2.0", "--fstep", "0.5", "--steady", "fixed", "--cycles", "6",
                                 "--out", str(out), "--netcdf", str(nc), "--plot", str(png)])
    assert result.exit_code == 0, result.output
    assert "nu_R" in result.output and "contact range [Hz]" in result.output
    assert "events per cycle" in result.output
    df = pd.read_csv(out)
    assert list(df.columns) == ["freq_hz", "alpha", "excursion_m", "eta", "e", "contact",
                                "contacts_per_cycle",
                                "restitution", "contact_time_s", "mean_force_n", "peak_force_n",
                                "dissipated_energy_j", "steady", "period_multiple",
                                "events_per_cycle", "sticks_per_cycle"]
    assert list(df["freq_hz"]) == [2.0, 1.5, 1.0]
    assert nc.stat().st_size > 0 and png.stat().st_size > 0


def test_sweep_errors_exit_2_with_the_fix():
    bad = runner.invoke(app, ["sweep", "--preset", "paper-printed", "--a-g", "0.05", "--direction", "left"])
    assert bad.exit_code == 2 and "direction" in bad.output and "Fix" in bad.output
    bad = runner.invoke(app, ["sweep", "--preset", "paper-printed", "--a-g", "0.05", "--cycles", "5"])
    assert bad.exit_code == 2 and "--cycles is for --steady fixed" in bad.output
    bad = runner.invoke(app, ["sweep", "--preset", "nope", "--a-g", "0.05"])
    assert bad.exit_code == 2 and "paper-printed" in bad.output


def test_campaign_writes_dataset_tables_and_figure(tmp_path):
    out = tmp_path / "run"
    result = runner.invoke(app, ["campaign", "--preset", "paper-printed", "--out", str(out), "--fmin", "1.0",
                                 "--fmax", "2.0", "--fstep", "1.0", "--steady", "fixed", "--cycles", "4",
                                 "--measure-cycles", "2"])
    assert result.exit_code == 0, result.output
    for name in ("campaign.nc", "steps.csv", "table2.csv", "table3.csv", "table4.csv", "campaign.png"):
        assert (out / name).stat().st_size > 0, name
    assert len(pd.read_csv(out / "table2.csv")) == 14
    steps = pd.read_csv(out / "steps.csv")
    assert len(steps) == 14 * 2 and {"configuration", "a_g", "direction", "freq_hz",
                                     "alpha"} <= set(steps.columns)
    bad = runner.invoke(app, ["campaign", "--out", str(out)])
    assert bad.exit_code == 2 and "--preset" in bad.output


def test_warm_up_is_a_no_op_that_says_so():
    result = runner.invoke(app, ["warm-up"])
    assert result.exit_code == 0 and "nothing to compile" in result.output, result.output
    assert "warm-up" not in runner.invoke(app, ["--help"]).output  # (kept for scripts, not offered)


def test_simulate_prints_a_triple_friction_pendulum_s_surface_slips_and_rings():
    """A triple friction pendulum's run: its sticks and slips, and its surfaces' slips and rings reached, as
    the run's summary counts them."""
    toml = Path(__file__).parents[1] / "examples" / "triple_friction_moat.toml"
    result = runner.invoke(app, ["simulate", str(toml), "--a-g", "0.4", "--freq", "0.5", "--duration", "6"])
    assert result.exit_code == 0, result.output
    assert "isolator sticks / slips" in result.output and "surface slips / rings reached" in result.output
