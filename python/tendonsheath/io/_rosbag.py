"""Reading a recording from a ROS bag: ROS 1 (.bag), ROS 2 (.db3 or .mcap, or a bag folder
with metadata.yaml) through the rosbags library (pure Python; no ROS install). The input,
output and curve angle are named "/topic:field" (see ``_rosfields``).

Time of a message (``time=``):
  None  its header stamp (``header.stamp``) when its type has a header whose stamps are set
        (not all zero), else the bag's receive time; each topic on its own, and the notes
        say which was used;
  "header" / "receive"  that one for every topic (no header: an error);
  "/topic:field"  a field of the input or output topic (a builtin_interfaces/msg/Time, or a
        number in seconds) times that topic's messages.
A topic whose stamps are out of order is sorted by stamp (noted). When some topics are
timed by header stamps and others by receive times, a note says so, with the median latency
(receive - header) of the header-stamped ones: the two bases differ by it.

Alignment of topics at different rates: the output topic's messages are the samples (with
no output, the input's); the input and a curve-angle topic are linearly interpolated at
their times; samples before another topic's first message or after its last are dropped
(noted: interpolation never extrapolates). Time starts at 0 at the first sample; the
absolute stamp is in the notes. A sample's "row" is its message number on its topic
(1 = the first in the bag).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._rosfields import (
    Signal,
    check_signal,
    field_value,
    header_stamp_ns,
    numeric_fields,
    only_number,
    parse_signal,
    stamp_ns,
    value_of,
)
from ._timecol import UNIT_NS

SUFFIXES = (".bag", ".db3", ".mcap")
INSTALL = "pip install 'tendonsheath[ros]'"
TIME_KEY = "time"
ROLES = ("input", "output", "curve angle")


def bag_path(path: Path) -> Path | None:
    """What to open if ``path`` names a ROS bag (by its suffix, a folder with metadata.yaml,
    or that metadata.yaml), else None."""
    if path.is_dir():
        return path if (path / "metadata.yaml").is_file() else None
    if path.name == "metadata.yaml":
        return path.parent
    return path if path.suffix.lower() in SUFFIXES else None


def _kind(path: Path) -> str:
    return "a ROS 1 bag" if path.suffix.lower() == ".bag" else "a ROS 2 bag"


@contextmanager
def _opened(path: Path):
    try:
        from rosbags.highlevel import AnyReader
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise ValueError(f"{path}: reading ROS bags needs the rosbags library: {INSTALL}") from None
    if not path.exists():
        raise ValueError(f"data file not found: {path}")
    # a ROS 2 bag written before Iron holds no type definitions: the standard ones serve
    reader = AnyReader([path], default_typestore=get_typestore(Stores.LATEST))
    try:
        reader.open()
    except Exception as exc:  # rosbags raises many types for a broken or foreign file
        raise ValueError(f"{path}: cannot read it as {_kind(path)} ({_reason(exc)})") from None
    try:
        yield reader
    finally:
        reader.close()


def _reason(exc: Exception) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    return text if len(text) <= 200 else text[:200] + "..."


def _topic_list(reader) -> str:
    return ", ".join(
        f"{name} ({info.msgtype}, {info.msgcount} messages)"
        for name, info in sorted(reader.topics.items())
    )


@dataclass
class _Topic:
    """The messages of one topic: receive and header stamps, and the named numbers."""

    name: str
    msgtype: str
    signals: dict[str, Signal]  # role -> signal
    time_field: Signal | None = None
    time_unit_ns: int = 1_000_000_000  # a time field that is a number: ns per its unit
    receive: list[int] = field(default_factory=list)
    header: list[int | None] = field(default_factory=list)
    stamps: list[int] = field(default_factory=list)  # from time_field
    values: dict[str, list[float]] = field(default_factory=dict)


def _messages(reader, path: Path, topics: dict[str, _Topic]) -> Iterator:
    conns = [c for c in reader.connections if c.topic in topics]
    try:
        for conn, receive_ns, raw in reader.messages(connections=conns):
            yield conn, receive_ns, reader.deserialize(raw, conn.msgtype)
    except Exception as exc:  # a truncated or corrupt bag
        raise ValueError(f"{path}: cannot read it as {_kind(path)} ({_reason(exc)})") from None


def _collect(reader, path: Path, topics: dict[str, _Topic]) -> None:
    for conn, receive_ns, msg in _messages(reader, path, topics):
        topic = topics[conn.topic]
        number = len(topic.receive) + 1
        if number == 1:
            _resolve(topic, msg, path)
        topic.receive.append(int(receive_ns))
        topic.header.append(header_stamp_ns(msg))
        try:
            for role, signal in topic.signals.items():
                topic.values[role].append(value_of(signal, msg, number))
            if topic.time_field is not None:
                topic.stamps.append(_time_value(topic.time_field, msg, number, topic.time_unit_ns))
        except ValueError as exc:
            raise ValueError(f"{path}: {exc}") from None
    for topic in topics.values():
        if not topic.receive:
            raise ValueError(f"{path}: topic {topic.name} ({topic.msgtype}) has no messages")


def _resolve(topic: _Topic, msg, path: Path) -> None:
    try:
        for role, signal in topic.signals.items():
            topic.signals[role] = check_signal(signal, msg, topic.msgtype, role)
            topic.values[role] = []
        if topic.time_field is not None:
            _time_value(topic.time_field, msg, 1, topic.time_unit_ns)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


def _time_value(signal: Signal, msg, number: int, unit_ns: int = 1_000_000_000) -> int:
    """A time field in nanoseconds: a builtin_interfaces/msg/Time, or a number of units
    (``unit_ns`` ns each: seconds by default)."""
    value, failed, why = field_value(msg, signal.steps)
    if failed is not None:
        raise ValueError(f"topic {signal.topic}, message {number}: time field {signal.field} {why}")
    ns = stamp_ns(value)
    if ns is not None:
        return ns
    try:
        seconds = float(value)
    except (TypeError, ValueError):
        raise ValueError(
            f"topic {signal.topic}, message {number}: the time field {signal.field!r} is "
            "neither a builtin_interfaces/msg/Time nor a number of seconds"
        ) from None
    if not np.isfinite(seconds):
        raise ValueError(f"topic {signal.topic}, message {number}: time {seconds} is not finite")
    return int(round(seconds * unit_ns))


def _time_mode(time) -> tuple[str, Signal | None]:
    if time is None or str(time).strip().lower() in ("auto", ""):
        return "auto", None
    mode = str(time).strip().lower()
    if mode in ("header", "receive"):
        return mode, None
    if not str(time).startswith("/") and ":" not in str(time):
        raise ValueError(
            f"for a ROS bag, time must be 'header', 'receive' or /topic:field (got {time!r})"
        )
    signal = parse_signal(time, "time")
    if signal.field is None:
        raise ValueError(f"name the time field as {signal.topic}:FIELD (e.g. header.stamp)")
    return "field", signal


def _stamps(topic: _Topic, mode: str, notes: list[str]) -> tuple[np.ndarray, str]:
    """The topic's message times (ns) by the rule in the module's doc, and their source
    ("field", "header" or "receive")."""
    if topic.time_field is not None:
        notes.append(f"time of {topic.name}: its field {topic.time_field.field}")
        return np.asarray(topic.stamps, dtype=np.int64), "field"
    receive = np.asarray(topic.receive, dtype=np.int64)
    has_header = all(h is not None for h in topic.header)
    set_ = has_header and all(h != 0 for h in topic.header)
    if mode == "receive":
        notes.append(f"time of {topic.name}: the bag's receive time")
        return receive, "receive"
    if mode == "header" and not set_:
        why = "set in every message" if has_header else "in its type"
        raise ValueError(
            f"topic {topic.name} ({topic.msgtype}) has no header stamp {why}; "
            "use the receive time (time='receive', --time receive)"
        )
    if set_:
        notes.append(f"time of {topic.name}: its header stamps (header.stamp)")
        return np.asarray(topic.header, dtype=np.int64), "header"
    why = "its header stamps are zero" if has_header else "no header"
    notes.append(f"time of {topic.name}: the bag's receive time ({why})")
    return receive, "receive"


def _mixed_note(topics: dict[str, _Topic], sources: dict[str, str]) -> str | None:
    """A note when some topics are timed by their header stamps (when measured) and others
    by the bag's receive time (when recorded): the latency between the two shifts them."""
    header = [n for n, s in sources.items() if s == "header"]
    receive = [n for n, s in sources.items() if s == "receive"]
    if not header or not receive:
        return None
    lags = []
    for name in header:
        lag = np.asarray(topics[name].receive, dtype=np.int64) - np.asarray(
            topics[name].header, dtype=np.int64
        )
        lags.append(f"{name} {np.median(lag) * 1e-6:.3g} ms")
    return (
        f"mixed time bases: {', '.join(header)} by header stamps (when measured), "
        f"{', '.join(receive)} by the bag's receive time (when recorded); the transport "
        f"latency shifts one against the other (median receive - header: {', '.join(lags)}); "
        "time='receive' (--time receive) times every topic alike"
    )


