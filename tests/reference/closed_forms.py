"""An independent reference for the closed forms of spec A (A1-A7) that the C++ core computes
(``physics/pull_pull_statics.hpp``, reached from Python through ``tendonsheath.plant.physics``).

Nothing here shares code or method with the core:

- the uniform-curvature forms are evaluated in 50-digit decimal arithmetic from exp alone
  (tanh and sinh written out), so they carry neither the core's series nor its rounding;
- the two-sheath full-slip offsets (A5, A6) solve the 2x2 tension balance with
  ``numpy.linalg.solve``, and the shape integrals g, G come from Gauss-Legendre quadrature on
  each piece of the route instead of the core's exact per-piece formula.
"""

from __future__ import annotations

import math
from decimal import Decimal, localcontext

import numpy as np

DIGITS = 50


def _high(fn):
    """fn evaluated on Decimal copies of its (exact binary) float arguments at 50 digits,
    rounded once to a float."""

    def wrapped(*args):
        with localcontext() as ctx:
            ctx.prec = DIGITS
            return float(fn(*(Decimal(float(a)) for a in args)))

    wrapped.__doc__ = fn.__doc__
    return wrapped


def _tanh_half_over(a: Decimal) -> Decimal:
    # tanh(a/2) = (e^a - 1)/(e^a + 1)
    return Decimal("0.5") if a == 0 else (a.exp() - 1) / (a.exp() + 1) / a


def _a_over_sinh(a: Decimal) -> Decimal:
    return Decimal(1) if a == 0 else 2 * a / (a.exp() - (-a).exp())


@_high
def tanh_half_over(a):
    """tanh(a/2)/a."""
    return _tanh_half_over(a)


@_high
def a_over_sinh(a):
    """a / sinh(a)."""
    return _a_over_sinh(a)


@_high
def expm1_over(x):
    """(e^x - 1)/x."""
    return Decimal(1) if x == 0 else (x.exp() - 1) / x


@_high
def backlash_half_width(length, stiffness, pretension, a):
    """e_b = (T0 L/EA) tanh(a/2) (A7)."""
    return pretension * length / stiffness * _tanh_half_over(a) * a


@_high
def load_compliance(length, stiffness, a):
    """C_L = (L/EA) tanh(a/2)/a (A7)."""
    return length / stiffness * _tanh_half_over(a)


@_high
def load_offset(length, stiffness, load, a):
    """e_L = F_L (L/EA) tanh(a/2)/a (A7)."""
    return load * length / stiffness * _tanh_half_over(a)


@_high
def spring_slope(length, stiffness, spring, a):
    """c = 1/(1 + k_e C_L) (A.4)."""
    return 1 / (1 + spring * length / stiffness * _tanh_half_over(a))


@_high
def no_slack_limit(pretension, a):
    """T0 (a/sinh a)(1 + e^-a) (A.4)."""
    return pretension * _a_over_sinh(a) * (1 + (-a).exp())


def shape_integrals(s, theta, mu: float, nodes: int = 12) -> tuple[float, float]:
    """g = (1/L) int e^{-mu theta} ds and G = (1/L) int e^{+mu theta} ds over a piecewise-linear
    theta(s), by Gauss-Legendre quadrature (``nodes`` points) on every piece."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    s, theta = np.asarray(s, float), np.asarray(theta, float)
    g = G = 0.0
    for i in range(1, s.size):
        ds = s[i] - s[i - 1]
        if ds <= 0.0:
            continue
        th = theta[i - 1] + (theta[i] - theta[i - 1]) * 0.5 * (x + 1.0)
        g += 0.5 * ds * float(w @ np.exp(-mu * th))
        G += 0.5 * ds * float(w @ np.exp(mu * th))
    return g / s[-1], G / s[-1]


def pull_pull_offsets(route1, stiffness, pretension, mu, load=0.0, route2=None):
    """Steady full-slip offsets Delta_1 (m) on the forward and backward branch (A5, A6): the
    tension balance (total elongation zero) and the distal load balance, solved as a 2x2
    linear system for the proximal tensions."""
    route2 = route1 if route2 is None else route2
    L1, L2 = route1.length, route2.length
    a1, a2 = mu * route1.curve_angle, mu * route2.curve_angle
    g1, G1 = shape_integrals(route1.s, route1.theta, mu)
    g2, G2 = shape_integrals(route2.s, route2.theta, mu)
    rhs = [pretension * (L1 + L2), load]
    # forward: tendon 1 pulled (distal T1p e^{-a1}), tendon 2 released (T2p e^{+a2})
    t1f = np.linalg.solve([[L1 * g1, L2 * G2], [math.exp(-a1), -math.exp(a2)]], rhs)[0]
    # backward: tendon 1 released, tendon 2 pulled
    t1b = np.linalg.solve([[L1 * G1, L2 * g2], [math.exp(a1), -math.exp(-a2)]], rhs)[0]
    compliance = L1 / stiffness
    return compliance * (t1f * g1 - pretension), compliance * (t1b * G1 - pretension)
