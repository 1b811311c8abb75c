"""Compensation over a population of drives: every pipeline built from one drive's calibration
logs alone, judged on that drive's own tests.

For one member of the population (:mod:`tendonsheath.plant.population`) :func:`member_study`
runs what a user of that drive would run, nothing copied from its plant:

* **calibration** (``bench.calibrate`` on the drive's three calibration shapes, the calibration
  excitation at 0.25 Hz, the drive's own sensors: quantised noisy motor encoder, tip sensor,
  noisy delayed shape sensing) and a motor calibration run (the servo, for the encoder loop);
* **sensorless**: the shape-aware InverseFeedforward alone and inside an EncoderLoop; the loop
  is kept only when a calibration trial (:func:`~tendonsheath.bench.trial.calibration_trial`,
  scored on the tip sensor's reading) shows it helps, else the pipeline leaves it out and says
  so;
* **TipLoop** at 1 ms and 5 ms of tip-sensor latency: designed from the loop dynamics
  identified on each calibration shape and chosen by calibration trials (scored on the tip
  sensor);
* **AdaptiveController** at 1 ms on the drive's torque motor, its inertia and damping
  identified from a torque chirp (:func:`~tendonsheath.bench.motor_calibration.
  calibrate_torque_motor`), not declared;
* **ILC**: 10 learning trials on the fixed route from the tip sensor (1 ms), noise drawn anew
  each trial, over several noise seeds; the learned table run without the sensor, and on a
  shifted route (no divergence);
* **continuum** (a continuum draw): the ContinuumFeedforward (exact) in its EncoderLoop, the
  percent error of lau2015.

Each test reference is drawn by the member (a main frequency off the calibration's 0.25 Hz),
each run starts from rest after a random hold (runs differ in where the drive starts), and
each random-route figure is the median and the minimum over the route seeds.
"""

from __future__ import annotations

import math
import time
import warnings
from typing import Any

import numpy as np

from ..plant.population import (
    PlantDraw,
    random_continuum_plant,
    random_realistic_plant,
)
from ..plant.route import Route
from .calibration import calibrate, calibration_input
from .loop_calibration import calibrate_loop
from .motor_calibration import calibrate_torque_motor
from .run import run
from .scenarios.common import ratio
from .trial import calibration_trial, choose

#: the tip sensor's latencies of the tip-feedback figures (s)
LATENCIES = (1e-3, 5e-3)
#: route-schedule seeds per member (the protocol's minimum)
ROUTE_SEEDS = 5
#: ILC noise seeds per member
ILC_SEEDS = 5
ILC_TRIALS = 10
SHAPE_LAWS = {"B_r": "tanh", "B_l": "tanh"}
#: the calibration trials' speeds: the calibration excitation as logged and twice as fast (a
#: loop is kept only when it helps on both)
TRIAL_SPEEDS = (1.0, 2.0)
SMOOTHING = 0.03
#: the studies a member can run
STUDIES = ("sensorless", "tip", "adaptive", "ilc")


def _sensing(draw: PlantDraw, seed: int):
    """The draw's shape sensing (``ShapeSensing``) with noise seed ``seed``."""
    from .shape_sensing import ShapeSensing

    return ShapeSensing(**draw.shape_sensing(seed))


def _factors(none: dict, runs: dict) -> dict[str, Any]:
    """MSE reduction over ``none`` on the fixed route and each route seed: {fixed, seeds,
    median, min}."""
    seeds = [ratio(none["random"][s], runs["random"][s]) for s in sorted(runs["random"])]
    return {
        "fixed": ratio(none["fixed"], runs["fixed"]),
        "seeds": seeds,
        "median": float(np.median(seeds)),
        "min": float(np.min(seeds)),
    }


#: seconds of each test run before its scored part: from rest through a random excursion
LEAD_IN = 3.0


