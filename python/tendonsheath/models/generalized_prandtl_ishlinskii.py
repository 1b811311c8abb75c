"""Generalized Prandtl-Ishlinskii model: asymmetric, saturated loops, with its inverse."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .._util.args import number_array
from .._util.typing import ArrayLike, FloatArray
from . import _bound as core
from ._param_table import from_table, table_default
from .base import HysteresisModel

_ENVELOPE = ("a", "b", "c", "d")
_ROWS = core.GeneralizedPrandtlIshlinskiiParams.fields()
# the envelope rows (rising, falling), each saved flat as <side>_a ... <side>_d
_SIDES = tuple(r["name"] for r in _ROWS if isinstance(r["default"], core.Envelope))
_FLAT = tuple(f"{side}_{k}" for side in _SIDES for k in _ENVELOPE)


class _GeneralizedBase(HysteresisModel):
    param_names = tuple(n for r in _ROWS for n in (_FLAT if r["name"] == _SIDES[0] else ()))
    param_names += tuple(r["name"] for r in _ROWS if r["name"] not in _SIDES)
    option_names = ("envelope_range",)

    def __init__(
        self,
        rising: Sequence[float] | FloatArray | None = None,
        falling: Sequence[float] | FloatArray | None = None,
        thresholds: ArrayLike | None = None,
        weights: ArrayLike | None = None,
        envelope_range: Sequence[float] | None = None,
        **flat: float,
    ):
        who = type(self).__name__
        values: dict[str, Any] = {}
        for side, env in (("rising", rising), ("falling", falling)):
            if env is None:
                env = table_default(type(self), side)
            if np.ndim(env) != 1 or len(env) != len(_ENVELOPE):
                raise ValueError(
                    f"{who}: {side} must be the 4 envelope coefficients (a, b, c, d) (got {env!r})"
                )
            values.update(zip((f"{side}_{k}" for k in _ENVELOPE), env, strict=True))
        values.update(flat)
        for name, given in (("thresholds", thresholds), ("weights", weights)):
            if given is not None:
                values[name] = [float(v) for v in number_array(who, name, given)]
        values["envelope_range"] = _checked_range(who, envelope_range)
        super().__init__(**values)

    @classmethod
    def _python_value(cls, name: str, value: Any) -> Any:
        if isinstance(value, core.Envelope):  # rising, falling: (a, b, c, d)
            return [float(getattr(value, k)) for k in _ENVELOPE]
        return super()._python_value(name, value)

    @classmethod
    def _core_values(cls, values: dict[str, Any]) -> dict[str, Any]:
        out = {k: v for k, v in values.items() if k not in (*_FLAT, "envelope_range")}
        span = values.get("envelope_range")
        for side in _SIDES:
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
        out = {f"{side}_{k}": getattr(getattr(s, side), k) for side in _SIDES for k in _ENVELOPE}
        for name in self.param_names[len(_FLAT) :]:  # the plays' thresholds and weights
            out[name] = [float(v) for v in getattr(s, name)]
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
        up, down = (_envelope(x, [p[f"{side}_{k}"] for k in _ENVELOPE], lo, hi) for side in _SIDES)
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


@from_table  # the signature's defaults and the rows' Parameters entries
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


@from_table  # the signature's defaults and the rows' Parameters entries
class GeneralizedPrandtlIshlinskiiInverse(  # type: ignore[misc]
    _GeneralizedBase, core.GeneralizedPrandtlIshlinskiiInverse
):
    """Inverse of :class:`GeneralizedPrandtlIshlinskii`: solves the monotone loading curve of
    the current play states each step (bounded bisection), clipped to the reachable range.

    Parameters
    ----------
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
