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
from rclpy.qos import QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

import tendonsheath as ts
from tendonsheath.ros2 import _env, compensator_node, plant_source, reference_node, sine
from tendonsheath.ros2._messages import joint_state
from tendonsheath.ros2.recorder import BagRecorder

MEMBER = 3
RATE = 200.0  # Hz: the compensator's, the plant's and the reference's
AMPLITUDE, FREQUENCY = 0.3, 0.5
# the observer's: best effort (it hears every publisher, and a lost sample does not hold back
# the rest), 100 deep so a busy observer drops none of the 200 Hz streams
OBSERVED = QoSProfile(depth=100, reliability=ReliabilityPolicy.BEST_EFFORT)


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
            self.node.create_subscription(JointState, "desired", stamped(self.desired), OBSERVED)
        self.node.create_subscription(JointState, "output_truth", self._truth, OBSERVED)
        take = stamped(self.command) if command_type is JointState else self._array
        self.node.create_subscription(command_type, "command", take, OBSERVED)
        self.node.create_subscription(
            DiagnosticArray, "diagnostics", lambda m: self.diagnostics.append(m.status[0]), OBSERVED
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
        # does (measured: up to 2.7 s after the first command)
        _spin(executor, 40.0, until=lambda: obs.command and obs.desired)
        assert obs.command and obs.desired, "no command within 40 s: " + _outputs(procs)
        # a node left running on this domain by an earlier run would mix its ticks in
        for topic in ("output_truth", "command", "desired"):
            assert obs.node.count_publishers(topic) == 1, f"another node publishes {topic}"
        start = time.time()
        _spin(executor, 4.0)
        killed = time.time()
        procs["reference"].send_signal(signal.SIGKILL)
        # the observer may lag the loop on a loaded machine: until the report, then 0.5 s
        _spin(executor, 10.0, until=lambda: _stale_reports(obs))
        _spin(executor, 0.5)
        alive = procs["compensate"].poll() is None
    finally:
        stuck = _stop(procs)
        ctx.shutdown()
    assert not stuck, f"{stuck} did not stop within 20 s of Ctrl-C"
    assert alive, _outputs(procs)
    _check_tracking(obs, start + 1.0, killed)
    _check_hold(obs, killed)


def _stop(procs):
    """Ctrl-C every node; kill one that does not stop within 20 s (none is left running to
    talk on the next run's domain). The names of those killed."""
    for p in procs.values():
        p.send_signal(signal.SIGINT)
    stuck = []
    for name, p in procs.items():
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()
            stuck.append(name)
    return stuck


def _check_tracking(obs, begin, end):
    """The live loop's tracking against bench.run's on the same plant and compensator, and
    what the loop's timing explains of the difference: the same plant replayed offline over
    the live ticks (their times, a tick late on a loaded machine included) with, at each
    tick, the command the plant node held over it (it publishes it with the tick) reproduces
    the live output. So the live loop is bench.run's loop but for its timing (latency,
    jitter, stalls), which the replay measures."""
    ticks = np.array(sorted(obs.output))  # (stamp, true output, the command held)
    scored = (ticks[:, 0] >= begin) & (ticks[:, 0] <= end - 0.1)
    reference = _heard_sine(obs.desired)(ticks[scored, 0])
    live = float(np.sqrt(np.mean((ticks[scored, 1] - reference) ** 2)))
    judged = scored & _settled(ticks[:, 0])
    assert judged.sum() > 0.5 * scored.sum(), "the observer missed most of the ticks"
    replay = _replay(ticks[:, 0], ticks[:, 2])
    gap = float(np.sqrt(np.mean((ticks[judged, 1] - replay[judged]) ** 2)))
    draw = ts.presets.random_realistic_plant(MEMBER)
    t = np.arange(0.0, 5.0, 1.0 / RATE)  # as the live run: 1 s of warm-up, 4 s scored
    y_d = AMPLITUDE * np.sin(2 * np.pi * FREQUENCY * t)
    bench = ts.bench.run(draw.plant(), _feedforward(), t, y_d, noise=draw.tip_sensor(), warmup=1.0)
    # the plant node publishes each tick's command, stamped with the tick's instant, so the
    # replay is the node's own loop but for a tick the observer missed (the replay then
    # steps two ticks as one: a longer dt; past a longer hole it is judged once settled):
    # measured gap 0 to 0.03 mrad (quiet, and beside a pytest run on 2 cores; it was up to
    # 0.8 mrad when the stamp was read after the step) against a live error of 2 to 10 mrad
    # (bench's: 1.0 mrad: the timing of three processes at 200 Hz adds the rest)
    assert gap <= 0.05 * live + 0.2e-3, (gap, live, bench.metrics["rmse"])
    # the loop tracks: a hold errs by 0.7 x the amplitude (rms), a wrong sign by 1.4 x, a
    # command 95 ms late by 0.3 x. Measured: 2 to 11 mrad; but twice in about 70 runs the
    # plant heard no command for 0.33 s (best-effort and reliable subscriptions alike, the
    # plant ticking on), which inside the scored window adds about 50 mrad
    assert live < 0.3 * AMPLITUDE, (live, bench.metrics["rmse"])


def _settled(stamps):
    """The ticks 0.2 s or more past any hole of two ticks or more in what the observer heard
    (a lost sample, or the stream frozen for 0.33 s as seen on CI). The replay steps a hole
    as one tick with one command, so its state differs from the plant's for a while after
    it: measured, back to 2e-5 rad within 0.2 s of a 0.33 s hole."""
    holes = stamps[1:][np.diff(stamps) > 2.5 / RATE]
    after = stamps[:, None] - holes[None, :]
    return ~np.any((after >= 0.0) & (after < 0.2), axis=1)


def _heard_sine(desired):
    """The reference node's sine, fitted to the desired samples the observer heard (stamp,
    value): its value at any time, whether or not the observer heard a sample near it (the
    observer's streams freeze now and then: a 0.32 s gap on CI). The samples must lie on a
    sine of the set amplitude and frequency to 0.5 mrad (measured: under 0.05 mrad)."""
    stamps = np.array([s for s, _, _ in desired])
    values = np.array([v for _, v, _ in desired])
    w, origin = 2 * np.pi * FREQUENCY, stamps[0]

    def basis(t):
        return np.column_stack([np.sin(w * (t - origin)), np.cos(w * (t - origin))])

    coef, *_ = np.linalg.lstsq(basis(stamps), values, rcond=None)
    residual = float(np.sqrt(np.mean((basis(stamps) @ coef - values) ** 2)))
    assert stamps.size > 0.5 * RATE and residual < 0.5e-3, (stamps.size, residual)
    assert abs(np.hypot(*coef) - AMPLITUDE) < 1e-3, coef
    return lambda t: basis(t) @ coef


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


def test_best_effort_streams_are_heard(context):
    """A robot that publishes its streams best effort (as many drivers do) is heard: the
    compensator commands from a best-effort ``desired``, the plant holds a best-effort
    ``command``. A reliable subscriber would match neither publisher."""
    from rclpy.qos import qos_profile_sensor_data

    from tendonsheath.ros2 import plant_node

    node = compensator_node(_feedforward(), context=context, parameters={"rate": RATE})
    plant = plant_node(
        plant_source(member=MEMBER),
        context=context,
        parameters={"rate": RATE, "command_topic": "robot_command"},
    )
    obs = _Observer(context, desired=False)
    robot = Node("robot", context=context)
    desired = robot.create_publisher(JointState, "desired", qos_profile_sensor_data)
    command = robot.create_publisher(JointState, "robot_command", qos_profile_sensor_data)

    def publish():
        stamp = robot.get_clock().now().to_msg()
        desired.publish(joint_state(JointState, ["joint0"], stamp, position=[0.1]))
        command.publish(joint_state(JointState, ["joint0"], stamp, position=[0.2]))

    robot.create_timer(1.0 / RATE, publish)
    executor = SingleThreadedExecutor(context=context)
    for n in (node, plant, obs.node, robot):
        executor.add_node(n)
    node.trigger_configure()
    node.trigger_activate()
    _spin(executor, 5.0, until=lambda: obs.command and obs.output and obs.output[-1][2] == 0.2)
    assert obs.command, "the compensator did not hear a best-effort desired"
    assert obs.output and obs.output[-1][2] == 0.2, "the plant did not hear a best-effort command"


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
