"""Do, Tjahjowidodo, Lau & Phee, Mechatronics 2015 (seed 002), in simulation."""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from ... import presets
from ...compensate import AdaptiveController, InverseFeedforward
from ...motor import Motor
from ...plant import PullPullPlant
from ...route import Route
from ..calibration import calibrate as bench_calibrate
from ..run import run
from .common import (
    ScenarioResult,
    announce,
    calibrated,
    encoder,
    honesty_panel,
    kinematic_told,
    piecewise_routes,
    ratio,
    scenario_result,
    target,
)

PAPER_MSE = {"none": 0.0158, "InverseFeedforward": 0.0012, "AdaptiveController": 8.2815e-5}

CONDITIONS = {
    "plant": "pull-pull pair, two 1.5 m sheaths, EA = 5000 N, T0 = 20 N, mu = 0.1, "
    "pulleys r_p = r_d = 15 mm, 40 elements per sheath, no distal load; realistic preset "
    "(tendonsheath.presets): distal inertia and damping, sheath viscosity, tendon creep, "
    "sheath 2 friction +15 %, tendon 2 EA -10 %",
    "nominal route": "straight 0.5 m, then two 0.5 m arcs of pi/2 each (Theta = pi)",
    "route changes": "at random times (mean 4 s apart) the sheaths take random 2-4 arc "
    "shapes with Theta between pi/2 and 2 pi",
    "reference": "1 rad sine at 0.25 Hz plus 0.3 rad at 0.6 Hz (distal angle)",
    "motors": "position servo (60 Hz, damping 0.8) for none and the feedforward; torque "
    "motor J = 0.01 kg m^2, b = 0.2 N m s, |tau| <= 5 N m for the adaptive controller; both "
    "with the realistic preset's Coulomb friction and 0.5 deg gear backlash (the encoder "
    "reads the motor shaft)",
    "sensor": "distal encoder, 1e-4 rad resolution, 2e-4 rad noise",
    "calibration": "bench.calibrate: BoucWenBacklash identified from a 20 s run on a "
    "calibration route (0.3 m straight, arcs of 0.55 pi and 0.35 pi) that no test run uses, "
    "from the motor encoder and the noisy distal encoder; the adaptive controller starts "
    "from it and the torque motor's datasheet J, b and torque limit (declared by the user)",
    "test routes": "the headline: the nominal route, then random route changes; the fixed-route "
    "column: the nominal route throughout (neither is the calibration route)",
    "rate": "1 kHz; first period excluded from the metrics",
}

_COMMON: dict[str, Any] = dict(
    friction=0.1,
    stiffness=5e3,
    pretension=20.0,
    proximal_radius=15e-3,
    distal_radius=15e-3,
    elements=40,
)
NOMINAL = Route.arcs([(0.5, 0.0), (0.5, math.pi / 2), (0.5, math.pi / 2)])
# the calibration shape: same sheath length, a shape none of the test runs takes
CALIBRATION_ROUTE = Route.arcs([(0.3, 0.0), (0.7, 0.55 * math.pi), (0.5, 0.35 * math.pi)])
INERTIA, VISCOUS = 0.01, 0.2


def random_route(rng: np.random.Generator, length: float = 1.5) -> Route:
    """2-4 arcs of random lengths summing to `length`, total angle in [pi/2, 2 pi]."""
    k = int(rng.integers(2, 5))
    lengths = rng.dirichlet(np.ones(k)) * length
    total = rng.uniform(math.pi / 2, 2 * math.pi)
    angles = rng.dirichlet(np.ones(k)) * total
    return Route.arcs(list(zip(lengths, angles, strict=True)))


def route_schedule(duration: float, rng: np.random.Generator):
    times, routes = [0.0], [NOMINAL]
    while True:
        nxt = times[-1] + rng.exponential(4.0) + 0.5
        if nxt >= duration:
            break
        times.append(nxt)
        routes.append(random_route(rng))
    return times, routes


def reference(duration: float, rate: float = 1000.0):
    t = np.arange(0.0, duration, 1.0 / rate)
    return t, 1.0 * np.sin(2 * np.pi * 0.25 * t) + 0.3 * np.sin(2 * np.pi * 0.6 * t)


def physics(**changes) -> dict[str, Any]:
    """The plant's keyword arguments: _COMMON with the realistic preset's effects (distal
    dynamics, sheath viscosity, creep, an unequal pair); ``changes`` replace _COMMON values."""
    base = {**_COMMON, **changes}
    return {
        **{k: v for k, v in base.items() if k not in ("friction", "stiffness")},
        **presets.realistic_plant(friction=base["friction"], stiffness=base["stiffness"]),
    }


