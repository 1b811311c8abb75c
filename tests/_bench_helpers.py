"""The closed-loop bench setup shared by the protocol and user-compensator tests: a pull-pull
pair with a dynamic distal joint, and a two-tone reference."""

from __future__ import annotations

import numpy as np

import tendonsheath as ts

T = np.arange(0.0, 4.0, 1e-3)
Y_D = 0.8 * np.sin(2 * np.pi * 0.5 * T) + 0.1 * np.sin(2 * np.pi * 1.7 * T)


def bench_plant(motor=None):
    """The pair driven by ``motor`` (default a 60 Hz position servo)."""
    route = ts.Route.arcs([(0.5, 0.0), (0.6, 2.0)])
    return ts.PullPullPlant(
        route,
        friction=0.1,
        stiffness=5e3,
        pretension=20.0,
        proximal_radius=0.015,
        distal_radius=0.015,
        elements=30,
        motor=ts.Motor.position(60.0, 0.8) if motor is None else motor,
        distal_inertia=2e-5,
        distal_damping=2e-3,
    )
