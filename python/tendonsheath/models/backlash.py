"""Classic backlash (Tao and Kokotovic)."""

from __future__ import annotations

from . import _bound as core
from .base import HysteresisModel


class Backlash(HysteresisModel, core.Backlash):  # type: ignore[misc]
    """Exact piecewise backlash: y = c_r (x - B_r) rising, y = c_l (x + B_l) falling, held between.

    Starts in the middle of the band at the first sample. Rate-independent.

    Parameters
    ----------
    c_r, c_l : float, default 1.0
        Slopes of the rising and falling branches (> 0).
    B_r, B_l : float, default 0.1
        Half-widths of the band on the rising and falling side (input unit), >= 0.
    """

    _core_params = core.BacklashParams
    param_names = ("c_r", "c_l", "B_r", "B_l")

    def __init__(self, c_r: float = 1.0, c_l: float = 1.0, B_r: float = 0.1, B_l: float = 0.1):
        super().__init__(c_r=c_r, c_l=c_l, B_r=B_r, B_l=B_l)


__all__ = ["Backlash"]
