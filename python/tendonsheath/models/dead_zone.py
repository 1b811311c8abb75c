"""Dead zone (Tao and Kokotovic)."""

from __future__ import annotations

from . import _bound as core
from ._param_table import from_table
from .base import HysteresisModel


@from_table  # param_names, the signature, the defaults and the Parameters section
class DeadZone(HysteresisModel, core.DeadZone):  # type: ignore[misc]
    """Dead zone: y = c_r (x - d_r) for x > d_r, y = c_l (x + d_l) for x < -d_l, 0 between.

    Memoryless and rate-independent: the slack a tendon takes up before it carries load.
    """

    _core_params = core.DeadZoneParams


__all__ = ["DeadZone"]
