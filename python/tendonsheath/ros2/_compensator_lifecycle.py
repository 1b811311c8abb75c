"""The compensator node's class (see :mod:`.compensator_node`), in a module of its own that
imports rclpy: :func:`~tendonsheath.ros2.compensator_node` imports it once the ros2 extra is
known to be installed."""

from __future__ import annotations

import math
import time
from collections import deque

import numpy as np
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray
from trajectory_msgs.msg import JointTrajectory

from ..status import Status
from ._messages import (
    COMMAND_TYPES,
    DESIRED_TYPES,
    Trajectory,
    by_name,
    declared,
    joint_state,
    stream_qos,
)
from .live_compensator import Limits, LiveCompensator

# the samples of period and compute time kept for timing() (about 3 min at 500 Hz)
TIMING_SAMPLES = 100_000


class CompensatorNode(LifecycleNode):
    """The compensator node (see the module)."""

    def __init__(self, compensator, name, context, values):
        super().__init__(name, context=context, **declared(values))
        self.compensator = compensator
        self.live: LiveCompensator | None = None
        self._timer = None
        self.periods: deque[float] = deque(maxlen=TIMING_SAMPLES)
        self.compute: deque[float] = deque(maxlen=TIMING_SAMPLES)
        self._subs: list = []
        self._pubs: list = []

    def param(self, key: str):
        return self.get_parameter(key).value

    # -- lifecycle -----------------------------------------------------------------
    def on_configure(self, state):
        try:
            self._configure()
        except (ValueError, TypeError) as exc:
            self.get_logger().error(f"configure failed: {exc}")
            return TransitionCallbackReturn.FAILURE
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state):
        assert self.live is not None
        self.live.reset()
        self._previous = None
        period = 1.0 / float(self.param("rate"))
        self._timer = self.create_timer(period, self._cycle)
        return super().on_activate(state)

    def on_deactivate(self, state):
        self._stop_timer()
        return super().on_deactivate(state)

    def on_cleanup(self, state):
        self._stop_timer()
        for sub in self._subs:
            self.destroy_subscription(sub)
        for pub in self._pubs:
            self.destroy_publisher(pub)
        self._subs, self._pubs, self.live = [], [], None
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state):
        self._stop_timer()
        return TransitionCallbackReturn.SUCCESS

    def _stop_timer(self):
        if self._timer is not None:
            self.destroy_timer(self._timer)
            self._timer = None

    def _configure(self):
        self.joints = [str(j) for j in self.param("joints")]
        rate = float(self.param("rate"))
        if not (math.isfinite(rate) and rate > 0):
            raise ValueError(f"rate must be > 0 Hz (got {rate:g})")
        for key, known in (("desired_type", DESIRED_TYPES), ("command_type", COMMAND_TYPES)):
            if self.param(key) not in known:
                raise ValueError(f"{key} must be one of {list(known)} (got {self.param(key)!r})")
        stop = float(self.param("stop_after"))
        limits = Limits(
            float(self.param("min_command")),
            float(self.param("max_command")),
            float(self.param("max_rate")),
        )
        self.live = LiveCompensator(
            self.compensator,
            joints=len(self.joints),
            stale_after=float(self.param("stale_after")),
            stop_after=stop if stop > 0 else math.inf,
            limits=limits,
        )
        if len(self.joints) != self.live.joints:
            self.joints = [f"joint{i}" for i in range(self.live.joints)]
        self.torque = getattr(self.compensator, "control_output", "x") == "torque"
        self._trajectory: Trajectory | None = None
        self._desired_stamp = None
        self._subscribe()
        kind = JointState if self.param("command_type") == "joint_state" else Float64MultiArray
        self._command_pub = self.create_publisher(kind, self.param("command_topic"), 10)
        self._diag_pub = self.create_publisher(DiagnosticArray, self.param("diagnostics_topic"), 10)
        self._pubs += [self._command_pub, self._diag_pub]

    def _subscribe(self):
        assert self.live is not None
        needs = self.live.inputs
        if self.param("desired_type") == "joint_trajectory":  # a plan, sent once: reliable
            self._sub(JointTrajectory, "desired_topic", self._on_trajectory, 10)
        else:
            self._sub(JointState, "desired_topic", self._on_desired)
        if "tip" in needs:
            self._sub(JointState, "tip_topic", lambda m: self._on_state("tip", m))
        if "motor" in needs or "load" in needs:
            self._sub(JointState, "motor_topic", self._on_motor)
        if "curve_angle" in needs:
            self._sub(Float64MultiArray, "curve_angle_topic", self._on_curve_angle)

    def _sub(self, kind, topic_key, callback, qos=None):
        qos = stream_qos() if qos is None else qos
        sub = self.create_subscription(kind, self.param(topic_key), callback, qos)
        self._subs.append(sub)

    # -- inputs ----------------------------------------------------------------------
    def _on_desired(self, msg):
        assert self.live is not None
        values = by_name(list(msg.name), msg.position, self.joints)
        self._desired_stamp = msg.header.stamp
        self.live.update("desired", values, time.monotonic())

    def _on_trajectory(self, msg):
        now = self.get_clock().now().nanoseconds * 1e-9
        self._trajectory = Trajectory(msg, self.joints, now)

    def _on_state(self, name, msg):
        assert self.live is not None
        self.live.update(name, by_name(list(msg.name), msg.position, self.joints), time.monotonic())

    def _on_motor(self, msg):
        assert self.live is not None
        now = time.monotonic()
        if "motor" in self.live.inputs:
            self.live.update("motor", by_name(list(msg.name), msg.position, self.joints), now)
        if "load" in self.live.inputs:
            self.live.update("load", by_name(list(msg.name), msg.effort, self.joints), now)

    def _on_curve_angle(self, msg):
        assert self.live is not None
        if len(msg.data):
            self.live.update("curve_angle", float(msg.data[0]), time.monotonic())

    # -- the cycle -----------------------------------------------------------------
    def _cycle(self):
        start = time.monotonic()
        dt = 0.0 if self._previous is None else start - self._previous
        if self._previous is not None:
            self.periods.append(dt)
        self._previous = start
        assert self.live is not None
        if self._trajectory is not None:
            values = self._trajectory.at(self.get_clock().now().nanoseconds * 1e-9)
            if np.any(np.isfinite(values)):
                self.live.update("desired", values, start)
        cycle = self.live.step(start, dt)
        stamp = self.get_clock().now().to_msg()
        if cycle.command is not None:
            self._publish_command(cycle.command, stamp)
        self.compute.append(time.monotonic() - start)
        self._publish_diagnostics(cycle, dt, stamp)

    def _publish_command(self, command, stamp):
        if self.param("command_type") == "float64_multi_array":
            msg = Float64MultiArray()
            msg.data = [float(c) for c in command]
        else:
            served = self._desired_stamp if self._desired_stamp is not None else stamp
            field = "effort" if self.torque else "position"
            msg = joint_state(JointState, self.joints, served, **{field: command})
        self._command_pub.publish(msg)

    def _publish_diagnostics(self, cycle, dt, stamp):
        status = DiagnosticStatus()
        status.name = self.get_name()
        status.hardware_id = type(self.compensator).__name__
        flags = [str(f.name).lower() for f in Status if f.value and cycle.status & f]
        if cycle.stopped:
            status.level, status.message = DiagnosticStatus.ERROR, "stopped: no desired input"
        elif cycle.stale or flags:
            status.level = DiagnosticStatus.WARN
            status.message = "; ".join(
                ([f"stale: {', '.join(cycle.stale)}"] if cycle.stale else []) + flags
            )
        else:
            status.level, status.message = DiagnosticStatus.OK, "ok"
        pairs = {
            "status": str(int(cycle.status)),
            "flags": ",".join(flags),
            "stale": ",".join(cycle.stale),
            "period_s": f"{dt:.6f}",
            "compute_s": f"{self.compute[-1]:.6f}" if self.compute else "nan",
        }
        status.values = [KeyValue(key=k, value=v) for k, v in pairs.items()]
        msg = DiagnosticArray()
        msg.header.stamp = stamp
        msg.status = [status]
        self._diag_pub.publish(msg)

    def timing(self) -> dict[str, np.ndarray]:
        return {"period": np.array(self.periods), "compute": np.array(self.compute)}