def _sorted(name: str, stamps: np.ndarray, notes: list[str]) -> np.ndarray:
    """The order that sorts a topic's messages by stamp (noted when it is not the bag's)."""
    order = np.argsort(stamps, kind="stable")
    moved = int(np.count_nonzero(order != np.arange(order.size)))
    if moved:
        notes.append(f"{moved} message(s) of {name} out of order by stamp: sorted by stamp")
    return order


@dataclass
class BagTable:
    """Aligned samples: the time ("time", s from the first sample), and one array for each
    role, keyed by the name the caller gave; the message number of every sample."""

    columns: dict[str, np.ndarray]
    rows: np.ndarray
    notes: list[str]


def _plan(reader, path: Path, specs: dict, time_signal: Signal | None) -> dict[str, _Topic]:
    """The topics to read, with the signals each carries (an error for a missing topic)."""
    infos = reader.topics
    topics: dict[str, _Topic] = {}
    try:
        named = [(role, parse_signal(spec, role)) for role, spec in specs.items()]
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
    if time_signal is not None:
        named.append(("time", time_signal))
    for role, signal in named:
        if signal.topic not in infos:
            raise ValueError(
                f"{path}: no {role} topic {signal.topic!r}; topics: {_topic_list(reader)}"
            )
        topic = topics.setdefault(
            signal.topic, _Topic(signal.topic, infos[signal.topic].msgtype or "?", {})
        )
        if role == "time":
            topic.time_field = signal
        else:
            topic.signals[role] = signal
    if time_signal is not None and len(topics[time_signal.topic].signals) == 0:
        raise ValueError(
            f"{path}: the time topic {time_signal.topic} must be the input's or the output's"
        )
    return topics


