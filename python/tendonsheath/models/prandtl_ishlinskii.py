"""Prandtl-Ishlinskii hysteresis (weighted play operators) and its exact inverse."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._util.args import number_array
from .._util.typing import ArrayLike
from . import _bound as core
from ._param_table import from_table
from .base import HysteresisModel


class _PlayOperators(HysteresisModel):
    """The weighted plays' parameters, shared by the operator and its inverse."""

    _core_params = core.PrandtlIshlinskiiParams

    @classmethod
    def _core_values(cls, values: dict[str, Any]) -> dict[str, Any]:
        return {k: None if v is None else _vector(cls, k, v) for k, v in values.items()}


@from_table  # param_names, the signature, the defaults and the Parameters section
class PrandtlIshlinskii(_PlayOperators, core.PrandtlIshlinskii):  # type: ignore[misc]
    """y = sum_i weights[i] * play_{thresholds[i]}[x].

    Thresholds: 0 <= r_0 < r_1 < ...; the partial sums of the weights must be > 0.
    With r_0 = 0 too, the loading curve is strictly increasing and the operator is
    exactly invertible: see :meth:`inverse`. Plays start on the virgin curve from x = 0.

    Raises
    ------
    ValueError
        Arrays that are not 1-D, or values the C++ core rejects.
    """

    @classmethod
    def uniform(
        cls, max_threshold: float, count: int, weights: ArrayLike | None = None
    ) -> PrandtlIshlinskii:
        """count thresholds evenly spaced on [0, max_threshold); weights default to a decay.

        Parameters
        ----------
        max_threshold : float
            Upper end of the thresholds' interval (input unit), > 0.
        count : int
            Number of plays, >= 1.
        weights : array_like of float, optional
            One weight per play (default 1 then 0.5 shared by the others).

        Returns
        -------
        PrandtlIshlinskii
            The operator.

        Raises
        ------
        ValueError
            count < 1 or max_threshold not > 0.
        """
        if count < 1:
            raise ValueError("PrandtlIshlinskii.uniform: count must be >= 1")
        if not max_threshold > 0:
            raise ValueError("PrandtlIshlinskii.uniform: max_threshold must be > 0")
        r = np.arange(count) * (max_threshold / count)
        if weights is None:
            weights = np.r_[1.0, np.full(count - 1, 0.5 / max(count - 1, 1))]
        return cls(r, weights)

    def inverse(self) -> PrandtlIshlinskiiInverse:
        """The exact inverse operator: maps a desired output to the input that produces it.

        Returns
        -------
        PrandtlIshlinskiiInverse
            With the same thresholds and weights.
        """
        p = self.params
        return PrandtlIshlinskiiInverse(p["thresholds"], p["weights"])


@from_table  # param_names, the signature, the defaults and the Parameters section
class PrandtlIshlinskiiInverse(_PlayOperators, core.PrandtlIshlinskiiInverse):  # type: ignore[misc]
    """Exact inverse of :class:`PrandtlIshlinskii` with the same thresholds and weights.

    Each sample solves the piecewise-linear loading curve of the current play states
    exactly, so ``forward.simulate(t, inverse.simulate(t, y)) == y`` to rounding.

    Raises
    ------
    ValueError
        Arrays that are not 1-D, or values the C++ core rejects.
    """

    def inverse(self) -> PrandtlIshlinskii:
        """The forward operator this one inverts.

        Returns
        -------
        PrandtlIshlinskii
            With the same thresholds and weights.
        """
        p = self.params
        return PrandtlIshlinskii(p["thresholds"], p["weights"])


def _vector(cls: type, name: str, values) -> list[float]:
    arr = number_array(cls.__name__, name, values)
    if arr.ndim != 1:
        raise ValueError(f"PrandtlIshlinskii: thresholds and weights must be 1-D (got {arr.shape})")
    return [float(v) for v in arr]


__all__ = ["PrandtlIshlinskii", "PrandtlIshlinskiiInverse"]
