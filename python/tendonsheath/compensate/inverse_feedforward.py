"""Direct inverse feedforward of an identified hysteresis model (seed 002, spec D.2)."""

from __future__ import annotations

from .. import _core as core
from ..models import Backlash, BoucWenBacklash, HysteresisModel, PrandtlIshlinskii
from .base import Feedforward
from .limits import as_limits


class InverseFeedforward(Feedforward):
    """Motor command that makes `model` produce the desired output, with no distal sensor.

    * ``Backlash`` and ``BoucWenBacklash``: the direct inverse of spec D.2,
      x = [y_d + phi c_r B_r - (1 - phi) c_l B_l] / [phi c_r + (1 - phi) c_l] with
      phi = (1 + tanh(y_d' / smoothing)) / 2; ``smoothing`` (output units per s, about
      2-5 % of the peak desired speed) sets how sharply the command switches branch at a
      reversal (-> 0: the exact backlash inverse, a jump of B_r + B_l).
    * ``PrandtlIshlinskii``: its exact inverse operator (continuous; no smoothing needed).

    ``limits`` (a :class:`CommandLimits`) saturates the command and its rate.
    """

    def __init__(self, model: HysteresisModel, smoothing: float = 0.05, limits=None):
        self.model = model
        self.smoothing = float(smoothing)
        self.limits = as_limits(limits)
        if isinstance(model, Backlash | BoucWenBacklash):
            p = core.BacklashInverseParams()
            for key in ("c_r", "c_l", "B_r", "B_l"):
                setattr(p, key, model.params[key])
            p.v_eps = self.smoothing
            p.limits = self.limits.to_core()
            self._engine = core.BacklashInverseFeedforward(p)
        elif isinstance(model, PrandtlIshlinskii):
            pi = core.PrandtlIshlinskiiParams()
            pi.thresholds = model.params["thresholds"]
            pi.weights = model.params["weights"]
            self._engine = core.PrandtlIshlinskiiFeedforward(pi, self.limits.to_core())
        else:
            raise ValueError(
                "InverseFeedforward supports Backlash, BoucWenBacklash and PrandtlIshlinskii "
                f"models (got {type(model).__name__})"
            )

    def __repr__(self) -> str:
        return f"InverseFeedforward({self.model!r}, smoothing={self.smoothing:g})"