class _Tests:
    """A member's test conditions: the drive a little drifted since its calibration, the
    reference (after a lead-in from rest through a random excursion, left out of the score
    with one period of the reference), the fixed route and the route seeds."""

    def __init__(self, draw: PlantDraw, duration: float, seed: int):
        self.draw, self.seed = draw.drifted(seed), seed
        self.t, self.y_d = draw.reference(duration + LEAD_IN, seed, lead_in=LEAD_IN)
        self.schedules = {s: draw.routes(duration + LEAD_IN + 1e-3, s) for s in range(ROUTE_SEEDS)}
        self.limit_cycles = 0

    def mse(self, plant, controller, sensor, *, shape_seed: int = 500) -> dict[str, Any]:
        """{fixed: MSE, random: {seed: MSE}} of ``controller`` on ``plant`` (the true tip
        error: what the figure reports; no tuner sees it)."""
        follows = getattr(controller, "follows_route", False) or _is_tip_loop(controller)
        out: dict[str, Any] = {"random": {}}
        cases: list[tuple[int | None, Any]] = [(None, None), *self.schedules.items()]
        for key, routes in cases:
            s = 0 if key is None else key + 1
            sensing = _sensing(self.draw, shape_seed + s) if follows else None
            r = run(
                plant,
                controller,
                self.t,
                self.y_d,
                routes=routes,
                noise=sensor,
                shape_sensing=sensing,
                warmup=LEAD_IN + 1.0,
            )
            m = r.metrics["mse"]
            self.limit_cycles += (
                bool(r.metrics["limit_cycle"]["detected"]) and controller is not None
            )
            if key is None:
                out["fixed"] = m
            else:
                out["random"][key] = m
        return out


def _is_tip_loop(controller) -> bool:
    """A TipLoop schedules its gains over the sensed shape, whatever its feedforward."""
    from ..compensate import TipLoop

    return isinstance(controller, TipLoop)


def demo_draw() -> PlantDraw:
    """The demo's plant (``bench.scenarios.do``) as a member of the population: its values
    all inside the priors; its routes, sensors and calibration shapes the demo's."""
    from ..plant.presets import REALISTIC
    from .scenarios import do, do_tip

    common = do._COMMON
    values = {
        "length": do.NOMINAL.length,
        "route_angle": do.NOMINAL.curve_angle,
        "bends": 2,
        "lead_in": 1.0 / 3.0,
        "friction": common["friction"],
        "stiffness": common["stiffness"],
        "pretension": common["pretension"],
        "proximal_radius": common["proximal_radius"],
        "radius_ratio": common["distal_radius"] / common["proximal_radius"],
        **{
            k: REALISTIC[k]
            for k in (
                "distal_inertia",
                "distal_damping",
                "sheath_viscosity",
                "relaxation_fraction",
                "relaxation_time",
                "friction2_ratio",
                "stiffness2_ratio",
            )
        },
        "servo_bandwidth_hz": 60.0,
        "servo_damping": 0.8,
        "servo_pid": 0.0,
        "motor_inertia": REALISTIC["motor_inertia"],
        "motor_coulomb": REALISTIC["motor_coulomb_friction"],
        "motor_viscous": REALISTIC["motor_viscous_friction"],
        "gear_play": REALISTIC["gear_backlash"],
        "encoder_lines_log2": 9,
        "gear_ratio": 14.0,
        "encoder_noise_counts": 0.25,
        "tip_noise": do_tip.TIP_NOISE_STD,
        "tip_resolution": do_tip.TIP_RESOLUTION,
        "shape_noise": do.SENSING["noise_std"],
        "shape_delay": do.SENSING["delay"],
        "shape_segments": do.SENSING["segments"],
        "torque_inertia": do.INERTIA,
        "torque_viscous": do.VISCOUS,
        "workspace": 1.3 / 1.15,
    }
    return PlantDraw(None, "pull-pull", values, do.NOMINAL, tuple(do.CALIBRATION_ROUTES))


def _quiet(fn, *args, **kwargs):
    from ..identify.diagnostics import IdentifiabilityWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IdentifiabilityWarning)
        return fn(*args, **kwargs)


def calibration_amplitude(draw: PlantDraw, seed: int = 0, rounds: int = 3) -> float:
    """The calibration excitation's amplitude (motor angle) whose tip range, as the tip sensor
    reads it, covers the workspace with a 15 % margin: from the pulleys' kinematic ratio, scaled
    by short calibration runs on the first calibration shape (what a user does by watching the
    tip; the tendons' stretch and the friction ask for more stroke than the ratio says)."""
    from .motor_calibration import run_experiment

    plant = draw.plant(encoder_seed=seed + 61)
    target = 2.0 * 1.15 * draw.values["workspace"]
    amplitude = draw.calibration_amplitude
    for i in range(rounds):
        t, command = calibration_input(8.0, amplitude)
        _, tip = run_experiment(
            plant,
            draw.calibration_routes[0],
            t,
            command,
            draw.tip_sensor(0.0, seed + 63 + i),
            seed + 63 + i,
        )
        seen = float(np.ptp(tip[t >= 2.0]))
        if seen <= 0.0:
            break
        amplitude *= float(np.clip(target / seen, 0.5, 4.0))
    return amplitude


