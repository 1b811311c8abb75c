"""A light stand-in study that exercises the sweep engine in the tests (not shipped).

It is not an honest comparison of compensators: they are tuned from the nominal plant's own
parameters, not identified from calibration logs. The package's robustness study is the
do2015 bench scenario (``tendonsheath.bench.scenarios.do:robustness_run``).

:func:`compensator_study` builds a pull-pull plant with the drawn friction, pretension,
stiffness and route, drives it with a sine three ways (uncompensated, curve-angle
feedforward and backlash-inverse feedforward, both tuned for the *nominal* parameters, as
a lab would tune them once) and returns the tracking error of each. It is a top-level
function, so it pickles to process pools and Dask workers.
"""

from __future__ import annotations

import math

import numpy as np

from tendonsheath.bench.metrics import tracking_metrics
from tendonsheath.bench.scenarios.routes import random_arcs
from tendonsheath.compensate import CurveAngleFeedforward, InverseFeedforward
from tendonsheath.models import Backlash
from tendonsheath.plant import PullPullPlant
from tendonsheath.plant.loads import ConstantTorque
from tendonsheath.plant.route import Route

#: Nominal values the compensators are tuned for (SI, rad).
NOMINAL = {
    "friction": 0.1,
    "pretension": 10.0,
    "stiffness": 2.4e4,
    "route_angle": math.pi,
    "route_pieces": 1,
    "route_seed": 0,
    "length": 1.2,
    "amplitude": 0.5,
    "frequency": 0.3,
    "load": 0.0,
    "samples": 500,
    "elements": 100,
}
RADIUS = 5e-3


def _commands(
    p: dict, t: np.ndarray, y_d: np.ndarray, measured_angle: float
) -> dict[str, np.ndarray]:
    """Motor commands of each compensator, tuned for the nominal parameters ``p``; the
    curve-angle feedforward is also told the route's measured total angle (shape sensing)."""
    nominal_route = Route.uniform(p["length"], p["route_angle"])
    curve = CurveAngleFeedforward(
        friction=p["friction"],
        stiffness=p["stiffness"],
        length=p["length"],
        pretension=p["pretension"],
        load_force=p["load"],
        proximal_radius=RADIUS,
        distal_radius=RADIUS,
        curve_angle=measured_angle,
        smoothing=0.03 * p["amplitude"] * 2 * math.pi * p["frequency"],
    )
    # backlash calibrated on the nominal plant: half the dead zone, as an angle
    calib = PullPullPlant(
        route=nominal_route,
        friction=p["friction"],
        stiffness=p["stiffness"],
        pretension=p["pretension"],
        elements=int(p["elements"]),
    )
    half = 0.5 * calib.closed_form()["dead_zone"] / RADIUS
    inverse = InverseFeedforward(
        Backlash(c_r=1.0, c_l=1.0, B_r=half, B_l=half),
        smoothing=0.03 * p["amplitude"] * 2 * math.pi * p["frequency"],
    )
    return {
        "none": y_d.copy(),
        "curve_angle": curve.command(t, y_d),
        "inverse_backlash": inverse.command(t, y_d),
    }


def compensator_study(params: dict) -> dict[str, dict[str, float]]:
    """MSE, RMSE, max |error| and % error (rad) of each compensator on the drawn plant.

    ``params`` may set any name in :data:`NOMINAL`; missing ones take the nominal value.
    The compensators always see the nominal values: this is a robustness study.
    """
    p = {**NOMINAL, **params}
    n = int(p["samples"])
    t = np.linspace(0.0, 2.0 / p["frequency"], n)
    y_d = p["amplitude"] * np.sin(2 * math.pi * p["frequency"] * t)
    route = random_arcs(p["length"], p["route_angle"], p["route_pieces"], p["route_seed"])
    shared = {k: p[k] for k in ("amplitude", "frequency", "elements", "length")}
    commands = _commands(NOMINAL | shared, t, y_d, route.curve_angle)
    plant = PullPullPlant(
        route=route,
        friction=float(p["friction"]),
        stiffness=float(p["stiffness"]),
        pretension=float(p["pretension"]),
        proximal_radius=RADIUS,
        distal_radius=RADIUS,
        elements=int(p["elements"]),
        load=ConstantTorque(float(p["load"]) * RADIUS) if p["load"] else None,
    )
    return {name: _metrics(y_d, plant.simulate(t, u)) for name, u in commands.items()}


def _metrics(y_d: np.ndarray, y: np.ndarray) -> dict[str, float]:
    """The bench's tracking metrics that a sweep table ranks."""
    m = tracking_metrics(y_d, y)
    return {k: m[k] for k in ("mse", "rmse", "max_abs", "percent_error")}


compensator_study.parameters = tuple(NOMINAL)


def tracking_mse(params: dict) -> dict[str, float]:
    """The uncompensated sine's metrics only (one row per run, no compensator column)."""
    return compensator_study(params)["none"]


tracking_mse.parameters = tuple(NOMINAL)
