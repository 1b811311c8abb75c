"""A model whose parameters are functions of the route's curve angle Theta."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.args import number
from .._util.arrays import checked_dt
from .._util.typing import ArrayLike, FloatArray
from ..plant.physics import route_dead_zone_factor
from ..plant.route import Route
from ..simulation_result import SimulationResult
from ..status import Status
from .base import _REGISTRY, HysteresisModel
from .curve_angle import curve_angle_samples

if TYPE_CHECKING:
    import control  # python-control ships no types: its systems are Any to mypy

LAWS = ("constant", "linear", "tanh")


def angle_factor(curve_angle: ArrayLike | Route, mu: ArrayLike) -> float | FloatArray:
    """The "tanh" law's basis: tanh(mu |Theta|/2) of a curve angle, or the dead-zone factor
    F(g, G, mu Theta) of a route (g, G at friction mu; :func:`~tendonsheath.plant.physics.
    dead_zone_factor`), which is tanh(mu Theta/2) for a uniform route.

    Parameters
    ----------
    curve_angle : float, array_like of float, or Route
        The curve angle(s) Theta (rad), or a route.
    mu : float or array_like of float
        The friction coefficient(s) (broadcast with the angles; for a route, one F per mu).

    Returns
    -------
    float or numpy.ndarray of float
        The factor(s), in [0, 1).
    """
    if isinstance(curve_angle, Route):
        return route_dead_zone_factor(curve_angle, mu)
    theta = np.abs(np.asarray(curve_angle, dtype=float))
    return np.tanh(0.5 * np.asarray(mu, dtype=float) * theta)


def total_angle(curve_angle: ArrayLike | Route) -> float | FloatArray:
    """The curve angle Theta of a number, an array or a route (rad).

    Parameters
    ----------
    curve_angle : float, array_like of float, or Route
        The curve angle(s), or a route.

    Returns
    -------
    float or numpy.ndarray of float
        Theta: the route's total angle, else the values as floats.
    """
    if isinstance(curve_angle, Route):
        return float(curve_angle.curve_angle)
    return np.asarray(curve_angle, dtype=float)


def law_value(law: str, coefficients, theta, angle_friction: float | None):
    """p(Theta) for one law: constant p0; linear p0 + p1 Theta; tanh p0 + p1 tanh(mu Theta/2),
    or p0 + p1 F(g, G, mu Theta) when ``theta`` is a Route (see :func:`angle_factor`)."""
    c = coefficients
    if law == "constant":
        return c[0] + 0.0 * total_angle(theta)
    if law == "linear":
        return c[0] + c[1] * total_angle(theta)
    if law == "tanh":
        assert angle_friction is not None  # AngleDependent requires it with a tanh law
        return c[0] + c[1] * angle_factor(theta, angle_friction)
    raise ValueError(f"unknown angle law {law!r}; expected one of {LAWS}")


def _stream_key(curve_angle: float | Route) -> float | Route:
    """What a streaming AngleDependent compares to notice a change: the route or the angle."""
    return curve_angle if isinstance(curve_angle, Route) else float(curve_angle)


class AngleDependent(HysteresisModel):
    """A base model (e.g. BoucWenBacklash) whose parameters depend on the curve angle Theta.

    Each parameter of the base model follows a law of Theta (rad):

    - ``"constant"``: p = p0
    - ``"linear"``: p = p0 + p1 Theta
    - ``"tanh"``: p = p0 + p1 tanh(angle_friction |Theta| / 2), the shape of the backlash
      half-width of spec B (e_b = T0 L/EA tanh(mu Theta/2)); all tanh laws share one
      ``angle_friction`` (the physical friction coefficient mu).

    Wherever it takes a curve angle it also takes a :class:`~tendonsheath.Route` (e.g. a
    sensed shape): "tanh" is then p0 + p1 F(g, G, mu Theta), the pull-pull dead-zone factor of
    the route's distribution of curvature (:func:`~tendonsheath.plant.physics.dead_zone_factor`,
    g and G at mu = ``angle_friction``; tanh(mu Theta/2) again for a uniform route), and
    "linear" takes the route's curve angle.

    ``coefficients`` maps every base parameter to its list of coefficients ([p0] or [p0, p1]).
    ``simulate(t, x, curve_angle=...)`` takes one curve angle per call (a number, an array
    that is constant, or a route); :meth:`at` gives the plain base model at an angle. Streaming
    ``step`` works at one angle until ``reset()``.

    Parameters
    ----------
    base : str or type
        The base model's class or class name (not one that takes the curve angle itself).
    coefficients : dict of str to list of float
        Every base parameter -> its coefficients: [p0] for a constant law, [p0, p1] otherwise.
    laws : dict of str to str, optional
        Base parameter -> "constant", "linear" or "tanh"; a parameter left out is constant.
    angle_friction : float, optional
        The friction coefficient mu of the tanh laws (> 0; required with a tanh law).
    base_options : dict, optional
        Options passed to the base model (e.g. ``max_step``).

    Raises
    ------
    ValueError
        An unknown base model or parameter, an unknown law, a wrong number of coefficients,
        a non-finite coefficient, a missing angle_friction, or base parameters invalid at
        Theta = 0 (pi with a tanh law).
    """

    param_names = ("base", "laws", "coefficients", "angle_friction")
    option_names = ("base_options",)
    nullable_params = ("angle_friction",)
    text_params = ("base",)
    uses_curve_angle = True

    def __init__(
        self,
        base: str,
        coefficients: dict[str, Any],
        laws: dict[str, str] | None = None,
        angle_friction: float | None = None,
        base_options: dict[str, Any] | None = None,
    ):
        if isinstance(base, type):
            base = base.__name__
        if base not in _REGISTRY or base == "AngleDependent":
            raise ValueError(f"AngleDependent: unknown base model {base!r}")
        self._base_cls = _REGISTRY[base]
        if getattr(self._base_cls, "uses_curve_angle", False):
            raise ValueError(f"AngleDependent: {base} already takes the curve angle as an input")
        laws = dict(laws or {})
        names = self._base_cls.param_names
        unknown = (set(laws) | set(coefficients)) - set(names)
        if unknown:
            raise ValueError(
                f"AngleDependent: unknown parameter(s) {sorted(unknown)} of {base}; "
                f"expected {list(names)}"
            )
        coefs: dict[str, list[float]] = {}
        for name in names:
            law = laws.setdefault(name, "constant")
            if law not in LAWS:
                raise ValueError(
                    f"AngleDependent: law of {name} must be one of {LAWS} (got {law!r})"
                )
            if name not in coefficients:
                raise ValueError(f"AngleDependent: no coefficients for parameter {name}")
            c = np.atleast_1d(np.asarray(coefficients[name], dtype=float)).tolist()
            want = 1 if law == "constant" else 2
            if len(c) != want:
                raise ValueError(
                    f"AngleDependent: parameter {name} ({law}) needs {want} coefficient(s), "
                    f"got {len(c)}"
                )
            if not np.all(np.isfinite(c)):
                raise ValueError(f"AngleDependent: coefficients of {name} must be finite")
            coefs[name] = c
        if any(law == "tanh" for law in laws.values()):
            if angle_friction is None:
                raise ValueError("AngleDependent: angle_friction must be > 0 with a tanh law")
            angle_friction = number("AngleDependent", "angle_friction", angle_friction)
            if not (math.isfinite(angle_friction) and angle_friction > 0):  # C++ AngleLaws' rule
                raise ValueError(
                    f"AngleDependent: angle_friction must be > 0 (got {angle_friction:g})"
                )
        else:
            angle_friction = None
        self._laws = laws
        self._coefs = coefs
        self._mu = angle_friction
        self._base_options = dict(base_options or {})
        self._stream: HysteresisModel | None = None
        self._stream_angle: float | Route | None = None
        self.at(0.0 if angle_friction is None else np.pi)  # validates the base parameters

    # -- parameters ------------------------------------------------------------------
    @property
    def base(self) -> type[HysteresisModel]:
        """The base model's class."""
        return self._base_cls

    @property
    def params(self) -> dict[str, Any]:
        """base, laws, coefficients and angle_friction, as a dict (a copy)."""
        return {
            "base": self._base_cls.__name__,
            "laws": dict(self._laws),
            "coefficients": {k: list(v) for k, v in self._coefs.items()},
            "angle_friction": self._mu,
        }

    @property
    def options(self) -> dict[str, Any]:
        """``{"base_options": ...}``, the base model's options (a copy)."""
        return {"base_options": dict(self._base_options)}

    def params_at(self, curve_angle: float | Route) -> dict[str, float]:
        """The base model's parameters at one curve angle or route.

        Parameters
        ----------
        curve_angle : float or Route
            The route's curve angle Theta (rad), or the route itself (its shape).

        Returns
        -------
        dict of str to float
            Each base parameter's value by its law.
        """
        theta = curve_angle if isinstance(curve_angle, Route) else float(curve_angle)
        return {
            k: float(law_value(self._laws[k], self._coefs[k], theta, self._mu))
            for k in self._base_cls.param_names
        }

    def at(self, curve_angle: float | Route) -> HysteresisModel:
        """The base model at one curve angle or route.

        Parameters
        ----------
        curve_angle : float or Route
            The route's curve angle Theta (rad), or the route itself (its shape).

        Returns
        -------
        HysteresisModel
            The base model with :meth:`params_at` ``(curve_angle)``.

        Raises
        ------
        ValueError
            The base parameters are invalid at that angle.
        """
        return self._base_cls(**self.params_at(curve_angle), **self._base_options)

    # -- simulation ------------------------------------------------------------------
    def _simulate(  # curve_angle is its input
        self,
        t: ArrayLike | None,
        x: ArrayLike,
        curve_angle: ArrayLike | None = None,
    ) -> SimulationResult:
        """Output of the base model at one curve angle for the input samples x at times t.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None when the base model is rate-independent.
        x : array_like of float, shape (n,)
            Input samples.
        curve_angle : float, array_like of float, or Route
            The curve angle Theta (rad): a number, or an array of n equal values; or the route
            (its shape).

        Returns
        -------
        SimulationResult, shape (n,)
            Output samples, with ``status`` each sample's :class:`~tendonsheath.Status`.

        Raises
        ------
        ValueError
            No curve angle, or one that varies during the run.
        """
        if isinstance(curve_angle, Route):
            return self.at(curve_angle).simulate(t, x)
        theta = curve_angle_samples(curve_angle, np.size(x), "AngleDependent")
        if np.any(theta != theta[0]):
            raise ValueError(
                "AngleDependent: simulate takes one curve angle per call (the array varies); "
                "CurveAngleModel handles a curve angle that changes during a run"
            )
        return self.at(theta[0]).simulate(t, x)

    def reset(self) -> None:
        """Forget the streaming state and its curve angle."""
        self._stream = None
        self._stream_angle = None

    def step(self, x: float, dt: float = 0.0, curve_angle: float | Route | None = None) -> float:
        """Advance one sample (streaming) at the curve angle (or route) fixed by the first step.

        Parameters
        ----------
        x : float
            The input sample.
        dt : float, default 0.0
            Time since the previous sample (s).
        curve_angle : float or Route, optional
            The curve angle (rad) or the route: required on the first step after a reset,
            and unchanged after it.

        Returns
        -------
        float
            The output sample.

        Raises
        ------
        ValueError
            No curve angle on the first step, or a different one later without a reset.
        """
        dt = checked_dt(dt)
        if self._stream is None:
            if curve_angle is None:
                raise ValueError("AngleDependent: the first step() needs curve_angle")
            self._stream = self.at(curve_angle)
            self._stream_angle = _stream_key(curve_angle)
        elif curve_angle is not None and _stream_key(curve_angle) != self._stream_angle:
            raise ValueError(
                "AngleDependent: the curve angle changed while streaming; reset() first"
            )
        return self._stream.step(x, dt)

    def to_control(
        self,
        dt: float,
        name: str | None = None,
        inputs: Sequence[str] | None = None,
        output: str | None = None,
        curve_angle: float | Route | None = None,
    ) -> control.NonlinearIOSystem:
        """The base model at one ``curve_angle`` (rad) as a python-control system (a run at one
        curve angle, as :meth:`simulate`); see :meth:`HysteresisModel.to_control`.

        Parameters
        ----------
        dt : float
            Sample time (s), > 0.
        name : str, optional
            The system's name.
        inputs : str or list of str, optional
            Input signal names.
        output : str, optional
            Output signal name.
        curve_angle : float or Route
            The curve angle (rad) or the route; required.

        Returns
        -------
        control.NonlinearIOSystem
            The discrete-time system of :meth:`at` ``(curve_angle)``.
        """
        if curve_angle is None:
            raise ValueError("AngleDependent.to_control needs curve_angle (rad): one per system")
        return self.at(curve_angle).to_control(dt, name, inputs, output)

    def status(self) -> Status:
        """The last step's Status (OK before the first step).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.
        """
        return self._stream.status() if self._stream is not None else Status.OK

    def __repr__(self) -> str:
        laws = {k: v for k, v in self._laws.items() if v != "constant"}
        return f"AngleDependent({self._base_cls.__name__}, laws={laws})"


__all__ = ["AngleDependent", "LAWS", "angle_factor", "law_value", "total_angle"]
