"""Identification on data of the physics plant (not of the model being fitted), with noise."""

import math

import numpy as np

import tendonsheath as ts

PHYSICS = dict(
    friction=0.1,
    stiffness=5e3,
    pretension=20.0,
    proximal_radius=10e-3,
    distal_radius=10e-3,
    elements=40,
)


def _record(theta, t, command, seed):
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(1.2, theta),
        **PHYSICS,
        motor=ts.Motor.position(60.0, 0.8),
        sensor=ts.Sensor(resolution=1e-4, noise_std=2e-4, seed=seed),
    )
    sim = plant.simulate(t, command, full=True)
    return sim.q_in, sim.measured, sim.q_out


def test_bouc_wen_backlash_predicts_another_reference_within_3_percent():
    t = np.arange(0.0, 20.0, 1e-3)
    x, y, _ = _record(math.pi, t, 1.0 * np.sin(2 * np.pi * 0.2 * t), seed=1)
    fit = ts.identify(
        ts.models.BoucWenBacklash, t, x, y, warmup=2000, progress=False, maxiter=40, popsize=10
    )
    t2 = np.arange(0.0, 10.0, 1e-3)  # other amplitude and frequency, and two tones
    command = 0.6 * np.sin(2 * np.pi * 0.7 * t2) + 0.2 * np.sin(2 * np.pi * 0.23 * t2)
    x2, y2, _ = _record(math.pi, t2, command, seed=2)
    check = fit.validate(t2, x2, y2, warmup=1500)
    assert check["nrmse"] < 0.03
    assert fit.nrmse < 0.03


def test_curve_angle_model_predicts_unseen_angles_within_2x_of_its_fit():
    t = np.arange(0.0, 12.0, 1e-3)
    command = 1.0 * np.sin(2 * np.pi * 0.2 * t) * (1 - 0.5 * np.sin(np.pi * t / 12.0))
    recordings = []
    for i, theta in enumerate((math.pi / 2, math.pi, 2 * math.pi)):
        x, y, _ = _record(theta, t, command, seed=10 + i)
        recordings.append((t, x, y, theta))
    fit = ts.identify(
        ts.models.CurveAngleModel,
        recordings=recordings,
        fixed={"pretension": 20.0, "length": 1.2, "proximal_radius": 10e-3, "distal_radius": 10e-3},
        warmup=1500,
        progress=False,
        maxiter=40,
        popsize=10,
    )
    assert abs(fit.model.params["friction"] - 0.1) < 0.01
    for theta in (3 * math.pi / 2, 3 * math.pi):
        x, y, _ = _record(theta, t, command, seed=20)
        check = fit.validate(t, x, y, curve_angle=theta, warmup=1500)
        assert check["rmse"] <= 2 * fit.rmse, theta
