"""What the ``tendonsheath ros2`` commands share: ``KEY=VALUE`` parameters typed by their
defaults, and spinning nodes until a duration, Ctrl-C or SIGTERM."""

from __future__ import annotations

import math
import signal
import time
from typing import Any


def parsed_parameters(items: list[str], defaults: dict[str, Any]) -> dict[str, Any]:
    """``KEY=VALUE`` strings as node parameters, each typed as its default (a list: comma
    separated strings; a float; a string).

    Raises
    ------
    ValueError
        No ``=``, an unknown key or a value that is not of its type.
    """
    out: dict[str, Any] = {}
    for item in items:
        key, sep, value = item.partition("=")
        key = key.strip()
        if not sep:
            raise ValueError(f"--param takes KEY=VALUE (got {item!r})")
        if key not in defaults:
            raise ValueError(f"unknown parameter {key!r}; known: {', '.join(defaults)}")
        default = defaults[key]
        if isinstance(default, list):
            out[key] = [v.strip() for v in value.split(",") if v.strip()]
        elif isinstance(default, float):
            try:
                out[key] = float(value)
            except ValueError:
                raise ValueError(f"parameter {key} takes a number (got {value!r})") from None
        else:
            out[key] = value
    return out


def spin(nodes: list[Any], context: Any, duration: float | None = None) -> str:
    """Spin ``nodes`` until ``duration`` seconds pass (None: forever), Ctrl-C or SIGTERM.
    Returns why it stopped."""
    from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor

    stop: list[str] = []
    previous = signal.signal(signal.SIGTERM, lambda *_: stop.append("SIGTERM"))
    executor = SingleThreadedExecutor(context=context)
    for node in nodes:
        executor.add_node(node)
    end = math.inf if duration is None else time.monotonic() + float(duration)
    why = "duration"
    try:
        while not stop and time.monotonic() < end and context.ok():
            executor.spin_once(timeout_sec=0.05)
        if stop:
            why = stop[0]
    except (KeyboardInterrupt, ExternalShutdownException):
        why = "Ctrl-C"
    finally:
        signal.signal(signal.SIGTERM, previous)
        executor.shutdown(timeout_sec=0.5)
    return why
