"""10: compensate without a tip sensor on a real servo, while the endoscope bends.

    python examples/10_no_tip_sensor.py [--scale 1.0]

The drive sits behind a PD position servo that yields to the tendons' torque, and its route
changes at random. Everything is calibrated from logs (bench.calibrate, never the plant):

1. three calibration shapes, logging the command, the motor encoder, the tip sensor and the
   sensed curvature profile (ShapeSensing(segments=10): noise and delay);
2. a motor calibration run (a chirp on a slow ramp) identifies the servo, and an EncoderLoop
   (a PI loop on the motor encoder) is tuned on it, its margins stated;
3. a BoucWenBacklash whose dead band follows the sensed shape (AngleDependent, "tanh" laws),
   fitted from the encoder (the signal the loop makes the shaft follow).

It prints the MSE reduction of the one-shape feedforward and of the shape-aware one inside
the encoder loop, on 3 route-schedule seeds (the demo uses 5), as the median and the worst.
"""

from __future__ import annotations

import argparse

import numpy as np

import tendonsheath as ts
from tendonsheath.bench.scenarios import do
from tendonsheath.bench.scenarios.common import encoder, piecewise_routes


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scale", type=float, default=1.0, help="run length (1: 30 s)")
    args = ap.parse_args()
    budget = {} if args.scale >= 1 else {"maxiter": 30, "popsize": 8}
    cal = do.calibrate(seed=0, budget=budget, servo="pd")  # the three shapes and the servo
    print(cal.servo.servo.summary())
    fits = do.calibrations(cal)  # one shape or all three, from the command or the encoder
    one_shape = fits["single command"].inverse_feedforward(smoothing=0.03)
    shape = fits["shape encoder"]
    loop = shape.encoder_loop(shape.inverse_feedforward(smoothing=0.03))
    print(loop.design.summary())
    t, y_d = do.reference(max(8.0, 30.0 * args.scale))
    plant = do.plants("pd")[0]
    factors: dict[str, list[float]] = {"one shape": [], "shape-aware + EncoderLoop": []}
    for seed in range(3):
        times, shapes = do.route_schedule(float(t[-1]), np.random.default_rng(seed))
        routes = piecewise_routes(times, shapes)
        sensing = do.shape_sensing(seed + 500)  # the test's shape sensor: its own noise
        none = ts.bench.run(plant, None, t, y_d, routes=routes, noise=encoder())
        a = ts.bench.run(plant, one_shape, t, y_d, routes=routes, noise=encoder())
        b = ts.bench.run(plant, loop, t, y_d, routes=routes, noise=encoder(), shape_sensing=sensing)
        factors["one shape"].append(none.metrics["mse"] / a.metrics["mse"])
        factors["shape-aware + EncoderLoop"].append(none.metrics["mse"] / b.metrics["mse"])
    for name, values in factors.items():
        print(f"{name}: MSE reduction {np.median(values):.1f}x median, {min(values):.1f}x worst")


if __name__ == "__main__":
    main()
