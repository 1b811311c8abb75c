"""do2015 with a tip sensor: controllers designed from calibration logs, at 0, 1 and 5 ms of
latency.

Do et al. close their adaptive controller on a distal encoder. Here both tip-feedback
controllers are designed from what calibration runs on the three calibration shapes identify,
never from a test route:

* the loop's dynamics (servo, distal resonance, sensor delay) from a chirp on a fast ramp per
  shape, logged through the tip sensor of each latency (:func:`~tendonsheath.bench.calibrate_loop`);
* ``TipLoop``: the shape-aware inverse feedforward (fitted from the command) inside a PI(D) on
  the tip, robust MIGO over the shapes' identified loops, the sensitivity bound and the
  dead-band scale chosen by trial runs on the calibration shapes (switching among them every
  2.5 s, the calibration excitation as the reference), then refined by trials under a
  robustness test (:meth:`~tendonsheath.compensate.TipLoop.from_calibration`);
* ``AdaptiveController``: its derivative filter at the identified resonance and its bandwidth
  chosen by the same trials on the torque-driven joint, within what the resonance and the
  delay allow (:meth:`~tendonsheath.compensate.AdaptiveController.from_calibration`); the
  motor's inertia and damping identified from a torque chirp
  (:func:`~tendonsheath.bench.motor_calibration.calibrate_torque_motor`), not declared.

Every trial is scored on the tip sensor's reading (:mod:`tendonsheath.bench.trial`).

Each is then judged on the fixed route and on the random route schedules of the feedforwards'
study, against the same uncompensated runs.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...compensate import AdaptiveController, TipLoop
from ...plant.sensor import Sensor
from ..loop_calibration import calibrate_loop
from ..motor_calibration import calibrate_torque_motor
from ..run import run
from ..trial import calibration_trial
from .common import piecewise_routes, ratio, runs_seen
from .seeds import spread

#: the tip sensor's latencies every tip-feedback figure is given at (s)
LATENCIES = (0.0, 1e-3, 5e-3)
#: the tip sensor: a distal encoder (the scenario's), with a latency
TIP_NOISE_STD, TIP_RESOLUTION = 2e-4, 1e-4
TIP_CONTROLLERS = ("TipLoop", "AdaptiveController")
#: the candidates the trials choose among
SENSITIVITY_BOUNDS = (1.7, 2.0)
DEAD_BAND_SCALES = (0.9, 0.8, 0.7)


def tip_sensor(latency: float, seed: int) -> Sensor:
    """The tip sensor at one latency."""
    return Sensor(noise_std=TIP_NOISE_STD, resolution=TIP_RESOLUTION, delay=latency, seed=seed)


def design(do: Any, fits: dict, latency: float, seed: int, scale: float) -> dict[str, Any]:
    """Both tip-feedback controllers for one latency, from calibration runs only."""
    servo_plant, torque_plant = do.plants("pid")
    sensor = tip_sensor(latency, seed + 41)
    routes_of = list(do.CALIBRATION_ROUTES)
    loops = [
        calibrate_loop(servo_plant, route, sensor, seed=seed + 601 + i)
        for i, route in enumerate(routes_of)
    ]
    dynamics = [loop.dynamics for loop in loops]
    shape_fit = fits["shape command"]
    angles = [r.sensed_angle for r in shape_fit.runs[: len(routes_of)]]
    duration = max(6.0, 20.0 * scale)
    sensing = do.shape_sensing(seed + 900)
    tip = TipLoop.from_calibration(
        shape_fit.backlash_model,
        dynamics,
        curve_angles=angles,
        max_sensitivity=SENSITIVITY_BOUNDS,
        dead_band_scale=DEAD_BAND_SCALES,
        trial=calibration_trial(
            servo_plant, routes_of, sensor, duration=duration, shape_sensing=sensing
        ),  # fmt: skip
        refine=True,
        feedforward_options={"smoothing": do.SMOOTHING},
    )
    motor = calibrate_torque_motor(torque_plant, routes_of[0])
    adaptive = AdaptiveController.from_calibration(
        fits["single encoder"].backlash_model,
        dynamics,
        inertia=motor.inertia,
        viscous=motor.viscous,
        max_torque=5.0,
        noise_std=TIP_NOISE_STD,
        trial=calibration_trial(torque_plant, routes_of, sensor, duration=duration),
    )
    return {"TipLoop": tip, "AdaptiveController": adaptive, "sensor": sensor, "loops": loops,
            "torque_motor": motor}  # fmt: skip


def study(do: Any, fits: dict, t, y_d, seeds, baseline: dict, seed: int, scale: float):
    """latency (ms) -> the designs and every run: the fixed route and each seed's schedule.

    ``baseline``: the uncompensated runs of the servo study ({"fixed": Result, "random":
    {seed: Result}}), the reference every factor is over."""
    servo_plant, torque_plant = do.plants("pid")
    out: dict[float, dict[str, Any]] = {}
    for latency in LATENCIES:
        made = design(do, fits, latency, seed, scale)
        sensor = made["sensor"]
        runs: dict[str, Any] = {"fixed": {}, "random": {s: {} for s in seeds}}
        for name in TIP_CONTROLLERS:
            ctrl = made[name]
            plant = servo_plant if name == "TipLoop" else torque_plant
            sensing = name == "TipLoop"
            runs["fixed"][name] = run(plant, ctrl, t, y_d, noise=sensor,
                                      shape_sensing=do.shape_sensing(seeds[0] + 500)
                                      if sensing else None)  # fmt: skip
            for s in seeds:
                times, shapes = do.route_schedule(float(t[-1]) + 1e-3, np.random.default_rng(s))
                runs["random"][s][name] = run(
                    plant, ctrl, t, y_d, routes=piecewise_routes(times, shapes), noise=sensor,
                    shape_sensing=do.shape_sensing(s + 500) if sensing else None,
                )  # fmt: skip
        out[1e3 * latency] = {"designs": made, "runs": runs, "summary": summary(runs, baseline)}
    return out


def summary(runs: dict, baseline: dict) -> dict[str, Any]:
    """controller -> fixed-route factor, the random-route factors' spread, saturated cycles,
    the runs with a limit cycle and what the runs show besides their error."""
    base_fixed = baseline["fixed"].metrics["mse"]
    out = {}
    for name in runs["fixed"]:
        fixed = runs["fixed"][name]
        by_seed = [
            ratio(baseline["random"][s].metrics["mse"], r[name].metrics["mse"])
            for s, r in runs["random"].items()
        ]
        every = [fixed] + [r[name] for r in runs["random"].values()]
        out[name] = {
            "mse_fixed": fixed.metrics["mse"],
            "factor_fixed": ratio(base_fixed, fixed.metrics["mse"]),
            "factor_random": spread(by_seed),
            **runs_seen(every),
        }
    return out


def as_record(tip: dict[float, dict[str, Any]]) -> dict[str, Any]:
    """The study as JSON-ready data: per latency, each controller's figures and its design
    (the resonance and delay it was designed from)."""
    return {
        f"{ms:g} ms": {
            name: {
                **tip[ms]["summary"][name],
                "design": tip[ms]["designs"][name].design.as_dict(),
                "designed_from": tip[ms]["designs"][name].design.summary(),
            }
            for name in TIP_CONTROLLERS
        }
        for ms in tip
    }


def targets(tip: dict[float, dict[str, Any]], target) -> list[dict]:
    """The claims the bench checks for tip feedback: the better tip-feedback controller's
    median >= 500x and minimum >= 190x at 1 ms, median >= 100x at 5 ms; each controller's own
    line beside it. A controller with a limit cycle in any of its runs meets no claim, whatever
    its figure; its limit cycles and saturated cycles are named beside the verdict."""
    out = []
    for ms, need_median, need_min in ((1.0, 500.0, 190.0), (5.0, 100.0, None)):
        s = tip[ms]["summary"]
        for name in TIP_CONTROLLERS:
            f, steady = s[name]["factor_random"], not s[name].get("limit_cycle", False)
            seen = s[name].get("seen", "")
            tag = f"{name} (tip sensor, {ms:g} ms latency) MSE reduction, random routes"
            paper = " (paper 190x)" if name == "AdaptiveController" else ""
            claim = f">= {need_median:g}x{paper}, no limit cycle"
            out.append(target(f"{tag}, median of {f['seeds']} seeds", claim, f["median"],
                              steady and f["median"] >= need_median, "x", seen))  # fmt: skip
            if need_min is not None:
                claim = f">= {need_min:g}x, no limit cycle"
                out.append(target(f"{tag}, worst seed", claim, f["min"],
                                  steady and f["min"] >= need_min, "x", seen))  # fmt: skip
    return out


__all__ = ["LATENCIES", "TIP_CONTROLLERS", "as_record", "design", "study", "targets", "tip_sensor"]
