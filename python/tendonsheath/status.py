"""The status a real-time step reports besides its value (C++: include/tendonsheath/status.hpp).

Read it right after a step: ``plant._engine.status()``, ``motor._engine.status()``,
``controller._engine.status()`` return these flags as an int; ``Status(value)`` names them.
"""

from __future__ import annotations

from enum import IntFlag


class Status(IntFlag):
    """Flags of one step; 0 (``OK``) when nothing happened besides the computation."""

    OK = 0
    HELD_NONFINITE_INPUT = 1 << 0  # a non-finite input was ignored; the last output is held
    INPUT_CLAMPED = 1 << 1  # an input (or dt, or a curve angle) beyond its bound was clamped
    NOT_CONVERGED = 1 << 2  # the solver kept its best bounded iterate
    SLACK = 1 << 3  # a tendon tension is <= 0: the model is not valid there
    FALLBACK = 1 << 4  # a controller ran its fallback (no measurement)
    SATURATED = 1 << 5  # the command hit its limit


__all__ = ["Status"]
