"""Compensators: streaming equals whole-trajectory commands, limits, closed forms, bad input."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.compensate import (
    AdaptiveController,
    CommandLimits,
    ContinuumFeedforward,
    CurveAngleFeedforward,
    InverseFeedforward,
)

T = np.linspace(0.0, 8.0, 4001)
Y_D = 0.4 * np.sin(2 * np.pi * 0.4 * T) + 0.1 * np.sin(2 * np.pi * 1.3 * T)

FEEDFORWARDS = [
    InverseFeedforward(ts.models.BoucWenBacklash(c_r=1.0, c_l=0.9, B_r=0.1, B_l=0.12)),
    InverseFeedforward(ts.models.Backlash(1.0, 0.9, 0.1, 0.12), smoothing=0.02),
    InverseFeedforward(ts.models.PrandtlIshlinskii([0, 0.05, 0.1], [0.7, 0.2, 0.1])),
    CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0, load_stiffness=500.0, curve_angle=2 * np.pi),
    ContinuumFeedforward(mode="exact"),
    ContinuumFeedforward(mode="published"),
]


@pytest.mark.parametrize("ff", FEEDFORWARDS, ids=lambda f: repr(f)[:40])
def test_streaming_equals_command(ff):
    batch = ff.command(T, Y_D)
    ff.reset()
    dts = np.r_[0.0, np.diff(T)]
    stream = np.array([ff.step(y, dt) for y, dt in zip(Y_D, dts, strict=True)])
    np.testing.assert_array_equal(stream, batch)


@pytest.mark.parametrize("ff", FEEDFORWARDS, ids=lambda f: repr(f)[:40])
def test_bad_trajectories_are_rejected(ff):
    with pytest.raises(ValueError, match="not finite"):
        ff.command(T, np.where(np.arange(T.size) == 7, np.nan, Y_D))
    with pytest.raises(ValueError, match="strictly increasing"):
        ff.command(T[::-1], Y_D)
    with pytest.raises(ValueError, match="different lengths"):
        ff.command(T[:-1], Y_D)


def test_no_nan_and_limits_for_random_finite_input(rng):
    limits = CommandLimits(min=-1.0, max=2.0, max_rate=40.0)
    ffs = [
        InverseFeedforward(ts.models.BoucWenBacklash(), limits=limits),
        CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0, limits=limits),
        ContinuumFeedforward(limits=limits, mode="published"),
    ]
    for _ in range(5):
        y = rng.normal(0, 1, 3000) * np.where(rng.random(3000) < 0.05, 1e5, 1.0)
        t = np.cumsum(rng.uniform(1e-4, 1e-2, 3000))
        for ff in ffs:
            u = ff.command(t, y)
            assert np.all(np.isfinite(u))
            assert u.min() >= -1.0 and u.max() <= 2.0
            assert np.all(np.abs(np.diff(u)) <= 40.0 * np.diff(t) + 1e-12)


def test_curve_angle_feedforward_inverts_the_closed_form_model(rng):
    """Far from reversals the command is x_d + e_b sigma + e_L of spec (A7), per curve angle."""
    for _ in range(20):
        mu, C, T0 = rng.uniform(0.05, 0.2), rng.uniform(1e-5, 1e-4), rng.uniform(5, 30)
        theta = rng.uniform(0.1, 3 * np.pi)
        r_p, r_d = rng.uniform(3e-3, 8e-3, 2)
        ff = CurveAngleFeedforward(
            mu, 1 / C, 1.0, T0, proximal_radius=r_p, distal_radius=r_d, curve_angle=theta,
            smoothing=1e-4,
        )  # fmt: skip
        t = np.linspace(0, 1, 1001)
        y = 0.3 * t  # rising at 0.3 rad/s
        q = ff.command(t, y)
        a = mu * theta
        e_b = C * T0 * np.tanh(a / 2)
        np.testing.assert_allclose(q[10:], (r_d * y[10:] + e_b) / r_p, rtol=1e-9)


def test_curve_angle_feedforward_uses_route_shape():
    """Curvature concentrated distally: the g/G correction differs from the Theta-only one."""

    class Route:  # minimal stand-in: samples of the accumulated angle
        s = np.array([0.0, 0.9, 1.0])
        theta = np.array([0.0, 1.0, 3.0])

    ff = CurveAngleFeedforward(0.15, 1 / 5e-5, 1.0, 20.0, curve_angle=3.0, smoothing=1e-4)
    uniform = ts._core.CurveAngleFeedforward.correction(ff, 0.0, 1.0)
    ff.set_route(Route)
    shaped = ts._core.CurveAngleFeedforward.correction(ff, 0.0, 1.0)
    assert ff.shape.curve_angle == 3.0
    assert abs(shaped - uniform) > 0.1 * abs(uniform)


def test_continuum_modes_differ_by_the_published_double_counting():
    exact = ContinuumFeedforward(mode="exact")
    published = ContinuumFeedforward(mode="published")
    theta = np.deg2rad(60.0)
    # exact: forward elongation under the bending force
    F = exact.bending_force(theta)
    assert F == pytest.approx(theta / 0.03 * 4e-4 / 2e-3)
    x_exact = exact.tendon_input(theta, 1.0)
    x_pub = published.tendon_input(theta, 1.0)
    a = 0.1 * np.pi
    L_EA = 1.0 / 2.4e4
    expected_exact = 2e-3 * theta + L_EA * np.tanh(a / 2) * (10.0 + F / a)
    assert x_exact == pytest.approx(expected_exact, rel=1e-10)
    assert x_pub > x_exact  # Lau's delta_0 is (1 + e^-a) times the exact dead zone


def test_bad_parameters_are_named():
    with pytest.raises(ValueError, match="smoothing"):
        InverseFeedforward(ts.models.Backlash(), smoothing=0.0)
    with pytest.raises(ValueError, match="stiffness"):
        CurveAngleFeedforward(0.1, -1.0, 1.0, 10.0)
    with pytest.raises(ValueError, match="mode"):
        ContinuumFeedforward(mode="fancy")
    with pytest.raises(ValueError, match="min < max"):
        CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0, limits=CommandLimits(min=1.0, max=0.0))
    with pytest.raises(TypeError, match="a Chain is inverted when"):
        InverseFeedforward(ts.models.Chain(ts.models.Backlash(), ts.models.BoucWen()))
    with pytest.raises(TypeError, match="model must be a tendonsheath model"):
        InverseFeedforward("Backlash")
    with pytest.raises(TypeError, match="unknown gain"):
        AdaptiveController(gain=3)
    with pytest.raises(ValueError, match="phi_0"):
        AdaptiveController(phi_0=-1.0)


def test_adaptive_controller_streams_and_falls_back_on_dropout():
    ctrl = AdaptiveController.from_model(ts.models.Backlash(1.0, 1.0, 0.1, 0.1), inertia=1e-4)
    u1 = ctrl.step(0.1, 0.0, 0.0, 1e-3)
    assert math.isfinite(u1) and not ctrl.in_fallback
    adapted = ctrl.estimates
    assert adapted["D"] > 0  # the first step's error moved the disturbance estimate
    u2 = ctrl.step(0.1, math.nan, 0.0, 1e-3)
    assert math.isfinite(u2) and ctrl.in_fallback
    assert u2 > 0  # pushes the motor toward the feedforward target above 0
    assert ctrl.estimates == adapted  # a dropout freezes the estimates
