"""Compensators judged on the physics plant with models identified by bench.calibrate from
the plant's logs alone (no inverse crime, nothing copied from the plant): calibration
routes differ from the test routes, sensed shapes have noise and delay, motor models,
sensor noise, references unlike the calibration input."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import presets
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


# Improvement factors (MSE none / MSE compensated) on the realistic plant (do_scenario
# .plants(): tendonsheath.plant.presets, the PID servo) with bench.calibrate's model (calibration
# route, not the nominal test route; fitted from the command), seed 0, budget 40 x 10;
# thresholds sit about 15 % below.
# measured:            feedforward  adaptive
#   sine 0.1 Hz           22.2        1.76
#   sine 0.5 Hz           23.9        6.48
#   sine 1 Hz             17.0       12.3
#   multi-sine            25.2        2.05
# (On the yielding PD servo, with the model fitted from the encoder, the feedforward's were
# 9.8 / 7.9 / 5.6 / 8.7: see docs/honesty.md on the servo choice and the fitted signal. The
# adaptive controller drives a torque motor either way; its factors fell because the
# uncompensated run, behind the position servo, got better.)
# Do et al.'s 190x (adaptive, -> 8.28e-5) is NOT reached on any reference: slow references
# suffer most from the motor's Coulomb friction and gear play under the torque-driven
# adaptive loop.
FACTORS = {
    "sine 0.1 Hz": (18.8, 1.5),
    "sine 0.5 Hz": (20.3, 5.5),
    "sine 1 Hz": (14.5, 10.5),
    "multi-sine": (21.4, 1.75),
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
    """The pull-pull robot with the realistic preset (outside every compensator's class)."""
    physics = {k: v for k, v in PHYSICS.items() if k not in ("friction", "stiffness")}
    return ts.PullPullPlant(
        route=ts.Route.uniform(1.2, theta),
        **physics,
        **presets.realistic_plant(friction=PHYSICS["friction"], stiffness=PHYSICS["stiffness"]),
        motor=presets.realistic_motor(bandwidth_hz=60.0, damping=0.8),
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
    # on the realistic robot the groups are effective values (measured mu 0.090 for a sheath
    # mu of 0.1 and 0.115, with viscosity and motor friction; T0 L/(EA r_p) 0.60 for 0.48;
    # the play 0.0157 rad for a gear play of 0.0087, with the motor's friction):
    # only the gain is checked against the design (tests/test_identify_on_plant.py checks
    # the groups on the ideal plant)
    assert cal.groups["gain r_p/r_d"]["value"] == pytest.approx(1.0, rel=0.02)
    # the declared scale is one row that says it is not a measurement, beside the groups
    scale = [r for r in cal.told("CurveAngleFeedforward") if "pretension" in r["quantity"]]
    assert [r["quantity"] for r in scale] == ["pretension, length, proximal_radius"]
    assert scale[0]["source"].startswith("not measured: a scale")
    identified = [r["quantity"] for r in cal.identified_rows()]
    assert identified.count("pretension, length, proximal_radius") == 1
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

    # measured on the realistic robot (PID servo, groups with the motor-side play): rmse
    # 2.80e-3 rad at pi; 0.76x of it at pi/2, 1.85x at 2 pi; the claim is "within 2x away from
    # the calibration angles (0.7-1.7 pi)". At 3 pi, far outside them, it is 3.0x: the 2x claim
    # does NOT hold there (the groups identified on this plant are effective values).
    at_pi = rmse(math.pi)  # pi is not a calibration angle
    at = {theta: rmse(theta) for theta in (math.pi / 2, 2 * math.pi)}
    for theta, value in at.items():
        assert value <= 2 * at_pi, theta
    assert rmse(3 * math.pi) <= 3.7 * at_pi

    def changing(tk):  # the endoscope bends over 2 s: pi/2 -> 2 pi, later 2 pi -> pi
        theta = np.interp(
            tk,
            [0.0, 2.0, 4.0, 6.0, 8.0],
            [math.pi / 2, math.pi / 2, 2 * math.pi, 2 * math.pi, math.pi],
        )
        return ts.Route.uniform(1.2, float(theta))

    # following the route while it changes costs little beyond the angles it passes through:
    # measured 1.33x the worse of pi/2 and 2 pi (2.47x the rmse at pi, which the PID servo and
    # the play made 5x smaller than the transients of a change: spec B's memory effect)
    assert rmse(routes=changing) <= 1.6 * max(at.values())
    fixed_at_pi = rmse(math.pi, compensator="fixed")  # measured: 4.7x worse at 3 pi
    assert rmse(3 * math.pi, compensator="fixed") > 3 * fixed_at_pi