def servo_motor() -> Motor:
    return presets.realistic_motor(bandwidth_hz=60.0, damping=0.8)


def torque_motor() -> Motor:
    return presets.realistic_motor("torque", inertia=INERTIA, viscous=VISCOUS, max_torque=5.0)


def plants():
    servo = PullPullPlant(route=NOMINAL, motor=servo_motor(), **physics())
    torque = PullPullPlant(route=NOMINAL, motor=torque_motor(), **physics())
    return servo, torque


def calibrate(seed: int = 0, budget: dict | None = None):
    """The calibration protocol (bench.calibrate) on the servo-driven robot: a
    BoucWenBacklash from a 20 s run on CALIBRATION_ROUTE, from its logs alone."""
    servo = plants()[0]
    return bench_calibrate(
        servo,
        [CALIBRATION_ROUTE],
        models_=("BoucWenBacklash",),
        duration=20.0,
        amplitude=1.3,
        warmup=2.0,
        sensor=encoder(seed=seed + 11),
        seed=seed,
        budget=budget,
        names=["calibration route, 20 s"],
    )


def motor_datasheet(sensor) -> dict[str, tuple[float, str]]:
    """What the adaptive controller is told besides the identified model: declared values."""
    return {
        "motor inertia J": (INERTIA, "declared by the user (torque motor datasheet)"),
        "motor viscous b": (VISCOUS, "declared by the user (torque motor datasheet)"),
        "max torque": (5.0, "declared by the user (torque motor datasheet)"),
        "sensor noise std": (sensor.noise_std, "declared by the user (encoder datasheet)"),
    }


def do2015(scale: float = 1.0, seed: int = 0, progress=None) -> ScenarioResult:
    """Pair of tendon-sheaths driving a distal rotary joint, on its calibration route and
    with the route changing at random.

    Compares no compensation, the direct inverse feedforward of an identified
    BoucWenBacklash (spec D.2) and the adaptive controller (spec D.3) by MSE (rad^2), beside
    the paper's 0.0158 / 0.0012 / 8.28e-5. The headline runs (metrics.json) are those with
    the random route changes; the fixed-route runs are in the table and in details.
    ``scale`` shortens the run (tests).
    """
    rng = np.random.default_rng(seed)
    duration = max(8.0, 40.0 * scale)
    t, y_d = reference(duration)
    times, shapes = route_schedule(duration, rng)
    routes = piecewise_routes(times, shapes)
    servo, torque = plants()
    cal, budget = calibrated("do2015", calibrate, scale, seed, progress)
    sensor = encoder(seed=seed + 3)
    announce(progress, "do2015: closed-loop runs")
    adaptive = _adaptive_controller(cal.backlash_model, sensor)
    ff = cal.inverse_feedforward(smoothing=0.03)
    runs = _compare(servo, torque, ff, adaptive, t, y_d, sensor, routes)  # the headline
    fixed = _compare(servo, torque, ff, adaptive, t, y_d, sensor)  # the nominal route
    announce(progress, "do2015: honesty panel")
    honesty = honesty_panel(
        cal,
        runs,
        told={"none": kinematic_told(servo), "AdaptiveController": motor_datasheet(sensor)},
        seed=seed,
        budget=budget,
    )
    fit = cal.fits["BoucWenBacklash"]
    return scenario_result(
        do2015,
        cal,
        targets=_targets(runs),
        title="Do et al. 2015: feedforward and adaptive control under changing routes",
        conditions=CONDITIONS,
        runs=runs,
        table=_table(runs, fixed),
        paper={"mse_rad2": PAPER_MSE},
        routes={f"t = {tk:.1f} s": r for tk, r in zip(times, shapes, strict=True)},
        route_schedule=[(tk, r.curve_angle) for tk, r in zip(times, shapes, strict=True)],
        extra={"fixed_route": {k: r.metrics for k, r in fixed.items()}},
        calibration={**cal.to_dict(), "rmse": fit.rmse, "nrmse": fit.nrmse, "seconds": fit.seconds},
        protocol="do2015: a BoucWenBacklash identified by bench.calibrate from a 20 s run on a "
        "calibration route that no test run takes (motor encoder in, noisy distal encoder "
        "out); the headline is the run with random route changes; the adaptive controller is "
        "also told the torque motor's datasheet values (declared by the user).",
        honesty=honesty,
    )


