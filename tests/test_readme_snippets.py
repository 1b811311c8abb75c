"""Every Python snippet of README.md runs as written (issue 17, item 3).

The snippets read top to bottom like one session: they run in order in one namespace, in a
temporary folder. What the README leaves to the reader (their data t, x, y, theta, the
desired trajectory, one control cycle's values, the file run.xlsx) is filled in by the
fixture below. A snippet with an ``if __name__ == "__main__":`` block is a script of its
own and runs as one, in a fresh interpreter, as a user would run it.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _snippets import MAIN_GUARD, python_blocks, run_as_script

import tendonsheath as ts

README = Path(__file__).resolve().parent.parent / "README.md"
# the only edits: run lengths (a sweep of 2 draws takes the same code path as 1000)
SHORTER = {"n=1000": "n=2"}


def python_snippets() -> list[str]:
    return python_blocks(README.read_text())


@pytest.fixture
def placeholders(tmp_path, monkeypatch):
    """The reader's own data: a logged run on the README's 10 s, 1 kHz grid (CurveAngleModel
    output with sensor noise at one curve angle), a desired trajectory, one control cycle,
    and run.xlsx (t, motor, tip in degrees, about 100 Hz, as Excel would hold it)."""
    monkeypatch.chdir(tmp_path)
    rng = np.random.default_rng(17)
    t = np.arange(0.0, 10.0, 1e-3)
    x = 0.8 * np.sin(2 * np.pi * 0.3 * t) * (1.0 - 0.4 * t / t[-1])
    theta = np.pi
    y = ts.models.CurveAngleModel().simulate(t, x, curve_angle=theta)
    y = y + 2e-4 * rng.standard_normal(t.size)
    ts_xlsx = np.arange(0.0, 12.0, 0.01) + 1e-4 * rng.standard_normal(1200)
    motor = np.sin(2 * np.pi * 0.25 * ts_xlsx)
    tip = ts.models.BoucWenBacklash(B_r=0.1, B_l=0.08).simulate(ts_xlsx, motor)
    frame = pd.DataFrame({"t": ts_xlsx, "motor": np.degrees(motor), "tip": np.degrees(tip)})
    frame.to_excel(tmp_path / "run.xlsx", index=False)
    _write_run_bag(tmp_path / "run", ts_xlsx, motor, tip)
    return {
        "t": t,
        "x": x,
        "y": y,
        "theta": theta,
        "y_desired": 0.5 * np.sin(2 * np.pi * 0.25 * t),
        "y_desired_k": 0.2,
        "dt": 1e-3,
        "y_measured_k": 0.19,
        "motor_position_k": 0.25,
    }


def _write_run_bag(path, t, motor, tip):
    """run.bag: the motor on a JointState topic, the tip on a PointStamped one (ROS 1)."""
    from _rosbag_helpers import EPOCH_NS, joint_state, point_stamped, write_bag

    ns = EPOCH_NS + np.round(np.sort(t - t.min()) * 1e9).astype(np.int64)
    write_bag(
        path,
        "ros1",
        {
            "/motor/joint_states": [
                (s, joint_state("ros1", s, [m])) for s, m in zip(ns, motor, strict=True)
            ],
            "/tip/point": [(s, point_stamped("ros1", s, y)) for s, y in zip(ns, tip, strict=True)],
        },
    )


def test_readme_has_its_snippets():
    snippets = python_snippets()
    assert len(snippets) >= 7
    assert sum(MAIN_GUARD in s for s in snippets) == 1  # the sweep


def test_every_readme_python_snippet_runs_as_written(placeholders, tmp_path):
    namespace = dict(placeholders)
    for i, code in enumerate(python_snippets()):
        if MAIN_GUARD in code:
            run_as_script(code, tmp_path / f"snippet_{i}.py", SHORTER, "README")
            continue
        exec(compile(code, f"README.md python snippet {i + 1}", "exec"), namespace)
    # what the snippets say they make
    assert (tmp_path / "fit.png").stat().st_size > 0
    assert (tmp_path / "compare-out" / "report.html").is_file()
    assert ts.load_model(tmp_path / "model.json") is not None
    assert namespace["bag_log"].y.size > 1000  # run.bag, read from its two topics
    assert np.isfinite(namespace["result"].metrics["rmse"])
    assert np.isfinite(namespace["tau"]) and np.isfinite(namespace["u_k"])
    assert (tmp_path / "sweep-out").is_dir()  # the sweep script's output
