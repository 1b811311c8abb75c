"""A user's own compensator in a `tendonsheath bench` scenario ([[compare.user]]): it runs
beside the shipped ones, and a bad entry is a one-line error naming it."""

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tendonsheath.apps.cli import app
from tendonsheath.bench.user_scenario import ScenarioError, parse

EXAMPLE_09 = Path(__file__).resolve().parent.parent / "examples" / "09_user_compensator.py"

SCENARIO = """
[plant]
elements = 20
realistic = false
[reference]
duration = 4.0
sines = [[0.8, 0.5, 0.0]]
[sensor]
noise_std = 0.0
resolution = 0.0
[compare]
compensators = ["none"]
"""


def _user(**entry) -> str:
    """The scenario with one [[compare.user]] entry; 'kwargs' is given as TOML text."""
    rows = "\n".join(f"{k} = {v if k == 'kwargs' else json.dumps(v)}" for k, v in entry.items())
    return f"{SCENARIO}\n[[compare.user]]\n{rows}\n"


def test_bench_command_runs_a_user_compensator(tmp_path):
    scenario = tmp_path / "s.toml"
    scenario.write_text(
        _user(
            file=str(EXAMPLE_09),
            **{"class": "PIFeedforward"},
            name="my PI",
            kwargs="{ kp = 0.8, ki = 6.0 }",
        )
    )
    result = CliRunner().invoke(app, ["bench", str(scenario), "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    runs = json.loads((tmp_path / "out" / "metrics.json").read_text())["scenarios"]["user"]
    assert set(runs) == {"none", "my PI"}
    # the PI loop with feedforward beats the uncompensated drive (with a margin)
    assert runs["my PI"]["rmse"] < 0.8 * runs["none"]["rmse"]


def test_a_file_is_found_beside_the_scenario(tmp_path):
    (tmp_path / "mine.py").write_text(EXAMPLE_09.read_text())
    scenario = tmp_path / "s.toml"
    scenario.write_text(_user(file="mine.py", **{"class": "PIFeedforward"}))
    sc = parse(scenario.read_text(), str(scenario))
    (user,) = sc.user_compensators
    assert user.name == "PIFeedforward" and user.build().kp == 0.5


def test_module_and_class_with_keyword_arguments():
    from tendonsheath.compensate import AdaptiveController

    text = _user(
        **{"class": "tendonsheath.compensate:AdaptiveController"},
        name="mine",
        kwargs="{ lambda_ = 12.0, max_torque = 3.0 }",
    )
    (user,) = parse(text, "s.toml").user_compensators
    built = user.build()
    assert user.cls is AdaptiveController and user.origin.endswith(":AdaptiveController")
    assert built.params["lambda_"] == 12.0 and built.params["max_torque"] == 3.0


@pytest.mark.parametrize(
    "entry, match",
    [
        ({"class": "PIFeedforward", "file": "nowhere.py"}, r"#1: file not found"),
        ({"class": "Nope", "file": str(EXAMPLE_09)}, r"has no class 'Nope'"),
        ({"class": "no_such_module_xyz:Thing"}, r"cannot import 'no_such_module_xyz'"),
        ({"class": "NoColon"}, r'must be "module:Class"'),
        (
            {"class": "PIFeedforward", "file": str(EXAMPLE_09), "kwargs": "{ kq = 1 }"},
            r"failed \(.*unexpected keyword argument 'kq'",
        ),
        ({"class": "pathlib:Path"}, r"not a compensator: it has no reset and no step"),
        (
            {"class": "PIFeedforward", "file": str(EXAMPLE_09), "name": "none"},
            r"the name 'none' is already used",
        ),
        (
            {"class": "tendonsheath.compensate:AdaptiveController"},
            r"the name 'AdaptiveController' is already used",
        ),
        ({"clas": "x"}, r"unknown key 'clas'"),
    ],
)
def test_bad_user_entries_name_the_problem(entry, match):
    with pytest.raises(ScenarioError, match=match):
        parse(_user(**entry), "s.toml")
