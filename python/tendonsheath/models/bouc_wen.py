"""Classic Bouc-Wen hysteresis, rate-independent input-output form."""

from __future__ import annotations

from . import _bound as core
from .base import HysteresisModel

# saved files' old parameter keys (old -> new): files that say "a" still load
_SAVED_AS = {"a": "alpha"}


class BoucWen(HysteresisModel, core.BoucWen):  # type: ignore[misc]
    """y = alpha x + (1 - alpha) k z with dz = A dx - beta |dx| |z|^(n-1) z - gamma dx |z|^n.

    Requires beta > 0 and |gamma| <= beta (bounded state, |z| <= (A/(beta+gamma))^(1/n)).
    ``alpha`` was called ``a`` before: model files that say ``a`` still load.

    No ``input_interpolation`` option (unlike HystereticOscillator and the plants): z is
    integrated in x, not in time (RK4 over the increment from one sample to the next), so
    the output at a sample depends on the samples only, never on the time between them or
    on how x gets from one to the next as long as it does not turn back: "hold" and "linear"
    give the same result (checked in tests/test_bouc_wen.py). A reconstruction could only
    matter through a reversal between samples (an overshoot of the band-limited
    interpolant), which a rate-independent model fed at its sample rate does not see.

    Parameters
    ----------
    A : float, default 1.0
        Amplitude of the state's increment, > 0.
    beta : float, default 0.5
        Shape parameter, > 0 (and beta + gamma > 0).
    gamma : float, default 0.5
        Shape parameter, |gamma| <= beta.
    n : float, default 1.0
        Sharpness of the transitions, >= 1.
    alpha : float, default 0.5
        Share of the linear path, in [0, 1].
    k : float, default 1.0
        Gain, finite.
    max_step : float, default 0.05
        Largest RK4 sub-step in x (input unit).
    max_substeps : int, default 256
        Most RK4 sub-steps per sample.

    Raises
    ------
    ValueError
        A parameter the C++ core rejects.
    """

    _core_params = core.BoucWenParams
    param_names = ("A", "beta", "gamma", "n", "alpha", "k")
    option_names = ("max_step", "max_substeps")
    renamed_params = _SAVED_AS

    def __init__(
        self,
        A: float = 1.0,
        beta: float = 0.5,
        gamma: float = 0.5,
        n: float = 1.0,
        alpha: float = 0.5,
        k: float = 1.0,
        max_step: float = 0.05,
        max_substeps: int = 256,
    ):
        super().__init__(
            A=A,
            beta=beta,
            gamma=gamma,
            n=n,
            alpha=alpha,
            k=k,
            max_step=max_step,
            max_substeps=max_substeps,
        )


__all__ = ["BoucWen"]
