"""Classic backlash (Tao and Kokotovic)."""

from __future__ import annotations

from . import _bound as core
from ._param_table import from_table
from .base import HysteresisModel


@from_table  # param_names, the signature, the defaults and the Parameters section
class Backlash(HysteresisModel, core.Backlash):  # type: ignore[misc]
    """Exact piecewise backlash: y = c_r (x - B_r) rising, y = c_l (x + B_l) falling, held between.

    Starts in the middle of the band at the first sample. Rate-independent. ``B_r`` and ``B_l``
    are the half-widths of the band on the rising and falling side.
    """

    _core_params = core.BacklashParams


__all__ = ["Backlash"]
