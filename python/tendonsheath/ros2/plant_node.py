"""The plant node: a simulated drive in real time, where the robot will be.

Each timer tick steps the plant with the last command received (held between commands) over
the real time since the previous tick, then publishes what the robot's sensors would
(topic names and the joint are ROS parameters; ``command`` is subscribed best effort, keep
last 5, as a stream; ``route`` and what the node publishes reliable, keep last 10):

* in: ``command`` (``sensor_msgs/JointState``: position, or effort for a torque motor; or
  ``std_msgs/Float64MultiArray``), ``route`` (``std_msgs/Float64MultiArray``: a curve angle,
  rad, a uniform bend of the drive's length);
* out: ``tip_state`` (JointState position: the tip sensor's reading, with its noise and
  latency), ``motor_state`` (JointState position: the motor encoder; effort: the tendons'
  torque on the drive, N m), ``output_truth`` (JointState position: the true output, which
  no robot measures, to score the simulation).
"""

from __future__ import annotations

import math
import time
from typing import Any

from . import _env
from ._messages import COMMAND_TYPES, by_name, declared, joint_state, stream_qos
from .live_plant import LivePlant

#: The node's parameters and their defaults.
PARAMETERS: dict[str, Any] = {
    "joint": "joint0",
    "rate": 500.0,
    "command_topic": "command",
    "command_type": "joint_state",
    "route_topic": "route",
    "tip_topic": "tip_state",
    "motor_topic": "motor_state",
    "output_topic": "output_truth",
}


def plant_node(
    plant: LivePlant,
    name: str = "tendonsheath_plant",
    context: Any = None,
    parameters: dict[str, Any] | None = None,
) -> Any:
    """A node that runs ``plant`` in real time: see the module.

    Parameters
    ----------
    plant : LivePlant
        The drive and its sensors (:func:`~tendonsheath.ros2.plant_source`).
    name : str, default "tendonsheath_plant"
        The node's name.
    context : rclpy.context.Context, optional
        The rclpy context (default the global one).
    parameters : dict, optional
        Values of :data:`PARAMETERS`.

    Returns
    -------
    rclpy.node.Node
        The node, stepping from its creation.

    Raises
    ------
    MissingExtraError
        rclpy or a message package is not installed.
    ValueError
        An unknown parameter or a bad value.
    """
    _env.ros()
    unknown = sorted(set(parameters or {}) - set(PARAMETERS))
    if unknown:
        raise ValueError(f"unknown plant node parameter(s) {unknown}; known: {list(PARAMETERS)}")
    values = {**PARAMETERS, **(parameters or {})}
    if values["command_type"] not in COMMAND_TYPES:
        raise ValueError(f"command_type must be one of {list(COMMAND_TYPES)}")
    if not (math.isfinite(float(values["rate"])) and float(values["rate"]) > 0):
        raise ValueError(f"rate must be > 0 Hz (got {values['rate']})")
    return _node_class()(plant, name, context, values)


_CLASS: list[type] = []


def _node_class() -> type:
    if _CLASS:
        return _CLASS[0]
    from rclpy.node import Node
    from sensor_msgs.msg import JointState
    from std_msgs.msg import Float64MultiArray

    class PlantNode(Node):
        """The plant node (see the module)."""

        def __init__(self, plant, name, context, values):

            super().__init__(name, context=context, **declared(values))
            self.plant = plant
            self.joint = str(values["joint"])
            motor = getattr(plant.plant, "motor", None)
            self.torque = motor is not None and motor.kind == "torque"
            self.command = 0.0
            kind = JointState if values["command_type"] == "joint_state" else Float64MultiArray
            self.create_subscription(kind, values["command_topic"], self._on_command, stream_qos())
            self.create_subscription(Float64MultiArray, values["route_topic"], self._on_route, 10)
            self._tip = self.create_publisher(JointState, values["tip_topic"], 10)
            self._motor = self.create_publisher(JointState, values["motor_topic"], 10)
            self._truth = self.create_publisher(JointState, values["output_topic"], 10)
            self._previous = time.monotonic()
            self.create_timer(1.0 / float(values["rate"]), self._tick)

        def _on_command(self, msg):
            if isinstance(msg, Float64MultiArray):
                value = float(msg.data[0]) if len(msg.data) else math.nan
            else:
                field = msg.effort if self.torque else msg.position
                value = float(by_name(list(msg.name), field, [self.joint])[0])
            if math.isfinite(value):
                self.command = value

        def _on_route(self, msg):
            if len(msg.data):
                try:
                    self.plant.set_route(float(msg.data[0]))
                except ValueError as exc:
                    self.get_logger().warning(f"route ignored: {exc}")

        def _tick(self):
            # the readings are of the plant stepped to this instant: stamped with it, not
            # with the end of the step (which a loaded machine delays by a varying time)
            now, stamp = time.monotonic(), self.get_clock().now().to_msg()
            dt, self._previous = now - self._previous, now
            applied = self.command  # the command held over this tick
            reading = self.plant.step(applied, dt)
            names = [self.joint]
            self._tip.publish(joint_state(JointState, names, stamp, position=[reading.tip]))
            self._motor.publish(
                joint_state(
                    JointState, names, stamp, position=[reading.motor], effort=[reading.load]
                )
            )
            self._truth.publish(
                joint_state(JointState, names, stamp, position=[reading.output], effort=[applied])
            )

    _CLASS.append(PlantNode)
    return PlantNode


__all__ = ["PARAMETERS", "plant_node"]
