"""C++ example 12 loads compensators saved by Python and gives Python's commands to 1e-12
on the same 1 kHz trajectory (issue 15, Done-when line 2)."""

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from tendonsheath.compensate import (
    ContinuumFeedforward,
    CurveAngleFeedforward,
    EncoderLoop,
    InverseFeedforward,
    LearnedFeedforward,
    TipLoop,
)
from tendonsheath.models import Backlash, BoucWenBacklash, PrandtlIshlinskii, Scaled

ROOT = Path(__file__).resolve().parents[1]
TARGET = "example_12_load_and_run"


@pytest.fixture(scope="module")
def example(tmp_path_factory) -> Path:
    """The example built by `make test-cpp`, else built here with CMake."""
    built = ROOT / "build" / "cpp" / "examples" / "cpp" / TARGET
    if built.is_file():
        return built
    if not Path("/usr/include/nlohmann/json.hpp").is_file() or shutil.which("cmake") is None:
        pytest.fail("example 12 needs cmake and nlohmann/json: run `make test-cpp` first")
    build = tmp_path_factory.mktemp("cpp")
    cmake = ["cmake", "-S", str(ROOT), "-B", str(build), "-DTENDONSHEATH_BUILD_EXAMPLES=ON"]
    subprocess.run([*cmake, "-DCMAKE_BUILD_TYPE=Release"], check=True, capture_output=True)
    subprocess.run(
        ["cmake", "--build", str(build), "--target", TARGET], check=True, capture_output=True
    )
    return build / "examples" / "cpp" / TARGET


COMPENSATORS = {
    "backlash": lambda: InverseFeedforward(
        Backlash(c_r=0.96, c_l=0.92, B_r=0.117, B_l=0.071), 0.05, (-3.0, 3.0, 50.0)
    ),
    "bouc_wen_backlash": lambda: InverseFeedforward(
        BoucWenBacklash(c_r=1.1, c_l=0.9, B_r=0.05, B_l=0.1, rho=12.0), 0.03
    ),
    "prandtl_ishlinskii": lambda: InverseFeedforward(
        PrandtlIshlinskii(thresholds=[0.0, 0.1, 0.2, 0.4], weights=[0.9, 0.3, 0.2, 0.1]),
        limits={"max_rate": 20.0},
    ),
    "scaled": lambda: InverseFeedforward(
        Scaled(Backlash(B_r=0.08, B_l=0.12), input_offset=0.1, input_scale=2.0, output_gain=-1.3),
        0.04,
        (-2.5, 2.0),
    ),
    "curve_angle": lambda: CurveAngleFeedforward(
        0.12,
        5000.0,
        1.0,
        15.0,
        load_force=1.0,
        curve_angle=2.5,
        play=0.02,
        max_correction_rate=0.5,
    ),
    "continuum": lambda: ContinuumFeedforward(mode="published", limits=(-4.0, 4.0, 30.0)),
}


@pytest.mark.parametrize("name", sorted(COMPENSATORS))
def test_cpp_commands_equal_python(example, tmp_path, name):
    ff = COMPENSATORS[name]()
    ff.to_json(tmp_path / "ff.json")
    t = np.arange(0.0, 4.0, 1e-3)  # 1 kHz
    y_d = 0.8 * np.sin(2 * np.pi * 0.5 * t) + 0.1 * np.sin(2 * np.pi * 3.1 * t)
    trajectory = tmp_path / "trajectory.csv"
    trajectory.write_text(
        "".join(f"{a!r},{b!r}\n" for a, b in zip(t.tolist(), y_d.tolist(), strict=True))
    )
    out = tmp_path / "commands.csv"
    run = subprocess.run(
        [example, tmp_path / "ff.json", trajectory, out], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    cpp = np.loadtxt(out)
    python = ff.command(t, y_d)
    assert cpp.shape == python.shape
    assert np.ptp(python) > 0.5  # the trajectory exercises the compensator
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)