def read_bag(path: Path, time, specs: dict, missing: str, time_unit: str = "s") -> BagTable:
    """Read and align the named signals (``specs``: role -> "/topic:field"; roles "input",
    "output", "curve angle") by the rules in the module's doc; ``time_unit`` is the unit of
    a /topic:field time that is a number (stamps carry their own)."""
    with _opened(path) as reader:
        try:
            mode, time_signal = _time_mode(time)
        except ValueError as exc:
            raise ValueError(f"{path}: {exc}") from None
        if time_unit != "s" and time_signal is None:
            raise ValueError(
                f"{path}: time_unit {time_unit!r} applies to a /topic:field time that is a "
                "number; a bag's header and receive stamps carry their unit"
            )
        if specs.get("input") is None:
            raise ValueError(
                f"{path}: name the input as /topic:field; topics: {_topic_list(reader)}"
            )
        specs = {role: spec for role, spec in specs.items() if spec is not None}
        topics = _plan(reader, path, specs, time_signal)
        for topic in topics.values():
            topic.time_unit_ns = UNIT_NS[time_unit]
        _collect(reader, path, topics)
    if missing == "error":
        _check_finite(path, topics)
    try:
        return _align(topics, specs, mode)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


def _check_finite(path: Path, topics: dict[str, _Topic]) -> None:
    for topic in topics.values():
        for role, values in topic.values.items():
            bad = np.flatnonzero(~np.isfinite(values))
            if bad.size:
                k = int(bad[0])
                raise ValueError(
                    f"{path}: topic {topic.name}, message {k + 1}: the {role} "
                    f"{topic.signals[role].field} is {values[k]}, not a finite number"
                )


