"""Motor command limits that every compensator enforces."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .. import _core as core


@dataclass(frozen=True)
class CommandLimits:
    """Saturation of a compensator's command: range and rate (units of the command, per s)."""

    min: float = -math.inf
    max: float = math.inf
    max_rate: float = math.inf

    def to_core(self) -> core.CommandLimits:
        lim = core.CommandLimits()
        lim.min, lim.max, lim.max_rate = float(self.min), float(self.max), float(self.max_rate)
        return lim


def as_limits(limits) -> CommandLimits:
    """Accept None, a CommandLimits, or any object with min/max/max_rate attributes."""
    if limits is None:
        return CommandLimits()
    if isinstance(limits, CommandLimits):
        return limits
    try:
        return CommandLimits(
            getattr(limits, "min", -math.inf),
            getattr(limits, "max", math.inf),
            getattr(limits, "max_rate", math.inf),
        )
    except TypeError:
        raise ValueError(f"limits must be a CommandLimits (got {limits!r})") from None
