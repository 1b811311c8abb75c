"""The ROS 2 nodes over DDS on this machine (issue 20): the plant, compensator and reference
nodes as `tendonsheath ros2` processes closing the loop, checked against bench.run; a killed
reference makes the compensator hold and report, not crash; the lifecycle arms it; the
trajectory and array conventions; the live loop's bag read back by read_log.

Each test has its own ROS_DOMAIN_ID (from the xdist worker) and discovery stays on this
host, so parallel workers never hear each other.
"""

import math
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from diagnostic_msgs.msg import DiagnosticArray  # the ros2 extra: the test extra has it
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

import tendonsheath as ts
from tendonsheath.ros2 import _env, compensator_node, plant_source, reference_node, sine
from tendonsheath.ros2.recorder import BagRecorder

MEMBER = 3
RATE = 200.0  # Hz: the compensator's, the plant's and the reference's
AMPLITUDE, FREQUENCY = 0.3, 0.5


def _domain(offset: int) -> int:
    worker = os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw")
    return 20 + 4 * (int(worker) if worker.isdigit() else 0) + offset


def _feedforward():
    g = 1.0 / ts.presets.random_realistic_plant(MEMBER).kinematic_gain
    return ts.compensate.InverseFeedforward(ts.models.Backlash(c_r=g, c_l=g, B_r=0.05, B_l=0.05))


def _spin(executor, seconds, until=None):
    end = time.monotonic() + seconds
    while time.monotonic() < end and not (until and until()):
        executor.spin_once(timeout_sec=0.01)


class _Observer:
    """Records what the loop publishes, each with its stamp and its receive time."""

    def __init__(self, context, command_type=JointState, desired=True):
        self.node = Node("observer", context=context)
        self.desired, self.output, self.command, self.diagnostics = [], [], [], []

        def stamped(into):
            def take(msg):
                s = msg.header.stamp
                into.append((s.sec + 1e-9 * s.nanosec, msg.position[0], time.time()))

            return take

        if desired:
            self.node.create_subscription(JointState, "desired", stamped(self.desired), 100)
        self.node.create_subscription(JointState, "output_truth", self._truth, 100)
        take = stamped(self.command) if command_type is JointState else self._array
        self.node.create_subscription(command_type, "command", take, 100)
        self.node.create_subscription(
            DiagnosticArray, "diagnostics", lambda m: self.diagnostics.append(m.status[0]), 100
        )

    def _truth(self, msg):
        """(stamp, true output, the command the plant held over that tick)."""
        s = msg.header.stamp
        self.output.append((s.sec + 1e-9 * s.nanosec, msg.position[0], msg.effort[0]))

    def _array(self, msg):
        self.command.append((math.nan, list(msg.data), time.time()))


def _cli(*args, domain):
    env = {**os.environ, "ROS_DOMAIN_ID": str(domain), "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
    cmd = [sys.executable, "-m", "tendonsheath", "ros2", *args]
    return subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)


