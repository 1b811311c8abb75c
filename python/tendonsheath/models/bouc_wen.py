"""Classic Bouc-Wen hysteresis, rate-independent input-output form."""

from __future__ import annotations

from .. import _core as core
from .base import HysteresisModel


class BoucWen(HysteresisModel):
    """y = a x + (1 - a) k z with dz = A dx - beta |dx| |z|^(n-1) z - gamma dx |z|^n.

    Requires beta > 0 and |gamma| <= beta (bounded state, |z| <= (A/(beta+gamma))^(1/n)).
    """

    _core = core.BoucWen
    _core_params = core.BoucWenParams
    param_names = ("A", "beta", "gamma", "n", "a", "k")
    option_names = ("max_step", "max_substeps")

    def __init__(
        self,
        A: float = 1.0,
        beta: float = 0.5,
        gamma: float = 0.5,
        n: float = 1.0,
        a: float = 0.5,
        k: float = 1.0,
        max_step: float = 0.05,
        max_substeps: int = 256,
    ):
        super().__init__(
            A=A,
            beta=beta,
            gamma=gamma,
            n=n,
            a=a,
            k=k,
            max_step=max_step,
            max_substeps=max_substeps,
        )