def _adaptive_controller(model, sensor) -> AdaptiveController:
    """The adaptive controller started from ``model`` and the torque motor's datasheet."""
    return AdaptiveController.from_model(
        model,
        inertia=INERTIA,
        viscous=VISCOUS,
        bandwidth_hz=8.0,
        max_torque=5.0,
        noise_std=sensor.noise_std,
    )


def _compare(servo, torque, ff, adaptive, t, y_d, sensor, routes=None) -> dict:
    """No compensation and the feedforward on the servo-driven plant, the adaptive
    controller on the torque-driven one, all under the route schedule ``routes``."""
    return {
        "none": run(servo, None, t, y_d, routes=routes, noise=sensor),
        "InverseFeedforward": run(servo, ff, t, y_d, routes=routes, noise=sensor),
        "AdaptiveController": run(torque, adaptive, t, y_d, routes=routes, noise=sensor),
    }


def _table(runs: dict, fixed: dict) -> list[dict]:
    """MSE and its reduction per compensator, on the fixed and the random routes, beside
    the paper's."""
    base, fixed_base = runs["none"].metrics["mse"], fixed["none"].metrics["mse"]
    return [
        {
            "compensator": name,
            "mse, fixed route": fixed[name].metrics["mse"],
            "improvement, fixed route": ratio(fixed_base, fixed[name].metrics["mse"]),
            "mse, random routes": result.metrics["mse"],
            "improvement, random routes": ratio(base, result.metrics["mse"]),
            "paper_mse": PAPER_MSE[name],
            "paper_improvement": ratio(PAPER_MSE["none"], PAPER_MSE[name]),
        }
        for name, result in runs.items()
    ]


def _targets(runs: dict) -> list[dict]:
    """The paper's MSE reductions under random route changes, checked."""
    base = runs["none"].metrics["mse"]
    factor = {k: ratio(base, r.metrics["mse"]) for k, r in runs.items()}
    return [
        target(
            f"{name} MSE reduction, random route changes",
            f">= {least}x",
            factor[name],
            factor[name] >= least,
            "x",
        )
        for name, least in (("InverseFeedforward", 13), ("AdaptiveController", 190))
    ]


# -- robustness: the do2015 comparison over perturbed plants (ts.sweep run function) --------

_NOMINAL_FIT: dict[int, object] = {}


def _nominal_model(seed: int = 0):
    """The BoucWenBacklash calibrated once per process on the nominal plant (in a sweep's
    worker: its identifiability warnings repeat the do2015 calibration's, reported there)."""
    if seed not in _NOMINAL_FIT:
        from ...identify.diagnostics import IdentifiabilityWarning

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", IdentifiabilityWarning)
            cal = calibrate(seed, {"maxiter": 40, "popsize": 10})
        _NOMINAL_FIT[seed] = cal.backlash_model
    return _NOMINAL_FIT[seed]


def robustness_run(params: dict) -> dict[str, dict[str, float]]:
    """One draw of the robustness study: the plant's friction, pretension and route differ
    from the nominal plant the compensators were calibrated on; 10 s of the do2015 reference
    on a fixed (random-arc) route. Returns compensator -> metrics (a ``ts.sweep`` run)."""
    from .routes import random_arcs

    kwargs = physics(
        friction=float(params.get("friction", _COMMON["friction"])),
        pretension=float(params.get("pretension", _COMMON["pretension"])),
    )
    route = random_arcs(
        NOMINAL.length,
        float(params.get("route_angle", NOMINAL.curve_angle)),
        int(params.get("route_pieces", 3)),
        int(params.get("route_seed", 0)),
    )
    model = _nominal_model()
    t, y_d = reference(10.0)
    servo = PullPullPlant(route=route, motor=servo_motor(), **kwargs)
    torque = PullPullPlant(route=route, motor=torque_motor(), **kwargs)
    sensor = encoder(seed=int(params.get("route_seed", 0)) % 100_000)
    ff = InverseFeedforward(model, smoothing=0.03)
    runs = _compare(servo, torque, ff, _adaptive_controller(model, sensor), t, y_d, sensor)
    return {
        name: {k: r.metrics[k] for k in ("mse", "rmse", "max_abs", "percent_error")}
        for name, r in runs.items()
    }


# the sweep reads a run's parameter names from this attribute (a function's own attribute)
robustness_run.parameters = (  # type: ignore[attr-defined]
    "friction",
    "pretension",
    "route_angle",
    "route_pieces",
    "route_seed",
)
