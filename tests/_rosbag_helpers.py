"""Writing real ROS bags with the rosbags writer, for the tests: ROS 1 (.bag) and ROS 2
(sqlite3 or MCAP storage, a folder with metadata.yaml), with standard message types."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_typestore

KINDS = ("ros1", "sqlite3", "mcap")
_STORE = {"ros1": get_typestore(Stores.ROS1_NOETIC), "ros2": get_typestore(Stores.ROS2_HUMBLE)}
EPOCH_NS = 1_700_000_000_123_456_789  # an epoch time: float64 seconds would round it


def _store(kind: str):
    return _STORE["ros1" if kind == "ros1" else "ros2"]


def _time(kind, ns: int):
    return _store(kind).types["builtin_interfaces/msg/Time"](
        sec=int(ns) // 1_000_000_000, nanosec=int(ns) % 1_000_000_000
    )


def header(kind, ns: int, frame: str = ""):
    types = _store(kind).types
    h = types["std_msgs/msg/Header"]
    if "seq" in h.__dataclass_fields__:  # ROS 1's header has a sequence number
        return h(seq=0, stamp=_time(kind, ns), frame_id=frame)
    return h(stamp=_time(kind, ns), frame_id=frame)


def float64(kind, value: float):
    return _store(kind).types["std_msgs/msg/Float64"](data=float(value))


def joint_state(kind, ns: int, positions, names=None):
    """A JointState stamped ``ns``; its joints are j0, j1, ... unless ``names`` are given."""
    types = _store(kind).types
    positions = np.asarray(positions, dtype=float)
    return types["sensor_msgs/msg/JointState"](
        header=header(kind, ns),
        name=list(names) if names is not None else [f"j{i}" for i in range(positions.size)],
        position=positions,
        velocity=np.zeros(0),
        effort=np.zeros(0),
    )


def point_stamped(kind, ns: int, x: float, y: float = 0.0, z: float = 0.0):
    types = _store(kind).types
    point = types["geometry_msgs/msg/Point"](x=float(x), y=float(y), z=float(z))
    return types["geometry_msgs/msg/PointStamped"](header=header(kind, ns), point=point)


def pose_stamped(kind, ns: int, x: float):
    types = _store(kind).types
    point = types["geometry_msgs/msg/Point"](x=float(x), y=0.0, z=0.0)
    q = types["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0)
    pose = types["geometry_msgs/msg/Pose"](position=point, orientation=q)
    return types["geometry_msgs/msg/PoseStamped"](header=header(kind, ns), pose=pose)


def write_bag(path: Path, kind: str, topics: dict) -> Path:
    """Write ``topics`` ({name: [(receive_ns, message), ...]}) as a bag of ``kind`` at
    ``path`` (ROS 1: path.bag; ROS 2: the folder ``path``); returns what was written.
    Messages are written in receive order, as a recorder does."""
    store = _store(kind)
    stream = sorted(
        ((ns, name, msg) for name, msgs in topics.items() for ns, msg in msgs),
        key=lambda item: item[0],
    )
    if kind == "ros1":
        path = path.with_suffix(".bag")
        writer, serialize = Writer1(path), store.serialize_ros1
    else:
        plugin = StoragePlugin.SQLITE3 if kind == "sqlite3" else StoragePlugin.MCAP
        writer, serialize = Writer2(path, version=9, storage_plugin=plugin), store.serialize_cdr
    with writer:
        conns = {}
        for name, msgs in topics.items():
            msgtype = msgs[0][1].__msgtype__
            conns[name] = writer.add_connection(name, msgtype, typestore=store)
        for ns, name, msg in stream:
            writer.write(conns[name], int(ns), serialize(msg, msg.__msgtype__))
    return path


def storage_file(folder: Path) -> Path:
    """The .db3 or .mcap file inside a ROS 2 bag folder."""
    (found,) = [p for p in folder.iterdir() if p.suffix in (".db3", ".mcap")]
    return found
