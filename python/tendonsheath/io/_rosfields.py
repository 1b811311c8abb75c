"""Naming a number inside a ROS message: "/topic:field", e.g. "/motor/joint_states:position[0]"
or "/tip/pose:pose.position.x" (attributes joined by dots, list indices in brackets, negative
indices count from the end). A topic whose messages hold one number (std_msgs/msg/Float64)
may be named alone ("/setpoint").

A name in brackets selects by name, as sensor_msgs/JointState lays its arrays out:
"/joint_states:position[bend]" is the item of ``position`` at the place of "bend" in the
``name`` list beside it, looked up in every message (a publisher may reorder its joints);
a message without that name is an error listing the names it has.

Messages are those the rosbags library deserializes: dataclasses, with NumPy arrays for
numeric arrays and lists for arrays of messages.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass

import numpy as np

_INDEX = r"(\[(-?\d+|[^\[\]\s][^\[\]]*)\])*"  # [0], [-1] or [a joint name]
_FIELD = re.compile(rf"[A-Za-z_]\w*{_INDEX}(\.[A-Za-z_]\w*{_INDEX})*")
_STEP = re.compile(r"\.?([A-Za-z_]\w*)|\[([^\[\]]+)\]")
MAX_LISTED = 40  # fields named in an error message
MAX_ITEMS = 64  # items listed of one array (an image's pixels are not fields to list)


@dataclass(frozen=True)
class ByName:
    """A step that selects an array's item by the place of ``label`` in the ``name`` list
    beside the array (sensor_msgs/JointState)."""

    label: str


def _step(text: str):
    return int(text) if re.fullmatch(r"-?\d+", text) else ByName(text)


@dataclass(frozen=True)
class Signal:
    """One number per message: a topic and a field path (None: the message's only number)."""

    topic: str
    field: str | None
    steps: tuple = ()  # ("pose", "position", "x"), ("position", 0), ("position", ByName("bend"))

    @property
    def text(self) -> str:
        return self.topic if self.field is None else f"{self.topic}:{self.field}"


def parse_signal(spec, role: str) -> Signal:
    """A "/topic:field" (or "/topic") -> Signal; a one-line ValueError for anything else."""
    s = str(spec).strip()
    topic, _, field = s.partition(":")
    if not topic or any(c.isspace() for c in topic):
        raise ValueError(
            f"the {role} {spec!r} is not a ROS topic and field: give /topic:field, "
            "e.g. /joint_states:position[0]"
        )
    if not field:
        return Signal(topic, None)
    if not _FIELD.fullmatch(field):
        raise ValueError(
            f"the {role} field {field!r} is not a field path (e.g. data, position[0], "
            "pose.position.x)"
        )
    steps = tuple(_step(m[2]) if m[2] is not None else m[1] for m in _STEP.finditer(field))
    return Signal(topic, field, steps)


def _fields(msg) -> list[str]:
    return [f.name for f in dataclasses.fields(msg) if not f.name.startswith("__")]


def _is_message(value) -> bool:
    return dataclasses.is_dataclass(value) and not isinstance(value, type)


def _is_number(value) -> bool:
    return isinstance(value, bool | int | float | np.number | np.bool_)


def numeric_fields(msg, prefix: str = "", limit: int | None = None) -> list[str]:
    """The field paths of every number in a message (array items one by one, the first
    ``MAX_ITEMS``; of an array of messages, the first item's), in order; at most ``limit``."""
    out: list[str] = []

    def walk(value, path):
        if limit is not None and len(out) >= limit:
            return
        if _is_message(value):
            for name in _fields(value):
                walk(getattr(value, name), f"{path}.{name}" if path else name)
        elif _is_number(value):
            out.append(path)
        elif isinstance(value, np.ndarray) and value.dtype.kind in "biuf":
            out.extend(f"{path}[{i}]" for i in range(min(value.size, MAX_ITEMS)))
        elif isinstance(value, list | tuple) and value:
            walk(value[0], f"{path}[0]")

    walk(msg, prefix)
    return out if limit is None else out[:limit]


def describe_fields(msg) -> str:
    """The numbers of a message for an error message: "position[0], position[1], ..."."""
    names = numeric_fields(msg, limit=MAX_LISTED + 1)
    if not names:
        return "none (the message holds no numbers)"
    more = ", ..." if len(names) > MAX_LISTED else ""
    return ", ".join(names[:MAX_LISTED]) + more


def only_number(msg) -> str | None:
    """The path of a message's number if it holds exactly one (std_msgs/msg/Float64: data)."""
    names = numeric_fields(msg, limit=2)
    return names[0] if len(names) == 1 else None


def field_value(msg, steps: tuple):
    """The value at a field path, or (None, the step that failed, why)."""
    value, holder = msg, None  # holder: the message whose field value is (for ByName)
    for k, step in enumerate(steps):
        if isinstance(step, ByName):
            place, why = _named_index(holder, step.label)
            if not why and isinstance(value, np.ndarray | list | tuple) and place >= len(value):
                why = f"has {len(value)} item(s), none for {step.label!r} (name {place + 1})"
            if why:
                return None, k, why
            step = place
        if isinstance(step, int):
            if not isinstance(value, np.ndarray | list | tuple):
                return None, k, "is not an array"
            if not -len(value) <= step < len(value):
                return None, k, f"has {len(value)} item(s), no index {step}"
            value, holder = value[step], None
        else:
            if not _is_message(value) or step not in _fields(value):
                return None, k, "has no such field"
            value, holder = getattr(value, step), value
    return value, None, ""


def _named_index(holder, label: str) -> tuple[int, str]:
    """The place of ``label`` in the ``name`` list of the message ``holder``, or (0, why)."""
    names = getattr(holder, "name", None) if holder is not None else None
    if not isinstance(names, list | tuple) or not all(isinstance(n, str) for n in names):
        return 0, "cannot be selected by name: no list of names ('name') beside it"
    places = [i for i, n in enumerate(names) if n == label]
    if len(places) != 1:
        how = "no" if not places else f"{len(places)} times the"
        return 0, f"has {how} name {label!r}; names: {', '.join(map(repr, names)) or 'none'}"
    return places[0], ""


def check_signal(signal: Signal, msg, msgtype: str, role: str) -> Signal:
    """The signal with its field resolved and checked on one message of its topic (a
    one-line ValueError naming the fields the message has if it does not hold a number)."""
    where = f"topic {signal.topic} ({msgtype})"
    if signal.field is None:
        name = only_number(msg)
        if name is None:
            raise ValueError(
                f"{where} holds more than one number: name the {role} field as "
                f"{signal.topic}:FIELD; fields: {describe_fields(msg)}"
            )
        return parse_signal(f"{signal.topic}:{name}", role)
    value, failed, why = field_value(msg, signal.steps)
    if failed is not None:
        raise ValueError(
            f"{where}: no {role} field {signal.field!r} ({_prefix(signal.steps, failed)} "
            f"{why}); fields: {describe_fields(msg)}"
        )
    if not _is_number(value):
        kind = _kind(value)
        raise ValueError(
            f"{where}: the {role} field {signal.field!r} is {kind}, not a number; "
            f"fields: {describe_fields(msg)}"
        )
    return signal


def _prefix(steps: tuple, upto: int) -> str:
    text = ""
    for step in steps[: upto + 1]:
        if isinstance(step, ByName):
            text += f"[{step.label}]"
        else:
            text += f"[{step}]" if isinstance(step, int) else (f".{step}" if text else step)
    return text


def _kind(value) -> str:
    if _is_message(value):
        return f"a {getattr(value, '__msgtype__', 'message')} message"
    if isinstance(value, np.ndarray | list | tuple):
        return f"an array of {len(value)} (give an index, e.g. [0])"
    if isinstance(value, str):
        return "text"
    return f"a {type(value).__name__}"


def value_of(signal: Signal, msg, number: int) -> float:
    """The signal's number in one message (checked on the topic's first message; later ones
    may still differ, e.g. a shorter array)."""
    value, failed, why = field_value(msg, signal.steps)
    where = f"topic {signal.topic}, message {number}"
    if failed is not None:
        raise ValueError(f"{where}: {_prefix(signal.steps, failed)} {why}")
    if not _is_number(value):
        raise ValueError(f"{where}: {signal.field} is {_kind(value)}, not a number")
    return float(value)


def stamp_ns(value) -> int | None:
    """A builtin_interfaces/msg/Time (sec, nanosec) in nanoseconds, or None."""
    sec = getattr(value, "sec", None)
    nsec = getattr(value, "nanosec", None)
    if isinstance(sec, int | np.integer) and isinstance(nsec, int | np.integer):
        return int(sec) * 1_000_000_000 + int(nsec)
    return None


def header_stamp_ns(msg) -> int | None:
    """The message's header.stamp in nanoseconds, or None without a header."""
    header = getattr(msg, "header", None)
    return None if header is None else stamp_ns(getattr(header, "stamp", None))
