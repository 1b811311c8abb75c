"""A user's own C++ compensator (examples/cpp/user_compensator, bound with
tendonsheath_bind/compensator.hpp) runs through bench.run and `tendonsheath bench` in the C++
closed loop, and gives what the same compensator written in Python gives."""

import importlib.machinery
import importlib.util
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from _bench_helpers import Y_D, T, bench_plant
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app
from tendonsheath.protocols import StreamingCompensator

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE_09 = ROOT / "examples" / "09_user_compensator.py"


def _built_module_dir() -> Path:
    """Where `make install` (the Python build) left the example module for this Python."""
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    found = sorted(
        ROOT.glob(f"build/*/examples/cpp/user_compensator/user_compensators{suffix}"),
        key=lambda p: p.stat().st_mtime,
    )
    assert found, "the example module is built by `make install` (CMakeLists.txt); run it first"
    return found[-1].parent


def _load(name: str, path: Path):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def cpp():
    # imported by name (once: a nanobind module registers its types once per process), as the
    # scenario's class = "user_compensators:PIFeedforward" imports it
    sys.path.insert(0, str(_built_module_dir()))
    try:
        return importlib.import_module("user_compensators")
    finally:
        sys.path.pop(0)


@pytest.fixture(scope="module")
def python_twin():
    return _load("example_09", EXAMPLE_09).PIFeedforward


def test_the_bound_class_meets_the_protocol_and_steps_like_its_python_twin(cpp, python_twin):
    rng = np.random.default_rng(0)
    for _ in range(20):
        kw = dict(
            gain=rng.uniform(0.5, 1.5),
            kp=rng.uniform(0, 2),
            ki=rng.uniform(0, 10),
            integral_limit=rng.uniform(0.01, 0.5),
        )
        c, p = cpp.PIFeedforward(**kw), python_twin(**kw)
        assert isinstance(c, StreamingCompensator) and c.params == pytest.approx(kw)
        assert c.step_inputs == ("y_d", "y") and c.control_output == "x"
        y = rng.normal(0, 1, 300)
        y[rng.uniform(size=300) < 0.1] = math.nan
        for yd, yk, dt in zip(rng.normal(0, 1, 300), y, rng.uniform(0, 0.01, 300), strict=True):
            assert c.step(yd, yk, dt) == pytest.approx(p.step(yd, yk, dt), abs=1e-12)


@pytest.mark.parametrize("seed", range(3))
def test_bench_run_in_cpp_equals_the_python_compensator(cpp, python_twin, seed):
    rng = np.random.default_rng(seed)
    kw = dict(gain=rng.uniform(0.9, 1.1), kp=rng.uniform(0.2, 1.0), ki=rng.uniform(1, 8))
    noise = ts.Sensor(noise_std=2e-4, seed=seed)
    dropout = [(1.5, 1.5 + rng.uniform(0.05, 0.3))]
    compiled = cpp.PIFeedforward(**kw)
    fast = ts.bench.run(bench_plant(), compiled, T, Y_D, noise=noise, dropout=dropout)
    slow = ts.bench.run(bench_plant(), python_twin(**kw), T, Y_D, noise=noise, dropout=dropout)
    for name in ("output", "measured", "command", "q_motor"):
        np.testing.assert_allclose(getattr(fast, name), getattr(slow, name), rtol=0, atol=1e-12)
    # the C++ loop ran a copy (the capsule's): the object itself was never stepped, so its
    # integral is still zero; stepped from Python, it would hold the run's integral
    assert compiled.step(1.0, 0.0, 0.01) == pytest.approx(kw["gain"] + kw["kp"] + kw["ki"] * 0.01)


def test_bad_settings_and_dt_are_clear_errors(cpp):
    with pytest.raises(ValueError, match="PIFeedforward: ki must be finite"):
        cpp.PIFeedforward(ki=math.nan)
    with pytest.raises(ValueError, match="dt must be finite and >= 0"):
        cpp.PIFeedforward().step(0.0, 0.0, -1.0)


def test_bench_command_runs_the_cpp_compensator(tmp_path, cpp):
    scenario = tmp_path / "s.toml"
    scenario.write_text(
        "[plant]\nelements = 20\nrealistic = false\n"
        "[reference]\nduration = 4.0\nsines = [[0.8, 0.5, 0.0]]\n"
        "[compare]\ncompensators = ['none']\n"
        "[[compare.user]]\nclass = 'user_compensators:PIFeedforward'\nname = 'C++ PI'\n"
        "kwargs = { kp = 0.8, ki = 6.0 }\n"
        f"[[compare.user]]\nfile = {json.dumps(str(EXAMPLE_09))}\nclass = 'PIFeedforward'\n"
        "name = 'Python PI'\nkwargs = { kp = 0.8, ki = 6.0 }\n"
    )
    result = CliRunner().invoke(app, ["bench", str(scenario), "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    runs = json.loads((tmp_path / "out" / "metrics.json").read_text())["scenarios"]["user"]
    assert set(runs) == {"none", "C++ PI", "Python PI"}
    for key in ("mse", "rmse", "max_abs"):
        assert runs["C++ PI"][key] == pytest.approx(runs["Python PI"][key], rel=0, abs=1e-12)
    assert runs["C++ PI"]["rmse"] < 0.8 * runs["none"]["rmse"]  # it tracks (a margin)
