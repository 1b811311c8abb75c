"""The stepping behind the ROS 2 nodes, without ROS (issue 20): a LiveCompensator and a
LivePlant stepped in lockstep are bench.run's loop, every saved kind is driven from its
inputs, and a stale input is handled as the compensator's status says."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.ros2 import Limits, LiveCompensator, LivePlant, needed_inputs, plant_source
from tendonsheath.status import Status

MEMBER = 3


def _feedforward(draw):
    g = 1.0 / draw.kinematic_gain
    return ts.compensate.InverseFeedforward(ts.models.Backlash(c_r=g, c_l=g, B_r=0.05, B_l=0.05))


def _lockstep(compensator, draw, t, y_d):
    """The live loop at a fixed dt: the compensator takes the readings of the previous step,
    as bench.run's controller does."""
    live = LiveCompensator(compensator)
    plant = LivePlant(draw.plant(), draw.tip_sensor(0.004, 1))
    out = np.empty(t.size)
    for k, tk in enumerate(t):
        dt = float(t[k] - t[k - 1]) if k else 0.0
        live.update("desired", y_d[k], tk)
        live.update("tip", plant.reading.tip, tk)  # the rest's reading at k = 0
        live.update("motor", plant.reading.motor, tk)
        cycle = live.step(tk, dt)
        out[k] = plant.step(cycle.command[0], dt).output
    return out


@pytest.mark.parametrize("kind", ["feedforward", "tip_loop", "encoder_loop"])
def test_the_live_loop_in_lockstep_is_bench_run(kind):
    draw = ts.presets.random_realistic_plant(MEMBER)
    ff = _feedforward(draw)
    compensator = {
        "feedforward": ff,
        "tip_loop": ts.compensate.TipLoop(ff, kp=0.3, ki=8.0),
        "encoder_loop": ts.compensate.EncoderLoop(ff, ki=20.0),
    }[kind]
    t = np.arange(0.0, 2.0, 0.005)
    y_d = 0.3 * np.sin(2 * np.pi * 0.7 * t)
    bench = ts.bench.run(draw.plant(), compensator, t, y_d, noise=draw.tip_sensor(0.004, 1))
    live = _lockstep(ts.compensate.load(compensator.to_json()), draw, t, y_d)
    # the same C++ cores in the same order: equal to rounding (measured 7e-14 rad)
    assert np.max(np.abs(live - bench.output)) < 1e-9
    assert bench.metrics["rmse"] < 0.2 * np.std(y_d)  # and the loop does track


def test_every_saved_kind_is_stepped_from_its_inputs():
    base = ts.models.Backlash(c_r=1.0, c_l=1.0, B_r=0.05, B_l=0.05)
    ff = ts.compensate.InverseFeedforward(base)
    coupled = ts.compensate.CoupledFeedforward(
        ts.models.Coupled([base, base], [[0.0, 0.1], [0.0, 0.0]])
    )
    loaded = ts.compensate.LoadCompensated(ts.models.Loaded(base, gain=0.01))
    curve = ts.compensate.CurveAngleFeedforward(
        friction=0.1, stiffness=2e4, length=1.0, pretension=20.0
    )
    cases = {
        ff: ("desired",),
        ts.compensate.TipLoop(ff, kp=0.5): ("desired", "tip"),
        ts.compensate.EncoderLoop(ff): ("desired", "motor"),
        loaded: ("desired", "load"),
        curve: ("desired", "curve_angle"),
        coupled: ("desired",),
    }
    for compensator, inputs in cases.items():
        saved = ts.compensate.load(compensator.to_json())
        assert needed_inputs(saved) == inputs, type(compensator).__name__
        joints = 2 if compensator is coupled else 1
        live = LiveCompensator(saved, joints=joints)
        for name in inputs:
            live.update(name, [0.2] * joints if name != "curve_angle" else 1.0, 0.0)
        cycle = live.step(0.0, 0.0)
        for name in inputs:
            live.update(name, [0.25] * joints if name != "curve_angle" else 1.0, 0.01)
        cycle = live.step(0.01, 0.01)
        assert cycle.command.shape == (joints,) and np.all(np.isfinite(cycle.command))
        assert not cycle.stale and not cycle.stopped


def test_a_load_moves_the_loadcompensated_command():
    base = ts.models.Backlash(c_r=1.0, c_l=1.0, B_r=0.05, B_l=0.05)
    live = LiveCompensator(ts.compensate.LoadCompensated(ts.models.Loaded(base, gain=0.01)))
    commands = []
    for load in (0.0, 10.0):
        live.reset()
        live.update("desired", 0.3, 0.0)
        live.update("load", load, 0.0)
        commands.append(live.step(0.0, 0.0).command[0])
    # y = base(x) + gain * load: the command falls by gain * load / c = 0.1
    assert commands[0] - commands[1] == pytest.approx(0.1, abs=1e-9)


