"""A desired trajectory as a topic: a sine (or any function of time) published as a
``sensor_msgs/JointState`` at a set rate, to try a compensator node without a robot's
planner. Each message is stamped with the time it was sampled at."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

from . import _env
from ._messages import joint_state


def sine(amplitude: float, frequency: float, offset: float = 0.0) -> Callable[[float], float]:
    """``t -> offset + amplitude * sin(2 pi frequency t)``.

    Parameters
    ----------
    amplitude : float
        Amplitude (rad).
    frequency : float
        Frequency (Hz), > 0.
    offset : float, default 0.0
        Offset (rad).

    Returns
    -------
    callable
        The signal, a function of the time since the start (s).

    Raises
    ------
    ValueError
        A frequency that is not > 0, or a non-finite value.
    """
    if not (math.isfinite(frequency) and frequency > 0):
        raise ValueError(f"frequency must be > 0 Hz (got {frequency:g})")
    if not (math.isfinite(amplitude) and math.isfinite(offset)):
        raise ValueError("amplitude and offset must be finite")
    w = 2 * math.pi * frequency

    def signal(t: float) -> float:
        return offset + amplitude * math.sin(w * t)

    return signal


def reference_node(
    signal: Callable[[float], float],
    rate: float = 200.0,
    topic: str = "desired",
    joint: str = "joint0",
    name: str = "tendonsheath_reference",
    context: Any = None,
) -> Any:
    """A node that publishes ``signal(t)`` (t: seconds since its creation) at ``rate``.

    Parameters
    ----------
    signal : callable
        t (s) -> the desired position (rad).
    rate : float, default 200.0
        Messages per second (> 0).
    topic : str, default "desired"
        The topic.
    joint : str, default "joint0"
        The joint's name in the JointState.
    name : str, default "tendonsheath_reference"
        The node's name.
    context : rclpy.context.Context, optional
        The rclpy context (default the global one).

    Returns
    -------
    rclpy.node.Node
        The node, publishing from its creation.

    Raises
    ------
    MissingExtraError
        rclpy or a message package is not installed.
    ValueError
        A rate that is not > 0.
    """
    _env.ros()
    if not (math.isfinite(rate) and rate > 0):
        raise ValueError(f"rate must be > 0 Hz (got {rate:g})")
    from rclpy.node import Node
    from sensor_msgs.msg import JointState

    node = Node(name, context=context)
    publisher = node.create_publisher(JointState, topic, 10)
    start = time.monotonic()

    def tick():
        value = float(signal(time.monotonic() - start))
        stamp = node.get_clock().now().to_msg()
        publisher.publish(joint_state(JointState, [joint], stamp, position=[value]))

    node.create_timer(1.0 / rate, tick)
    return node


__all__ = ["reference_node", "sine"]
