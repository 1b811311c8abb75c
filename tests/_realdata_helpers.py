"""Small logs generated with the project's own plant (never the shared real data)."""

from __future__ import annotations

import numpy as np

import tendonsheath as ts


def plant_log(n: int = 400, periods: float = 2.0, amplitude: float = 0.8, saturate: bool = True):
    """(t, x, y): a pull-pull plant (capstan friction, elongation) driven by a sine; with
    ``saturate`` its output goes through an asymmetric saturating sensor map."""
    t = np.linspace(0.0, 2.0 * periods, n)
    x = amplitude * np.sin(2 * np.pi * 0.5 * t)
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(length=1.2, curve_angle=2 * np.pi),
        friction=0.15,
        stiffness=2.0e4,
        pretension=10.0,
        elements=40,
    )
    y = np.asarray(plant.simulate(t, x))
    if saturate:
        y = 0.5 * np.tanh(1.8 * y) + 0.08 * y**2
    return t, x, y
