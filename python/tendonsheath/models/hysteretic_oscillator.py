"""Single-degree-of-freedom oscillator with a Bouc-Wen restoring force."""

from __future__ import annotations

from typing import Any

from .. import _core as core
from .base import HysteresisModel

_INTERPOLATIONS = ("linear", "hold")


class HystereticOscillator(HysteresisModel):
    """m y'' + c y' + k y + z = u,
    z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + delta y' |z|^nu).

    Force u in, displacement y out, starting at rest. RK4 with at least ``substeps``
    sub-steps per sample (raised automatically for stability, at most ``max_substeps``).
    ``input_interpolation`` is "linear" (default) or "hold" between samples.
    """

    _core = core.HystereticOscillator
    _core_params = core.HystereticOscillatorParams
    param_names = ("m", "c", "k", "alpha", "beta", "gamma", "delta", "nu")
    option_names = ("substeps", "max_substeps", "input_interpolation")
    rate_independent = False

    def __init__(
        self,
        m: float = 1.0,
        c: float = 0.1,
        k: float = 1.0,
        alpha: float = 1.0,
        beta: float = 1.0,
        gamma: float = 0.5,
        delta: float = 0.5,
        nu: float = 1.0,
        substeps: int = 4,
        max_substeps: int = 4096,
        input_interpolation: str = "linear",
    ):
        super().__init__(
            m=m,
            c=c,
            k=k,
            alpha=alpha,
            beta=beta,
            gamma=gamma,
            delta=delta,
            nu=nu,
            substeps=substeps,
            max_substeps=max_substeps,
            input_interpolation=input_interpolation,
        )

    @classmethod
    def _core_values(cls, values: dict[str, Any]) -> dict[str, Any]:
        values = dict(values)
        mode = values.pop("input_interpolation", "linear")
        if mode not in _INTERPOLATIONS:
            raise ValueError(
                f"HystereticOscillator: input_interpolation must be one of {_INTERPOLATIONS} "
                f"(got {mode!r})"
            )
        values["hold_input"] = mode == "hold"
        return values

    @property
    def options(self) -> dict[str, Any]:
        s = self._engine.params
        return {
            "substeps": s.substeps,
            "max_substeps": s.max_substeps,
            "input_interpolation": "hold" if s.hold_input else "linear",
        }
