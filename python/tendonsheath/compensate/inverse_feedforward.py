"""The real-time inverse of every identified model, as a feedforward (Do et al. 2015, spec D.2, and
the engines of ``tendonsheath/compensators/model_inverse.hpp``)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.args import core_errors_as, number
from .._util.arrays import as_signal, as_timed_signal, checked_dt
from .._util.param_table import TABLE, table_constructor
from .._util.typing import ArrayLike
from .._util.units import checked_curve_angle
from ..models import HysteresisModel
from ..plant.physics import route_shape as shape_of
from ..simulation_result import SimulationResult
from . import _bound as core
from ._kinds import require_model
from .base import Feedforward, command_result
from .inverse_model import describe, follows_route, route_friction
from .limits import CommandLimits, LimitsLike, as_limits

if TYPE_CHECKING:
    from ..plant.route import Route

RangeLike = str | tuple[float, float] | list[float] | None


@table_constructor(core.BacklashInverseParams)  # smoothing, limits
class InverseFeedforward(Feedforward, core.ModelInverse):  # type: ignore[misc]
    """Motor command that makes `model` produce the desired output, with no distal sensor.

    Every model class :func:`~tendonsheath.identify` and ``compare_models`` return has a
    real-time inverse (C++ ``ModelInverse``: noexcept, no allocation, bounded work):

    * ``Backlash``, ``BoucWenBacklash``: the direct inverse of spec D.2,
      x = [y_d + phi c_r B_r - (1 - phi) c_l B_l] / [phi c_r + (1 - phi) c_l] with
      phi = (1 + tanh(y_d' / smoothing)) / 2; ``smoothing`` (output units per s, about 2-5 %
      of the peak desired speed) sets how sharply the command switches branch at a reversal.
    * ``PrandtlIshlinskii`` with thresholds[0] = 0: its exact inverse operator (monotone for
      any signs of weights the model accepts).
    * ``PrandtlIshlinskii`` (thresholds[0] > 0), ``GeneralizedPrandtlIshlinskii``,
      ``BoucWen``, ``PlantModel``, ``Polynomial`` and ``Chain(model, Polynomial)``: a root
      finder, each cycle the command nearest the previous one that makes the model's next
      output equal y_d (a bracket expanded geometrically both ways, then Brent; at most 160
      model evaluations a cycle).
    * ``Chain(model, FirstOrderLag | SecondOrderLag)`` (Hammerstein) and ``Chain(lag, model)``
      (Wiener): the lag inverted by a filter, (tau s + 1)/(tau_f s + 1) or
      (s^2/w^2 + 2 zeta s/w + 1)/(s/w_f + 1)^2 (Tustin at each dt), with the model's inverse
      after (Hammerstein) or before (Wiener) it; the output follows y_d through
      1/(tau_f s + 1) or 1/(s/w_f + 1)^2.
    * ``HystereticOscillator``: the force from the desired displacement filtered by
      1/(s/w_f + 1)^2 and the hysteretic force integrated along it.
    * ``CurveAngleModel`` and ``AngleDependent`` (over Backlash, BoucWenBacklash, BoucWen or
      HystereticOscillator) follow the route (``follows_route``): :meth:`set_curve_angle`,
      :meth:`set_shape`, :meth:`set_route`, or ``command(..., curve_angle=...)``; their
      parameters are re-evaluated at every route (an AngleDependent "tanh" law with the
      route's shape integrals). Give the route before streaming: until then a CurveAngleModel's
      inverse assumes a straight sheath and an AngleDependent one the curve angle its model
      is validated at (pi with a "tanh" law, else 0).
    * ``Scaled`` around any of these: x = x_c + x_s inv((y_d - y_c) / g).

    ``input_range`` keeps every command inside the range the model was identified on, widened
    by ``range_margin`` of its span beyond each end: a command that would leave it is held at
    its edge and the cycle's status has :attr:`~tendonsheath.Status.OUT_OF_RANGE` (its target is
    unreachable inside the range). ``limits`` (a :class:`CommandLimits`) then saturates the
    command and its rate.

    Parameters
    ----------
    model : HysteresisModel
        The identified model (any class above).
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the command and its rate (see :class:`CommandLimits`).
    input_range : "identified", (float, float) or None, default "identified"
        The training inputs' range (lo, hi): "identified" takes ``model.input_range`` (None
        when the model has none: unbounded), None is unbounded.
    range_margin : float, default 0.1
        Fraction of the range's span allowed beyond each end, >= 0.
    filter_hz : float or None, optional
        Corner (Hz) of the lag and oscillator inverses' filter; None: 5 x the block's corner
        (natural) frequency. Capped at 0.2 / dt.

    Raises
    ------
    TypeError
        A model of a class (or in a place) without an inverse.
    ValueError
        A bad smoothing, limit, range, margin or filter corner, or model parameters the C++
        core rejects.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    model: HysteresisModel
    smoothing: float
    limits: CommandLimits
    input_range: tuple[float, float] | None
    range_margin: float
    filter_hz: float | None

    # whether the model's law depends on the route: a bool here, where the C++ class has a
    # method of that name
    follows_route: bool  # type: ignore[assignment]
    _saved_settings = (
        "model",
        "smoothing",
        "limits",
        "input_range",
        "range_margin",
        "filter_hz",
    )
    # settings a file written before them may lack (their defaults then apply)
    _optional_settings = ("input_range", "range_margin", "filter_hz")

    def __init__(
        self,
        model: HysteresisModel,
        smoothing: float = TABLE,
        limits: LimitsLike = None,
        input_range: RangeLike = "identified",
        range_margin: float = 0.1,
        filter_hz: float | None = None,
    ):
        require_model("InverseFeedforward", model)
        self.model = model
        self.smoothing = number("InverseFeedforward", "smoothing", smoothing)
        self.limits = as_limits(limits)
        self.input_range = _resolved_range(model, input_range)
        self.range_margin = _margin(range_margin)
        self.filter_hz = _filter_hz(filter_hz)
        self._settings = {
            "smoothing": self.smoothing,
            "limits": self.limits,
            "input_range": None if self.input_range is None else list(self.input_range),
            "range_margin": self.range_margin,
            "filter_hz": self.filter_hz,
        }
        with core_errors_as("InverseFeedforward"):
            core.ModelInverse.__init__(self, describe(model), self._core_settings())
        self.follows_route = follows_route(model)
        if self.follows_route:
            self.control_inputs = ("y_d", "curve_angle")

    def _core_settings(self):
        s = core.InverseSettings()
        s.smoothing = self.smoothing
        s.limits = self.limits.to_core()
        if self.input_range is not None:
            with core_errors_as("InverseFeedforward"):
                s.range = core.InputRange.identified(*self.input_range, self.range_margin)
        s.filter_hz = 0.0 if self.filter_hz is None else self.filter_hz
        return s

    @property
    def params(self) -> dict:
        """The constructor settings and the model (a copy)."""
        return {**super().params, "model": self.model}

    @property
    def command_range(self) -> tuple[float, float]:
        """The commands allowed: ``input_range`` widened by ``range_margin`` ((-inf, inf) when
        unbounded)."""
        if self.input_range is None:
            return (-math.inf, math.inf)
        lo, hi = self.input_range
        m = self.range_margin * (hi - lo)
        return (lo - m, hi + m)

    @property
    def friction(self) -> float | None:  # type: ignore[override]
        """The friction coefficient of the route's shape integrals (a CurveAngleModel's
        friction, an AngleDependent's angle_friction, 0 without a tanh law); None when the
        inverse does not follow the route."""
        return route_friction(self.model)

    def to_dict(self) -> dict:
        """The compensator as a dict, its model saved whole.

        Returns
        -------
        dict
            What :func:`~tendonsheath.compensate.load_compensator` reads back.
        """
        data = super().to_dict()
        return {**data, "model": self.model.to_dict()}

    def set_curve_angle(self, curve_angle: float) -> None:
        """Uniform curvature with this curve angle (rad), for an inverse that follows the
        route (ignored otherwise).

        Parameters
        ----------
        curve_angle : float
            The curve angle Theta (rad), finite and >= 0.

        Raises
        ------
        ValueError
            A curve angle that is not finite or negative (the C++ core would ignore it).
        """
        who = "InverseFeedforward.set_curve_angle"
        core.ModelInverse.set_curve_angle(
            self, checked_curve_angle(who, number(who, "curve_angle", curve_angle))
        )
        self._route_given = True

    def set_shape(self, shape: Any) -> None:
        """A route's shape integrals (``ts.physics.route_shape(route, self.friction)``), for an
        inverse that follows the route (ignored otherwise).

        Parameters
        ----------
        shape : ShapeIntegrals
            g, G (computed with :attr:`friction`) and the total angle.
        """
        core.ModelInverse.set_shape(self, shape)
        self._route_given = True

    def set_route(self, route: Route) -> None:
        """Any route: its shape integrals with :attr:`friction` (see :meth:`set_shape`).

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
        if self.follows_route:
            core.ModelInverse.set_shape(self, shape_of(route, self.friction or 0.0))
            self._route_given = True

    def step(
        self, y_d: float, dt: float, curve_angle: float | None = None, route: Route | None = None
    ) -> float:
        """One control cycle (real-time core, no allocation), after taking a new route or curve
        angle when one is given.

        Parameters
        ----------
        y_d : float
            Desired output (the model's output unit).
        dt : float
            Time since the previous cycle (s), >= 0.
        curve_angle : float, optional
            A new curve angle (rad), for an inverse that follows the route.
        route : Route, optional
            A new route (takes precedence over curve_angle).

        Returns
        -------
        float
            The motor command.

        Raises
        ------
        ValueError
            An inverse that follows the route, with no route or curve angle given yet (now,
            or by set_curve_angle, set_shape or set_route).
        """
        dt = checked_dt(dt)
        if route is not None:
            self.set_route(route)
        elif curve_angle is not None:
            self.set_curve_angle(curve_angle)
        elif self.follows_route and not getattr(self, "_route_given", False):
            raise ValueError(
                f"InverseFeedforward.step: the inverse of {type(self.model).__name__} follows "
                "the route: give curve_angle= or route= (or set_curve_angle) before the first "
                "step; its command depends on it"
            )
        return core.ModelInverse.step(self, float(y_d), float(dt))

    def _control_step(self, u, dt: float) -> float:
        if self.follows_route:
            return self.step(u[0], dt, curve_angle=u[1])
        return self.step(u[0], dt)

    def command(  # type: ignore[override]
        self,
        t: ArrayLike,
        y_desired: ArrayLike,
        curve_angle: ArrayLike | None = None,
        routes: Callable[[float], Route] | None = None,
    ) -> SimulationResult:
        """Motor commands for a whole trajectory, from the initial state. An inverse that
        follows the route takes it from `routes` (a callable t -> route) or `curve_angle`
        (scalar or one per sample), and needs one of them.

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing; required.
        y_desired : array_like of float, shape (n,)
            Desired outputs.
        curve_angle : float or array_like of float, optional
            Curve angle (rad), one value or one per sample (route-following inverses).
        routes : callable, optional
            t -> the route at time t (takes precedence over curve_angle).

        Returns
        -------
        SimulationResult, shape (n,)
            Motor commands (an array), with ``t``, ``input`` (y_desired) and ``status`` (each
            cycle's :class:`~tendonsheath.Status`, uint8).

        Raises
        ------
        ValueError
            t missing, samples not finite or of different lengths, or no route for an
            inverse that follows it.
        """
        ts, ys = as_timed_signal(t, y_desired, "y_desired", "InverseFeedforward.command")
        g, G, theta = self._route_samples(ts, ys, curve_angle, routes)
        out = core.ModelInverse.command(self, ts, ys, g, G, theta, True)
        return command_result(ts, ys, out)

    def _route_samples(self, ts, ys, curve_angle, routes):
        """(g, G, curve angle) per sample for the engine (None where not given)."""
        if not self.follows_route:
            return None, None, None
        if routes is not None:
            shapes = [shape_of(routes(tk), self.friction or 0.0) for tk in ts]
            return tuple(
                np.array([getattr(s, k) for s in shapes]) for k in ("g", "G", "curve_angle")
            )
        if curve_angle is None:
            raise ValueError(
                "InverseFeedforward.command: this inverse follows the route; give curve_angle "
                "(rad, one value or one per sample) or routes"
            )
        theta = np.broadcast_to(np.asarray(curve_angle, dtype=np.float64), ys.shape)
        return None, None, as_signal(np.ascontiguousarray(theta), "curve_angle")

    def __repr__(self) -> str:
        return f"InverseFeedforward({self.model!r}, smoothing={self.smoothing:g})"


def _resolved_range(model: HysteresisModel, value: RangeLike) -> tuple[float, float] | None:
    """The (lo, hi) the commands are held in (before the margin), or None."""
    if isinstance(value, str):
        if value != "identified":
            raise ValueError(
                f"InverseFeedforward: input_range must be 'identified', (lo, hi) or None "
                f"(got {value!r})"
            )
        value = getattr(model, "input_range", None)
    if value is None:
        return None
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(
            "InverseFeedforward: input_range must be 'identified', (lo, hi) or None "
            f"(got {value!r})"
        ) from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(
            f"InverseFeedforward: input_range needs finite lo < hi (got lo={lo:g}, hi={hi:g})"
        )
    return (lo, hi)


def _margin(value) -> float:
    m = number("InverseFeedforward", "range_margin", value)
    if not (math.isfinite(m) and m >= 0.0):
        raise ValueError(f"InverseFeedforward: range_margin must be >= 0 (got {m:g})")
    return m


def _filter_hz(value) -> float | None:
    if value is None:
        return None
    f = number("InverseFeedforward", "filter_hz", value)
    if not (math.isfinite(f) and f > 0.0):
        raise ValueError(f"InverseFeedforward: filter_hz must be > 0 or None/null (got {f:g})")
    return f


__all__ = ["InverseFeedforward", "RangeLike"]
