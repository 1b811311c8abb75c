"""The `tendonsheath` command: help on every command and the demo's outputs."""

import json

from typer.testing import CliRunner

from tendonsheath.apps.cli import app

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


def test_demo_writes_report_metrics_and_figures(tmp_path, monkeypatch, scenario_results):
    from tendonsheath.bench import scenarios

    # the session's lau2015 result, asked for at the demo's scale (tests/test_scenarios.py
    # judges the scenario itself); the robustness study and the model figures run for real
    asked = []

    def session_lau(scale, seed, progress):
        asked.append(scale)
        return scenario_results["lau2015"]

    monkeypatch.setitem(scenarios.SCENARIOS, "lau2015", session_lau)
    result = runner.invoke(
        app, ["demo", "--out", str(tmp_path), "--scenario", "lau2015", "--scale", "0.2"]
    )
    assert result.exit_code == 0, result.output
    assert asked == [0.2]
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert metrics["schema"] == "tendonsheath.metrics" and metrics["version"] == 3
    assert set(metrics["scenarios"]) == {"lau2015"}
    assert "ContinuumFeedforward (exact)" in metrics["scenarios"]["lau2015"]
    robust = metrics["robustness"]
    assert robust["runs"] == 40 and robust["metric"] == "mse"
    head = "shape-aware InverseFeedforward + EncoderLoop"
    assert set(robust["compensators"]) == {
        "none",
        "InverseFeedforward",
        head,
        "AdaptiveController",
    }
    # over perturbed plants every compensator still beats no compensation (median MSE), and
    # the shape-aware one in its encoder loop the one-shape feedforward
    med = {k: v["median"] for k, v in robust["compensators"].items()}
    assert all(med[k] < med["none"] for k in med if k != "none")
    assert med[head] < med["InverseFeedforward"]
    assert (tmp_path / "robustness_mse.png").exists()
    names = set(metrics["models"])
    assert {"Backlash", "BoucWenBacklash", "BoucWen", "PrandtlIshlinskii"} <= names
    for name, m in metrics["models"].items():
        png = tmp_path / f"loop_{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert m["loop_width_last_cycle"] > 0
    assert (tmp_path / "report.html").stat().st_size > 10_000
    said = result.output.replace("\n", "")  # rich wraps long paths
    assert "report.html" in said and "metrics.json" in said


def test_demo_rejects_unknown_scenario_bad_scale_and_workers(tmp_path):
    result = runner.invoke(app, ["demo", "--out", str(tmp_path), "--scenario", "nope"])
    assert result.exit_code == 2 and "unknown scenario" in result.output
    result = runner.invoke(app, ["demo", "--out", str(tmp_path), "--scale", "0"])
    assert result.exit_code == 2 and "--scale" in result.output
    result = runner.invoke(app, ["demo", "--out", str(tmp_path), "--workers", "0"])
    assert result.exit_code == 2 and "--workers" in result.output
