"""User scenarios in TOML: validation that names the bad key, and an end-to-end bench run."""

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tendonsheath.apps.cli import app
from tendonsheath.bench.user_scenario import ScenarioError, parse

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "scenarios" / "changing_route.toml"


@pytest.mark.parametrize(
    "text, match",
    [
        ("[plant]\nfrction = 0.1\n", r"\[plant\]: unknown key 'frction'"),
        ("[plant]\nfriction = 'high'\n", r"'friction' must be a number"),
        ("[plant]\ntype = 'tripod'\n", r"'type' must be"),
        ("[route]\narcs = [[0.5, 'x']]\n", r"\[route\]"),
        ("[[route.changes]]\ntotal_angle = 1.0\n", r"needs a time 't'"),
        ("[[route.changes]]\nt = 2.0\nwhen = 3\n", r"unknown key 'when'"),
        ("[compare]\ncompensators = ['magic']\n", r"unknown compensator 'magic'"),
        ("[reference]\nsines = [[1.0]]\n", r"sines\[0\]"),
        # no sines: no reference to track (it once reached the bench as the number 0)
        ("[reference]\nsines = []\n", r"sines must list at least one sine"),
        ("[reference]\nduration = -1.0\n", r"duration and rate must be > 0"),
        ("[load]\ntype = 'gravity'\n", r"\[load\]: 'type' must be"),
        ("[plnt]\n", r"unknown table or key 'plnt'"),
        ("[plant\n", r"not valid TOML"),
    ],
)
def test_bad_scenarios_name_the_problem(text, match):
    with pytest.raises(ScenarioError, match=match):
        parse(text, "s.toml")


def test_example_scenario_parses():
    sc = parse(EXAMPLE.read_text(), str(EXAMPLE))
    assert sc.plant["elements"] == 30 and len(sc.route_changes) == 1
    assert sc.compensators[0] == "none"


def test_bench_command_runs_a_scenario_end_to_end(tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text(
        EXAMPLE.read_text()
        .replace("duration = 16.0", "duration = 8.0")
        .replace("t = 8.0", "t = 4.0")
        .replace("duration = 15.0", "duration = 8.0")
        .replace('"curve_angle_feedforward", "adaptive"', '"curve_angle_feedforward"')
    )
    result = CliRunner().invoke(app, ["bench", str(scenario), "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    runs = metrics["scenarios"]["user"]
    assert set(runs) == {"none", "InverseFeedforward", "CurveAngleFeedforward"}
    # the curve-angle feedforward follows the route change; the fixed inverse cannot
    assert runs["CurveAngleFeedforward"]["rmse"] < runs["InverseFeedforward"]["rmse"]
    assert runs["CurveAngleFeedforward"]["rmse"] < runs["none"]["rmse"] / 3


def test_bench_command_fails_cleanly(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[plant]\nfrction = 0.1\n")
    result = CliRunner().invoke(app, ["bench", str(bad)])
    assert result.exit_code == 2 and "unknown key 'frction'" in result.output
    result = CliRunner().invoke(app, ["bench", str(tmp_path / "missing.toml")])
    assert result.exit_code == 2 and "not found" in result.output


def test_tension_bench_recovers_friction(rng):
    import tendonsheath as ts
    from tendonsheath.bench.user_scenario import tension_bench_friction

    for _ in range(5):
        mu = rng.uniform(0.03, 0.25)
        route = ts.Route.arcs([(rng.uniform(0.2, 0.8), rng.uniform(0, 3)) for _ in range(3)])
        plant = ts.PullPullPlant(
            route=route, friction=mu, stiffness=5e3, pretension=20.0, elements=30
        )
        assert tension_bench_friction(plant) == pytest.approx(mu, rel=1e-6)
