"""Sheath routes: the accumulated curve angle theta(s) along the arc length (spec A.1, A.5)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

from .._util.args import core_errors_as, number, number_array
from .._util.arrays import as_signal
from .._util.pyobject import bound_attribute
from .._util.typing import ArrayLike, FloatArray
from .._util.units import LENGTH, warn_if_curve_angle_in_degrees, warn_if_unit_slip
from .._util.units import UnitWarning as UnitWarning
from . import _bound as core

# 100 full turns: the largest curve angle accepted in measured data (no sheath route comes near
# it; a larger logged value is a unit or column mistake). The plant itself takes any angle.
MAX_CURVE_ANGLE = 200 * np.pi

_PIECE = ("Route.arcs", "piece")


class Route(core.Route):
    """The centreline of a sheath as its accumulated curve angle theta(s) = int_0^s |kappa| ds.

    Stored as samples (s_i, theta_i) with s from 0 to the length L and theta non-decreasing,
    linear in between; two samples at the same s are a jump (a polyline corner). Only the
    distribution of theta along s matters to the friction physics, not the 3-D shape.
    Build one with :meth:`uniform`, :meth:`arcs`, :meth:`from_points` or :meth:`from_curvature`.

    Parameters
    ----------
    s : array_like of float, shape (k,)
        Arc lengths (m), from 0 to the length L, non-decreasing.
    theta : array_like of float, shape (k,)
        Accumulated curve angle at each s (rad), from 0, non-decreasing.

    Raises
    ------
    ValueError
        Samples that are not finite, of different lengths, or not as above.

    Notes
    -----
    A Route is the C++ ``tendonsheath::Route`` (a subclass of the bound class), so the
    plants' and compensators' C++ functions take it as it is.
    """

    __slots__ = ()

    def __init__(self, s: ArrayLike, theta: ArrayLike):
        s_arr = as_signal(number_array("Route", "s", s), "s")
        th_arr = as_signal(number_array("Route", "theta", theta), "theta")
        with core_errors_as("Route"):
            core.Route.__init__(self, s_arr.tolist(), th_arr.tolist())
        warn_if_curve_angle_in_degrees(self.curve_angle, "Route", "theta[-1]")
        warn_if_unit_slip(self.length, "Route", "s[-1] (the length)", LENGTH)

    @classmethod
    def _wrap(cls, built: core.Route) -> Route:
        """A Route that is a copy of the C++ route ``built``."""
        obj = cls.__new__(cls)
        core.Route.__init__(obj, built)
        return obj

    @classmethod
    def uniform(cls, length: float, curve_angle: float) -> Route:
        """Constant curvature: theta(s) = curve_angle * s / length.

        Parameters
        ----------
        length : float
            Sheath length L (m), > 0.
        curve_angle : float
            Curve angle Theta (rad), >= 0.

        Returns
        -------
        Route
            The uniform route.
        """
        length = number("Route.uniform", "length", length)
        angle = number("Route.uniform", "curve_angle", curve_angle)
        with core_errors_as("Route.uniform"):
            route = cls._wrap(core.Route.uniform(length, angle))
        warn_if_curve_angle_in_degrees(angle, "Route.uniform")
        warn_if_unit_slip(length, "Route.uniform", "length", LENGTH)
        return route

    @classmethod
    def arcs(cls, pieces: Iterable[Sequence[float]]) -> Route:
        """Consecutive constant-curvature pieces [(length m, bend angle rad), ...].

        A bend to the other side (negative angle) accumulates |angle|.

        Parameters
        ----------
        pieces : iterable of (float, float)
            (length in m, bend angle in rad) of each piece, proximal to distal.

        Returns
        -------
        Route
            The piecewise-uniform route.

        Raises
        ------
        ValueError
            pieces that are not (length, angle) pairs, or invalid values.
        """
        try:
            items = [(number(*_PIECE, a), number(*_PIECE, b)) for a, b in pieces]
        except (TypeError, ValueError):
            raise TypeError(
                f"Route.arcs: pieces must be (length, angle) pairs of numbers (got {pieces!r})"
            ) from None
        with core_errors_as("Route.arcs"):
            route = cls._wrap(core.Route.arcs(items))
        warn_if_curve_angle_in_degrees(route.curve_angle, "Route.arcs", "the pieces' total angle")
        warn_if_unit_slip(route.length, "Route.arcs", "the pieces' total length", LENGTH)
        return route

    @classmethod
    def from_points(cls, xyz: ArrayLike) -> Route:
        """A 3-D polyline (K x 3, metres); each corner adds its turning angle.

        Parameters
        ----------
        xyz : array_like of float, shape (K, 3)
            The polyline's points (m), proximal to distal.

        Returns
        -------
        Route
            The route, with a jump of theta at each corner.

        Raises
        ------
        TypeError
            Points that are not numbers.
        ValueError
            Points not K x 3, or not valid (fewer than two, not finite, repeated).
        """
        pts = np.ascontiguousarray(number_array("Route.from_points", "xyz", xyz))
        if pts.ndim != 2 or pts.shape[1] != 3:
            raise ValueError(f"Route.from_points: points must be K x 3 (got shape {pts.shape})")
        route = cls._wrap(core.Route.from_points(pts))
        warn_if_unit_slip(route.length, "Route.from_points", "the polyline's length", LENGTH)
        return route

    @classmethod
    def from_curvature(cls, s: ArrayLike, kappa: ArrayLike) -> Route:
        """A sampled curvature profile |kappa(s)| (1/m); theta is its trapezoidal integral.

        Parameters
        ----------
        s : array_like of float, shape (k,)
            Arc lengths (m), from 0, increasing.
        kappa : array_like of float, shape (k,)
            Curvature at each s (1/m); its absolute value is integrated.

        Returns
        -------
        Route
            The route.

        Raises
        ------
        TypeError
            s or kappa that are not numbers.
        ValueError
            s and kappa of different lengths, or invalid samples.
        """
        s_arr = as_signal(number_array("Route.from_curvature", "s", s), "s")
        k_arr = as_signal(number_array("Route.from_curvature", "kappa", kappa), "kappa")
        if s_arr.shape != k_arr.shape:
            raise ValueError(
                f"Route.from_curvature: s and kappa have different lengths "
                f"({s_arr.size} and {k_arr.size})"
            )
        route = cls._wrap(core.Route.from_curvature(s_arr, k_arr))
        warn_if_curve_angle_in_degrees(route.curve_angle, "Route.from_curvature", "the curve angle")
        warn_if_unit_slip(route.length, "Route.from_curvature", "s[-1] (the length)", LENGTH)
        return route

    # -- properties ------------------------------------------------------------------
    @property
    def length(self) -> float:
        """Sheath length L (m)."""
        return bound_attribute(self, "length")

    @property
    def curve_angle(self) -> float:
        """Curve angle Theta = theta(L) (rad)."""
        return bound_attribute(self, "curve_angle")

    @property
    def s(self) -> np.ndarray:
        """The sample arc lengths (m)."""
        return self.s_samples()

    @property
    def theta(self) -> np.ndarray:
        """The accumulated curve angle at each sample (rad)."""
        return self.theta_samples()

    def angle_at(self, s: ArrayLike) -> float | FloatArray:  # type: ignore[override]
        """theta(s) (rad), vectorised; right-continuous at corners, clamped outside [0, L].

        Parameters
        ----------
        s : float or array_like of float
            Arc length(s) (m).

        Returns
        -------
        float or numpy.ndarray of float
            theta at each s, shaped as s.
        """
        arr = np.asarray(s, dtype=np.float64)
        if arr.ndim == 0:
            return core.Route.angle_at(self, float(arr))
        flat = np.ascontiguousarray(arr.ravel())
        return self.angles_at(flat).reshape(arr.shape)

    def element_angles(self, n: int) -> np.ndarray:
        """Angles of n equal elements, proximal to distal (they sum to curve_angle).

        Parameters
        ----------
        n : int
            Number of elements, >= 1.

        Returns
        -------
        numpy.ndarray of float, shape (n,)
            The curve angle of each element (rad).
        """
        return core.Route.element_angles(self, int(n))

    def node_angles(self, n: int) -> np.ndarray:
        """Lumped angles of the n-1 interior nodes of an n-element sheath (sum: curve_angle).

        Parameters
        ----------
        n : int
            Number of elements, >= 2.

        Returns
        -------
        numpy.ndarray of float, shape (n - 1,)
            The curve angle lumped at each interior node (rad).
        """
        return core.Route.node_angles(self, int(n))

    def scaled(self, factor: float) -> Route:
        """The same shape with every bend scaled by factor >= 0 (same length).

        Parameters
        ----------
        factor : float
            Scale of theta, >= 0.

        Returns
        -------
        Route
            A new route.
        """
        return Route(self.s, self.theta * float(factor))

    def __eq__(self, other) -> bool:
        return (
            isinstance(other, Route)
            and np.array_equal(self.s, other.s)
            and np.array_equal(self.theta, other.theta)
        )

    def __hash__(self):
        return hash((self.s.tobytes(), self.theta.tobytes()))

    def __reduce__(self):  # pickled as its samples (a route is immutable)
        return Route, (self.s, self.theta)

    def __copy__(self) -> Route:  # immutable: itself (the bound class's copy is no Route)
        return self

    def __deepcopy__(self, memo: dict) -> Route:  # type: ignore[override]
        return self

    def __repr__(self) -> str:
        return f"Route(length={self.length:.6g} m, curve_angle={self.curve_angle:.6g} rad)"


def check_curve_angle(value: ArrayLike, what: str = "curve angle") -> None:
    """A curve angle (rad, scalar or array) must be finite, >= 0 and at most 100 turns.

    Parameters
    ----------
    value : float or array_like of float
        The curve angle(s) (rad).
    what : str, default "curve angle"
        What the value is, for the error message.

    Raises
    ------
    ValueError
        A value not finite, negative, or above 200 pi rad.
    """
    arr = np.asarray(value, dtype=float).ravel()
    for bad, rule in (
        (~np.isfinite(arr), "be finite"),
        (arr < 0, "be >= 0"),
        (arr > MAX_CURVE_ANGLE, f"be <= {MAX_CURVE_ANGLE:.4g} rad (100 turns)"),
    ):
        if np.any(bad):
            raise ValueError(f"{what} must {rule} (got {arr[np.argmax(bad)]:g})")


__all__ = ["MAX_CURVE_ANGLE", "Route", "UnitWarning", "check_curve_angle"]
