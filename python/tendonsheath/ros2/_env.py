"""The ROS 2 client library, imported only where a node is made, or said missing in one line.

The ``ros2`` extra installs rclpy and the message packages as pip wheels (a rmw of Fast DDS
among them); they need no sourced ROS install: no AMENT_PREFIX_PATH, LD_LIBRARY_PATH or
RMW_IMPLEMENTATION (the wheels find their libraries themselves, and Fast DDS is the default).
"""

from __future__ import annotations

from types import ModuleType

from .._util.extras import require

FEATURE = "tendonsheath ros2 (its nodes)"
# what a node imports: rclpy and the message packages of its topics
MODULES = (
    "rclpy",
    "rclpy.lifecycle",
    "sensor_msgs.msg",
    "std_msgs.msg",
    "trajectory_msgs.msg",
    "diagnostic_msgs.msg",
    "lifecycle_msgs.msg",
)


def ros() -> ModuleType:
    """rclpy, after checking that every module a node uses imports.

    Raises
    ------
    MissingExtraError
        A module is missing: ``pip install 'tendonsheath[ros2]'``.
    """
    for module in MODULES:
        require(module, extra="ros2", feature=FEATURE)
    import rclpy

    return rclpy


def init(domain_id: int | None = None) -> object:
    """A started rclpy context of its own (ROS_DOMAIN_ID ``domain_id``, default the
    environment's), so that nodes in one process may share it and tests may isolate theirs.

    Parameters
    ----------
    domain_id : int, optional
        The DDS domain (0-232); default ``ROS_DOMAIN_ID`` or 0.

    Returns
    -------
    rclpy.context.Context
        The context; ``shutdown()`` it when done.
    """
    rclpy = ros()
    from rclpy.context import Context

    context = Context()
    if domain_id is None:
        rclpy.init(context=context)
    else:
        rclpy.init(context=context, domain_id=int(domain_id))
    return context
