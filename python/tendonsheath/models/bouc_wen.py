"""Classic Bouc-Wen hysteresis, rate-independent input-output form."""

from __future__ import annotations

import warnings
from typing import Any

from .. import _core as core
from .base import HysteresisModel

# Parameters renamed (old name -> new name); the old names still work, with a warning.
_RENAMED = {"a": "alpha"}


def _renamed(values: dict[str, Any], warn: bool) -> dict[str, Any]:
    for old, new in _RENAMED.items():
        if old not in values:
            continue
        if new in values and values[new] is not None:
            raise ValueError(f"BoucWen: give {new} or its old name {old}, not both")
        if warn:
            warnings.warn(
                f"BoucWen: the parameter {old!r} is now called {new!r} (the share of the linear "
                f"path; A is the amplitude); {old!r} will be removed",
                DeprecationWarning,
                stacklevel=3,
            )
        values[new] = values.pop(old)
    return values


class BoucWen(HysteresisModel):
    """y = alpha x + (1 - alpha) k z with dz = A dx - beta |dx| |z|^(n-1) z - gamma dx |z|^n.

    Requires beta > 0 and |gamma| <= beta (bounded state, |z| <= (A/(beta+gamma))^(1/n)).
    ``alpha`` was called ``a`` before; ``a=`` still works with a DeprecationWarning, and model
    files that say ``a`` still load.
    """

    _core = core.BoucWen
    _core_params = core.BoucWenParams
    param_names = ("A", "beta", "gamma", "n", "alpha", "k")
    option_names = ("max_step", "max_substeps")

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
        **renamed,
    ):
        unknown = sorted(set(renamed) - set(_RENAMED))
        if unknown:
            raise TypeError(f"BoucWen: unknown parameter(s) {unknown}")
        alpha = _renamed({"alpha": alpha, **renamed}, warn=True)["alpha"]
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

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> HysteresisModel:
        """Also reads files written before ``a`` was renamed ``alpha`` (without a warning)."""
        params = data.get("params")
        if not isinstance(params, dict):  # the base class names what is wrong
            return super().from_dict(data)
        return super().from_dict({**data, "params": _renamed(dict(params), warn=False)})
