"""Motor command limits that every compensator enforces."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TypeAlias

from .._util.args import number
from . import _bound as core


@dataclass(frozen=True)
class CommandLimits:
    """Saturation of a compensator's command: range and rate (units of the command, per s).

    Parameters
    ----------
    min : float, default -inf
        Lowest command.
    max : float, default inf
        Highest command.
    max_rate : float, default inf
        Largest command rate (command units per s).
    """

    min: float = -math.inf
    max: float = math.inf
    max_rate: float = math.inf

    def __post_init__(self):
        for name in _FIELDS:  # a number, or a TypeError naming the field
            object.__setattr__(self, name, number("CommandLimits", name, getattr(self, name)))

    def to_core(self) -> core.CommandLimits:
        """The C++ struct the real-time cores take.

        Returns
        -------
        tendonsheath._core.CommandLimits
            min, max and max_rate.
        """
        lim = core.CommandLimits()
        lim.min, lim.max, lim.max_rate = float(self.min), float(self.max), float(self.max_rate)
        return lim


_FIELDS = ("min", "max", "max_rate")


# what a compensator's ``limits`` accepts (see as_limits)
LimitsLike: TypeAlias = "CommandLimits | Sequence[float] | Mapping[str, float] | None"


def as_limits(limits: LimitsLike) -> CommandLimits:
    """Accept None, a CommandLimits, a (min, max[, max_rate]) tuple or list, or a dict with
    min/max/max_rate keys; anything else is a TypeError (a limit is never silently ignored)."""
    if limits is None:
        return CommandLimits()
    if isinstance(limits, CommandLimits):
        return limits
    if isinstance(limits, core.CommandLimits):
        return CommandLimits(limits.min, limits.max, limits.max_rate)
    if isinstance(limits, dict):
        unknown = sorted(set(map(str, limits)) - set(_FIELDS))
        if unknown:
            raise TypeError(f"limits: unknown key(s) {unknown}; use min, max, max_rate")
        return CommandLimits(**{k: _limit_value(k, v) for k, v in limits.items()})
    if isinstance(limits, (tuple, list)) and len(limits) in (2, 3):
        names = _FIELDS[: len(limits)]
        return CommandLimits(*(_limit_value(k, v) for k, v in zip(names, limits, strict=True)))
    raise TypeError(
        "limits must be a CommandLimits, a (min, max[, max_rate]) tuple or a dict "
        f"with min/max/max_rate (got {limits!r})"
    )


def _limit_value(name: str, value) -> float:
    return number("limits", name, value)


__all__ = ["CommandLimits", "LimitsLike", "as_limits"]
