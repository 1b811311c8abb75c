"""Values in and out of the messages, by joint name: JointState, JointTrajectory and
Float64MultiArray (imported with the node, never at ``import tendonsheath``)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

#: The message conventions a node takes in and sends out.
DESIRED_TYPES = ("joint_state", "joint_trajectory")
COMMAND_TYPES = ("joint_state", "float64_multi_array")


def declared(values: dict[str, Any]) -> dict[str, Any]:
    """A node's keyword arguments that declare ``values`` as its ROS parameters (the
    defaults, which a launch file or ``--ros-args -p`` overrides)."""
    from rclpy.parameter import Parameter

    return {
        "parameter_overrides": [Parameter(k, value=v) for k, v in values.items()],
        "automatically_declare_parameters_from_overrides": True,
    }


def stream_qos() -> Any:
    """The QoS a node subscribes to a stream with (a sample each cycle: desired positions,
    sensor states, commands): best effort, keep last 5, rclpy's sensor-data profile.

    A best-effort reader hears reliable and best-effort publishers alike (many robot drivers
    publish their states best effort; a reliable reader does not match them), and each
    cycle wants the newest sample: one lost in transport is superseded by the next, never
    repaired late."""
    from rclpy.qos import qos_profile_sensor_data

    return qos_profile_sensor_data


def stamp_seconds(stamp: Any) -> float:
    """A builtin_interfaces/Time in seconds."""
    return float(stamp.sec) + 1e-9 * float(stamp.nanosec)


def by_name(names: list[str], values: Any, joints: list[str]) -> np.ndarray:
    """``values`` listed beside ``names``, picked in the order of ``joints`` (NaN for a joint
    the message lacks)."""
    out = np.full(len(joints), math.nan)
    values = list(values)
    if len(values) != len(names):
        return out
    where = {n: i for i, n in enumerate(names)}
    for j, joint in enumerate(joints):
        i = where.get(joint)
        if i is not None:
            out[j] = float(values[i])
    return out


def joint_state(msg_type: Any, joints: list[str], stamp: Any, **fields: Any) -> Any:
    """A JointState of ``joints`` with ``fields`` (position, velocity, effort) filled."""
    msg = msg_type()
    msg.header.stamp = stamp
    msg.name = list(joints)
    for key, values in fields.items():
        setattr(msg, key, [float(v) for v in values])
    return msg


class Trajectory:
    """The last JointTrajectory received: its points' positions over time, linearly
    interpolated, held at its last point after its end (as a trajectory controller holds)."""

    def __init__(self, msg: Any, joints: list[str], received: float):
        header = stamp_seconds(msg.header.stamp)
        # a zero stamp means "start now" (trajectory_msgs' convention)
        self.start = received if header == 0.0 else header
        self.times = np.array([stamp_seconds(p.time_from_start) for p in msg.points])
        names = list(msg.joint_names)
        self.positions = np.array(
            [by_name(names, p.positions, joints) for p in msg.points]
        ).reshape(len(self.times), len(joints))

    def at(self, t: float) -> np.ndarray:
        """The positions at time ``t`` (s, the node's clock); NaN before its start."""
        if self.times.size == 0:
            return np.full(self.positions.shape[1], math.nan)
        s = t - self.start
        if s < self.times[0]:
            return np.full(self.positions.shape[1], math.nan)
        return np.array(
            [np.interp(s, self.times, self.positions[:, j]) for j in range(self.positions.shape[1])]
        )
