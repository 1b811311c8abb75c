"""Compensators judged on the physics plant with models identified by bench.calibrate from
the plant's logs alone (no inverse crime, nothing copied from the plant): calibration
routes differ from the test routes, sensed shapes have noise and delay, motor models,
sensor noise, references unlike the calibration input."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench.scenarios import do as do_scenario
from tendonsheath.bench.scenarios.common import encoder

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
    # bench.calibrate on do_scenario.CALIBRATION_ROUTE; judged on the nominal route
    cal = do_scenario.calibrate(seed=0, budget={"maxiter": 40, "popsize": 10})
    servo, torque = do_scenario.plants()
    return cal, servo, torque


@pytest.mark.parametrize("name", list(REFERENCES))
def test_inverse_feedforward_and_adaptive_beat_the_papers_factors(do_setup, name):
    cal, servo, torque = do_setup
    y_d = REFERENCES[name]
    none = ts.bench.run(servo, None, T, y_d, noise=encoder())
    ff = cal.inverse_feedforward(smoothing=0.03)
    with_ff = ts.bench.run(servo, ff, T, y_d, noise=encoder())
    ctrl = ts.compensate.AdaptiveController.from_model(
        cal.backlash_model,
        inertia=do_scenario.INERTIA,
        viscous=do_scenario.VISCOUS,
        bandwidth_hz=8.0,
        max_torque=5.0,
        noise_std=2e-4,
    )
    adaptive = ts.bench.run(torque, ctrl, T, y_d, noise=encoder())
    base = none.metrics["mse"]
    ff_factor, adaptive_factor = FACTORS[name]
    assert base / with_ff.metrics["mse"] >= ff_factor
    assert base / adaptive.metrics["mse"] >= adaptive_factor


# Improvement factors (MSE none / MSE compensated) measured with bench.calibrate's model
# (calibration route, not the nominal test route), seed 0, budget 40 x 10; thresholds sit
# about 15 % below. Do et al.: feedforward 13x (0.0158 -> 0.0012), adaptive 190x (-> 8.28e-5).
# measured:            feedforward  adaptive
#   sine 0.1 Hz           19.9        710
#   sine 0.5 Hz           13.9        581
#   sine 1 Hz              9.5        101   <- neither paper factor is reached at 1 Hz: the
#                                              60 Hz servo's lag (feedforward) and the 1 kHz
#                                              loop's delay and derivative filter (adaptive)
#   multi-sine            15.7        522
FACTORS = {
    "sine 0.1 Hz": (17, 600),
    "sine 0.5 Hz": (12, 500),
    "sine 1 Hz": (8, 85),
    "multi-sine": (13, 450),
}


CAL_ANGLES = (0.7 * math.pi, 1.3 * math.pi, 1.7 * math.pi)  # no test angle among them
PHYSICS = dict(  # the robot; the calibration never reads these
    friction=0.1,
    stiffness=5e3,
    pretension=20.0,
    proximal_radius=10e-3,
    distal_radius=10e-3,
    elements=40,
)


def _robot(theta):
    return ts.PullPullPlant(
        route=ts.Route.uniform(1.2, theta), **PHYSICS, motor=ts.Motor.position(60.0, 0.8)
    )


def _calibrate(seed=0):
    """bench.calibrate on the robot's logs at three calibration angles; the fixed
    feedforward's BoucWenBacklash comes from the run at 1.3 pi only."""
    return ts.bench.calibrate(
        _robot(CAL_ANGLES[0]),
        [ts.Route.uniform(1.2, a) for a in CAL_ANGLES],
        backlash_route=1,
        sensor=encoder(seed=seed),
        seed=seed,
        budget={"maxiter": 40, "popsize": 10},
    )


def test_curve_angle_feedforward_holds_its_accuracy_away_from_its_calibration_angles():
    cal = _calibrate()
    # friction is identified from the three angles (true 0.1), and the groups of spec B
    assert cal.groups["mu"]["value"] == pytest.approx(0.1, rel=0.05)
    assert cal.groups["T0 L/(EA r_p)"]["value"] == pytest.approx(20 * 1.2 / 5e3 / 10e-3, rel=0.05)
    assert cal.groups["gain r_p/r_d"]["value"] == pytest.approx(1.0, rel=0.01)
    t = np.arange(0.0, 10.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.2 * t)
    shape = cal.shape  # the feedforward is told the sensed curve angle (noise, delay)

    def rmse(theta=None, routes=None, compensator="curve"):
        plant = _robot(theta if theta is not None else math.pi)
        if compensator == "curve":
            ctrl = cal.curve_angle_feedforward(smoothing=0.02)
            sensing = shape
        else:
            ctrl = cal.inverse_feedforward(smoothing=0.02)
            sensing = None
        return ts.bench.run(
            plant, ctrl, t, y_d, routes=routes, noise=encoder(), shape_sensing=sensing
        ).metrics["rmse"]

    # measured: rmse 3.2e-3 rad at pi, and 1.00x of it at pi/2, 2 pi and 3 pi, 0.95x with
    # the route changing; the claim is "within 2x away from the calibration angles"
    at_pi = rmse(math.pi)  # pi is not a calibration angle
    for theta in (math.pi / 2, 2 * math.pi, 3 * math.pi):
        assert rmse(theta) <= 2 * at_pi, theta

    def changing(tk):  # the endoscope bends over 2 s: pi/2 -> 2 pi, later 2 pi -> pi
        theta = np.interp(
            tk,
            [0.0, 2.0, 4.0, 6.0, 8.0],
            [math.pi / 2, math.pi / 2, 2 * math.pi, 2 * math.pi, math.pi],
        )
        return ts.Route.uniform(1.2, float(theta))

    assert rmse(routes=changing) <= 2 * at_pi
    fixed_at_pi = rmse(math.pi, compensator="fixed")  # measured: 5.6x worse at 3 pi
    assert rmse(3 * math.pi, compensator="fixed") > 3 * fixed_at_pi