def _align(topics: dict[str, _Topic], specs: dict, mode: str) -> BagTable:
    notes: list[str] = []
    base_role = "output" if "output" in specs else "input"
    base = topics[parse_signal(specs[base_role], base_role).topic]
    timed = {name: _stamps(topic, mode, notes) for name, topic in topics.items()}
    stamps = {name: s for name, (s, _) in timed.items()}
    mixed = _mixed_note(topics, {name: source for name, (_, source) in timed.items()})
    if mixed is not None:
        notes.append(mixed)
    order = _sorted(base.name, stamps[base.name], notes)
    t_ns = stamps[base.name][order]
    rows = order + 1
    keep = np.ones(t_ns.size, dtype=bool)
    others = [name for name in topics if name != base.name]
    for name in others:
        s = stamps[name]
        inside = (t_ns >= s.min()) & (t_ns <= s.max())
        if not inside.any():
            raise ValueError(
                f"the topics {base.name} and {name} do not overlap in time "
                f"({_span(t_ns)} and {_span(s)})"
            )
        if not inside.all():
            notes.append(
                f"{int((~inside).sum())} of {t_ns.size} messages of {base.name} lie outside "
                f"the time span of {name}: dropped (before its first message: "
                f"{int((t_ns < s.min()).sum())}, after its last: {int((t_ns > s.max()).sum())})"
            )
        keep &= inside
    if not keep.any():
        raise ValueError(
            f"no message of {base.name} lies within the time span of every other topic "
            f"({', '.join(f'{n}: {_span(stamps[n])}' for n in others)})"
        )
    t_ns, rows = t_ns[keep], rows[keep]
    start = int(t_ns[0])
    columns = {TIME_KEY: (t_ns - start) * 1e-9}
    for role, spec in specs.items():
        topic = topics[parse_signal(spec, role).topic]
        values = np.asarray(topic.values[role], dtype=float)
        if topic is base:
            columns[str(spec)] = values[order][keep]
        else:
            columns[str(spec)] = _interpolated(topic, stamps[topic.name], values, t_ns, notes)
    notes.insert(0, _rule(base, base_role, others, start))
    return BagTable(columns, rows, notes)


def _interpolated(topic: _Topic, stamps, values, t_ns, notes: list[str]) -> np.ndarray:
    order = _sorted(topic.name, stamps, notes)
    s, v = stamps[order], values[order]
    unique = np.r_[True, np.diff(s) != 0]
    if not unique.all():
        notes.append(
            f"{int((~unique).sum())} message(s) of {topic.name} with a duplicate stamp "
            "ignored (first kept)"
        )
        s, v = s[unique], v[unique]
    ref = int(t_ns[0])  # differences in integer ns, then float: no rounding of epoch times
    return np.interp((t_ns - ref) * 1e-9, (s - ref) * 1e-9, v)


def _seconds(ns: int) -> str:
    """A stamp in seconds, every digit kept (a float64 rounds epoch times)."""
    ns = int(ns)
    sign = "-" if ns < 0 else ""
    return f"{sign}{abs(ns) // 1_000_000_000}.{abs(ns) % 1_000_000_000:09d}"


def _span(stamps_ns) -> str:
    return f"{_seconds(stamps_ns.min())} to {_seconds(stamps_ns.max())} s"


def _rule(base: _Topic, role: str, others: list[str], start: int) -> str:
    text = f"samples: the messages of {base.name} (the {role})"
    if others:
        text += f"; {', '.join(others)} linearly interpolated at their times"
    return f"{text}; time from 0 at the first sample (stamp {_seconds(start)} s)"


def bag_columns(path: Path) -> list[str]:
    """Every number a bag's topics hold, as /topic:field (from each topic's first message;
    a topic with one number is also listed alone)."""
    names: list[str] = []
    with _opened(path) as reader:
        for name in sorted(reader.topics):
            conns = [c for c in reader.connections if c.topic == name]
            for conn, _, raw in reader.messages(connections=conns):
                msg = reader.deserialize(raw, conn.msgtype)
                if only_number(msg) is not None:
                    names.append(name)
                names.extend(f"{name}:{f}" for f in numeric_fields(msg))
                break
    return names
