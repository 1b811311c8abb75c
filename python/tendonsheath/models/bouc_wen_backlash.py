"""Backlash-like hysteresis of Do et al. on a normalised Bouc-Wen state (spec D.1)."""

from __future__ import annotations

import math

from .._args import number
from . import _bound as core
from .base import HysteresisModel


class BoucWenBacklash(HysteresisModel, core.BoucWenBacklash):  # type: ignore[misc]
    """y = phi c_r (x - B_r) + (1 - phi) c_l (x + B_l), phi = (1 + w)/2, w in [-1, 1].

    dw = rho [dx - sigma |dx| |w|^(n-1) w + (sigma - 1) dx |w|^n]. ``rho`` defaults to
    2 / (B_r + B_l). Larger n makes the dead zone flatter (n -> inf tends to Backlash).
    ``max_step`` and ``max_substeps`` set the RK4 sub-stepping in x (numerical options).

    Parameters
    ----------
    c_r, c_l : float, default 1.0
        Slopes of the rising and falling branches (> 0).
    B_r, B_l : float, default 0.1
        Dead-zone offsets on the rising and falling side (input unit), >= 0.
    rho : float, optional
        Rate of the state w per unit input, > 0; default 2 / (B_r + B_l).
    sigma : float, default 1.0
        Shape of the transitions, >= 0.5.
    n : float, default 4.0
        Flatness of the dead zone (>= 1).
    max_step : float, default 0.05
        Largest RK4 sub-step in x (input unit).
    max_substeps : int, default 256
        Most RK4 sub-steps per sample.

    Raises
    ------
    ValueError
        rho not given with B_r + B_l not > 0 (or too small), or a parameter the C++ core
        rejects.
    """

    _core_params = core.BoucWenBacklashParams
    param_names = ("c_r", "c_l", "B_r", "B_l", "rho", "sigma", "n")
    option_names = ("max_step", "max_substeps")

    def __init__(
        self,
        c_r: float = 1.0,
        c_l: float = 1.0,
        B_r: float = 0.1,
        B_l: float = 0.1,
        rho: float | None = None,
        sigma: float = 1.0,
        n: float = 4.0,
        max_step: float = 0.05,
        max_substeps: int = 256,
    ):
        if rho is None:
            rho = _default_rho(B_r, B_l)
        super().__init__(
            c_r=c_r,
            c_l=c_l,
            B_r=B_r,
            B_l=B_l,
            rho=rho,
            sigma=sigma,
            n=n,
            max_step=max_step,
            max_substeps=max_substeps,
        )


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
