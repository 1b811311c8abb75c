"""A model used in other units: an affine map on its input and on its output."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._util.args import number
from .._util.typing import ArrayLike, FloatArray
from ..simulation_result import SimulationResult
from ..status import Status
from .base import FORMAT_NAME, FORMAT_VERSION, HysteresisModel, split_wrapped_changes

_MAP = ("input_offset", "input_scale", "output_offset", "output_gain")


class Scaled(HysteresisModel):
    """y = output_offset + output_gain * inner((x - input_offset) / input_scale).

    What ``ts.identify`` returns when the data's sign, offsets or units do not fit the model
    class's own parameters (a negative gain, an output offset a Backlash cannot hold, motor
    steps 1017-2202 in and degrees out): the inner model is the one identified on centred,
    scaled data with a positive gain. ``output_gain`` may be negative; ``input_scale > 0``.
    Parameters are ``inner.<name>`` and the four map values; saved to JSON like any model.

    Parameters
    ----------
    inner : HysteresisModel
        The model in its own units (not a Scaled one).
    input_offset : float, default 0.0
        Subtracted from x.
    input_scale : float, default 1.0
        Divides x - input_offset; > 0.
    output_offset : float, default 0.0
        Added to the scaled inner output.
    output_gain : float, default 1.0
        Multiplies the inner output; any sign, not 0.

    Raises
    ------
    ValueError
        inner not a model (or a Scaled one), a map value not finite, input_scale not > 0 or
        output_gain 0.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    inner: HysteresisModel
    map: dict[str, float]
    uses_curve_angle: bool

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
        _check_map(dict(zip(_MAP, values, strict=True)))
        self.inner = inner
        self.map = dict(zip(_MAP, values, strict=True))
        self.rate_independent = inner.rate_independent
        self.uses_curve_angle = getattr(inner, "uses_curve_angle", False)
        self.control_inputs = inner.control_inputs  # x, and the inner model's curve_angle

    @property
    def params(self) -> dict[str, Any]:
        """The inner parameters as ``inner.<name>`` and the four map values (a copy)."""
        out = {f"inner.{k}": v for k, v in self.inner.params.items()}
        out.update(self.map)
        return out

    @property
    def options(self) -> dict[str, Any]:
        """No options of its own: an empty dict."""
        return {}

    def with_params(self, **changes: Any) -> Scaled:
        """A new Scaled model with some parameters changed.

        Parameters
        ----------
        **changes
            New values by ``inner.<name>`` or by map value name.

        Returns
        -------
        Scaled
            A new model; this one is unchanged.

        Raises
        ------
        ValueError
            An unknown name.
        """
        inner, mapping = split_wrapped_changes(changes, "inner", self.map, "Scaled")
        return Scaled(self.inner.with_params(**inner), **mapping)

    def to_inner_input(self, x: ArrayLike) -> FloatArray:
        """(x - input_offset) / input_scale.

        Parameters
        ----------
        x : array_like of float
            Inputs in the data's units.

        Returns
        -------
        numpy.ndarray of float
            Inputs in the inner model's units.
        """
        return (np.asarray(x, dtype=float) - self.map["input_offset"]) / self.map["input_scale"]

    def from_inner_output(self, u: ArrayLike) -> FloatArray:
        """output_offset + output_gain * u.

        Parameters
        ----------
        u : array_like of float
            Outputs of the inner model.

        Returns
        -------
        numpy.ndarray of float
            Outputs in the data's units.
        """
        return self.map["output_offset"] + self.map["output_gain"] * np.asarray(u, dtype=float)

    @property
    def reports_status(self) -> bool:  # type: ignore[override]  # the inner model's class flag
        """Whether the inner model reports a Status."""
        return self.inner.reports_status

    def status(self) -> Status:
        """The inner model's last step's Status.

        Returns
        -------
        Status
            The inner model's flags.
        """
        return self.inner.status()

    def _simulate(  # the rest pass through to the inner model
        self, t: ArrayLike | None, x: ArrayLike, **kwargs: Any
    ) -> SimulationResult:
        """The inner model's simulation, in the data's units.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None when the inner model is rate-independent.
        x : array_like of float, shape (n,)
            Input samples in the data's units.
        **kwargs
            Passed to the inner model's ``simulate`` (``curve_angle``, ...).

        Returns
        -------
        SimulationResult, shape (n,)
            Output samples, with ``status`` the inner model's per-sample flags.
        """
        out = self.inner.simulate(t, self.to_inner_input(x), **kwargs)
        return SimulationResult(self.from_inner_output(out), status=out.status)

    def reset(self) -> None:
        """Forget the inner model's streaming state."""
        self.inner.reset()

    def step(self, x: float, dt: float = 0.0) -> float:
        """Advance one sample (streaming), in the data's units.

        Parameters
        ----------
        x : float
            The input sample.
        dt : float, default 0.0
            Time since the previous sample (s).

        Returns
        -------
        float
            The output sample.
        """
        u = self.inner.step((float(x) - self.map["input_offset"]) / self.map["input_scale"], dt)
        return self.map["output_offset"] + self.map["output_gain"] * u

    def _control_step(self, u, dt: float) -> float:
        x = (float(u[0]) - self.map["input_offset"]) / self.map["input_scale"]
        inner = self.inner._control_step([x, *u[1:]], dt)
        return self.map["output_offset"] + self.map["output_gain"] * inner

    def _dict_fields(self) -> dict[str, Any]:
        """The model as a JSON-ready dict: the inner model whole and the map.

        Returns
        -------
        dict
            format, version, model ("Scaled"), inner and map.
        """
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


def _check_map(values: dict[str, float]) -> None:
    """The rule of the C++ ``ScaledMap::validate``, with its messages (one per value)."""
    for name in ("input_offset", "output_offset"):
        if not math.isfinite(values[name]):
            raise ValueError(f"Scaled: {name} must be finite (got {values[name]:g})")
    if not (math.isfinite(values["input_scale"]) and values["input_scale"] > 0):
        raise ValueError(f"Scaled: input_scale must be > 0 (got {values['input_scale']:g})")
    gain = values["output_gain"]
    if not (math.isfinite(gain) and gain != 0):
        raise ValueError(f"Scaled: output_gain must be finite and not 0 (got {gain:g})")


__all__ = ["Scaled"]
