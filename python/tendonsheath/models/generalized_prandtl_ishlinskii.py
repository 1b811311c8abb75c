"""Generalized Prandtl-Ishlinskii model: asymmetric, saturated loops, with its inverse."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .._args import number_array
from .._typing import ArrayLike, FloatArray
from . import _bound as core
from .base import HysteresisModel

_ENVELOPE = ("a", "b", "c", "d")
_FLAT = tuple(f"{side}_{k}" for side in ("rising", "falling") for k in _ENVELOPE)


class _GeneralizedBase(HysteresisModel):
    param_names = (*_FLAT, "thresholds", "weights")
    option_names = ("envelope_range",)

    def __init__(
        self,
        rising: Sequence[float] | FloatArray = (1.0, 1.0, 0.0, 0.0),
        falling: Sequence[float] | FloatArray = (1.0, 1.0, 0.0, 0.0),
        thresholds: ArrayLike = (0.0, 0.05, 0.1, 0.2),
        weights: ArrayLike = (0.6, 0.2, 0.1, 0.1),
        envelope_range: Sequence[float] | None = None,
        **flat: float,
    ):
        for side, env in (("rising", rising), ("falling", falling)):
            if np.ndim(env) != 1 or len(env) != len(_ENVELOPE):
                raise ValueError(
                    f"{type(self).__name__}: {side} must be the 4 envelope coefficients "
                    f"(a, b, c, d) (got {env!r})"
                )
        values = dict(zip(_FLAT, [*rising, *falling], strict=True))
        values.update(flat)
        who = type(self).__name__
        values["thresholds"] = [float(v) for v in number_array(who, "thresholds", thresholds)]
        values["weights"] = [float(v) for v in number_array(who, "weights", weights)]
        values["envelope_range"] = _checked_range(who, envelope_range)
        super().__init__(**values)

    @classmethod
    def _core_values(cls, values: dict[str, Any]) -> dict[str, Any]:
        out = {k: v for k, v in values.items() if k not in (*_FLAT, "envelope_range")}
        span = values.get("envelope_range")
        for side in ("rising", "falling"):
            env = core.Envelope()
            for k in _ENVELOPE:
                key = f"{side}_{k}"
                if key in values:
                    setattr(env, k, float(values[key]))
            if span is not None:
                env.lo, env.hi = span
            out[side] = env
        return out

    @property
    def options(self) -> dict[str, Any]:
        """``envelope_range``: the envelopes' tanh input range [lo, hi] (beyond it, their
        tangent lines); left out when there is none (the tanh everywhere: saved files stay
        as before)."""
        env = self.params_struct().rising
        if not (np.isfinite(env.lo) and np.isfinite(env.hi)):
            return {}
        return {"envelope_range": [float(env.lo), float(env.hi)]}

    @property
    def params(self) -> dict[str, Any]:
        """The flat envelope coefficients, thresholds and weights, as a dict (a copy)."""
        s = self.params_struct()
        out = {
            f"{side}_{k}": getattr(getattr(s, side), k)
            for side in ("rising", "falling")
            for k in _ENVELOPE
        }
        out["thresholds"] = [float(v) for v in s.thresholds]
        out["weights"] = [float(v) for v in s.weights]
        return out

    def envelopes(self, x: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """The rising and falling envelope functions evaluated at x.

        Parameters
        ----------
        x : array_like of float
            Inputs.

        Returns
        -------
        up, down : numpy.ndarray of float
            The rising and falling envelopes at x, shaped as x.
        """
        p = self.params
        x = np.asarray(x, dtype=float)
        span = self.options.get("envelope_range")
        lo, hi = (-np.inf, np.inf) if span is None else span
        up, down = (
            _envelope(x, [p[f"{side}_{k}"] for k in _ENVELOPE], lo, hi)
            for side in ("rising", "falling")
        )
        return up, down


def _envelope(x: FloatArray, coefficients: list[float], lo: float, hi: float) -> FloatArray:
    """a tanh(b (x - c)) + d inside [lo, hi], its tangent line beyond (as the C++ Envelope)."""
    a, b, c, d = coefficients

    def tanh(u):
        return a * np.tanh(b * (u - c)) + d

    def slope(u):
        with np.errstate(over="ignore"):
            return a * b / np.cosh(b * (u - c)) ** 2

    out = tanh(np.clip(x, lo, hi))
    for end, past in ((hi, x > hi), (lo, x < lo)):
        if np.any(past):
            out = np.where(past, tanh(end) + slope(end) * (x - end), out)
    return out


def _checked_range(who: str, value: Sequence[float] | None) -> list[float] | None:
    """``envelope_range``: None or (lo, hi), finite with lo < hi."""
    if value is None:
        return None
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(
            f"{who}: envelope_range must be None or (lo, hi) (got {value!r})"
        ) from None
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"{who}: envelope_range must be finite with lo < hi (got ({lo}, {hi}))")
    return [lo, hi]


class GeneralizedPrandtlIshlinskii(_GeneralizedBase, core.GeneralizedPrandtlIshlinskii):  # type: ignore[misc]
    """Plays bounded by saturating envelopes gamma(x) = a tanh(b (x - c)) + d, one for rising
    and one for falling input; the threshold-0 play is the centre line between them. Beyond
    ``envelope_range`` (the training inputs' range, once identified) the envelopes follow their
    tangent lines: the model extrapolates the slope it was fitted on, not a saturation the data
    never showed.

    ``rising`` and ``falling`` are (a, b, c, d); thresholds start at 0 and increase; weights
    are >= 0 with weights[0] > 0, which makes the operator invertible (:meth:`inverse`)
    inside the envelopes' range.

    Parameters
    ----------
    rising, falling : sequence of 4 float, default (1.0, 1.0, 0.0, 0.0)
        Envelope coefficients (a, b, c, d) of gamma(x) = a tanh(b (x - c)) + d for rising and
        falling input.
    thresholds : sequence of float, default (0.0, 0.05, 0.1, 0.2)
        Play thresholds (input unit): the first 0, increasing.
    weights : sequence of float, default (0.6, 0.2, 0.1, 0.1)
        Play weights, one per threshold: >= 0, weights[0] > 0.
    envelope_range : (float, float), optional
        The input range (lo, hi) of both envelopes' tanh; beyond it each envelope continues
        along its tangent line (continuous, with a continuous slope, still increasing) instead
        of saturating. ``identify`` sets it to the training inputs' range, so that past the
        data the model keeps the slope it saw last. None (default): the tanh everywhere.
    **flat
        The envelope coefficients by flat name (``rising_a`` ... ``falling_d``), as in
        :attr:`params`; they override ``rising``/``falling``.

    Raises
    ------
    ValueError
        An envelope that is not 4 numbers, an unknown name, or parameters the C++ core
        rejects.
    """

    _core_params = core.GeneralizedPrandtlIshlinskiiParams

    def inverse(self) -> GeneralizedPrandtlIshlinskiiInverse:
        """The inverse operator with the same parameters.

        Returns
        -------
        GeneralizedPrandtlIshlinskiiInverse
            Maps a desired output to the input that gives it.
        """
        return GeneralizedPrandtlIshlinskiiInverse(**self.params)


class GeneralizedPrandtlIshlinskiiInverse(  # type: ignore[misc]
    _GeneralizedBase, core.GeneralizedPrandtlIshlinskiiInverse
):
    """Inverse of :class:`GeneralizedPrandtlIshlinskii`: solves the monotone loading curve of
    the current play states each step (bounded bisection), clipped to the reachable range.

    Parameters
    ----------
    rising, falling : sequence of 4 float, default (1.0, 1.0, 0.0, 0.0)
        Envelope coefficients (a, b, c, d) of gamma(x) = a tanh(b (x - c)) + d for rising and
        falling input.
    thresholds : sequence of float, default (0.0, 0.05, 0.1, 0.2)
        Play thresholds (input unit): the first 0, increasing.
    weights : sequence of float, default (0.6, 0.2, 0.1, 0.1)
        Play weights, one per threshold: >= 0, weights[0] > 0.
    envelope_range : (float, float), optional
        The input range (lo, hi) of both envelopes' tanh; beyond it each envelope continues
        along its tangent line (continuous, with a continuous slope, still increasing) instead
        of saturating. ``identify`` sets it to the training inputs' range, so that past the
        data the model keeps the slope it saw last. None (default): the tanh everywhere.
    **flat
        The envelope coefficients by flat name (``rising_a`` ... ``falling_d``), as in
        :attr:`params`; they override ``rising``/``falling``.

    Raises
    ------
    ValueError
        An envelope that is not 4 numbers, an unknown name, or parameters the C++ core
        rejects.
    """

    _core_params = core.GeneralizedPrandtlIshlinskiiParams

    def inverse(self) -> GeneralizedPrandtlIshlinskii:
        """The forward operator with the same parameters.

        Returns
        -------
        GeneralizedPrandtlIshlinskii
            The operator this one inverts.
        """
        return GeneralizedPrandtlIshlinskii(**self.params)


__all__ = ["GeneralizedPrandtlIshlinskii", "GeneralizedPrandtlIshlinskiiInverse"]
