"""Backlash-like hysteresis of Do et al. on a normalised Bouc-Wen state (spec D.1)."""

from __future__ import annotations

import math
from typing import Any

from .._util.args import number
from . import _bound as core
from ._param_table import from_table, table_default
from .base import HysteresisModel


@from_table  # param_names, option_names, the signature, the defaults, the Parameters section
class BoucWenBacklash(HysteresisModel, core.BoucWenBacklash):  # type: ignore[misc]
    """y = phi c_r (x - B_r) + (1 - phi) c_l (x + B_l), phi = (1 + w)/2, w in [-1, 1].

    dw = rho [dx - sigma |dx| |w|^(n-1) w + (sigma - 1) dx |w|^n]. ``rho`` defaults to
    2 / (B_r + B_l). Larger n makes the dead zone flatter (n -> inf tends to Backlash).
    ``max_step`` and ``max_substeps`` set the RK4 sub-stepping in x (numerical options).

    Raises
    ------
    ValueError
        rho not given with B_r + B_l not > 0 (or too small), or a parameter the C++ core
        rejects.
    """

    _core_params = core.BoucWenBacklashParams
    derived_params = ("rho",)  # None: 2 / (B_r + B_l)

    @classmethod
    def _core_values(cls, values: dict[str, Any]) -> dict[str, Any]:
        if values.get("rho") is not None:
            return values
        B_r = values.get("B_r", table_default(cls, "B_r"))
        B_l = values.get("B_l", table_default(cls, "B_l"))
        return {**values, "rho": _default_rho(B_r, B_l)}


def _default_rho(B_r, B_l) -> float | None:
    """rho = 2 / (B_r + B_l); None (the core's default) when B_r or B_l is out of range, so
    that the core names the bad one, as it does for a saved file that gives rho."""
    B_r, B_l = (number("BoucWenBacklash", k, v) for k, v in (("B_r", B_r), ("B_l", B_l)))
    if not all(math.isfinite(b) and b >= 0 for b in (B_r, B_l)):
        return None
    width = B_r + B_l
    if not width > 0:
        raise ValueError("BoucWenBacklash: give rho when B_r + B_l is not > 0")
    rho = 2.0 / width
    if not math.isfinite(rho):
        raise ValueError(
            f"BoucWenBacklash: B_r + B_l = {width:g} is too small to derive "
            "rho = 2 / (B_r + B_l); give rho"
        )
    return rho


__all__ = ["BoucWenBacklash"]
