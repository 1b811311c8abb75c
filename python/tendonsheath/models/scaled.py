"""A model used in other units: an affine map on its input and on its output."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._args import number
from ..status import Status
from .base import FORMAT_NAME, FORMAT_VERSION, HysteresisModel

_MAP = ("input_offset", "input_scale", "output_offset", "output_gain")


class Scaled(HysteresisModel):
    """y = output_offset + output_gain * inner((x - input_offset) / input_scale).

    What ``ts.identify`` returns when the data's sign, offsets or units do not fit the model
    class's own parameters (a negative gain, an output offset a Backlash cannot hold, motor
    steps 1017-2202 in and degrees out): the inner model is the one identified on centred,
    scaled data with a positive gain. ``output_gain`` may be negative; ``input_scale > 0``.
    Parameters are ``inner.<name>`` and the four map values; saved to JSON like any model.
    """

    param_names = ()
    option_names = ()

    def __init__(
        self,
        inner: HysteresisModel,
        input_offset: float = 0.0,
        input_scale: float = 1.0,
        output_offset: float = 0.0,
        output_gain: float = 1.0,
    ):
        if not isinstance(inner, HysteresisModel) or isinstance(inner, Scaled):
            raise TypeError(
                "Scaled: inner must be a tendonsheath model, not a Scaled one "
                f"(got {type(inner).__name__})"
            )
        values = [
            number("Scaled", k, v)
            for k, v in zip(
                _MAP, (input_offset, input_scale, output_offset, output_gain), strict=True
            )
        ]
        if not all(np.isfinite(values)):
            raise ValueError(f"Scaled: the map values must be finite (got {values})")
        if not values[1] > 0:
            raise ValueError(f"Scaled: input_scale must be > 0 (got {values[1]})")
        if values[3] == 0:
            raise ValueError("Scaled: output_gain must not be 0")
        self.inner = inner
        self.map = dict(zip(_MAP, values, strict=True))
        self.rate_independent = inner.rate_independent
        self.uses_curve_angle = getattr(inner, "uses_curve_angle", False)
        self.control_inputs = inner.control_inputs  # x, and the inner model's curve_angle

    @property
    def params(self) -> dict[str, Any]:
        out = {f"inner.{k}": v for k, v in self.inner.params.items()}
        out.update(self.map)
        return out

    @property
    def options(self) -> dict[str, Any]:
        return {}

    def with_params(self, **changes) -> Scaled:
        inner, mapping = {}, dict(self.map)
        for key, value in changes.items():
            if key.startswith("inner."):
                inner[key.removeprefix("inner.")] = value
            elif key in mapping:
                mapping[key] = value
            else:
                raise TypeError(f"Scaled: unknown parameter {key!r}; inner.<name> or {_MAP}")
        return Scaled(self.inner.with_params(**inner), **mapping)

    def to_inner_input(self, x) -> np.ndarray:
        return (np.asarray(x, dtype=float) - self.map["input_offset"]) / self.map["input_scale"]

    def from_inner_output(self, u) -> np.ndarray:
        return self.map["output_offset"] + self.map["output_gain"] * np.asarray(u, dtype=float)

    @property
    def reports_status(self) -> bool:
        return self.inner.reports_status

    def status(self) -> Status:
        """The inner model's last step's Status."""
        return self.inner.status()

    def simulate(self, t, x, **kwargs):
        out = self.inner.simulate(t, self.to_inner_input(x), **kwargs)
        if kwargs.get("status"):  # (inner output, per-sample flags)
            return self.from_inner_output(out[0]), out[1]
        return self.from_inner_output(out)

    def reset(self) -> None:
        self.inner.reset()

    def step(self, x: float, dt: float = 0.0) -> float:
        u = self.inner.step((float(x) - self.map["input_offset"]) / self.map["input_scale"], dt)
        return self.map["output_offset"] + self.map["output_gain"] * u

    def _control_step(self, u, dt: float) -> float:
        x = (float(u[0]) - self.map["input_offset"]) / self.map["input_scale"]
        inner = self.inner._control_step([x, *u[1:]], dt)
        return self.map["output_offset"] + self.map["output_gain"] * inner

    def to_dict(self) -> dict[str, Any]:
        return {
            "format": FORMAT_NAME,
            "version": FORMAT_VERSION,
            "model": "Scaled",
            "inner": self.inner.to_dict(),
            "map": dict(self.map),
        }

    @classmethod
    def _from_parts(cls, data: dict[str, Any]) -> Scaled:
        try:
            inner, mapping = data["inner"], data["map"]
        except KeyError as exc:
            raise ValueError(f"Scaled file is missing its '{exc.args[0]}' part") from None
        unknown = set(mapping) - set(_MAP)
        if unknown:
            raise ValueError(f"Scaled: unknown map value(s) {sorted(unknown)}; expected {_MAP}")
        return cls(HysteresisModel.from_dict(inner), **mapping)

    def __repr__(self) -> str:
        m = ", ".join(f"{k}={v:.6g}" for k, v in self.map.items())
        return f"Scaled({self.inner!r}, {m})"
