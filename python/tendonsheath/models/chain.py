"""A hysteresis model followed by a static output map, fitted and used as one model."""

from __future__ import annotations

from typing import Any

import numpy as np

from .base import FORMAT_NAME, FORMAT_VERSION, HysteresisModel


class Chain(HysteresisModel):
    """y = second(first(x)), e.g. ``Chain(BoucWenBacklash(), Polynomial(3))``.

    Parameters are addressed as ``first.<name>`` and ``second.<name>``.
    """

    param_names = ()
    option_names = ()

    def __init__(self, first: HysteresisModel, second: HysteresisModel):
        if not isinstance(first, HysteresisModel) or not isinstance(second, HysteresisModel):
            raise ValueError("Chain: both parts must be tendonsheath models")
        if isinstance(first, Chain) or isinstance(second, Chain):
            raise ValueError("Chain: parts cannot themselves be chains")
        self.first, self.second = first, second
        self.rate_independent = first.rate_independent and second.rate_independent

    @property
    def params(self) -> dict[str, Any]:
        out = {f"first.{k}": v for k, v in self.first.params.items()}
        out.update({f"second.{k}": v for k, v in self.second.params.items()})
        return out

    @property
    def options(self) -> dict[str, Any]:
        return {}

    def with_params(self, **changes) -> Chain:
        parts = {"first": {}, "second": {}}
        for key, value in changes.items():
            part, _, name = key.partition(".")
            if part not in parts or not name:
                raise ValueError(
                    f"Chain: parameter names are first.<name> or second.<name> ({key})"
                )
            parts[part][name] = value
        return Chain(
            self.first.with_params(**parts["first"]), self.second.with_params(**parts["second"])
        )

    def simulate(self, t, x) -> np.ndarray:
        u = self.first.simulate(t, x)
        return self.second.simulate(None if self.second.rate_independent else t, u)

    def reset(self) -> None:
        self.first.reset()
        self.second.reset()

    def step(self, x: float, dt: float = 0.0) -> float:
        return self.second.step(self.first.step(x, dt), dt)

    def to_dict(self) -> dict[str, Any]:
        return {
            "format": FORMAT_NAME,
            "version": FORMAT_VERSION,
            "model": "Chain",
            "first": self.first.to_dict(),
            "second": self.second.to_dict(),
        }

    @classmethod
    def _from_parts(cls, data: dict[str, Any]) -> Chain:
        try:
            first, second = data["first"], data["second"]
        except KeyError as exc:
            raise ValueError(f"Chain file is missing its '{exc.args[0]}' part") from None
        return cls(HysteresisModel.from_dict(first), HysteresisModel.from_dict(second))

    def __repr__(self) -> str:
        return f"Chain({self.first!r}, {self.second!r})"
