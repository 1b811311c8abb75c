"""Classic Bouc-Wen hysteresis, rate-independent input-output form."""

from __future__ import annotations

from .. import _core as core
from .base import HysteresisModel


class BoucWen(HysteresisModel):
    """y = a x + (1 - a) k z with dz = A dx - beta |dx| |z|^(n-1) z - gamma dx |z|^n.

    Requires beta > 0 and |gamma| <= beta (bounded state, |z| <= (A/(beta+gamma))^(1/n)).

    No ``input_interpolation`` option (unlike HystereticOscillator and the plants): z is
    integrated in x, not in time (RK4 over the increment from one sample to the next), so
    the output at a sample depends on the samples only, never on the time between them or
    on how x gets from one to the next as long as it does not turn back: "hold" and "linear"
    give the same result (checked in tests/test_bouc_wen.py). A reconstruction could only
    matter through a reversal between samples (an overshoot of the band-limited
    interpolant), which a rate-independent model fed at its sample rate does not see.
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
