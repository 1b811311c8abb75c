"""Closed-form pull-pull tendon-sheath model with the curve angle as a second input (spec B)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._util.arrays import as_signal, as_time_and_signal, checked_dt
from .._util.typing import ArrayLike, FloatOrArray
from ..plant import physics
from ..plant.route import Route
from ..simulation_result import SimulationResult
from . import _bound as core
from ._param_table import from_table
from .base import HysteresisModel

# saved files' old parameter keys (old -> new, docs/vocabulary.md): such files still load
_SAVED_AS = {"load": "load_force", "spring": "load_stiffness"}


@from_table  # param_names, the signature, the defaults and the Parameters section
class CurveAngleModel(HysteresisModel, core.CurveAngleModel):  # type: ignore[misc]
    """Distal angle of a pull-pull TSM from the motor angle and the route's curve angle.

    Inputs: ``x`` the proximal (motor) angle in rad and ``curve_angle`` Theta in rad (a
    scalar or one value per sample). Output: the distal angle in rad. With a = mu Theta,
    linear displacements at the tendon level (spec A.7, B1, A.4):

    - backlash half-width ``e_b = (T0 L/EA) tanh(a/2)`` (dead zone of input width 2 e_b),
    - load offset ``e_L = (F_L L/EA) tanh(a/2)/a``,
    - branch slope ``c = 1/(1 + k_e L tanh(a/2)/(EA a))`` (spring environment),
    - slip: ``x_out = c (x_in - sigma_v e_b - e_L)``; inside the dead zone x_out holds;
      ``x_in = r_p q_in`` and ``q_out = x_out / r_d``.

    A change of Theta at rest obeys spec B's memory effect: raising it does not move the
    output, lowering it moves the held output onto the new, narrower branch.

    Wherever it takes a curve angle it also takes a :class:`~tendonsheath.Route` (e.g. a
    sensed shape, :class:`~tendonsheath.bench.shape_sensing.ShapeSensing`): the terms are then
    those of spec A5/A6 for that route's distribution of curvature, with the shape integrals
    g, G computed at the model's own friction (:meth:`route_shape`): tanh(a/2) becomes the
    dead-zone factor :func:`~tendonsheath.plant.physics.dead_zone_factor` F(g, G, a) and
    tanh(a/2)/a becomes g G e^{-a}/(g + G e^{-2a}). Only the route's shape counts (g, G are
    normalised by its length); the model's ``length`` sets T0 L/EA as before.

    ``play`` (a gearhead's backlash) is a dead zone
    in series with the tendons', the same at every curve angle (held at 0 by ``identify``
    unless freed; curve angles that differ tell it from the tendons').

    Notes
    -----

    Identifiability: T0, F_L and k_e enter only through the products T0 L/EA, F_L L/EA and
    k_e L/EA. :func:`tendonsheath.identify` therefore holds the pretension, the length and the
    two radii at their given values and identifies friction, stiffness (EA), load_force and (when
    freed) load_stiffness: a wrong pretension scales the identified EA, F_L and k_e by the same
    factor and leaves the predictions unchanged.
    """

    _core_params = core.CurveAngleParams
    uses_curve_angle = True
    added_params = ("play",)  # files saved before the play was a parameter: its default
    control_inputs = ("x", "curve_angle")
    renamed_params = _SAVED_AS

    def _simulate(  # curve_angle is its input
        self,
        t: ArrayLike | None,
        x: ArrayLike,
        curve_angle: ArrayLike | None = None,
    ) -> SimulationResult:
        """Distal angle for motor angles x and curve angle(s) (scalar or per sample), with each
        sample's Status flags (held, slack) in ``status``.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); may be None (rate-independent).
        x : array_like of float, shape (n,)
            Motor angles (rad).
        curve_angle : float, array_like of float, shape (n,), or Route
            The curve angle Theta (rad), one value or one per sample, or the route (its shape,
            held over the run); required.

        Returns
        -------
        SimulationResult, shape (n,)
            Distal angles (rad), with ``status`` each sample's flags.

        Raises
        ------
        ValueError
            No curve angle, a non-finite one, or one of another length than x.
        """
        ts, xs = as_time_and_signal(t, x)
        if isinstance(curve_angle, Route):
            engine = core.CurveAngleModel(self)  # a copy: this model's shape stays
            engine.set_shape(self.route_shape(curve_angle))
            return engine.simulate(ts, xs, None, True)
        theta = curve_angle_samples(curve_angle, xs.size, type(self).__name__)
        out: Any = core.CurveAngleModel.simulate(self, ts, xs, theta, True)  # (output, flags)
        return out

    def step(self, x: float, dt: float = 0.0, curve_angle: float | Route | None = None) -> float:
        """One sample; ``curve_angle`` may be omitted after the first call (the last is kept).

        Parameters
        ----------
        x : float
            Motor angle (rad).
        dt : float, default 0.0
            Time since the previous sample (s).
        curve_angle : float or Route, optional
            The curve angle (rad) or the route (its shape); the last one when left out,
            required on the first call (or after :meth:`set_shape`).

        Returns
        -------
        float
            Distal angle (rad).

        Raises
        ------
        ValueError
            No curve angle yet: neither given now nor before (the output depends on it).
        """
        dt = checked_dt(dt)
        if isinstance(curve_angle, Route):
            self.set_shape(self.route_shape(curve_angle))
            curve_angle = None
        if curve_angle is None:
            if not getattr(self, "_angle_given", False):
                raise ValueError(
                    "CurveAngleModel.step needs the curve angle (rad) or the route on its "
                    "first call: the output depends on it, and none was given"
                )
            return core.CurveAngleModel.step(self, float(x), float(dt))
        self._angle_given = True
        return core.CurveAngleModel.step(self, float(x), float(dt), float(curve_angle))

    def set_shape(self, shape: core.ShapeIntegrals) -> None:
        """The route's shape for the following steps (:meth:`route_shape` of a route).

        Parameters
        ----------
        shape : ShapeIntegrals
            g, G (at this model's friction) and the curve angle.
        """
        core.CurveAngleModel.set_shape(self, shape)
        self._angle_given = True

    def route_shape(self, route: Route) -> core.ShapeIntegrals:
        """The route's shape integrals g, G at this model's friction, and its curve angle
        (:func:`tendonsheath.plant.physics.route_shape`): what the C++ model's ``set_shape`` takes.

        Parameters
        ----------
        route : Route
            The sheath's route.

        Returns
        -------
        ShapeIntegrals
            ``g``, ``G`` and ``curve_angle``.
        """
        return physics.route_shape(route, self.params["friction"])

    def _route_factors(self, route: Route) -> tuple[float, float]:
        """(dead-zone factor F, load factor K) of a route, spec A5/A6: F(g, G, a) and
        g G e^{-a}/(g + G e^{-2a}) (tanh(a/2) and tanh(a/2)/a for uniform curvature)."""
        shape = self.route_shape(route)
        a = self.params["friction"] * shape.curve_angle
        ema = np.exp(-a)
        load = shape.g * shape.G * ema / (shape.g + shape.G * ema * ema)
        return float(physics.dead_zone_factor(shape.g, shape.G, a)), float(load)

    def _control_step(self, u, dt: float) -> float:
        return self.step(u[0], dt, curve_angle=u[1])

    # closed-form terms, in the rotary units of the model (rad at the motor / at the joint),
    # from tendonsheath.plant.physics (the C++ closed forms that step() uses); curve_angle: a
    # number or an array, and |curve_angle| counts, as in step()
    def backlash_half_width(self, curve_angle: ArrayLike | Route) -> FloatOrArray:  # type: ignore[override]
        """Half the dead-zone width at the motor, rad: e_b / r_p.

        Parameters
        ----------
        curve_angle : float, array_like or Route
            The curve angle Theta (rad; its magnitude counts, as in step()), or a route.

        Returns
        -------
        float or numpy.ndarray
            e_b / r_p (rad).
        """
        p = self.params
        if isinstance(curve_angle, Route):
            factor = self._route_factors(curve_angle)[0]
            return p["pretension"] * p["length"] / p["stiffness"] * factor / p["proximal_radius"]
        e_b = physics.backlash_half_width(
            p["length"], p["stiffness"], p["pretension"], p["friction"], np.abs(curve_angle)
        )
        return e_b / p["proximal_radius"]

    def load_offset(self, curve_angle: ArrayLike | Route) -> FloatOrArray:  # type: ignore[override]
        """Load offset at the motor, rad: e_L / r_p.

        Parameters
        ----------
        curve_angle : float, array_like or Route
            The curve angle Theta (rad; its magnitude counts, as in step()), or a route.

        Returns
        -------
        float or numpy.ndarray
            e_L / r_p (rad).
        """
        p = self.params
        if isinstance(curve_angle, Route):
            factor = self._route_factors(curve_angle)[1]
            return p["load_force"] * p["length"] / p["stiffness"] * factor / p["proximal_radius"]
        e_L = physics.load_offset(
            p["length"], p["stiffness"], p["load_force"], p["friction"], np.abs(curve_angle)
        )
        return e_L / p["proximal_radius"]

    def slope(self, curve_angle: ArrayLike | Route) -> FloatOrArray:  # type: ignore[override]
        """Branch slope c of the linear displacements (dimensionless).

        Parameters
        ----------
        curve_angle : float, array_like or Route
            The curve angle Theta (rad; its magnitude counts, as in step()), or a route.

        Returns
        -------
        float or numpy.ndarray
            c = 1/(1 + k_e L tanh(a/2)/(EA a)), a = mu Theta (a route: g G e^{-a}/(g + G
            e^{-2a}) in place of tanh(a/2)/a).
        """
        p = self.params
        if isinstance(curve_angle, Route):
            factor = self._route_factors(curve_angle)[1]
            return 1.0 / (1.0 + p["load_stiffness"] * p["length"] / p["stiffness"] * factor)
        return physics.spring_slope(
            p["length"], p["stiffness"], p["friction"], np.abs(curve_angle), p["load_stiffness"]
        )


def curve_angle_samples(curve_angle, n: int, who: str) -> np.ndarray:
    """A per-sample curve-angle array of length n from a scalar or an array; ValueError if bad."""
    if curve_angle is None:
        raise ValueError(f"{who} needs curve_angle (rad): a number or one value per sample")
    if np.ndim(curve_angle) == 0:
        value = float(curve_angle)
        if not np.isfinite(value):
            raise ValueError(f"{who}: curve_angle must be finite (got {value})")
        return np.full(n, value)
    theta = as_signal(curve_angle, "curve_angle")
    if theta.size != n:
        raise ValueError(f"{who}: curve_angle and x have different lengths ({theta.size} and {n})")
    return theta


__all__ = ["CurveAngleModel", "curve_angle_samples"]