@pytest.fixture
def context(monkeypatch):
    """An rclpy context of the worker's second domain (the subprocess test has the first),
    discovery on this host only; the tests of a worker run one after the other."""
    monkeypatch.setenv("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    ctx = _env.init(domain_id=_domain(1))
    yield ctx
    if ctx.ok():
        ctx.shutdown()


def test_the_live_loop_tracks_as_bench_run_and_holds_when_the_reference_dies(tmp_path, monkeypatch):
    domain = _domain(0)
    path = tmp_path / "ff.json"
    _feedforward().to_json(path)
    rate = f"{RATE:g}"
    procs = {
        "plant": _cli("plant", "--member", str(MEMBER), "--rate", rate, domain=domain),
        "compensate": _cli("compensate", str(path), "--rate", rate, domain=domain),
    }
    monkeypatch.setenv("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")  # this process's too
    ctx = _env.init(domain_id=domain)
    try:
        obs = _Observer(ctx)
        executor = SingleThreadedExecutor(context=ctx)
        executor.add_node(obs.node)
        # the reference starts once both nodes run, at sin(0) = 0 as bench.run's does
        _spin(executor, 40.0, until=lambda: obs.output and obs.diagnostics)
        assert obs.output and obs.diagnostics, "no node within 40 s: " + _outputs(procs)
        procs["reference"] = _cli(
            "reference",
            "--amplitude",
            str(AMPLITUDE),
            "--frequency",
            str(FREQUENCY),
            "--rate",
            rate,
            domain=domain,
        )
        # DDS discovery: the compensator may hear the reference seconds before this observer
        # does (measured: up to 2.7 s after the first command); scoring before the observer
        # hears the desired trajectory would hold its first sample as the reference
        _spin(executor, 40.0, until=lambda: obs.command and obs.desired)
        assert obs.command and obs.desired, "no command within 40 s: " + _outputs(procs)
        start = time.time()
        _spin(executor, 4.0)
        killed = time.time()
        procs["reference"].send_signal(signal.SIGKILL)
        # the observer may lag the loop on a loaded machine: until the report, then 0.5 s
        _spin(executor, 10.0, until=lambda: _stale_reports(obs))
        _spin(executor, 0.5)
        alive = procs["compensate"].poll() is None
    finally:
        for p in procs.values():
            p.send_signal(signal.SIGINT)
        for p in procs.values():
            p.wait(timeout=20)
        ctx.shutdown()
    assert alive, _outputs(procs)
    _check_tracking(obs, start + 1.0, killed)
    _check_hold(obs, killed)


def _check_tracking(obs, begin, end):
    """The live loop's tracking against bench.run's on the same plant and compensator, and
    what the loop's timing explains of the difference: the same plant replayed offline over
    the live ticks (their times, a tick late on a loaded machine included) with, at each
    tick, the command the plant node held over it (it publishes it with the tick) reproduces
    the live output. So the live loop is bench.run's loop but for its timing (latency,
    jitter, stalls), which the replay measures."""
    desired = np.array([(s, v) for s, v, _ in obs.desired])
    ticks = np.array(sorted(obs.output))  # (stamp, true output, the command held)
    scored = (ticks[:, 0] >= begin) & (ticks[:, 0] <= end - 0.1)
    # the reference is interpolated between desired samples the observer heard, never held
    # past their ends, and never across more than 0.1 s (a chord of the 0.5 Hz sine errs by
    # at most 4 mrad there)
    heard = desired[:, 0]
    assert heard[0] <= ticks[scored, 0][0] and ticks[scored, 0][-1] <= heard[-1]
    inside = (heard >= begin - 0.1) & (heard <= end)
    assert np.diff(heard[inside]).max() < 0.1, "the observer missed desired samples"
    reference = np.interp(ticks[scored, 0], desired[:, 0], desired[:, 1])
    live = float(np.sqrt(np.mean((ticks[scored, 1] - reference) ** 2)))
    replay = _replay(ticks[:, 0], ticks[:, 2])[scored]
    gap = float(np.sqrt(np.mean((ticks[scored, 1] - replay) ** 2)))
    draw = ts.presets.random_realistic_plant(MEMBER)
    t = np.arange(0.0, 5.0, 1.0 / RATE)  # as the live run: 1 s of warm-up, 4 s scored
    y_d = AMPLITUDE * np.sin(2 * np.pi * FREQUENCY * t)
    bench = ts.bench.run(draw.plant(), _feedforward(), t, y_d, noise=draw.tip_sensor(), warmup=1.0)
    # the plant node publishes each tick's command, so the replay is the node's own loop
    # but for a tick the observer missed (the replay then steps two ticks as one: a
    # longer dt) and the tick times, stamped after the step: measured gap 0.03 mrad (quiet,
    # and with three busy loops beside it on 2 cores) against a live error of 2 to 8 mrad
    # quiet, 5 to 9 mrad beside two busy loops on 2 cores (bench's: 1.0 mrad: the timing of
    # three processes at 200 Hz adds the rest)
    assert gap <= 0.05 * live + 0.2e-3, (gap, live, bench.metrics["rmse"])
    # the loop tracks: a hold errs by 0.7 x the amplitude (rms), a wrong sign by 1.4 x, a
    # command 68 ms late by 0.15 x: 5 x the worst live error measured
    assert live < 0.15 * AMPLITUDE, (live, bench.metrics["rmse"])


def _replay(stamps, commands):
    """The member's plant stepped over the live ticks (``stamps``) with the command the plant
    node held over each (as it published it), as the node steps it: its true output."""
    plant = plant_source(member=MEMBER)
    out, previous = [], stamps[0] - 1.0 / RATE
    for stamp, command in zip(stamps, commands, strict=True):
        out.append(plant.step(command, stamp - previous).output)
        previous = stamp
    return np.array(out)


def _stale_reports(obs):
    return [d for d in obs.diagnostics if d.message.startswith("stale: desired")]


def _check_hold(obs, killed):
    after = _stale_reports(obs)
    assert len(after) > 0.5 * RATE * 0.3, "the compensator did not report the stale input"
    values = {kv.key: kv.value for kv in after[-1].values}
    assert "held_nonfinite_input" in values["flags"] and values["stale"] == "desired"
    held = [v for _, v, r in obs.command if r > killed + 0.2][-int(0.2 * RATE) :]
    assert held and np.ptp(held) == 0.0  # the command held at one value


def _outputs(procs):
    out = []
    for name, p in procs.items():
        if p.poll() is not None and p.stdout is not None:
            out.append(f"{name} (exit {p.returncode}): {p.stdout.read().decode()[-500:]}")
    return "; ".join(out)


def test_the_lifecycle_arms_the_compensator(context):
    node = compensator_node(_feedforward(), context=context, parameters={"rate": RATE})
    ref = reference_node(sine(0.2, 1.0), rate=RATE, context=context)
    obs = _Observer(context)
    executor = SingleThreadedExecutor(context=context)
    for n in (node, ref, obs.node):
        executor.add_node(n)
    _spin(executor, 0.5)
    assert obs.command == [] and obs.desired  # unconfigured: it hears nothing, says nothing
    node.trigger_configure()
    _spin(executor, 0.3)
    assert obs.command == []  # configured, inactive
    node.trigger_activate()
    _spin(executor, 1.0, until=lambda: len(obs.command) > 20)
    assert len(obs.command) > 20
    node.trigger_deactivate()
    _spin(executor, 0.1)
    count = len(obs.command)
    _spin(executor, 0.3)
    assert len(obs.command) == count  # deactivated: silent
    timing = node.timing()
    assert timing["period"].size > 10 and np.all(timing["compute"] > 0)


def test_a_bad_parameter_fails_the_configure(context):
    node = compensator_node(_feedforward(), context=context, parameters={"command_type": "x"})
    node.trigger_configure()
    assert node.live is None
    with pytest.raises(ValueError, match="unknown compensator node parameter"):
        compensator_node(_feedforward(), context=context, parameters={"speed": 1.0})


def test_a_trajectory_in_and_an_array_out_for_two_joints(context):
    base = ts.models.Backlash(c_r=1.0, c_l=1.0, B_r=0.05, B_l=0.05)
    coupled = ts.compensate.CoupledFeedforward(
        ts.models.Coupled([base, base], [[0.0, 0.1], [0.0, 0.0]])
    )
    params = {
        "joints": ["a", "b"],
        "desired_type": "joint_trajectory",
        "command_type": "float64_multi_array",
        "rate": RATE,
    }
    node = compensator_node(coupled, context=context, parameters=params)
    obs = _Observer(context, command_type=Float64MultiArray, desired=False)
    pub = obs.node.create_publisher(JointTrajectory, "desired", 10)
    executor = SingleThreadedExecutor(context=context)
    for n in (node, obs.node):
        executor.add_node(n)
    node.trigger_configure()
    node.trigger_activate()
    msg = JointTrajectory()
    msg.joint_names = ["b", "a"]  # the other order: looked up by name
    for t, (b, a) in ((0.0, (0.0, 0.0)), (0.2, (0.1, 0.3))):
        point = JointTrajectoryPoint(positions=[b, a])
        point.time_from_start.nanosec = int(t * 1e9)
        msg.points.append(point)
    _spin(
        executor,
        1.0,
        until=lambda: node.count_subscribers("desired") and pub.get_subscription_count(),
    )
    pub.publish(msg)
    _spin(executor, 0.6)  # past the trajectory's end: its last point held
    last = np.array(obs.command[-1][1])
    coupled.reset()
    expected = coupled.command([0.0, 0.2, 0.4], [[0.0, 0.0], [0.3, 0.1], [0.3, 0.1]]).output[-1]
    np.testing.assert_allclose(last, expected, atol=1e-12)


def test_the_recorded_loop_reads_back(context, tmp_path):
    plant = plant_source(member=MEMBER)
    from tendonsheath.ros2 import plant_node

    nodes = [
        compensator_node(_feedforward(), context=context, parameters={"rate": RATE}),
        plant_node(plant, context=context, parameters={"rate": RATE}),
        reference_node(sine(AMPLITUDE, FREQUENCY), rate=RATE, context=context),
    ]
    recorder = BagRecorder(tmp_path / "bag", context=context)
    executor = SingleThreadedExecutor(context=context)
    for n in (*nodes, recorder.node):
        executor.add_node(n)
    nodes[0].trigger_configure()
    nodes[0].trigger_activate()
    _spin(executor, 2.0)
    recorder.close()
    log = ts.io.read_log(
        tmp_path / "bag", input="/command:position[joint0]", output="/tip_state:position[joint0]"
    )
    assert log.t.size > 0.5 * RATE * 1.5 and recorder.counts["command"] > 0.5 * RATE * 1.5
    # the tip follows the command through the drive: the same sign, most of the swing
    assert np.corrcoef(log.x, log.y)[0, 1] > 0.9