def test_cpp_encoder_loop_equals_python(example, tmp_path):
    """An EncoderLoop around an inverse of a Scaled model, given a motor encoder trajectory
    (with a dropout), gives Python's servo commands to 1e-12 in C++."""
    inner = InverseFeedforward(
        Scaled(BoucWenBacklash(B_r=0.08, B_l=0.05), input_offset=0.1, output_gain=1.2), 0.04
    )
    loop = EncoderLoop(inner, kp=1.3, ki=420.0, kd=0.002, max_correction=0.3, limits=(-2.0, 2.0))
    loop.to_json(tmp_path / "loop.json")
    t = np.arange(0.0, 3.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.5 * t)
    rng = np.random.default_rng(3)
    q = 0.9 * y_d + 0.05 * np.sin(2 * np.pi * 7.0 * t) + rng.normal(0.0, 1e-3, t.size)
    q[1500:1510] = np.nan  # an encoder dropout: the loop holds its correction
    rows = zip(t.tolist(), y_d.tolist(), q.tolist(), strict=True)
    (tmp_path / "trajectory.csv").write_text("".join(f"{a!r},{b!r},{c!r}\n" for a, b, c in rows))
    run = subprocess.run(
        [example, tmp_path / "loop.json", tmp_path / "trajectory.csv", tmp_path / "out.csv"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    loop.reset()
    dts = np.concatenate([[0.0], np.diff(t)])  # as the C++ loop computes them
    python = np.array([loop.step(a, b, dt) for a, b, dt in zip(y_d, q, dts, strict=True)])
    cpp = np.loadtxt(tmp_path / "out.csv")
    assert np.ptp(python - inner.command(t, y_d)) > 0.01  # the loop did correct
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)


def test_cpp_tip_loop_equals_python(example, tmp_path):
    """A TipLoop with a gain schedule around an inverse of a Scaled model, given a tip
    trajectory (with a dropout) and a curve angle that changes, gives Python's servo commands
    to 1e-12 in C++."""
    inner = InverseFeedforward(
        Scaled(BoucWenBacklash(B_r=0.08, B_l=0.05), input_offset=0.1, output_gain=1.2), 0.04
    )
    loop = TipLoop(
        inner,
        kp=0.8,
        ki=60.0,
        kd=0.002,
        max_correction=0.3,
        schedule=[(0.5, 0.6), (1.5, 1.0), (3.0, 2.5)],
        limits=(-2.0, 2.0, 40.0),
    )
    loop.to_json(tmp_path / "loop.json")
    t = np.arange(0.0, 3.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.5 * t)
    rng = np.random.default_rng(5)
    y = 0.85 * y_d + 0.05 * np.sin(2 * np.pi * 3.0 * t) + rng.normal(0.0, 1e-3, t.size)
    y[1500:1510] = np.nan  # a tip sensor dropout: back toward the feedforward
    angle = np.where(t < 1.0, 0.8, np.where(t < 2.0, 2.0, 3.5))  # the curve angle moves
    rows = zip(t.tolist(), y_d.tolist(), y.tolist(), angle.tolist(), strict=True)
    (tmp_path / "trajectory.csv").write_text(
        "".join(f"{a!r},{b!r},{c!r},{d!r}\n" for a, b, c, d in rows)
    )
    run = subprocess.run(
        [example, tmp_path / "loop.json", tmp_path / "trajectory.csv", tmp_path / "out.csv"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    loop.reset()
    dts = np.concatenate([[0.0], np.diff(t)])  # as the C++ loop computes them
    python = []
    for a, b, c, d in zip(y_d, y, angle, dts, strict=True):
        loop.set_curve_angle(c)
        python.append(loop.step(a, b, d))
    cpp = np.loadtxt(tmp_path / "out.csv")
    assert np.ptp(np.array(python) - inner.command(t, y_d)) > 0.01  # the loop did correct
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)


def _run_example(example, path, rows, tmp_path):
    (tmp_path / "trajectory.csv").write_text(
        "".join(",".join(repr(v) for v in row) + "\n" for row in rows)
    )
    run = subprocess.run(
        [example, path, tmp_path / "trajectory.csv", tmp_path / "out.csv"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    return np.loadtxt(tmp_path / "out.csv")


def test_cpp_learned_feedforward_equals_python(example, tmp_path):
    """A LearnedFeedforward (a random table, shorter than the trajectory, zero past its end)
    around an inverse of a Scaled model, and an EncoderLoop and a TipLoop around one (the loop
    correcting the corrected command): C++ gives Python's commands to 1e-12."""
    inner = InverseFeedforward(
        Scaled(Backlash(B_r=0.08, B_l=0.05), input_offset=0.1, output_gain=1.2), 0.04
    )
    rng = np.random.default_rng(5)
    table = np.cumsum(rng.normal(0.0, 0.005, 1100))  # 2.5 ms apart: to 2.75 s of 3 s
    learned = LearnedFeedforward(inner, table, 2.5e-3, hold_last=False, limits=(-1.5, 1.5, 30.0))
    learned.to_json(tmp_path / "learned.json")
    t = np.arange(0.0, 3.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.5 * t)
    cpp = _run_example(
        example, tmp_path / "learned.json", zip(t.tolist(), y_d.tolist(), strict=True), tmp_path
    )
    python = learned.command(t, y_d)
    assert np.ptp(python - inner.command(t, y_d)) > 0.05  # the table did correct
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)

    loop = EncoderLoop(learned, kp=0.5, ki=200.0, max_correction=0.3)
    loop.to_json(tmp_path / "loop.json")
    q = 0.9 * y_d + rng.normal(0.0, 1e-3, t.size)
    q[700:720] = np.nan
    cpp = _run_example(
        example,
        tmp_path / "loop.json",
        zip(t.tolist(), y_d.tolist(), q.tolist(), strict=True),
        tmp_path,
    )
    loop.reset()
    dts = np.concatenate([[0.0], np.diff(t)])
    python = np.array([loop.step(a, b, dt) for a, b, dt in zip(y_d, q, dts, strict=True)])
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)

    tip = TipLoop(learned, kp=0.5, ki=40.0, schedule=[(0.5, 0.8), (2.0, 1.5)])
    tip.to_json(tmp_path / "tip.json")
    y = 0.95 * y_d + rng.normal(0.0, 1e-3, t.size)
    y[900:910] = np.nan
    angle = np.where(t < 1.5, 1.0, 2.5)
    rows = zip(t.tolist(), y_d.tolist(), y.tolist(), angle.tolist(), strict=True)
    cpp = _run_example(example, tmp_path / "tip.json", rows, tmp_path)
    tip.reset()
    python = []
    for a, b, c, dt in zip(y_d, y, angle, dts, strict=True):
        tip.set_curve_angle(c)
        python.append(tip.step(a, b, dt))
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)


def test_cpp_rejects_a_bad_file_naming_the_key(example, tmp_path):
    text = InverseFeedforward(Backlash()).to_json().replace('"B_l"', '"B_left"')
    (tmp_path / "ff.json").write_text(text)
    run = subprocess.run([example, tmp_path / "ff.json"], capture_output=True, text=True)
    assert run.returncode == 2
    assert "unknown key 'B_left'" in run.stderr


def test_cpp_rejects_a_bad_tip_loop_schedule(example, tmp_path):
    data = TipLoop(InverseFeedforward(Backlash()), ki=10.0, schedule=[(0.0, 1.0)]).to_dict()
    for schedule, words in (
        ([[0.0, 1.0, 2.0]], "entry 0"),
        ([[1.0, 1.0], [0.5, 2.0]], "increasing"),
    ):
        (tmp_path / "loop.json").write_text(json.dumps({**data, "schedule": schedule}))
        trajectory = tmp_path / "trajectory.csv"
        trajectory.write_text("0.0,0.1,0.1\n")
        run = subprocess.run(
            [example, tmp_path / "loop.json", trajectory, tmp_path / "out.csv"],
            capture_output=True,
            text=True,
        )
        assert run.returncode == 2
        assert "schedule" in run.stderr and words in run.stderr
