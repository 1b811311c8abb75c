"""09: bench your own compensator, written in Python, on the physics plant.

    python examples/09_user_compensator.py

``ts.bench.run`` takes any object with ``reset()`` and ``step(...)`` (the
:class:`tendonsheath.protocols.StreamingCompensator` protocol); it need not inherit from a
tendonsheath class. ``step_inputs`` names what ``step`` is given before ``dt``: ``"y_d"``
the desired output, ``"y"`` the measured output (NaN in a sensor dropout), ``"q"`` the motor
encoder angle. The same class runs from a scenario file with ``tendonsheath bench`` (a
``[[compare.user]]`` entry naming ``module:Class`` or ``file`` + ``class``). The C++
version of this compensator, benched at C++ speed, is in ``examples/cpp/user_compensator/``.
"""

from __future__ import annotations

import math

import numpy as np

import tendonsheath as ts


class PIFeedforward:
    """u = gain * y_d + kp * e + ki * integral(e), e = y_d - y measured; during a dropout
    (y is NaN) the error counts as zero and the integral holds. The integral is clamped to
    +-``integral_limit`` (anti-windup)."""

    step_inputs = ("y_d", "y")

    def __init__(self, gain: float = 1.0, kp: float = 0.5, ki: float = 5.0, integral_limit=0.2):
        self.gain, self.kp, self.ki = float(gain), float(kp), float(ki)
        self.integral_limit = float(integral_limit)
        self.reset()

    def reset(self) -> None:
        self.integral = 0.0

    def step(self, y_d: float, y: float, dt: float) -> float:
        e = y_d - y if math.isfinite(y) else 0.0
        self.integral = min(max(self.integral + e * dt, -self.integral_limit), self.integral_limit)
        return self.gain * y_d + self.kp * e + self.ki * self.integral

    @property
    def params(self) -> dict:
        return {
            "gain": self.gain,
            "kp": self.kp,
            "ki": self.ki,
            "integral_limit": self.integral_limit,
        }


def main() -> None:
    route = ts.Route.arcs([(0.5, 0.0), (0.5, np.pi / 2), (0.5, np.pi / 2)])
    plant = ts.PullPullPlant(
        route,
        friction=0.1,
        stiffness=5e3,
        pretension=20.0,
        proximal_radius=15e-3,
        distal_radius=15e-3,
        elements=40,
        motor=ts.Motor.position(60.0, 0.8),
    )
    encoder = ts.Sensor(resolution=1e-4, noise_std=2e-4, seed=1)
    t = np.arange(0.0, 8.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.25 * t) + 0.2 * np.sin(2 * np.pi * 0.6 * t)

    plain = ts.bench.run(plant, None, t, y_d, noise=encoder)
    mine = ts.bench.run(plant, PIFeedforward(), t, y_d, noise=encoder, dropout=[(4.0, 4.2)])
    print(f"uncompensated : rmse {plain.metrics['rmse']:.4f} rad")
    print(f"PIFeedforward : rmse {mine.metrics['rmse']:.4f} rad (a 0.2 s sensor dropout at 4 s)")


if __name__ == "__main__":
    main()