def test_a_stale_desired_holds_and_a_long_one_stops():
    live = LiveCompensator(ts.compensate.InverseFeedforward(ts.models.Backlash()), stop_after=0.5)
    assert live.step(0.0, 0.0).stopped  # nothing received yet: no command
    live.update("desired", 0.3, 0.0)
    held = live.step(0.0, 0.0).command[0]
    cycle = live.step(0.2, 0.2)  # 0.2 s > stale_after: NaN to the feedforward, which holds
    assert cycle.stale == ("desired",) and cycle.status & Status.HELD_NONFINITE_INPUT
    assert cycle.command[0] == held
    assert live.step(0.6, 0.4).stopped  # past stop_after
    live.update("desired", 0.1, 0.7)
    assert not live.step(0.7, 0.1).stopped  # a fresh one: back


def test_a_stale_tip_makes_the_tip_loop_fall_back():
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash())
    live = LiveCompensator(ts.compensate.TipLoop(ff, kp=0.5, ki=5.0))
    live.update("desired", 0.2, 0.0)
    live.update("tip", 0.1, 0.0)
    assert not live.step(0.0, 0.0).status & Status.FALLBACK
    live.update("desired", 0.2, 0.1)
    cycle = live.step(0.1, 0.1)
    assert cycle.stale == ("tip",) and cycle.status & Status.FALLBACK
    assert np.isfinite(cycle.command[0])


def test_the_loop_limits_cut_and_say_so():
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash())
    live = LiveCompensator(ff, limits=Limits(-0.2, 0.2, max_rate=1.0))
    live.update("desired", 0.1, 0.0)
    first = live.step(0.0, 0.0)
    assert first.status == Status.OK
    live.update("desired", 1.0, 0.01)
    cycle = live.step(0.01, 0.01)  # the rate limit: 0.01 rad from the last command
    assert cycle.status & Status.SATURATED
    assert cycle.command[0] == pytest.approx(first.command[0] + 0.01)
    live.update("desired", 5.0, 1.0)
    assert live.step(1.0, 1.0).command[0] == 0.2  # the range
    with pytest.raises(ValueError, match="minimum"):
        Limits(1.0, 0.0)


def test_bad_joints_and_inputs_are_one_line_errors():
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash())
    with pytest.raises(ValueError, match="drives one joint"):
        LiveCompensator(ff, joints=2)
    with pytest.raises(ValueError, match="unknown input"):
        LiveCompensator(ff).update("speed", 1.0, 0.0)


def test_the_plant_sources_and_route_changes():
    plant = plant_source(preset="realistic", noise=0.001, latency=0.01)
    readings = [plant.step(0.3, 0.002) for _ in range(200)]
    assert readings[-1].output > 0.05 and math.isfinite(readings[-1].load)
    plant.set_route(math.pi)  # a bend of 180 degrees: more friction, less output
    assert plant.plant.route.curve_angle == pytest.approx(math.pi)
    with pytest.raises(ValueError, match="curve angle"):
        plant.set_route(-1.0)
    with pytest.raises(ValueError, match="one plant source"):
        plant_source(preset="realistic", member=3)
    with pytest.raises(ValueError, match="unknown plant preset"):
        plant_source(preset="nope")
    member = plant_source(member=MEMBER, torque=True)
    assert member.plant.motor.kind == "torque"


def test_without_the_extra_the_commands_say_so_in_one_line(monkeypatch, tmp_path):
    import subprocess
    import sys

    from typer.testing import CliRunner

    from tendonsheath.apps.cli import app

    # importing the package (and tendonsheath.ros2) loads no rclpy
    code = "import sys, tendonsheath.ros2, tendonsheath.apps.cli; print('rclpy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
    monkeypatch.setitem(sys.modules, "rclpy", None)  # import rclpy: ImportError
    path = tmp_path / "ff.json"
    ts.compensate.InverseFeedforward(ts.models.Backlash()).to_json(path)
    for args in (["plant"], ["compensate", str(path)], ["reference"], ["record", "bag"]):
        result = CliRunner().invoke(app, ["ros2", *args])
        assert result.exit_code == 2, result.output
        assert result.output.strip() == (
            "error: tendonsheath ros2 (its nodes) needs rclpy: pip install 'tendonsheath[ros2]'"
        )
