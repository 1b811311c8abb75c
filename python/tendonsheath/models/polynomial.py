"""Static polynomial output map, to compose after a hysteresis model."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._util.args import integer
from .._util.typing import ArrayLike, FloatArray
from . import _bound as core
from ._param_table import from_table, table_default
from .base import HysteresisModel


@from_table  # param_names, option_names, the signature and the rows' Parameters entries
class Polynomial(HysteresisModel, core.Polynomial):  # type: ignore[misc]
    """y = sum_k a_k u^k: ``Polynomial(3)`` is the identity cubic (a = [0, 1, 0, 0]);
    ``odd=True`` keeps odd powers only (coefficients a_1, a_3, ...).

    Static and rate-independent; use it after a hysteresis model with :class:`Chain`.

    Parameters
    ----------
    degree : int, optional
        Degree >= 1 of the identity polynomial (its coefficients are then derived); ignored
        when coefficients are given.

    Raises
    ------
    ValueError
        Neither a degree >= 1 nor coefficients.
    """

    _core_params = core.PolynomialParams
    derived_params = ("coefficients",)  # None: the identity polynomial of the degree

    def __init__(
        self, degree: int | None = None, coefficients: ArrayLike | None = None, **values: Any
    ):
        odd = bool(values.get("odd", table_default(type(self), "odd")))
        if coefficients is None:
            if degree is None or integer("Polynomial", "degree", degree) < 1:
                raise ValueError("Polynomial: give a degree >= 1 or the coefficients")
            degree = int(degree)
            count = (degree + 1) // 2 if odd else degree + 1
            coefficients = np.zeros(count)
            coefficients[0 if odd else 1] = 1.0
        values["coefficients"] = [float(c) for c in np.atleast_1d(np.asarray(coefficients, float))]
        super().__init__(**values)

    @property
    def degree(self) -> int:
        """The highest power."""
        n = len(self.params["coefficients"])
        return 2 * n - 1 if self.options["odd"] else n - 1

    def basis(self, u: ArrayLike) -> FloatArray:
        """Columns u^k of the powers in use: y = basis(u) @ coefficients.

        Parameters
        ----------
        u : array_like of float
            Inputs.

        Returns
        -------
        numpy.ndarray of float, shape u.shape + (len(coefficients),)
            The powers of u in use.
        """
        u = np.asarray(u, dtype=float)
        powers = range(1, self.degree + 1, 2) if self.options["odd"] else range(self.degree + 1)
        return np.stack([u**k for k in powers], axis=-1)


__all__ = ["Polynomial"]
