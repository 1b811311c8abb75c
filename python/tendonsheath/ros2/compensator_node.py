"""The compensator node: a saved compensator run on a robot at a set rate, as a ROS 2
lifecycle node (configure, activate, deactivate, cleanup).

Topics (names and the joints are ROS parameters). The streams in are subscribed best effort,
keep last 5 (rclpy's sensor-data profile: any publisher is heard, a lost sample is
superseded by the next), a trajectory reliable; what the node publishes is reliable, keep last 10:

* in: ``desired`` (``sensor_msgs/JointState`` positions, or ``trajectory_msgs/JointTrajectory``
  with ``desired_type: joint_trajectory``), and what the compensator takes: ``tip_state``
  (JointState positions: the measured output), ``motor_state`` (JointState positions: the
  encoders; efforts: the load), ``curve_angle`` (``std_msgs/Float64MultiArray``: one curve
  angle, rad);
* out: ``command`` (JointState positions, efforts for a torque controller; or
  ``std_msgs/Float64MultiArray`` with ``command_type: float64_multi_array``), stamped with
  the desired sample's stamp it serves; ``diagnostics`` (``diagnostic_msgs/DiagnosticArray``,
  each cycle: the status flags, the stale inputs, the cycle's period and compute time).

A stale or missing input goes to the compensator as NaN (see :mod:`.live_compensator`).
"""

from __future__ import annotations

import math
from typing import Any

from . import _env

#: The node's parameters and their defaults.
PARAMETERS: dict[str, Any] = {
    "joints": ["joint0"],
    "rate": 200.0,
    "desired_topic": "desired",
    "desired_type": "joint_state",
    "tip_topic": "tip_state",
    "motor_topic": "motor_state",
    "curve_angle_topic": "curve_angle",
    "command_topic": "command",
    "command_type": "joint_state",
    "diagnostics_topic": "diagnostics",
    "stale_after": 0.05,
    "stop_after": 0.0,
    "min_command": -math.inf,
    "max_command": math.inf,
    "max_rate": math.inf,
}


def compensator_node(
    compensator: Any,
    name: str = "tendonsheath_compensator",
    context: Any = None,
    parameters: dict[str, Any] | None = None,
) -> Any:
    """A lifecycle node that runs ``compensator``: see the module.

    Parameters
    ----------
    compensator : compensator
        A saved compensator (``ts.compensate.load(path)``), any kind.
    name : str, default "tendonsheath_compensator"
        The node's name.
    context : rclpy.context.Context, optional
        The rclpy context (default the global one, after ``rclpy.init()``).
    parameters : dict, optional
        Values of :data:`PARAMETERS` (ROS parameters: a launch file may set them instead).

    Returns
    -------
    rclpy.lifecycle.LifecycleNode
        The node, unconfigured: ``trigger_configure()`` then ``trigger_activate()`` arm it
        (or a lifecycle manager through its services).

    Raises
    ------
    MissingExtraError
        rclpy or a message package is not installed.
    ValueError
        An unknown parameter.
    """
    _env.ros()
    unknown = sorted(set(parameters or {}) - set(PARAMETERS))
    if unknown:
        raise ValueError(
            f"unknown compensator node parameter(s) {unknown}; known: {list(PARAMETERS)}"
        )
    return _node_class()(compensator, name, context, {**PARAMETERS, **(parameters or {})})


def _node_class() -> type:
    """The node's class, from the module that imports rclpy."""
    from ._compensator_lifecycle import CompensatorNode

    return CompensatorNode


__all__ = ["PARAMETERS", "compensator_node"]
