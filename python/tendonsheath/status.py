"""The status a real-time step reports besides its value (C++: include/tendonsheath/status.hpp).

Streaming: ``obj.status()`` right after ``obj.step(...)`` (plants, Motor, Sensor after
``measure``, every model, feedforward and controller) returns a :class:`Status`. Batch: the
per-sample flags come in the ``status`` field of every run's result
(``model.simulate(t, x).status``, ``feedforward.command(t, y_d).status``,
``plant.simulate(...).status``) as a uint8 array; :func:`status_counts` counts each flag.
"""

from __future__ import annotations

from enum import IntFlag

import numpy as np
from numpy.typing import ArrayLike


class Status(IntFlag):
    """Flags of one step; 0 (``OK``) when nothing happened besides the computation."""

    OK = 0
    HELD_NONFINITE_INPUT = 1 << 0  # a non-finite input was ignored; the last output is held
    INPUT_CLAMPED = 1 << 1  # an input (or dt, or a curve angle) beyond its bound was clamped
    NOT_CONVERGED = 1 << 2  # the solver kept its best bounded iterate
    SLACK = 1 << 3  # a tendon tension is <= 0: the model is not valid there
    FALLBACK = 1 << 4  # a controller ran its fallback (no measurement)
    SATURATED = 1 << 5  # the command hit its limit
    # an inverse's command would have left the input range its model was identified on (plus
    # the stated margin): the command was held at the range's edge (the target is unreachable)
    OUT_OF_RANGE = 1 << 6


# Every flag's name (lower case, as in C++ and in metrics.json), in bit order.
STATUS_FLAGS: tuple[str, ...] = tuple(str(f.name).lower() for f in Status if f.value)


def status_counts(flags: ArrayLike) -> dict[str, int]:
    """How many samples of a per-sample flag array carry each flag, by name (every flag
    listed, 0 when absent).

    Parameters
    ----------
    flags : array_like of int
        Per-sample :class:`Status` values (e.g. ``simulate(...).status``).

    Returns
    -------
    dict of str to int
        Flag name (lower case) -> number of samples carrying it.

    Raises
    ------
    ValueError
        flags that are not non-negative integers.
    """
    a = np.asarray(flags)
    if a.size and (not np.issubdtype(a.dtype, np.integer) or a.min() < 0):
        raise ValueError("status_counts: flags must be non-negative integers (Status values)")
    a = a.astype(np.int64, copy=False)
    return {str(f.name).lower(): int(np.count_nonzero(a & f.value)) for f in Status if f.value}


__all__ = ["STATUS_FLAGS", "Status", "status_counts"]
