"""`tendonsheath identify` and `predict` on ROS bags written by the tests (ROS 1, ROS 2 sqlite3
and MCAP): the motor angle on a JointState topic, the tip on a PointStamped topic at another
rate. Self-class data (a Backlash): it checks the plumbing from bag to fitted model."""

import json

import numpy as np
import pytest
from _rosbag_helpers import EPOCH_NS, KINDS, joint_state, point_stamped, write_bag
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app

runner = CliRunner()
B_R = 0.05
SIGNALS = ["--input", "/motor/joint_states:position[0]", "--output", "/tip/point:point.x"]


def _motor(ns):
    return np.sin(2 * np.pi * 0.5 * (ns - EPOCH_NS) * 1e-9)


def _run_bag(path, kind):
    in_ns = EPOCH_NS + np.arange(1500, dtype=np.int64) * 4_000_000  # 250 Hz commands
    out_ns = EPOCH_NS + 3_000_000 + np.arange(590, dtype=np.int64) * 10_000_000  # 100 Hz tip
    t_out = (out_ns - EPOCH_NS) * 1e-9
    tip = ts.models.Backlash(B_r=B_R).simulate(t_out, _motor(out_ns))
    topics = {
        "/motor/joint_states": [
            (s + 400_000, joint_state(kind, s, [_motor(s), 0.0])) for s in in_ns
        ],
        "/tip/point": [
            (s + 900_000, point_stamped(kind, s, y)) for s, y in zip(out_ns, tip, strict=True)
        ],
    }
    return write_bag(path, kind, topics)


@pytest.mark.parametrize("kind", KINDS)
def test_identify_then_predict_on_a_bag(tmp_path, kind):
    bag = _run_bag(tmp_path / "run", kind)
    model = tmp_path / "model.json"
    args = ["identify", str(bag), "--model", "Backlash", *SIGNALS, "--maxiter", "10"]
    result = runner.invoke(app, [*args, "-o", str(model)])
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "samples: the messages of /tip/point (the output)" in text
    assert "time of /tip/point: its header stamps" in text
    fitted = ts.load_model(model)
    # the input is interpolated at the tip's stamps: error <= h^2 w^2 / 8 = 2.5e-5 rad, far
    # below this margin on the half-width
    assert abs(fitted.params["B_r"] - B_R) < 1e-3
    assert json.loads(model.read_text())["data"]["input"] == "/motor/joint_states:position[0]"

    pred = tmp_path / "pred.csv"
    result = runner.invoke(app, ["predict", str(model), str(bag), "-o", str(pred)])
    assert result.exit_code == 0, result.output
    log = ts.io.read_log(
        pred, time="time", input="/motor/joint_states:position[0]", output="predicted"
    )
    np.testing.assert_allclose(log.t[1] - log.t[0], 0.01, atol=1e-6)
    assert "nrmse" in result.output


def test_a_missing_topic_is_one_line_through_the_command(tmp_path):
    bag = _run_bag(tmp_path / "run", "mcap")
    args = [
        "identify",
        str(bag),
        "--model",
        "Backlash",
        "--input",
        "/motor:x",
        "--output",
        "/tip/point:point.x",
        "-o",
        str(tmp_path / "m.json"),
    ]
    result = runner.invoke(app, args)
    assert result.exit_code == 2, result.output
    text = " ".join(result.output.split())
    assert (
        "no input topic '/motor'; topics: /motor/joint_states (sensor_msgs/msg/JointState" in text
    )
    assert "Traceback" not in result.output and not (tmp_path / "m.json").exists()


def test_compare_ranks_candidates_on_a_bag(tmp_path):
    bag = _run_bag(tmp_path / "run", "sqlite3")
    args = ["compare", str(bag), *SIGNALS, "--models", "backlash", "--maxiter", "5", "--quiet"]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "Backlash" in text and "samples: the messages of /tip/point" in text


@pytest.mark.parametrize("kind", KINDS)
def test_resample_a_bag_onto_a_uniform_grid(tmp_path, kind):
    log = ts.io.read_log(
        _run_bag(tmp_path / "run", kind),
        input="/motor/joint_states:position[0]",
        output="/tip/point:point.x",
        resample=50.0,
    )
    np.testing.assert_allclose(np.diff(log.t), 0.02, atol=1e-12)
    # the input is a 0.5 Hz sine (w = pi rad/s), interpolated twice: from the 4 ms commands
    # to the 10 ms tip stamps, then onto the 20 ms grid; each errs by at most h^2 w^2 / 8
    t_abs = log.t + 3e-3  # the tip's first stamp is 3 ms after the motor's
    bound = (0.004**2 + 0.01**2) * np.pi**2 / 8
    assert np.max(np.abs(log.x - np.sin(np.pi * t_abs))) <= bound
