"""Classic Bouc-Wen hysteresis, rate-independent input-output form."""

from __future__ import annotations

from .. import _args
from . import _bound as core
from .base import HysteresisModel

# Parameters renamed (old name -> new name); the old names still work, with a warning.
_RENAMED = {"a": "alpha"}


class BoucWen(HysteresisModel, core.BoucWen):  # type: ignore[misc]
    """y = alpha x + (1 - alpha) k z with dz = A dx - beta |dx| |z|^(n-1) z - gamma dx |z|^n.

    Requires beta > 0 and |gamma| <= beta (bounded state, |z| <= (A/(beta+gamma))^(1/n)).
    ``alpha`` was called ``a`` before; ``a=`` still works with a DeprecationWarning, and model
    files that say ``a`` still load.

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
    alpha : float, optional
        Share of the linear path, in [0, 1] (default 0.5).
    k : float, default 1.0
        Gain, finite.
    max_step : float, default 0.05
        Largest RK4 sub-step in x (input unit).
    max_substeps : int, default 256
        Most RK4 sub-steps per sample.
    **renamed
        Only ``a``, the old name of ``alpha`` (DeprecationWarning).

    Raises
    ------
    TypeError
        A keyword other than the parameters above and ``a``.
    ValueError
        Both ``alpha`` and ``a``, or a parameter the C++ core rejects.
    """

    _core_params = core.BoucWenParams
    param_names = ("A", "beta", "gamma", "n", "alpha", "k")
    option_names = ("max_step", "max_substeps")
    renamed_params = _RENAMED

    def __init__(
        self,
        A: float = 1.0,
        beta: float = 0.5,
        gamma: float = 0.5,
        n: float = 1.0,
        alpha: float | None = None,
        k: float = 1.0,
        max_step: float = 0.05,
        max_substeps: int = 256,
        **renamed: float,
    ):
        _args.reject_unknown("BoucWen", renamed, _RENAMED)
        alpha = _args.renamed("BoucWen", {"alpha": alpha, **renamed}, _RENAMED)["alpha"]
        super().__init__(
            A=A,
            beta=beta,
            gamma=gamma,
            n=n,
            alpha=0.5 if alpha is None else alpha,
            k=k,
            max_step=max_step,
            max_substeps=max_substeps,
        )


__all__ = ["BoucWen"]
