"""Closed forms of the capstan/Coulomb model (spec A.1-A.4, B), at the tendon level (metres, N).

All functions take the friction coefficient ``mu``, lengths in m, the tendon stiffness ``EA``
in N and angles in rad, and are safe at mu*Theta -> 0 (series, spec pitfall 7). Rotary
quantities: divide a tendon displacement by the pulley radius to get an angle.

The closed forms are computed by the C++ core (``physics/pull_pull_statics.hpp``), the one
source that the real-time models and compensators use too; the uniform-curvature ones take
NumPy arrays (broadcast together) and loop in C++.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from .._util.typing import ArrayLike, FloatArray, FloatOrArray
from . import _bound as core
from .route import Route


def _elementwise(kernel: Callable[..., Any], *args: ArrayLike) -> FloatOrArray:
    """kernel (a C++ loop over equal-length float64 arrays) on the broadcast arguments; a
    NumPy scalar for scalar arguments, else an array of their broadcast shape."""
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in args))
    flat = [np.ascontiguousarray(a).ravel() for a in arrays]
    out = np.asarray(kernel(*flat)).reshape(arrays[0].shape)
    return out[()] if out.ndim == 0 else out


def _friction_angle(mu: ArrayLike, curve_angle: ArrayLike) -> FloatArray:
    """a = mu Theta, the argument of every uniform closed form."""
    return np.multiply(np.asarray(mu, dtype=np.float64), np.asarray(curve_angle, np.float64))


def tanh_half_over(a: ArrayLike) -> FloatOrArray:
    """tanh(a/2)/a, -> 1/2 - a^2/24 as a -> 0.

    Parameters
    ----------
    a : float or array_like
        The capstan exponent mu Theta.

    Returns
    -------
    numpy.ndarray of float
        tanh(a/2)/a, shaped as a (the series below 1e-4).
    """
    return _elementwise(core.tanh_half_over, a)


def capstan_ratio(
    mu: ArrayLike, curve_angle: ArrayLike, direction: ArrayLike = 1.0
) -> FloatOrArray:
    """Full-slip distal/proximal tension ratio T_d/T_p = exp(-direction mu Theta) (A1).

    Parameters
    ----------
    mu : float or array_like
        Friction coefficient mu.
    curve_angle : float or array_like
        Curve angle Theta (rad).
    direction : float or array_like, default 1.0
        +1 when the tendon is pulled (slides towards the motor), -1 when released.

    Returns
    -------
    numpy.ndarray of float
        T_d / T_p, broadcast over the arguments.
    """
    return np.exp(-np.asarray(direction) * np.asarray(mu) * np.asarray(curve_angle))


def route_shape(route: Route, mu: float) -> core.ShapeIntegrals:
    """g, G and Theta of a route (anything with ``s`` and ``theta`` samples) for friction mu,
    as the C++ core's compensators take them.

    Parameters
    ----------
    route : Route
        Or any object with ``s`` (m) and ``theta`` (rad) sample arrays.
    mu : float
        Friction coefficient.

    Returns
    -------
    ShapeIntegrals
        The C++ struct with ``g``, ``G`` and the total angle.
    """
    return core.shape_integrals(
        np.ascontiguousarray(route.s, dtype=np.float64),
        np.ascontiguousarray(route.theta, dtype=np.float64),
        float(mu),
    )


def dead_zone_factor(g: ArrayLike, G: ArrayLike, a: ArrayLike) -> FloatOrArray:
    """F = g/(g + G e^{-2a}) - G/(G + g e^{2a}): the pull-pull dead-zone half-width per unit
    T0 L/EA for a route of shape integrals g, G and friction angle a = mu Theta (spec A5/A6
    with F_L = 0: 2 e_b = (T0 L/EA) 2 F). It equals tanh(a/2) for uniform curvature.

    Evaluated as tanh(a + ln(g/G)/2) (the same value: with u = g e^{a} and v = G e^{-a},
    F = (u - v)/(u + v)), which neither overflows for large a nor loses more than a few
    ulp of the result's scale near a = 0, where the two fractions of the definition cancel.

    Parameters
    ----------
    g : float or array_like
        (1/L) int e^{-mu theta(s)} ds, > 0.
    G : float or array_like
        (1/L) int e^{+mu theta(s)} ds, > 0.
    a : float or array_like
        The friction angle mu Theta (>= 0).

    Returns
    -------
    float or numpy.ndarray of float
        F, broadcast over the arguments (NaN where g or G is not > 0).
    """
    g_arr = np.asarray(g, dtype=np.float64)
    G_arr = np.asarray(G, dtype=np.float64)
    a_arr = np.asarray(a, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where((g_arr > 0) & (G_arr > 0), g_arr / G_arr, np.nan)
        out = np.tanh(a_arr + 0.5 * np.log(ratio))
    return out[()] if out.ndim == 0 else out


def route_dead_zone_factor(route: Route, mu: ArrayLike) -> FloatOrArray:
    """The dead-zone factor :func:`dead_zone_factor` of a route for friction mu (a number or
    an array of them): g, G from :func:`route_shape` and a = mu Theta.

    Parameters
    ----------
    route : Route
        The sheath's route.
    mu : float or array_like of float
        Friction coefficient(s), >= 0.

    Returns
    -------
    numpy.float64 or numpy.ndarray of float
        F for each mu (tanh(mu Theta/2) for a uniform route), shaped as mu.
    """
    mus = np.asarray(mu, dtype=np.float64)
    flat = mus.ravel()
    out = np.empty(flat.size)
    for i, m in enumerate(flat):
        shape = route_shape(route, float(m))
        out[i] = dead_zone_factor(shape.g, shape.G, float(m) * shape.curve_angle)
    return out[0] if mus.ndim == 0 else out.reshape(mus.shape)


def shape_integrals(route: Route, mu: float) -> tuple[float, float]:
    """g = (1/L) int e^{-mu theta} ds and G = (1/L) int e^{+mu theta} ds (spec A.2), exact for
    the piecewise-linear theta(s) of a route (the C++ core's computation).

    Parameters
    ----------
    route : Route
        The sheath's route.
    mu : float
        Friction coefficient.

    Returns
    -------
    g, G : float
        The two shape integrals (dimensionless).
    """
    shape = route_shape(route, mu)
    return float(shape.g), float(shape.G)


def backlash_half_width(
    length: ArrayLike, EA: ArrayLike, pretension: ArrayLike, mu: ArrayLike, curve_angle: ArrayLike
) -> FloatOrArray:
    """e_b = T0 L tanh(mu Theta/2) / EA: half the pull-pull dead zone, uniform curvature (A7).

    Parameters
    ----------
    length : float or array_like
        Sheath length L (m).
    EA : float or array_like
        Tendon axial stiffness EA (N).
    pretension : float or array_like
        Pretension T0 (N).
    mu : float or array_like
        Friction coefficient mu.
    curve_angle : float or array_like
        Curve angle Theta (rad).

    Returns
    -------
    numpy.ndarray of float
        e_b (m), broadcast over the arguments.
    """
    a = _friction_angle(mu, curve_angle)
    return _elementwise(core.uniform_backlash_half_width, length, EA, pretension, a)


def load_offset(
    length: ArrayLike, EA: ArrayLike, load_force: ArrayLike, mu: ArrayLike, curve_angle: ArrayLike
) -> FloatOrArray:
    """e_L = F_L L tanh(a/2) / (EA a), a = mu Theta: the load shift of both branches (A7).

    Parameters
    ----------
    length : float or array_like
        Sheath length L (m).
    EA : float or array_like
        Tendon axial stiffness EA (N).
    load_force : float or array_like
        Distal load F_L (N), positive resisting forward motion.
    mu : float or array_like
        Friction coefficient mu.
    curve_angle : float or array_like
        Curve angle Theta (rad).

    Returns
    -------
    numpy.ndarray of float
        e_L (m), broadcast over the arguments.
    """
    a = _friction_angle(mu, curve_angle)
    return _elementwise(core.uniform_load_offset, length, EA, load_force, a)


def load_compliance(
    length: ArrayLike, EA: ArrayLike, mu: ArrayLike, curve_angle: ArrayLike
) -> FloatOrArray:
    """C_L = L tanh(a/2) / (EA a) (m/N): output shift per newton of distal load.

    Parameters
    ----------
    length : float or array_like
        Sheath length L (m).
    EA : float or array_like
        Tendon axial stiffness EA (N).
    mu : float or array_like
        Friction coefficient mu.
    curve_angle : float or array_like
        Curve angle Theta (rad).

    Returns
    -------
    numpy.ndarray of float
        C_L (m/N), broadcast over the arguments.
    """
    return _elementwise(core.uniform_load_compliance, length, EA, _friction_angle(mu, curve_angle))


def spring_slope(
    length: ArrayLike, EA: ArrayLike, mu: ArrayLike, curve_angle: ArrayLike, k: ArrayLike
) -> FloatOrArray:
    """Branch slope dx_out/dx_in = 1/(1 + k C_L) with a spring load F_L = k x_out (spec A.4).

    Parameters
    ----------
    length : float or array_like
        Sheath length L (m).
    EA : float or array_like
        Tendon axial stiffness EA (N).
    mu : float or array_like
        Friction coefficient mu.
    curve_angle : float or array_like
        Curve angle Theta (rad).
    k : float or array_like
        Stiffness of the spring load (N/m).

    Returns
    -------
    numpy.ndarray of float
        The slope (dimensionless, in (0, 1]), broadcast over the arguments.
    """
    a = _friction_angle(mu, curve_angle)
    return _elementwise(core.uniform_spring_slope, length, EA, k, a)


def dead_zone_width(
    length: ArrayLike, EA: ArrayLike, pretension: ArrayLike, mu: ArrayLike, curve_angle: ArrayLike
) -> FloatOrArray:
    """2 e_b: the input dead zone of a pull-pull pair, uniform curvature (A7).

    Parameters
    ----------
    length : float or array_like
        Sheath length L (m).
    EA : float or array_like
        Tendon axial stiffness EA (N).
    pretension : float or array_like
        Pretension T0 (N).
    mu : float or array_like
        Friction coefficient mu.
    curve_angle : float or array_like
        Curve angle Theta (rad).

    Returns
    -------
    numpy.ndarray of float
        2 e_b (m), broadcast over the arguments.
    """
    return 2.0 * backlash_half_width(length, EA, pretension, mu, curve_angle)


def no_slack_limit(pretension: ArrayLike, mu: ArrayLike, curve_angle: ArrayLike) -> FloatOrArray:
    """Largest distal load F_L before the released tendon goes slack: T0 (a/sinh a)(1 + e^-a).

    Parameters
    ----------
    pretension : float or array_like
        Pretension T0 (N).
    mu : float or array_like
        Friction coefficient mu.
    curve_angle : float or array_like
        Curve angle Theta (rad).

    Returns
    -------
    numpy.ndarray of float
        The load limit (N), broadcast over the arguments (a -> 0: 2 T0).
    """
    return _elementwise(core.uniform_no_slack_limit, pretension, _friction_angle(mu, curve_angle))


def pull_pull_offsets(
    route1: Route,
    EA: float,
    pretension: float,
    mu: float,
    load_force: float = 0.0,
    route2: Route | None = None,
) -> tuple[float, float]:
    """Steady full-slip offsets x_in - x_out = Delta_1 (m) on the forward and backward branch.

    General (A5)/(A6) with the shape integrals g, G of each sheath (they may differ in shape
    and length); with equal uniform sheaths this is (A7):
    x_out = x_in - (L/EA) tanh(a/2) [T0 sigma + F_L/a].

    Parameters
    ----------
    route1 : Route
        Route of sheath 1 (the tendon pulled forward).
    EA : float
        Tendon axial stiffness (N), both tendons.
    pretension : float
        Pretension T0 (N).
    mu : float
        Friction coefficient, both sheaths.
    load_force : float, default 0.0
        Distal load F_L (N).
    route2 : Route, optional
        Route of sheath 2 (default: route1).

    Returns
    -------
    forward, backward : float
        x_in - x_out on the forward and the backward branch (m).
    """
    route2 = route1 if route2 is None else route2
    statics = core.PullPullStatics()
    statics.friction = float(mu)
    statics.compliance = route1.length / EA
    statics.pretension = float(pretension)
    shapes = (route_shape(route1, mu), route_shape(route2, mu), route2.length / route1.length)
    fwd = statics.forward_elongation(*shapes, float(load_force))
    bwd = statics.backward_elongation(*shapes, float(load_force))
    return float(fwd), float(bwd)


def pull_pull_dead_zone(
    route1: Route,
    EA: float,
    pretension: float,
    mu: float,
    load_force: float = 0.0,
    route2: Route | None = None,
) -> float:
    """Input dead-zone width (m) of a pull-pull pair: forward minus backward steady offset.

    Parameters
    ----------
    route1 : Route
        Route of sheath 1.
    EA : float
        Tendon axial stiffness (N).
    pretension : float
        Pretension T0 (N).
    mu : float
        Friction coefficient.
    load_force : float, default 0.0
        Distal load F_L (N).
    route2 : Route, optional
        Route of sheath 2 (default: route1).

    Returns
    -------
    float
        The dead-zone width (m).
    """
    f, b = pull_pull_offsets(route1, EA, pretension, mu, load_force, route2)
    return f - b


def single_tendon_dead_zone(route: Route, EA: float, distal_tension: float, mu: float) -> float:
    """(A4): input travel to reverse a single tendon pulled at distal tension T_d (m).

    b = (L/EA) T_p0 [g - e^{-2a} G] with T_p0 = T_d e^{a}; uniform: 4 T_d L sinh^2(a/2)/(EA a).

    Parameters
    ----------
    route : Route
        The sheath's route.
    EA : float
        Tendon axial stiffness (N).
    distal_tension : float
        Distal tension T_d (N).
    mu : float
        Friction coefficient.

    Returns
    -------
    float
        The input travel b (m).
    """
    a = mu * route.curve_angle
    g, G = shape_integrals(route, mu)
    Tp0 = distal_tension * np.exp(a)
    return float(route.length / EA * Tp0 * (g - np.exp(-2 * a) * G))


def single_tendon_elongation(
    route: Route,
    EA: float,
    proximal_tension: float,
    mu: float,
    reference_tension: float,
    sign: float = 1,
) -> float:
    """(A3) in full slip: Delta = (L/EA)(T_p g - T_ref) when pulled (sign +1),
    (L/EA)(T_p G - T_ref) when released (sign -1).

    Parameters
    ----------
    route : Route
        The sheath's route.
    EA : float
        Tendon axial stiffness (N).
    proximal_tension : float
        Proximal tension T_p (N).
    mu : float
        Friction coefficient.
    reference_tension : float
        Tension T_ref at which the tendon has its rest length (N).
    sign : int, default 1
        +1 pulled, -1 released.

    Returns
    -------
    float
        The elongation Delta (m).
    """
    g, G = shape_integrals(route, mu)
    shape = g if sign > 0 else G
    return float(route.length / EA * (proximal_tension * shape - reference_tension))


__all__ = [
    "backlash_half_width",
    "capstan_ratio",
    "dead_zone_factor",
    "dead_zone_width",
    "load_compliance",
    "load_offset",
    "no_slack_limit",
    "pull_pull_dead_zone",
    "pull_pull_offsets",
    "route_dead_zone_factor",
    "route_shape",
    "shape_integrals",
    "single_tendon_dead_zone",
    "single_tendon_elongation",
    "spring_slope",
    "tanh_half_over",
]
