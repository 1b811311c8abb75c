"""04: identify a model from a calibration run, then compensate on the physics plant.

    python examples/04_compensate_on_the_plant.py

No inverse crime: the model is identified from data of the N-element plant, and the
compensators are judged on that plant, with a motor model and a noisy distal encoder.
"""

from __future__ import annotations

import numpy as np

import tendonsheath as ts


def main() -> None:
    route = ts.Route.arcs([(0.5, 0.0), (0.5, np.pi / 2), (0.5, np.pi / 2)])
    physics = dict(
        route=route,
        friction=0.1,
        stiffness=5e3,
        pretension=20.0,
        proximal_radius=15e-3,
        distal_radius=15e-3,
        elements=40,
    )
    encoder = ts.Sensor(resolution=1e-4, noise_std=2e-4, seed=1)

    # 1. calibration run: motor position in, measured distal angle out
    t = np.arange(0.0, 20.0, 1e-3)
    command = 1.2 * np.sin(2 * np.pi * 0.15 * t) * (1 - 0.6 * np.sin(np.pi * t / 20.0))
    servo = ts.PullPullPlant(**physics, motor=ts.Motor.position(60.0, 0.8), sensor=encoder)
    calib = servo.simulate(t, command)
    fit = ts.identify(
        ts.models.BoucWenBacklash, t, calib.q_in, calib.measured, warmup=2000, progress=False
    )
    print(f"identified {fit.model}  (rmse {fit.rmse:.2e} rad in {fit.seconds:.1f} s)")

    # 2. track a different reference
    t = np.arange(0.0, 15.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.3 * t) + 0.2 * np.sin(2 * np.pi * 0.7 * t)
    servo = ts.PullPullPlant(**physics, motor=ts.Motor.position(60.0, 0.8))
    torque = ts.PullPullPlant(**physics, motor=ts.Motor.torque(0.01, 0.2, max_torque=5.0))
    runs = {
        "none": ts.bench.run(servo, None, t, y_d, noise=encoder),
        "InverseFeedforward": ts.bench.run(
            servo,
            ts.compensate.InverseFeedforward(fit.model, smoothing=0.03),
            t,
            y_d,
            noise=encoder,
        ),
        "AdaptiveController": ts.bench.run(
            torque,
            ts.compensate.AdaptiveController.from_model(
                fit.model, inertia=0.01, viscous=0.2, max_torque=5.0, noise_std=2e-4
            ),
            t,
            y_d,
            noise=encoder,
        ),
    }
    base = runs["none"].metrics["mse"]
    for name, result in runs.items():
        m = result.metrics
        print(f"{name:20s} MSE {m['mse']:.2e} rad^2   {base / m['mse']:7.1f}x better than none")


if __name__ == "__main__":
    main()