def _calibration(draw: PlantDraw, seed: int, budget: dict | None):
    cal = _quiet(
        calibrate,
        draw.plant(encoder_seed=seed + 3),
        list(draw.calibration_routes),
        models_=("BoucWenBacklash",),
        duration=20.0,
        amplitude=calibration_amplitude(draw, seed),
        warmup=2.0,
        sensor=draw.tip_sensor(0.0, seed + 11),
        shape=_sensing(draw, seed),
        seed=seed,
        budget=budget,
        servo=True,
    )
    shape = _quiet(cal.refit, depends_on_angle=SHAPE_LAWS)
    return {
        "single command": cal,
        "single encoder": _quiet(cal.refit, "encoder"),
        "shape command": shape,
        "shape encoder": _quiet(shape.refit, "encoder"),
    }


def _sensorless(draw, fits, tests, none, trials) -> dict[str, Any]:
    shape, enc = fits["shape command"], fits["shape encoder"]
    ff = shape.inverse_feedforward(smoothing=SMOOTHING)
    looped = enc.encoder_loop(enc.inverse_feedforward(smoothing=SMOOTHING))
    choice = choose({"feedforward": ff, "feedforward + EncoderLoop": looped}, trials)
    plant = tests.draw.plant(encoder_seed=tests.seed + 5)
    sensor = draw.tip_sensor(0.0, tests.seed + 7)
    alone = _factors(none, tests.mse(plant, ff, sensor))
    inside = _factors(none, tests.mse(plant, looped, sensor))
    keep = choice.name != "feedforward"
    ratios = [row["feedforward + EncoderLoop"] / row["feedforward"] for row in choice.all_scores]
    return {
        "feedforward": alone,
        "feedforward + EncoderLoop": inside,
        "chosen": inside if keep else alone,
        "loop kept": keep,
        "trial ratio": float(max(ratios)),
        "why": choice.reason,
        "servo": enc.servo.servo.summary(),
    }


def _loops(draw, latency: float, seed: int):
    plant = draw.plant(encoder_seed=seed + 13)
    sensor = draw.tip_sensor(latency, seed + 41)
    loops = [
        calibrate_loop(plant, route, sensor, seed=seed + 601 + i)
        for i, route in enumerate(draw.calibration_routes)
    ]
    return sensor, loops


def _tip(draw, fits, tests, none, seed: int, loops_at: dict) -> dict[str, Any]:
    from ..compensate import TipLoop

    out = {}
    shape = fits["shape command"]
    angles = [r.sensed_angle for r in shape.runs[: len(draw.calibration_routes)]]
    plant = tests.draw.plant(encoder_seed=seed + 17)
    for latency in LATENCIES:
        sensor, loops = loops_at[latency]
        trial = calibration_trial(
            draw.plant(encoder_seed=seed + 18),
            draw.calibration_routes,
            sensor,
            amplitude=draw.values["workspace"],
            shape_sensing=_sensing(draw, seed + 900),
        )
        try:
            tip = TipLoop.from_calibration(
                shape.backlash_model,
                [loop.dynamics for loop in loops],
                curve_angles=angles,
                max_sensitivity=(1.7, 2.0),
                dead_band_scale=(0.9, 0.8, 0.7),
                trial=trial,
                refine=True,
                feedforward_options={"smoothing": SMOOTHING},
            )
        except ValueError as refused:  # the tuner found no design that holds: said so
            out[f"{1e3 * latency:g} ms"] = _refused(str(refused))
            continue
        test_sensor = draw.tip_sensor(latency, seed + 43)
        out[f"{1e3 * latency:g} ms"] = {
            **_factors(none, tests.mse(plant, tip, test_sensor)),
            "designed_from": tip.design.summary(),
        }
    return out


