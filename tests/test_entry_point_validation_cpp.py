"""One validation for every entry point, the C++ loader among them (issue 27, step 17 item 1).

A file Python saved (``to_json``), one number in it replaced, is loaded by Python
(``ts.compensate.load``) and by the C++ loader (``tendonsheath/io/json.hpp`` and
``io/json_multi_input.hpp``, run by C++ example 12): both refuse it, with the same rule text
(the message after its last ``": "``: "kp must be >= 0 (got -1)"), or both take it. The rows
are not written by hand: every numeric leaf of one saved file of each compensator (the
composite models inside an InverseFeedforward, a LoadCompensated, a CoupledFeedforward) gets
-1 and 0. nan and +-inf cannot be written in JSON: the text ``NaN``, ``Infinity`` and
``1e999`` are refused by both, naming the key.
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_cpp_example_12 import example  # noqa: E402,F401  (the fixture: the built example)

import tendonsheath as ts  # noqa: E402
from tendonsheath.compensate import (  # noqa: E402
    ContinuumFeedforward,
    CoupledFeedforward,
    CurveAngleFeedforward,
    EncoderLoop,
    InverseFeedforward,
    LearnedFeedforward,
    LoadCompensated,
    TipLoop,
)
from tendonsheath.models import (  # noqa: E402
    AngleDependent,
    Backlash,
    Chain,
    Coupled,
    FirstOrderLag,
    Loaded,
    PrandtlIshlinskii,
    Scaled,
)


def _samples() -> dict:
    """One saved file of each compensator the C++ loader reads, and of each composite model
    it inverts (inside an InverseFeedforward), every optional number given."""
    b = Backlash(B_r=0.05, B_l=0.04)
    angle = AngleDependent(
        "Backlash",
        {"c_r": 1.0, "c_l": 1.0, "B_r": [0.05, 0.01], "B_l": 0.05},
        laws={"B_r": "tanh"},
        angle_friction=0.2,
    )
    loaded = Loaded(b, gain=0.1, slack=0.01, slack_load=0.2, friction=0.05)
    compensators = {
        "EncoderLoop": EncoderLoop(InverseFeedforward(b), kp=0.5, max_correction=0.3),
        "TipLoop": TipLoop(InverseFeedforward(b), ki=1.0, schedule=[(0.5, 1.0), (1.5, 2.0)]),
        "LearnedFeedforward": LearnedFeedforward(InverseFeedforward(b), [0.0, 0.1], 0.01),
        "LoadCompensated": LoadCompensated(loaded, switch=0.01, filter_hz=30.0),
        "CoupledFeedforward": CoupledFeedforward(
            Coupled([b, b], [[0.0, 0.1], [0.1, 0.0]]), filter_hz=30.0
        ),
        "InverseFeedforward": InverseFeedforward(
            PrandtlIshlinskii([0.0, 0.1, 0.2], [0.8, 0.2, 0.1]),
            0.03,
            (-2.0, 2.0, 30.0),
            input_range=(-1.0, 1.0),
            filter_hz=20.0,
        ),
        "CurveAngleFeedforward": CurveAngleFeedforward(0.1, 2e4, 1.0, 10.0, curve_angle=2.0),
        "ContinuumFeedforward": ContinuumFeedforward(),
        "Scaled": InverseFeedforward(Scaled(b, 0.1, 2.0, 0.05, -1.5)),
        "Chain": InverseFeedforward(Chain(b, FirstOrderLag(time_constant=0.01))),
        "AngleDependent": InverseFeedforward(angle),
    }
    return {name: c.to_dict() for name, c in compensators.items()}


def _leaves(value, path=()):
    """The path of every number in a saved file (the version aside)."""
    if isinstance(value, dict):
        for key, v in value.items():
            if key != "version":
                yield from _leaves(v, (*path, key))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _leaves(v, (*path, i))
    elif isinstance(value, int | float) and not isinstance(value, bool):
        yield path


def _replaced(saved: dict, path: tuple, value) -> dict:
    out = copy.deepcopy(saved)
    leaf = out
    for key in path[:-1]:
        leaf = leaf[key]
    leaf[path[-1]] = value
    return out


SAMPLES = _samples()
ROWS = [
    (name, path, bad)
    for name, saved in SAMPLES.items()
    for path in _leaves(saved)
    for bad in (-1.0, 0.0)
]


def _python(file: Path) -> str | None:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a unit warning is not a refusal
            ts.compensate.load(file)
    except ValueError as exc:
        return str(exc)
    return None


def _cpp(example, file: Path, tmp_path: Path) -> str | None:  # noqa: F811
    """The C++ loader's refusal (example 12 prints it and exits 2), or None: it loaded and
    ran an empty trajectory."""
    empty = tmp_path / "empty.csv"
    empty.write_text("")
    run = subprocess.run(
        [example, file, empty, tmp_path / "out.csv"], capture_output=True, text=True
    )
    if run.returncode == 0:
        return None
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr  # one line
    return run.stderr.strip()


def _rule(message: str) -> str:
    """The rule a message states, without where it was found ("f.json: model: map: ")."""
    return message.rsplit(": ", 1)[-1]


def test_the_rows_reach_every_compensator_and_composite():
    kinds = {name for name, *_ in ROWS}
    assert kinds == set(SAMPLES)
    assert len(ROWS) >= 240  # measured 246: every number of the eleven files, twice


@pytest.mark.parametrize("name, path, bad", ROWS, ids=str)
def test_cpp_and_python_load_a_file_alike(example, tmp_path, name, path, bad):  # noqa: F811
    file = tmp_path / "f.json"
    file.write_text(json.dumps(_replaced(SAMPLES[name], path, bad)))
    python, cpp = _python(file), _cpp(example, file, tmp_path)
    assert (python is None) == (cpp is None), (python, cpp)
    if python is not None:
        assert _rule(cpp) == _rule(python), (python, cpp)
        assert "\n" not in python


NOT_JSON = [
    ("EncoderLoop", ("kp",)),
    ("EncoderLoop", ("max_correction",)),  # null: unbounded; never inf or NaN
    ("EncoderLoop", ("limits", "max")),
    ("LoadCompensated", ("switch",)),
    ("CoupledFeedforward", ("model", "coupling", 0, 1)),
    ("Scaled", ("model", "map", "input_scale")),
    ("TipLoop", ("schedule", 0, 1)),
]


@pytest.mark.parametrize("text", ["NaN", "Infinity", "-Infinity", "1e999"])
@pytest.mark.parametrize("name, path", NOT_JSON, ids=str)
def test_numbers_json_cannot_hold_are_refused_by_both(example, tmp_path, name, path, text):  # noqa: F811
    """Python's json reads NaN, Infinity and 1e999 (as inf); the C++ loader refuses them. Both
    refuse them now (Python's loader had taken max_correction = 1e999 as unbounded)."""
    marker = 123456.5
    file = tmp_path / "f.json"
    file.write_text(json.dumps(_replaced(SAMPLES[name], path, marker)).replace(str(marker), text))
    python, cpp = _python(file), _cpp(example, file, tmp_path)
    assert python is not None and cpp is not None, (python, cpp)
    key = next(k for k in reversed(path) if isinstance(k, str))
    assert f"key '{key}'" in python, python
    if text == "1e999":  # nlohmann reads it and names the key; NaN is not JSON to it at all
        assert f"{key}' is out of range" in cpp, cpp
    else:
        assert "not valid JSON" in cpp, cpp
