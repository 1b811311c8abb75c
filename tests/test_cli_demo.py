"""The `tendonsheath` command: help on every command and the demo's outputs."""

import json

from typer.testing import CliRunner

from tendonsheath.cli import app

runner = CliRunner()


def test_every_command_has_help():
    result = runner.invoke(app, ["--help"])
    assert result.exit_code == 0
    commands = [c.name or c.callback.__name__.replace("_", "-") for c in app.registered_commands]
    assert "demo" in commands
    for name in commands:
        sub = runner.invoke(app, [name, "--help"])
        assert sub.exit_code == 0, name
        assert "Usage" in sub.output


def test_demo_writes_metrics_and_one_loop_per_model(tmp_path):
    result = runner.invoke(app, ["demo", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert metrics["schema_version"] >= 1
    names = set(metrics["models"])
    assert {"Backlash", "BoucWenBacklash", "BoucWen", "PrandtlIshlinskii"} <= names
    for name, m in metrics["models"].items():
        png = tmp_path / f"loop_{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert m["loop_width_last_cycle"] > 0
    assert "metrics.json" in result.output
