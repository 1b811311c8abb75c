"""Conversion of user arrays to the contiguous float64 vectors the core expects."""

from __future__ import annotations

import numpy as np


def as_vector(values, name: str) -> np.ndarray:
    """Return `values` as a 1-D contiguous float64 array (a number: one sample), or raise
    ValueError naming it."""
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a 1-D array of numbers ({exc})") from None
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be 1-D (got shape {arr.shape})")
    return np.ascontiguousarray(arr)


def as_signal(values, name: str) -> np.ndarray:
    """:func:`as_vector`, not empty."""
    arr = as_vector(values, name)
    if arr.size == 0:
        raise ValueError(f"{name} is empty")
    return arr


def as_time_and_signal(t, x, name: str = "x") -> tuple[np.ndarray | None, np.ndarray]:
    """Check a (t, x) pair: same length, 1-D. NaN and ordering are checked in the core."""
    xs = as_signal(x, name)
    if t is None:
        return None, xs
    ts = as_signal(t, "t")
    if ts.shape != xs.shape:
        raise ValueError(f"t and {name} have different lengths ({ts.size} and {xs.size})")
    return ts, xs


def as_timed_signal(t, x, name: str, who: str) -> tuple[np.ndarray, np.ndarray]:
    """:func:`as_time_and_signal` where the time vector is required (`who` names the call)."""
    ts, xs = as_time_and_signal(t, x, name)
    if ts is None:
        raise ValueError(f"{who} needs the time vector t")
    return ts, xs


def checked_dt(dt) -> float:
    """A streaming step's dt (s): finite and >= 0. The C++ step holds its output on a bad dt
    (real time never throws); the Python call says so instead."""
    value = float(dt)
    if not (value >= 0.0 and value < float("inf")):
        raise ValueError(f"dt must be a finite number of seconds >= 0 (got {dt!r})")
    return value