def _adaptive(draw, fits, tests, seed: int, loops_at: dict) -> dict[str, Any]:
    from ..compensate import AdaptiveController

    latency = LATENCIES[0]
    torque_plant = draw.torque_plant(encoder_seed=seed + 19)
    motor = calibrate_torque_motor(torque_plant, draw.calibration_routes[0])
    test_plant = tests.draw.torque_plant(encoder_seed=seed + 20)
    sensor, loops = loops_at[latency]
    trial = calibration_trial(
        torque_plant, draw.calibration_routes, sensor, amplitude=draw.values["workspace"]
    )
    try:
        ctrl = AdaptiveController.from_calibration(
            fits["single encoder"].backlash_model,
            [loop.dynamics for loop in loops],
            inertia=motor.inertia,
            viscous=motor.viscous,
            max_torque=5.0,
            noise_std=draw.values["tip_noise"],
            trial=trial,
        )
    except ValueError as refused:  # every trial saturated or diverged: the tuner refuses
        return {"refused": str(refused), "identified": motor.summary()}
    test_sensor = draw.tip_sensor(latency, seed + 47)
    # the factor is over the uncompensated servo drive (as do2015's): a torque joint has no
    # uncompensated command
    return {
        "runs": tests.mse(test_plant, ctrl, test_sensor),
        "identified": motor.summary(),
        "designed_from": ctrl.design.summary(),
    }


def _refused(reason: str) -> dict[str, Any]:
    """A pipeline whose tuner refused the drive: the user runs it uncompensated (1x), and the
    reason is kept."""
    return {"fixed": 1.0, "seeds": [], "median": 1.0, "min": 1.0, "refused": reason}


def _ilc(draw, fits, tests, none_fixed: float, seed: int, loops_at: dict) -> dict[str, Any]:
    from ..compensate import IterativeLearning

    plant = tests.draw.plant(encoder_seed=seed + 23)
    _, loops = loops_at[LATENCIES[0]]
    ff = fits["single command"].inverse_feedforward(smoothing=SMOOTHING)
    t, y_d = tests.t, tests.y_d
    dt = float(t[1] - t[0])
    learned_factors, shifted_ok, trials = [], [], []
    v = draw.values
    bent = Route.arcs([(draw.nominal_route.length, min(1.4 * v["route_angle"], 4 * math.pi))])
    shifted = tests.draw.plant(bent, encoder_seed=seed + 29)
    ff_shift = run(shifted, ff, t, y_d).metrics["mse"]
    for k in range(ILC_SEEDS):
        ilc = IterativeLearning.from_dynamics(
            ff, t, y_d, loops[0].dynamics, dt, max_trials=ILC_TRIALS
        )
        n = 0
        while not ilc.stopped:
            sensor = draw.tip_sensor(LATENCIES[0], seed + 700 + 37 * k + n)
            r = run(plant, ilc.compensator(), t, y_d, noise=sensor)
            ilc.update(r.measured)
            n += 1
        learned = ilc.best_compensator()
        learned_factors.append(ratio(none_fixed, run(plant, learned, t, y_d).metrics["mse"]))
        shifted_ok.append(run(shifted, learned, t, y_d).metrics["mse"] <= ff_shift)
        trials.append(n - 1)
    return {
        "factors": learned_factors,
        "min": float(min(learned_factors)),
        "shifted_no_divergence": bool(all(shifted_ok)),
        "trials": trials,
    }


