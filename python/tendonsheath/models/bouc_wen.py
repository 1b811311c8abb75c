"""Classic Bouc-Wen hysteresis, rate-independent input-output form."""

from __future__ import annotations

from . import _bound as core
from ._param_table import from_table
from .base import HysteresisModel

# saved files' old parameter keys (old -> new): files that say "a" still load
_SAVED_AS = {"a": "alpha"}


@from_table  # param_names, option_names, the signature, the defaults, the Parameters section
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

    Raises
    ------
    TypeError
        A keyword other than the parameters above.
    ValueError
        A parameter the C++ core rejects.
    """

    _core_params = core.BoucWenParams
    renamed_params = _SAVED_AS


__all__ = ["BoucWen"]
