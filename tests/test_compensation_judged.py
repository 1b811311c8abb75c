"""Compensators judged on the physics plant with models identified from calibration runs
(no inverse crime): motor models, sensor noise, references unlike the calibration input."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench.scenarios import do as do_scenario
from tendonsheath.bench.scenarios.common import calibration_input, encoder

T = np.arange(0.0, 12.0, 1e-3)
REFERENCES = {
    "sine 0.1 Hz": 0.8 * np.sin(2 * np.pi * 0.1 * T),
    "sine 0.5 Hz": 0.8 * np.sin(2 * np.pi * 0.5 * T),
    "sine 1 Hz": 0.8 * np.sin(2 * np.pi * 1.0 * T),
    "multi-sine": 0.5 * np.sin(2 * np.pi * 0.2 * T)
    + 0.3 * np.sin(2 * np.pi * 0.45 * T + 1.0)
    + 0.15 * np.sin(2 * np.pi * 0.9 * T + 2.0),
}


@pytest.fixture(scope="module")
def do_setup():
    fit = do_scenario.calibrate(seed=0, budget={"maxiter": 40, "popsize": 10})
    servo, torque = do_scenario.plants()
    return fit, servo, torque


@pytest.mark.parametrize("name", list(REFERENCES))
def test_inverse_feedforward_and_adaptive_beat_the_papers_factors(do_setup, name):
    fit, servo, torque = do_setup
    y_d = REFERENCES[name]
    none = ts.bench.run(servo, None, T, y_d, noise=encoder())
    ff = ts.compensate.InverseFeedforward(fit.model, smoothing=0.03)
    with_ff = ts.bench.run(servo, ff, T, y_d, noise=encoder())
    ctrl = ts.compensate.AdaptiveController.from_model(
        fit.model,
        inertia=do_scenario.INERTIA,
        viscous=do_scenario.VISCOUS,
        bandwidth_hz=8.0,
        max_torque=5.0,
        noise_std=2e-4,
    )
    adaptive = ts.bench.run(torque, ctrl, T, y_d, noise=encoder())
    base = none.metrics["mse"]
    # Do et al.: 0.0158 -> 0.0012 (13x). Measured (seed 0): 1265x, 154x, 43.5x, 417x for
    # 0.1 Hz, 0.5 Hz, 1 Hz, multi-sine; the paper's 13x holds with a margin of 3.3x or more.
    assert base / with_ff.metrics["mse"] >= 13
    # Do et al.: -> 8.28e-5 (190x). Measured: 709x, 581x, 521x at 0.1 Hz, 0.5 Hz, multi-sine
    # (the paper's 190x with a margin of 2.7x or more). At 1 Hz the paper's 190x is NOT met:
    # measured 101x (the 1 kHz loop's delay and derivative filter); the bound there is 50x,
    # 2x below the measured figure, a guard against regression, not the paper's claim.
    needed = 50 if name == "sine 1 Hz" else 190
    assert base / adaptive.metrics["mse"] >= needed


def _calibrate_at_pi(seed=0):
    """Sun et al.'s calibration at one curve angle: friction from the capstan ratio of a
    tension bench (T_d/T_p = exp(-mu Theta) in full slip), EA from a tracking record at pi."""
    route = ts.Route.uniform(1.2, math.pi)
    bench = ts.SingleTendonPlant(
        route=route, friction=0.1, stiffness=5e3, elements=60, load=ts.loads.ConstantForce(20.0)
    )
    bench.reset()
    for x in np.linspace(0.0, 3e-3, 300):  # pull until the whole tendon slips
        bench.step(x)
    tension = bench.tensions()
    mu = -math.log(tension[-1] / tension[0]) / route.total_angle
    plant = ts.PullPullPlant(
        route=route,
        friction=0.1,
        stiffness=5e3,
        pretension=20.0,
        proximal_radius=10e-3,
        distal_radius=10e-3,
        elements=40,
        motor=ts.Motor.position(60.0, 0.8),
        sensor=encoder(seed=seed),
    )
    t, command = calibration_input(15.0, 1.0)
    sim = plant.simulate(t, command, full=True)
    fit = ts.identify(
        ts.models.CurveAngleModel,
        t,
        sim.q_in,
        sim.measured,
        curve_angle=math.pi,
        fixed={
            "friction": mu,
            "pretension": 20.0,
            "length": 1.2,
            "proximal_radius": 10e-3,
            "distal_radius": 10e-3,
        },
        warmup=1500,
        seed=seed,
        progress=False,
        maxiter=40,
        popsize=10,
    )
    fixed = ts.identify(
        ts.models.BoucWenBacklash,
        t,
        sim.q_in,
        sim.measured,
        warmup=1500,
        seed=seed,
        progress=False,
        maxiter=40,
        popsize=10,
    )
    return mu, fit.model, fixed.model


def test_curve_angle_feedforward_holds_its_accuracy_away_from_its_calibration_angle():
    mu, curve_model, fixed_model = _calibrate_at_pi()
    assert mu == pytest.approx(0.1, rel=0.02)
    t = np.arange(0.0, 10.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.2 * t)

    def rmse(theta=None, routes=None, compensator="curve"):
        plant = ts.PullPullPlant(
            route=ts.Route.uniform(1.2, theta if theta is not None else math.pi),
            friction=0.1,
            stiffness=5e3,
            pretension=20.0,
            proximal_radius=10e-3,
            distal_radius=10e-3,
            elements=40,
            motor=ts.Motor.position(60.0, 0.8),
        )
        if compensator == "curve":
            ctrl = ts.compensate.CurveAngleFeedforward.from_model(curve_model, smoothing=0.02)
        else:
            ctrl = ts.compensate.InverseFeedforward(fixed_model, smoothing=0.02)
        return ts.bench.run(plant, ctrl, t, y_d, routes=routes, noise=encoder()).metrics["rmse"]

    calibrated = rmse(math.pi)
    # measured rmse / calibrated: 1.00, 1.00, 1.00 at pi/2, 2 pi, 3 pi and 0.98 on the
    # changing route; the bound 2x leaves a 2x margin
    for theta in (math.pi / 2, 2 * math.pi, 3 * math.pi):
        assert rmse(theta) <= 2 * calibrated, theta

    def changing(tk):  # the endoscope bends over 2 s: pi/2 -> 2 pi, later 2 pi -> pi
        theta = np.interp(
            tk,
            [0.0, 2.0, 4.0, 6.0, 8.0],
            [math.pi / 2, math.pi / 2, 2 * math.pi, 2 * math.pi, math.pi],
        )
        return ts.Route.uniform(1.2, float(theta))

    assert rmse(routes=changing) <= 2 * calibrated
    fixed_at_pi = rmse(math.pi, compensator="fixed")
    # measured 48.6x; the bound 3x is 16x below
    assert rmse(3 * math.pi, compensator="fixed") > 3 * fixed_at_pi