def member_study(
    seed: int,
    *,
    studies: tuple[str, ...] = STUDIES,
    duration: float = 40.0,
    budget: dict | None = None,
    draw: PlantDraw | None = None,
) -> dict[str, Any]:
    """Every pipeline on population member ``seed`` (or on ``draw``), from its calibration
    logs alone; MSE reductions over the uncompensated drive (fixed route, and the median and
    minimum over :data:`ROUTE_SEEDS` route schedules).

    Parameters
    ----------
    seed : int
        The member (:func:`~tendonsheath.plant.population.random_realistic_plant`).
    studies : tuple of str
        Any of :data:`STUDIES`.
    duration : float, default 40.0
        Length of each test run (s).
    budget : dict, optional
        The identification budget (options of ``tendonsheath.identify``).
    draw : PlantDraw, optional
        A member given directly (the demo's plant: ``population.demo_draw()``).

    Returns
    -------
    dict
        The member's figures, what each pipeline was designed from, and its time (s).
    """
    unknown = set(studies) - set(STUDIES)
    if unknown:
        raise ValueError(f"member_study: unknown studies {sorted(unknown)}; known: {STUDIES}")
    start = time.perf_counter()
    draw = random_realistic_plant(seed) if draw is None else draw
    tests = _Tests(draw, duration, seed)
    fits = _calibration(draw, seed, budget)
    plant = tests.draw.plant(encoder_seed=seed + 5)
    none = tests.mse(plant, None, draw.tip_sensor(0.0, seed + 7))
    out: dict[str, Any] = {"seed": seed, "draw": draw.describe(), "servo": draw.servo}
    if "sensorless" in studies:
        trials = [
            calibration_trial(
                draw.plant(encoder_seed=seed + 31 + k),
                draw.calibration_routes,
                draw.tip_sensor(0.0, seed + 53 + k),
                amplitude=draw.values["workspace"],
                shape_sensing=_sensing(draw, seed + 901 + k),
                speed=speed,
            )
            for k, speed in enumerate(TRIAL_SPEEDS)
        ]
        out["sensorless"] = _sensorless(draw, fits, tests, none, trials)
    # the loop calibrations (one per latency, on every calibration shape), run once for the
    # tip loop, the adaptive controller and the learning that each design from them
    latencies = LATENCIES if "tip" in studies else LATENCIES[:1]
    loops_at = (
        {lat: _loops(draw, lat, seed) for lat in latencies}
        if {"tip", "adaptive", "ilc"} & set(studies)
        else {}
    )
    if "tip" in studies:
        out["tip"] = _tip(draw, fits, tests, none, seed, loops_at)
    if "adaptive" in studies:
        a = _adaptive(draw, fits, tests, seed, loops_at)
        if "refused" in a:
            out["adaptive"] = {**_refused(a["refused"]), "identified": a["identified"]}
        else:
            out["adaptive"] = {
                **_factors(none, a["runs"]),
                "identified": a["identified"],
                "designed_from": a["designed_from"],
            }
    if "ilc" in studies:
        out["ilc"] = _ilc(draw, fits, tests, none["fixed"], seed, loops_at)
    out["limit_cycle_runs"] = tests.limit_cycles
    out["seconds"] = time.perf_counter() - start
    return out


def continuum_member_study(
    seed: int, *, duration: float = 20.0, budget: dict | None = None
) -> dict[str, Any]:
    """lau2015's pipeline on continuum member ``seed``: CurveAngleModel groups with the
    backbone spring identified on the calibration shapes, the ContinuumFeedforward (exact)
    told the test route's sensed curve angle, inside an EncoderLoop where a calibration trial
    shows the loop helps (else alone); percent error (mean |e|
    over the reference's range) on the fixed route and the route seeds (held routes: the
    feedforward is told one sensed angle per run)."""
    start = time.perf_counter()
    draw = random_continuum_plant(seed)
    cal = _quiet(
        calibrate,
        draw.plant(encoder_seed=seed + 3),
        list(draw.calibration_routes),
        models_=("CurveAngleModel",),
        spring=True,
        duration=15.0,
        amplitude=calibration_amplitude(draw, seed),
        sensor=draw.tip_sensor(0.0, seed + 30),
        shape=_sensing(draw, seed),
        seed=seed,
        budget=budget,
        servo=True,
    )
    enc = _quiet(cal.refit, "encoder")
    # the loop is kept when calibration trials (first calibration shape, tip sensor, two
    # speeds) show it helps
    shape0 = draw.calibration_routes[0]
    sensed0 = cal.runs[0].sensed_angle
    trials = [
        calibration_trial(
            draw.plant(shape0, encoder_seed=seed + 31 + k),
            [shape0],
            draw.tip_sensor(0.0, seed + 53 + k),
            duration=15.0,
            amplitude=draw.values["workspace"],
            speed=speed,
        )
        for k, speed in enumerate(TRIAL_SPEEDS)
    ]
    alone0 = cal.continuum_feedforward(sensed0, mode="exact", smoothing=0.1)
    looped0 = enc.encoder_loop(enc.continuum_feedforward(sensed0, mode="exact", smoothing=0.1))
    keep = choose({"alone": alone0, "looped": looped0}, trials).name == "looped"
    t, y_d = draw.reference(duration, seed)
    sensor = draw.tip_sensor(0.0, seed + 7)
    errors, none_errors = [], []
    routes = [draw.nominal_route] + [
        draw.route_schedule(100.0, s)[1][-1] for s in range(ROUTE_SEEDS)
    ]
    for i, route in enumerate(routes):
        plant = draw.plant(route, encoder_seed=seed + 5 + i)
        sensed = cal.shape.static_reading(route.curve_angle, duration, seed_offset=99 + i)
        if keep:
            comp = enc.encoder_loop(enc.continuum_feedforward(sensed, mode="exact", smoothing=0.1))
        else:
            comp = cal.continuum_feedforward(sensed, mode="exact", smoothing=0.1)
        errors.append(run(plant, comp, t, y_d, noise=sensor).metrics["percent_error"])
        none_errors.append(run(plant, None, t, y_d, noise=sensor).metrics["percent_error"])
    return {
        "seed": seed,
        "draw": draw.describe(),
        "percent_error": errors,
        "median": float(np.median(errors)),
        "max": float(np.max(errors)),
        "none_median": float(np.median(none_errors)),
        "loop kept": bool(keep),
        "seconds": time.perf_counter() - start,
    }


