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
    result = runner.invoke(app, ["simulate", str(EXAMPLE), "--a-g", "0.05", "--freq", "2.2", "--duration", "5",
                                 "--velocity", "0.6", "--contacts", str(contacts), "--history", str(history)])
    assert result.exit_code == 0, result.output
    assert "D max / min [mm]" in result.output
    df = pd.read_csv(contacts)
    assert list(df.columns) == ["side", "t_start", "t_end", "v_in", "v_out", "impulse", "peak_force",
                                "max_compression", "bumper_dissipation"]
    assert len(df) > 10
    assert pd.read_csv(history)["t"].iloc[-1] == 5.0


def test_simulate_preset_and_errors():
    assert runner.invoke(app, ["simulate", "--preset", "paper-printed", "--a-g", "0.05", "--freq", "1.5",
                               "--duration", "2"]).exit_code == 0
    bad = runner.invoke(app, ["simulate", str(EXAMPLE), "--a-g", "0.05", "--freq", "-1"])
    assert bad.exit_code == 2 and "freq_hz" in bad.output and "Fix" in bad.output
    missing = runner.invoke(app, ["simulate", "nope.toml", "--a-g", "0.05", "--freq", "1"])
    assert missing.exit_code == 2 and "does not exist" in missing.output
