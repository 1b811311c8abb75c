"""Curve-angle feedforward (Sun, Wang & Phee 2015, spec B2): it follows the route's shape."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.args import core_errors_as, number
from .._util.arrays import as_signal, as_timed_signal, checked_dt
from .._util.param_table import TABLE, number_rows, table_constructor
from .._util.pyobject import bound_attribute
from .._util.typing import ArrayLike
from .._util.units import checked_curve_angle, warn_unit_slips
from ..plant.physics import route_shape as shape_of
from ..simulation_result import SimulationResult
from . import _bound as core
from .base import Feedforward, command_result
from .limits import LimitsLike, as_limits

if TYPE_CHECKING:
    from ..models import CurveAngleModel
    from ..plant.route import Route


@table_constructor(core.CurveAngleFeedforwardParams)
class CurveAngleFeedforward(Feedforward, core.CurveAngleFeedforward):  # type: ignore[misc]
    """x_in = r_d y_d + phi Delta_fwd + (1 - phi) Delta_bwd, re-evaluated every cycle.

    Delta_fwd/bwd are the full-slip elongations of the pulled tendon (spec A5/A6) for the
    route's current shape (its g/G integrals; or uniform curvature with the given curve
    angle) and the distal load F_L = load_force + load_stiffness * r_d * y_d. No distal
    sensor is needed: the route (or its curve angle) is the only extra input, from shape
    sensing or bending-knob readings. ``smoothing`` is the direction-switch speed (rad/s of
    the distal angle); ``max_correction_rate`` (m/s at the tendon) limits how fast the
    correction may change, e.g. after a sudden change of the route. Angles in rad. Only L/EA
    (``length`` / ``stiffness``) enters the feedforward (a file saved with the old
    ``compliance`` L/EA loads as stiffness 1/compliance and length 1 m; docs/vocabulary.md);
    ``play``, crossed at each reversal, adds r_p play / 2 in the direction of motion.

    Parameters
    ----------
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the command and its rate (see :class:`CommandLimits`).

    Raises
    ------
    TypeError
        A value of the wrong type, or an unknown keyword.
    ValueError
        A value out of range (the message names the argument and the value).
    """

    control_inputs = ("y_d", "curve_angle")
    _saved_settings = (*number_rows(core.CurveAngleFeedforwardParams), "limits")

    def __init__(
        self,
        friction: float,
        stiffness: float,
        length: float,
        pretension: float,
        load_force: float = TABLE,
        load_stiffness: float = TABLE,
        proximal_radius: float = TABLE,
        distal_radius: float = TABLE,
        curve_angle: float = TABLE,
        play: float = TABLE,
        smoothing: float = TABLE,
        max_correction_rate: float = TABLE,
        limits: LimitsLike = None,
    ):
        who = type(self).__name__
        arguments = locals()
        values = {k: arguments[k] for k in number_rows(core.CurveAngleFeedforwardParams)}
        self._settings = {k: number(who, k, v) for k, v in values.items()}
        self._settings["limits"] = as_limits(limits)
        with core_errors_as(who):
            core.CurveAngleFeedforward.__init__(self, _params(who, self._settings))
        warn_unit_slips(who, _params(who, self._settings))

    @classmethod
    def from_model(
        cls,
        model: CurveAngleModel,
        load_force: float | None = None,
        load_stiffness: float | None = None,
        **options: Any,
    ) -> CurveAngleFeedforward:
        """Built from an identified ``CurveAngleModel``: its friction, stiffness EA, length L,
        pretension, radii and play; the distal load defaults to the model's own (``load_force``,
        ``load_stiffness``) and can be replaced by the load expected in use (N, N/m at the tendon).

        Parameters
        ----------
        model : CurveAngleModel
            The identified model.
        load_force : float, optional
            Distal load (N at the tendon); default the model's ``load_force``.
        load_stiffness : float, optional
            Environment stiffness (N/m at the tendon); default the model's ``load_stiffness``.
        **options
            Other constructor settings (curve_angle, smoothing, max_correction_rate, limits).

        Returns
        -------
        CurveAngleFeedforward
            The compensator.

        Raises
        ------
        TypeError
            model has no parameter dict.
        ValueError
            model lacks a CurveAngleModel parameter.
        """
        p = getattr(model, "params", None)
        if not isinstance(p, dict):
            raise TypeError(
                f"CurveAngleFeedforward.from_model needs a CurveAngleModel (got {model!r})"
            )
        missing = {"friction", "stiffness", "pretension", "length"} - set(p)
        if missing:
            raise ValueError(
                "CurveAngleFeedforward.from_model needs a CurveAngleModel "
                f"(missing {sorted(missing)})"
            )
        return cls(
            friction=p["friction"],
            stiffness=p["stiffness"],
            length=p["length"],
            pretension=p["pretension"],
            load_force=p.get("load_force", 0.0) if load_force is None else load_force,
            load_stiffness=(
                p.get("load_stiffness", 0.0) if load_stiffness is None else load_stiffness
            ),
            proximal_radius=p.get("proximal_radius", 5e-3),
            distal_radius=p.get("distal_radius", 5e-3),
            play=p.get("play", 0.0),
            **options,
        )

    @property
    def friction(self) -> float:
        """Friction coefficient mu."""
        return bound_attribute(self, "params").friction

    def set_curve_angle(self, curve_angle: float) -> None:  # type: ignore[override]
        """Uniform curvature with this curve angle (rad).

        Parameters
        ----------
        curve_angle : float
            The curve angle Theta (rad), finite and >= 0.

        Raises
        ------
        ValueError
            A curve angle that is not finite or negative (the C++ core keeps the last angle and
            reports ``input_clamped``; the Python call says so instead).
        """
        who = "CurveAngleFeedforward.set_curve_angle"
        core.CurveAngleFeedforward.set_curve_angle(
            self, checked_curve_angle(who, number(who, "curve_angle", curve_angle))
        )

    def set_route(self, route: Route) -> None:
        """Any route: its exact g/G shape integrals are used (spec A.2 warning on Theta-only).

        Parameters
        ----------
        route : Route
            Or any object with ``s`` and ``theta`` samples.

        Raises
        ------
        TypeError
            route has no ``s`` and ``theta``.
        """
        if not (hasattr(route, "s") and hasattr(route, "theta")):
            raise TypeError(f"set_route needs a Route (got {route!r})")
        core.CurveAngleFeedforward.set_shape(self, shape_of(route, self.friction))

    def step(
        self, y_d: float, dt: float, curve_angle: float | None = None, route: Route | None = None
    ) -> float:
        """One control cycle, after taking a new route or curve angle when one is given.

        Parameters
        ----------
        y_d : float
            Desired distal angle (rad).
        dt : float
            Time since the previous cycle (s), >= 0.
        curve_angle : float, optional
            A new curve angle (rad): uniform curvature.
        route : Route, optional
            A new route (takes precedence over curve_angle).

        Returns
        -------
        float
            The motor angle (rad).
        """
        dt = checked_dt(dt)
        if route is not None:
            self.set_route(route)
        elif curve_angle is not None:
            self.set_curve_angle(curve_angle)
        return core.CurveAngleFeedforward.step(self, float(y_d), float(dt))

    def _control_step(self, u, dt: float) -> float:
        return self.step(u[0], dt, curve_angle=u[1])

    def command(  # type: ignore[override]  # curve_angle is its input
        self,
        t: ArrayLike,
        y_desired: ArrayLike,
        curve_angle: ArrayLike | None = None,
        routes: Callable[[float], Route] | None = None,
    ) -> SimulationResult:
        """Motor angles for a whole trajectory; the shape from `curve_angle` (scalar or one
        per sample) or `routes` (a callable t -> route), else the constructor's curve angle.
        The result's ``status`` holds each cycle's Status flags (uint8).

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing; required.
        y_desired : array_like of float, shape (n,)
            Desired distal angles (rad).
        curve_angle : float or array_like of float, optional
            Curve angle (rad), one value or one per sample, >= 0.
        routes : callable, optional
            t -> the route at time t (takes precedence over curve_angle).

        Returns
        -------
        SimulationResult, shape (n,)
            Motor angles (rad), with ``t``, ``input`` (y_desired) and ``status`` (each cycle's
            :class:`~tendonsheath.Status`, uint8).

        Raises
        ------
        ValueError
            t missing, or samples not finite or of different lengths.
        """
        who = "CurveAngleFeedforward.command"
        ts, ys = as_timed_signal(t, y_desired, "y_desired", who)
        if routes is not None:
            shapes = [shape_of(routes(tk), self.friction) for tk in ts]
            g = np.array([s.g for s in shapes])
            G = np.array([s.G for s in shapes])
            theta = np.array([s.curve_angle for s in shapes])
            out = core.CurveAngleFeedforward.command(self, ts, ys, g, G, theta, True)
            return command_result(ts, ys, out)
        if curve_angle is not None:
            theta = np.broadcast_to(np.asarray(curve_angle, dtype=np.float64), ys.shape)
            theta = as_signal(theta, "curve_angle")
            if np.any(theta < 0):
                bad = theta[np.argmax(theta < 0)]
                raise ValueError(
                    f"CurveAngleFeedforward.command: curve_angle must be >= 0 (got {bad:g})"
                )
            out = core.CurveAngleFeedforward.command(self, ts, ys, None, None, theta, True)
            return command_result(ts, ys, out)
        out = core.CurveAngleFeedforward.command(self, ts, ys, None, None, None, True)
        return command_result(ts, ys, out)


def _params(who: str, v: dict):
    """The C++ parameter struct of these settings (stiffness and length checked first)."""
    for name in ("stiffness", "length"):
        if not v[name] > 0:
            raise ValueError(f"{who}: {name} must be > 0 (got {v[name]:g})")
    p = core.CurveAngleFeedforwardParams()
    p.friction, p.stiffness, p.length = v["friction"], v["stiffness"], v["length"]
    p.pretension = v["pretension"]
    p.load_force, p.load_stiffness = v["load_force"], v["load_stiffness"]
    p.proximal_radius, p.distal_radius = v["proximal_radius"], v["distal_radius"]
    p.curve_angle, p.smoothing, p.play = v["curve_angle"], v["smoothing"], v["play"]
    p.max_correction_rate = v["max_correction_rate"]
    p.limits = v["limits"].to_core()
    return p


__all__ = ["CurveAngleFeedforward"]