__all__ = [
    "ILC_SEEDS",
    "LATENCIES",
    "ROUTE_SEEDS",
    "STUDIES",
    "continuum_member_study",
    "demo_draw",
    "member_study",
]


#: the identification budget of the population runs (the robustness sweep's: a smaller search
#: than the demo's default, the same for every member)
POPULATION_BUDGET = {"maxiter": 40, "popsize": 10}


def population_run(params: dict) -> dict[str, dict[str, float]]:
    """One member of the population as a ``ts.sweep`` run: pipeline -> its figures
    (``fixed``, ``median`` and ``min`` MSE reductions; ILC: ``min`` and ``median`` over its
    noise seeds and ``shifted_ok``). ``params``: ``seed`` (the member), ``kind``
    ("pull-pull" or "continuum")."""
    from .._util.blas import one_blas_thread

    # the BLAS on one thread: the figures then do not depend on the machine's core count (the
    # fits' small least-squares problems gain nothing from BLAS threads; see _util.jobs)
    with one_blas_thread():
        return _population_run(params)


def _population_run(params: dict) -> dict[str, dict[str, float]]:
    seed = int(params["seed"])
    if params.get("kind", "pull-pull") == "continuum":
        c = continuum_member_study(seed, budget=POPULATION_BUDGET)
        return {
            "ContinuumFeedforward (exact) + EncoderLoop": {
                "median": c["median"],
                "max": c["max"],
                "none_median": c["none_median"],
                "loop_kept": float(c["loop kept"]),
                "seconds": c["seconds"],
            }
        }
    m = member_study(seed, budget=POPULATION_BUDGET)
    return flatten(m)


population_run.parameters = ("seed", "kind")  # type: ignore[attr-defined]


def flatten(m: dict[str, Any]) -> dict[str, dict[str, float]]:
    """A :func:`member_study` as pipeline -> figure -> float (the sweep table's rows)."""

    def figures(f: dict) -> dict[str, float]:
        return {
            **{k: float(f[k]) for k in ("fixed", "median", "min")},
            "refused": float("refused" in f),
        }

    s = m["sensorless"]
    out = {
        "sensorless (encoder loop where it helps)": {
            **figures(s["chosen"]),
            "loop_kept": float(s["loop kept"]),
            "trial_ratio": float(s["trial ratio"]),
        },
        "shape-aware InverseFeedforward": figures(s["feedforward"]),
        "shape-aware InverseFeedforward + EncoderLoop": figures(s["feedforward + EncoderLoop"]),
        "AdaptiveController, 1 ms": figures(m["adaptive"]),
        "ILC, 10 trials": {
            "min": float(m["ilc"]["min"]),
            "median": float(np.median(m["ilc"]["factors"])),
            "shifted_ok": float(m["ilc"]["shifted_no_divergence"]),
        },
        "member": {
            "seconds": float(m["seconds"]),
            "limit_cycle_runs": float(m["limit_cycle_runs"]),
            "pid": float(m["servo"] == "pid"),
        },
    }
    for latency, f in m["tip"].items():
        out[f"TipLoop, {latency}"] = figures(f)
    return out


__all__ += ["POPULATION_BUDGET", "flatten", "population_run"]
