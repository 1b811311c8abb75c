"""Recordings of coupled joints for :func:`~tendonsheath.identify.identify_coupled`: the two
calling forms (t, x, y, or ``recordings=[(t, x, y), ...]``) normalised into checked
(t, x, y) triples, x and y of shape (n, J) with the same J in every recording."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._util.typing import FloatArray

_OWNER = "identify_coupled"


@dataclass(frozen=True)
class CoupledRecording:
    """One session of all joints: times (or None), inputs and measured angles, shape (n, J).
    Each starts from the models' rest state (no state carries over from another)."""

    t: FloatArray | None
    x: FloatArray
    y: FloatArray

    @property
    def n(self) -> int:
        return int(self.x.shape[0])


def coupled_recordings(t, x, y, recordings: Sequence | None) -> list[CoupledRecording]:
    """Check and normalise the arrays or the recordings (one-line errors naming the problem)."""
    arrays = x is not None or y is not None or t is not None
    if recordings is not None and arrays:
        raise TypeError(f"{_OWNER}: give either t, x, y or recordings=[(t, x, y), ...], not both")
    if recordings is None:
        if x is None or y is None:
            raise TypeError(f"{_OWNER}: give t, x and y, or recordings=[(t, x, y), ...]")
        items = [(t, x, y)]
    else:
        if isinstance(recordings, tuple) and len(recordings) == 3 and _is_array(recordings[1]):
            recordings = [recordings]  # one (t, x, y) tuple
        items = [_unpack(item, i) for i, item in enumerate(recordings)]
        if not items:
            raise ValueError(f"{_OWNER}: recordings is empty")
    out: list[CoupledRecording] = []
    for i, (ti, xi, yi) in enumerate(items):
        who = f"{_OWNER}: " if recordings is None else f"{_OWNER}: recording {i}: "
        rec = _check(ti, xi, yi, who)
        if out and rec.x.shape[1] != out[0].x.shape[1]:
            raise ValueError(
                f"{who}{rec.x.shape[1]} joints, but recording 0 has {out[0].x.shape[1]}"
            )
        if out and (rec.t is None) != (out[0].t is None):
            raise ValueError(f"{who}give times t for every recording or for none")
        out.append(rec)
    return out


def _is_array(value) -> bool:
    return np.ndim(value) >= 1


def _unpack(item, index: int):
    """(t, x, y), or an object with t, x and y attributes."""
    if hasattr(item, "x") and hasattr(item, "y"):
        return getattr(item, "t", None), item.x, item.y
    if not isinstance(item, tuple | list) or len(item) != 3:
        raise ValueError(
            f"{_OWNER}: recording {index} must be a (t, x, y) tuple, got {type(item).__name__}"
            + (f" of length {len(item)}" if isinstance(item, tuple | list) else "")
        )
    return tuple(item)


def _matrix(values, name: str, who: str) -> FloatArray:
    a = np.asarray(values, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] < 1:
        raise ValueError(
            f"{who}{name} must have shape (n, J), one column per joint (got {a.shape})"
        )
    bad = np.argwhere(~np.isfinite(a))
    if bad.size:
        k, j = (int(v) for v in bad[0])
        raise ValueError(f"{who}{name} has a non-finite value ({a[k, j]}) at sample {k}, joint {j}")
    return np.ascontiguousarray(a)


def _check(t, x, y, who: str) -> CoupledRecording:
    xs = _matrix(x, "x", who)
    ys = _matrix(y, "y", who)
    if ys.shape != xs.shape:
        raise ValueError(f"{who}y must have shape {xs.shape}, the shape of x (got {ys.shape})")
    if t is None:
        return CoupledRecording(None, xs, ys)
    ts = np.asarray(t, dtype=np.float64)
    if ts.ndim != 1 or ts.size != xs.shape[0]:
        raise ValueError(
            f"{who}t must have shape ({xs.shape[0]},), one time per sample (got {ts.shape})"
        )
    bad = np.flatnonzero(~np.isfinite(ts))
    if bad.size:
        raise ValueError(f"{who}t has a non-finite value ({ts[bad[0]]}) at sample {bad[0]}")
    back = np.flatnonzero(np.diff(ts) <= 0.0)
    if back.size:
        k = int(back[0]) + 1
        raise ValueError(
            f"{who}time is not strictly increasing at sample {k} "
            f"(t[{k}] = {ts[k]} after t[{k - 1}] = {ts[k - 1]})"
        )
    return CoupledRecording(np.ascontiguousarray(ts), xs, ys)


__all__ = ["CoupledRecording", "coupled_recordings"]
