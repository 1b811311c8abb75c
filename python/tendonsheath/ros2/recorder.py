"""Record the live loop's topics into a ROS 2 bag that ``ts.io.read_log`` reads back.

rosbag2 (``ros2 bag record``) records the same topics where a ROS install has it; the pip
wheels have no rosbag2, so this node writes the bag itself with the ``rosbags`` library (the
``ros`` extra, which read_log uses too): a rosbag2 folder (SQLite, ``metadata.yaml``), each
message's serialized bytes as they came, timed by their receive time.
"""

from __future__ import annotations

import importlib
import time
from pathlib import Path
from typing import Any

from .._util.extras import require
from . import _env

#: The topics of the live loop and their types, recorded by default.
LOOP_TOPICS = {
    "desired": "sensor_msgs/msg/JointState",
    "command": "sensor_msgs/msg/JointState",
    "tip_state": "sensor_msgs/msg/JointState",
    "motor_state": "sensor_msgs/msg/JointState",
    "output_truth": "sensor_msgs/msg/JointState",
}


def _message_class(type_name: str) -> Any:
    package, _, name = type_name.split("/")
    try:
        return getattr(importlib.import_module(f"{package}.msg"), name)
    except (ImportError, AttributeError):
        raise ValueError(
            f"cannot record {type_name}: its message package is not installed"
        ) from None


class BagRecorder:
    """A node that writes ``topics`` into the bag folder ``path`` until :meth:`close`.

    Parameters
    ----------
    path : str or Path
        The bag's folder (it must not exist: rosbag2's rule).
    topics : dict, optional
        Topic -> message type ("sensor_msgs/msg/JointState"); default :data:`LOOP_TOPICS`.
    name : str, default "tendonsheath_recorder"
        The node's name.
    context : rclpy.context.Context, optional
        The rclpy context (default the global one).

    Raises
    ------
    MissingExtraError
        rclpy or rosbags is not installed.
    ValueError
        The folder exists, or a type whose package is not installed.
    """

    def __init__(
        self,
        path: str | Path,
        topics: dict[str, str] | None = None,
        name: str = "tendonsheath_recorder",
        context: Any = None,
    ):
        _env.ros()
        require("rosbags", extra="ros", feature="recording a bag")
        from rclpy.node import Node
        from rosbags.rosbag2 import Writer
        from rosbags.typesys import Stores, get_typestore

        self.path = Path(path)
        if self.path.exists():
            raise ValueError(f"{self.path} exists: a bag is written into a new folder")
        topics = dict(LOOP_TOPICS if topics is None else topics)
        classes = {topic: _message_class(kind) for topic, kind in topics.items()}
        store = get_typestore(Stores.LATEST)
        self._writer: Any = Writer(self.path, version=9)
        self._writer.open()
        self.node = Node(name, context=context)
        self.counts = dict.fromkeys(topics, 0)
        for topic, kind in topics.items():
            connection = self._writer.add_connection("/" + topic.lstrip("/"), kind, typestore=store)
            self.node.create_subscription(
                classes[topic], topic, self._writes(topic, connection), 100, raw=True
            )

    def _writes(self, topic: str, connection: Any):
        def write(data: bytes) -> None:
            if self._writer is not None:
                self._writer.write(connection, time.time_ns(), data)
                self.counts[topic] += 1

        return write

    def close(self) -> Path:
        """Finish the bag (its metadata.yaml) and destroy the node.

        Returns
        -------
        Path
            The bag's folder.
        """
        if self._writer is not None:
            self._writer.close()
            self._writer = None
            self.node.destroy_node()
        return self.path


__all__ = ["LOOP_TOPICS", "BagRecorder"]
