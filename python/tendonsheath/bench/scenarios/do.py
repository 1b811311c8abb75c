"""Do, Tjahjowidodo, Lau & Phee, Mechatronics 2015, in simulation."""

from __future__ import annotations

import math
import sys
import warnings
from typing import Any

import numpy as np

from ...compensate import AdaptiveController
from ...plant import PullPullPlant, presets
from ...plant.motor import Motor
from ...plant.route import Route
from ..calibration import calibrate as bench_calibrate
from ..run import Result, run
from ..shape_sensing import ShapeSensing
from . import do_ilc, do_tip
from .common import (
    ScenarioResult,
    announce,
    encoder,
    honesty_panel,
    identification_budget,
    kinematic_told,
    piecewise_routes,
    ratio,
    runs_seen,
    scenario_result,
    target,
)
from .seeds import ROUTE_SEEDS, factors, spread

PAPER_MSE = {"none": 0.0158, "InverseFeedforward": 0.0012, "AdaptiveController": 8.2815e-5}

CONDITIONS = {
    "plant": "pull-pull pair, two 1.5 m sheaths, EA = 5000 N, T0 = 20 N, mu = 0.1, "
    "pulleys r_p = r_d = 15 mm, 40 elements per sheath, no distal load; realistic preset "
    "(tendonsheath.plant.presets): distal inertia and damping, sheath viscosity, tendon creep, "
    "sheath 2 friction +15 %, tendon 2 EA -10 %",
    "nominal route": "straight 0.5 m, then two 0.5 m arcs of pi/2 each (Theta = pi)",
    "route changes": "at random times (mean 4 s apart) the sheaths take random 2-4 arc "
    "shapes with Theta between pi/2 and 2 pi; every random-route figure is the median and the "
    "minimum over 5 route-schedule seeds",
    "reference": "1 rad sine at 0.25 Hz plus 0.3 rad at 0.6 Hz (distal angle)",
    "motors": "position servo (60 Hz, damping 0.8) for the feedforwards, run twice: a PID servo "
    "(integral action, the preset's default: servo amplifiers cascade a PI velocity loop) and a "
    "PD servo that yields to the tendons' torque; torque motor J = 0.01 kg m^2, b = 0.2 N m s, "
    "|tau| <= 5 N m for the adaptive controller; all with the realistic preset's Coulomb "
    "friction and 0.5 deg gear backlash (the encoder reads the motor shaft)",
    "sensor": "distal encoder, 1e-4 rad resolution, 2e-4 rad noise; the feedforwards use no tip "
    "sensor; the tip-feedback controllers (TipLoop around the PID servo, AdaptiveController on "
    "the torque motor) read it with 0, 1 and 5 ms of latency, each latency designed and judged "
    "on its own (the main table: 1 ms)",
    "shape sensing": "the curvature profile in 10 arcs, 0.05 rad noise on the total angle, "
    "0.1 s delay, 10 Hz readings (calibration and test runs alike)",
    "calibration": "bench.calibrate on three calibration shapes that no test run takes "
    "(Theta = 0.9 pi, 0.55 pi, 1.8 pi), 20 s each: command, motor encoder, noisy distal "
    "encoder and sensed profile logged; a BoucWenBacklash from the first shape (the paper's "
    "one configuration) and an AngleDependent BoucWenBacklash whose dead band follows the "
    "sensed shape (B = p0 + p1 F(g, G, mu Theta), spec A5/A6) from all three; each fitted from "
    "the command (a feedforward drives the servo) and from the encoder (inside an "
    "EncoderLoop); a 10 s motor calibration run (chirp on a ramp) identifies the servo the "
    "EncoderLoop is tuned on (MIGO, peak sensitivity <= 1.7); for the tip-feedback controllers, "
    "a 5 s chirp on a fast ramp per calibration shape through the tip sensor identifies the "
    "loop's dynamics (servo, distal resonance, sensor delay) and trial runs on the calibration "
    "shapes (switching every 2.5 s, the calibration excitation as reference), scored on the "
    "tip sensor's reading, choose among the designs; a 6 s torque chirp identifies the torque "
    "motor's inertia and damping for the adaptive controller",
    "test routes": "fixed route: the nominal route throughout (the paper's setting); random "
    "routes: the nominal route, then random route changes; neither is a calibration shape",
    "iterative learning": "the paper's reference repeated on the fixed route: the "
    "InverseFeedforward of the first calibration shape plus a correction table learned over at "
    "most 10 trials from the tip sensor (1 ms latency, noise drawn anew each trial), the law "
    "designed from the loop dynamics identified on the first calibration shape; the learned "
    "table then run without the sensor, and on a shifted route (both arcs at 0.7 pi)",
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
# the calibration shapes: same sheath length, shapes none of the test runs takes
CALIBRATION_ROUTE = Route.arcs([(0.3, 0.0), (0.7, 0.55 * math.pi), (0.5, 0.35 * math.pi)])
CALIBRATION_ROUTES = (
    CALIBRATION_ROUTE,
    Route.arcs([(0.4, 0.0), (0.6, 0.2 * math.pi), (0.5, 0.35 * math.pi)]),
    Route.arcs([(0.5, 0.9 * math.pi), (0.5, 0.3 * math.pi), (0.5, 0.6 * math.pi)]),
)
INERTIA, VISCOUS = 0.01, 0.2
SERVOS = ("pid", "pd")  # the preset's default (on provenance) first
SENSING: dict[str, Any] = {"noise_std": 0.05, "delay": 0.1, "rate_hz": 10.0, "segments": 10}
SHAPE_LAWS = {"B_r": "tanh", "B_l": "tanh"}
SMOOTHING = 0.03
FEEDFORWARDS = (
    "InverseFeedforward",
    "InverseFeedforward + EncoderLoop",
    "shape-aware InverseFeedforward",
    "shape-aware InverseFeedforward + EncoderLoop",
)
# the no-tip-sensor compensator judged, on either servo: chosen before any test run (the loop
# is harmless on a servo that holds its command and needed on one that yields)
HEADLINE = "shape-aware InverseFeedforward + EncoderLoop"
# the tip sensor's latency of the tip-feedback rows in the main table (ms); every latency is in
# the tip-sensor table
TIP_HEADLINE_MS = 1.0


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


def servo_motor(servo: str = "pid") -> Motor:
    return presets.realistic_motor(bandwidth_hz=60.0, damping=0.8, servo=servo)


def torque_motor() -> Motor:
    return presets.realistic_motor("torque", inertia=INERTIA, viscous=VISCOUS, max_torque=5.0)


def plants(servo: str = "pid"):
    servo_plant = PullPullPlant(route=NOMINAL, motor=servo_motor(servo), **physics())
    torque = PullPullPlant(route=NOMINAL, motor=torque_motor(), **physics())
    return servo_plant, torque


def shape_sensing(seed: int) -> ShapeSensing:
    """The shape sensor of the scenario (the curvature profile, with noise and delay)."""
    return ShapeSensing(**SENSING, seed=seed)


def calibrate(seed: int = 0, budget: dict | None = None, servo: str = "pid"):
    """The calibration protocol (bench.calibrate) on the servo-driven robot: three
    calibration shapes of 20 s (command, encoder, distal encoder and sensed profile logged),
    the BoucWenBacklash of the first fitted from the command, and a motor calibration run."""
    return bench_calibrate(
        plants(servo)[0],
        list(CALIBRATION_ROUTES),
        models_=("BoucWenBacklash",),
        duration=20.0,
        amplitude=1.3,
        warmup=2.0,
        sensor=encoder(seed=seed + 11),
        shape=shape_sensing(seed),
        seed=seed,
        budget=budget,
        names=["calibration shape 1 (0.9 pi), 20 s", "shape 2 (0.55 pi)", "shape 3 (1.8 pi)"],
        servo=True,
    )


def calibrations(cal) -> dict[str, Any]:
    """The four fits the feedforwards use, from the same calibration runs: one shape or all
    three (shape-aware), from the command or from the encoder."""
    shape = cal.refit(depends_on_angle=SHAPE_LAWS)
    return {
        "single command": cal,
        "single encoder": cal.refit("encoder"),
        "shape command": shape,
        "shape encoder": shape.refit("encoder"),
    }


def feedforwards(fits: dict[str, Any]) -> dict[str, Any]:
    """The no-tip-sensor compensators, each from the fit of the signal it outputs."""
    single, shape = fits["single encoder"], fits["shape encoder"]
    return {
        "InverseFeedforward": fits["single command"].inverse_feedforward(smoothing=SMOOTHING),
        "InverseFeedforward + EncoderLoop": single.encoder_loop(
            single.inverse_feedforward(smoothing=SMOOTHING)
        ),
        "shape-aware InverseFeedforward": fits["shape command"].inverse_feedforward(
            smoothing=SMOOTHING
        ),
        "shape-aware InverseFeedforward + EncoderLoop": shape.encoder_loop(
            shape.inverse_feedforward(smoothing=SMOOTHING)
        ),
    }


def motor_datasheet(sensor, motor=None) -> dict[str, tuple[float, str]]:
    """What the adaptive controller is told besides the identified model: the motor's inertia
    and damping identified from a torque chirp (``motor``, a TorqueMotorCalibration; without
    one, the datasheet's values as declared), the torque limit and the sensor's noise as
    declared."""
    if motor is not None:
        source = "identified from a torque chirp on calibration shape 1"
        inertia, viscous = (motor.inertia, source), (motor.viscous, source)
    else:
        inertia = (INERTIA, "declared by the user (torque motor datasheet)")
        viscous = (VISCOUS, "declared by the user (torque motor datasheet)")
    return {
        "motor inertia J": inertia,
        "motor viscous b": viscous,
        "max torque": (5.0, "declared by the user (torque motor datasheet)"),
        "sensor noise std": (sensor.noise_std, "declared by the user (encoder datasheet)"),
    }


def do2015(scale: float = 1.0, seed: int = 0, progress=None) -> ScenarioResult:
    """Pair of tendon-sheaths driving a distal rotary joint, on a fixed route and with the route
    changing at random, behind a PID servo and a yielding PD servo.

    Compares no compensation, the direct inverse feedforward of an identified BoucWenBacklash
    (spec D.2: from one calibration shape, as the paper; and shape-aware, its dead band
    following the sensed route), each alone and inside a motor-encoder loop, and the adaptive
    controller (spec D.3), by MSE (rad^2), beside the paper's 0.0158 / 0.0012 / 8.28e-5. The
    feedforwards' verdict is on the fixed route (the paper's setting) with the random-route
    column beside it, the median and the minimum over 5 route-schedule seeds. ``scale``
    shortens the runs (tests).
    """
    lead = lead_study(scale, seed, progress)
    others = {servo: servo_study(servo, scale, seed, progress) for servo in SERVOS[1:]}
    return assemble(lead, others, scale, seed)


# do2015 in parts that share nothing but their arguments (the demo runs them in parallel
# processes): lead_study (the PID servo, then the tip sensor and the learning designed on
# it), servo_study of each other servo, and assemble, which only puts their outcomes together


def _setup(scale: float, seed: int):
    """The reference (t, y_d), the route seeds, the identification budget and the sensor."""
    t, y_d = reference(max(8.0, 40.0 * scale))
    seeds = [seed + i for i in range(ROUTE_SEEDS)]
    return t, y_d, seeds, identification_budget(scale), encoder(seed=seed + 3)


def servo_study(servo: str, scale: float = 1.0, seed: int = 0, progress=None) -> dict[str, Any]:
    """One servo's part of do2015: its calibration (the four fits), then every feedforward on
    the fixed route and on each seed's random schedule."""
    t, y_d, seeds, budget, sensor = _setup(scale, seed)
    announce(progress, f"do2015: calibration ({servo} servo)")
    fits = calibrations(calibrate(seed, budget, servo))
    announce(progress, f"do2015: runs ({servo} servo)")
    study = _servo_study(servo, fits, t, y_d, sensor, seeds)
    comps = study.pop("feedforwards")
    design = comps["InverseFeedforward + EncoderLoop"].design.as_dict()
    return {"servo": servo, "fits": fits, "study": study, "encoder_loop_design": design}


def lead_study(scale: float = 1.0, seed: int = 0, progress=None) -> dict[str, Any]:
    """The headline servo's part (:func:`servo_study` of the PID servo), then what is designed
    on it: the tip-sensor controllers, the iterative learning, and the honesty panel of its
    runs. Returns that part with ``tip`` and ``ilc`` (as records and target rows), the tip
    runs at the headline latency and the panel."""
    first = servo_study(SERVOS[0], scale, seed, progress)
    t, y_d, seeds, budget, _ = _setup(scale, seed)
    study = first["study"]
    announce(progress, "do2015: tip sensor (loop calibration, designs, runs at 0, 1, 5 ms)")
    baseline = {"fixed": study["fixed"]["none"],
                "random": {s: r["none"] for s, r in study["random"].items()}}  # fmt: skip
    tip = do_tip.study(sys.modules[__name__], first["fits"], t, y_d, seeds, baseline, seed,
                       scale)  # fmt: skip
    tip_runs = tip[TIP_HEADLINE_MS]["runs"]
    _add_tip(SERVOS[0], study, tip_runs)
    announce(progress, "do2015: iterative learning (10 trials), the learned table without sensor")
    ilc = do_ilc.study(sys.modules[__name__], first["fits"], t, y_d, tip,
                       baseline["fixed"].metrics["mse"], seed)  # fmt: skip
    announce(progress, "do2015: honesty panel")
    tip_sensor = tip[TIP_HEADLINE_MS]["designs"]["sensor"]
    told = {"none": kinematic_told(plants()[0]),
            "AdaptiveController": motor_datasheet(
                tip_sensor, tip[TIP_HEADLINE_MS]["designs"]["torque_motor"])}  # fmt: skip
    honesty = honesty_panel(
        first["fits"]["shape encoder"], _runs_only(study["random"][seeds[0]]), told=told,
        seed=seed, budget=budget, calibrations=_calibration_of(first["fits"]),
    )  # fmt: skip
    ilc_record = do_ilc.as_record(ilc)
    return {
        **first,
        "tip": {"record": do_tip.as_record(tip), "targets": do_tip.targets(tip, target),
                "runs": tip_runs},
        "ilc": {"record": ilc_record, "targets": do_ilc.targets(ilc_record, target)},
        "honesty": honesty,
    }  # fmt: skip


def assemble(lead: dict[str, Any], others: dict[str, dict[str, Any]], scale: float = 1.0,
             seed: int = 0) -> ScenarioResult:  # fmt: skip
    """do2015's result from :func:`lead_study` and the other servos' :func:`servo_study`
    (servo -> its outcome): the tip controllers' runs join every servo's table."""
    for servo, part in others.items():
        _add_tip(servo, part["study"], lead["tip"]["runs"])
    parts = {SERVOS[0]: lead, **others}
    return _result(parts, lead, seed, identification_budget(scale))


def _servo_study(servo: str, fits: dict, t, y_d, sensor, seeds) -> dict[str, Any]:
    """Every feedforward on one servo: the fixed route, and the random schedule of each seed."""
    plant = plants(servo)[0]
    comps = feedforwards(fits)
    fixed = _run_all(plant, comps, t, y_d, sensor, None, shape_sensing(seeds[0] + 500))
    random = {}
    for s in seeds:
        times, shapes = route_schedule(float(t[-1]) + 1e-3, np.random.default_rng(s))
        routes = piecewise_routes(times, shapes)
        random[s] = _run_all(plant, comps, t, y_d, sensor, routes, shape_sensing(s + 500))
        random[s]["_schedule"] = (times, shapes)
    return {"fixed": fixed, "random": random, "feedforwards": comps}


def _run_all(plant, comps: dict, t, y_d, sensor, routes, shape) -> dict[str, Any]:
    """No compensation and every feedforward on ``plant`` under ``routes``; the shape-aware
    ones are told the sensed shape (``shape``), the others nothing."""
    runs = {"none": run(plant, None, t, y_d, routes=routes, noise=sensor)}
    for name, comp in comps.items():
        sensing = shape if getattr(comp, "follows_route", False) else None
        runs[name] = run(plant, comp, t, y_d, routes=routes, noise=sensor, shape_sensing=sensing)
    return runs


def _add_tip(servo: str, study: dict, runs: dict) -> None:
    """The tip-feedback controllers' runs at the headline latency beside one servo's
    feedforwards: the adaptive controller (its own torque motor) in every servo's table, the
    TipLoop (around the PID servo it was designed on) in the PID servo's."""
    for name in do_tip.TIP_CONTROLLERS:
        if name == "TipLoop" and servo != SERVOS[0]:
            continue
        study["fixed"][name] = runs["fixed"][name]
        for s, result in runs["random"].items():
            study["random"][s][name] = result[name]


def _runs_only(runs: dict) -> dict[str, Result]:
    return {k: v for k, v in runs.items() if not k.startswith("_")}


def _summary(study: dict) -> dict[str, Any]:
    """compensator -> fixed-route MSE and factor, random-route factor's median/min/max, and
    what its runs show besides (limit cycles, saturation)."""
    fixed = study["fixed"]
    base = fixed["none"].metrics["mse"]
    by_seed = factors({s: _runs_only(r) for s, r in study["random"].items()})
    return {
        name: {
            "mse_fixed": fixed[name].metrics["mse"],
            "factor_fixed": ratio(base, fixed[name].metrics["mse"]),
            "factor_random": spread(by_seed[name]),
            "mse_random_median": float(
                np.median([r[name].metrics["mse"] for r in study["random"].values()])
            ),
            **_seen([fixed[name]] + [r[name] for r in study["random"].values()]),
        }
        for name in fixed
    }


def _seen(runs: list) -> dict[str, Any]:
    """What a compensator's runs show besides their error (common.runs_seen; the keys the
    servo summary has always carried)."""
    seen = runs_seen(runs)
    return {k: seen[k] for k in ("seen", "limit_cycle", "saturated_cycles")}


def _result(parts: dict, lead: dict, seed: int, budget: dict) -> ScenarioResult:
    studies = {servo: parts[servo]["study"] for servo in SERVOS}
    summaries = {servo: _summary(studies[servo]) for servo in SERVOS}
    seeds = sorted(studies[SERVOS[0]]["random"])
    headline = studies[SERVOS[0]]["random"][seeds[0]]
    runs = _runs_only(headline)
    times, shapes = headline["_schedule"]
    first = lead["fits"]
    designs = {servo: parts[servo]["encoder_loop_design"] for servo in SERVOS}
    return scenario_result(
        do2015,
        first["shape command"],
        targets=_targets(summaries) + lead["tip"]["targets"] + lead["ilc"]["targets"],
        title="Do et al. 2015: feedforward and adaptive control under changing routes",
        conditions=CONDITIONS,
        runs=runs,
        table=_table(summaries),
        paper={"mse_rad2": PAPER_MSE},
        routes={f"t = {tk:.1f} s": r for tk, r in zip(times, shapes, strict=True)},
        route_schedule=[(tk, r.curve_angle) for tk, r in zip(times, shapes, strict=True)],
        extra={
            "fixed_route": {
                s: {k: r.metrics for k, r in studies[s]["fixed"].items()} for s in SERVOS
            },  # fmt: skip
            "servo_summary": summaries,
            "route_seeds": seeds,
            "encoder_loop_design": designs,
            "headline_servo": SERVOS[0],
            "tip_sensor": lead["tip"]["record"],
            "tip_headline_ms": TIP_HEADLINE_MS,
            "ilc": lead["ilc"]["record"],
        },
        calibration=_calibration_record(first),
        protocol="do2015: every model identified by bench.calibrate from runs on three "
        "calibration shapes that no test run takes (command, motor encoder, noisy distal encoder "
        "and sensed curvature profile logged); each compensator inverts the model of the signal "
        "it outputs (the command, or inside an EncoderLoop the encoder, whose gains come from "
        "a motor calibration run); the shape-aware ones are told the sensed profile (noise "
        "0.05 rad, delay 0.1 s, 10 Hz) during the test; feedforwards are judged on the fixed "
        "route, random-route figures are the median and the minimum over 5 route seeds. The "
        "runs shown are the PID servo's, route seed 0.",
        honesty=lead["honesty"],
    )


def _calibration_of(fits: dict) -> dict[str, Any]:
    """compensator -> the calibration it was built from (for the honesty panel)."""
    return {
        "InverseFeedforward": fits["single command"],
        "InverseFeedforward + EncoderLoop": fits["single encoder"],
        "shape-aware InverseFeedforward": fits["shape command"],
        "shape-aware InverseFeedforward + EncoderLoop": fits["shape encoder"],
        "AdaptiveController": fits["single encoder"],
        "TipLoop": fits["shape command"],
    }


def _calibration_record(fits: dict) -> dict[str, Any]:
    cal = fits["shape command"]
    fit = cal.fits["BoucWenBacklash"]
    return {**cal.to_dict(), "rmse": fit.rmse, "nrmse": fit.nrmse, "seconds": fit.seconds}


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


def _table(summaries: dict) -> list[dict]:
    """Per servo and compensator: the fixed-route MSE and reduction, the random-route
    reduction's median and minimum over the seeds, beside the paper's."""
    rows = []
    for servo, summary in summaries.items():
        for name, s in summary.items():
            paper = PAPER_MSE.get(name.removesuffix(" + EncoderLoop").removeprefix("shape-aware "))
            rows.append(
                {
                    "servo": "torque motor" if name == "AdaptiveController" else servo.upper(),
                    "compensator": name,
                    "mse, fixed route": s["mse_fixed"],
                    "improvement, fixed route": s["factor_fixed"],
                    "improvement, random routes (median)": s["factor_random"]["median"],
                    "improvement, random routes (min)": s["factor_random"]["min"],
                    "paper_mse": paper,
                    "paper_improvement": ratio(PAPER_MSE["none"], paper) if paper else None,
                    "also seen": s["seen"] or "-",
                }
            )
    return rows


def _targets(summaries: dict) -> list[dict]:
    """The paper's claims, checked on both servos: the feedforward's on the fixed route (the
    paper's setting) and under random route changes (median and minimum over the seeds); the
    tip-feedback controllers' claims are do_tip's. A limit cycle in any run meets no claim."""
    out = []
    for servo, summary in summaries.items():
        best = summary[HEADLINE]
        tag = f"{servo.upper()} servo, {HEADLINE}"
        steady, seen = not best["limit_cycle"], best["seen"]
        out += [
            target(f"InverseFeedforward MSE reduction, fixed route ({tag})", ">= 30x (paper 13x)",
                   best["factor_fixed"], steady and best["factor_fixed"] >= 30, "x", seen),
            target(f"InverseFeedforward MSE reduction, random routes, median of "
                   f"{best['factor_random']['seeds']} seeds ({tag})", ">= 30x",
                   best["factor_random"]["median"],
                   steady and best["factor_random"]["median"] >= 30, "x", seen),
            target(f"InverseFeedforward MSE reduction, random routes, worst seed ({tag})",
                   ">= 13x", best["factor_random"]["min"],
                   steady and best["factor_random"]["min"] >= 13, "x", seen),
        ]  # fmt: skip
    return out


# -- robustness: the do2015 comparison over perturbed plants (ts.sweep run function) --------

_NOMINAL_FITS: dict[int, dict[str, Any]] = {}


def _nominal_fits(seed: int = 0) -> dict[str, Any]:
    """The fits the robustness study uses, calibrated once per process on the nominal plant:
    the one-shape command fit, the shape-aware encoder fit and the one-shape encoder fit (in
    a sweep's worker: their identifiability warnings repeat the do2015 calibration's,
    reported there)."""
    if seed not in _NOMINAL_FITS:
        from ...identify.diagnostics import IdentifiabilityWarning

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", IdentifiabilityWarning)
            cal = calibrate(seed, {"maxiter": 40, "popsize": 10})
            _NOMINAL_FITS[seed] = {
                "single command": cal,
                "single encoder": cal.refit("encoder"),
                "shape encoder": cal.refit("encoder", depends_on_angle=SHAPE_LAWS),
            }
    return _NOMINAL_FITS[seed]


_NOMINAL_FEEDFORWARDS: dict[int, dict[str, Any]] = {}


def _nominal_feedforwards(seed: int = 0) -> dict[str, Any]:
    """The feedforwards the robustness study judges, built once per process from the
    nominal fits: the EncoderLoop's tuning (on the identified servo, about 0.1 s) is the same
    for every draw, and bench.run starts each run from the compensator's reset, as the
    do2015 study runs one compensator on every route."""
    if seed not in _NOMINAL_FEEDFORWARDS:
        fits = _nominal_fits(seed)
        shape = fits["shape encoder"]
        _NOMINAL_FEEDFORWARDS[seed] = {
            "InverseFeedforward": fits["single command"].inverse_feedforward(smoothing=SMOOTHING),
            HEADLINE: shape.encoder_loop(shape.inverse_feedforward(smoothing=SMOOTHING)),
        }
    return _NOMINAL_FEEDFORWARDS[seed]


def robustness_run(params: dict) -> dict[str, dict[str, float]]:
    """One draw of the robustness study: the plant's friction, pretension and route differ
    from the nominal plant the compensators were calibrated on; 10 s of the do2015 reference
    on a fixed (random-arc) route, behind the PID servo. Returns compensator -> metrics (a
    ``ts.sweep`` run; ``limit_cycle`` is 1 when the tip oscillated on its own)."""
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
    fits = _nominal_fits()
    t, y_d = reference(10.0)
    seed = int(params.get("route_seed", 0)) % 100_000
    sensor = encoder(seed=seed)
    plant = PullPullPlant(route=route, motor=servo_motor(), **kwargs)
    comps = _nominal_feedforwards()
    runs = _run_all(plant, comps, t, y_d, sensor, None, shape_sensing(seed + 500))
    torque = PullPullPlant(route=route, motor=torque_motor(), **kwargs)
    adaptive = _adaptive_controller(fits["single encoder"].backlash_model, sensor)
    runs["AdaptiveController"] = run(torque, adaptive, t, y_d, noise=sensor)
    return {
        name: {
            **{k: r.metrics[k] for k in ("mse", "rmse", "max_abs", "percent_error")},
            "limit_cycle": float(r.metrics["limit_cycle"]["detected"]),
        }
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


__all__ = [
    "CALIBRATION_ROUTE",
    "CALIBRATION_ROUTES",
    "CONDITIONS",
    "FEEDFORWARDS",
    "HEADLINE",
    "INERTIA",
    "NOMINAL",
    "PAPER_MSE",
    "SENSING",
    "SERVOS",
    "SHAPE_LAWS",
    "SMOOTHING",
    "TIP_HEADLINE_MS",
    "VISCOUS",
    "assemble",
    "calibrate",
    "calibrations",
    "do2015",
    "feedforwards",
    "lead_study",
    "motor_datasheet",
    "physics",
    "plants",
    "random_route",
    "reference",
    "robustness_run",
    "route_schedule",
    "servo_motor",
    "servo_study",
    "shape_sensing",
    "torque_motor",
]
