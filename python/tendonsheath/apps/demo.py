"""The main job: `tendonsheath demo --out DIR`.

Runs the built-in virtual bench (the three seed experiments on the physics plant:
do2015, sun2015, lau2015), and a tour of the hysteresis models on a standard input, and
writes DIR/report.html (self-contained), DIR/metrics.json and the figures as PNG files.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, cast

import numpy as np

from .. import models
from .._util.atomic import write_bytes
from .._util.extras import require_plotly
from ..bench.metrics import loop_width
from ..report.units import check_angle_unit, rows_in_unit

DEMO_SCHEMA_VERSION = 1


def standard_input(duration: float = 20.0, rate: float = 1000.0, amplitude: float = 1.0):
    """0.25 Hz sine whose amplitude decays from `amplitude` to a third: nested loops."""
    t = np.arange(0.0, duration, 1.0 / rate)
    envelope = amplitude * (1.0 - (2.0 / 3.0) * t / duration)
    return t, envelope * np.sin(2 * np.pi * 0.25 * t)


def demo_models() -> dict[str, models.HysteresisModel]:
    return {
        "Backlash": models.Backlash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.10),
        "BoucWenBacklash": models.BoucWenBacklash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.10, n=8),
        "BoucWen": models.BoucWen(A=1.0, beta=2.0, gamma=1.0, n=1.5, alpha=0.3, k=1.0),
        "PrandtlIshlinskii": models.PrandtlIshlinskii.uniform(0.4, 8),
        "GeneralizedPrandtlIshlinskii": models.GeneralizedPrandtlIshlinskii(
            rising=(1.1, 1.6, 0.15, 0.0),
            falling=(0.9, 1.6, -0.15, 0.0),
            thresholds=[0.0, 0.1, 0.2],
            weights=[0.8, 0.3, 0.2],
        ),
        "HystereticOscillator": models.HystereticOscillator(
            m=1.0, c=0.5, k=2.0, alpha=3.0, beta=2.0, gamma=0.6, delta=0.4, nu=1.0
        ),
    }


def model_section(out: Path) -> tuple[str, dict, list[Path]]:
    """Each hysteresis model on the standard input: a loop figure and a few numbers."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..report import figures, html

    t, x = standard_input()
    metrics, parts, written = {}, [], []
    for name, model in demo_models().items():
        start = time.perf_counter()
        y = cast(np.ndarray, model.simulate(t, x))  # the outputs (an array); status unused
        elapsed = time.perf_counter() - start
        last = t >= t[-1] - 4.0  # the last input period
        metrics[name] = {
            "params": model.params,
            "samples": int(x.size),
            "output_min": float(y.min()),
            "output_max": float(y.max()),
            "loop_width_last_cycle": loop_width(x[last], y[last]),
            "simulate_seconds": elapsed,
        }
        fig, ax = plt.subplots(figsize=(4.2, 3.5))
        ax.plot(x, y, lw=1.0)
        ax.set_xlabel("input force u [N]" if name == "HystereticOscillator" else "input x [rad]")
        ax.set_ylabel("output y [m]" if name == "HystereticOscillator" else "output y [rad]")
        ax.set_title(name)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        data = figures.png(fig)
        path = out / f"loop_{name}.png"
        write_bytes(path, data)
        written.append(path)
        parts.append(html.figure(data, f"{name}: input-output loop on a decaying 0.25 Hz sine"))
    return "".join(parts), metrics, written


#: seconds of CPU each job of the demo takes at full length (measured on the 2-core machine,
#: BLAS on one thread): the workers take the longest first, so that they finish together
_COST = {"do2015": 38.1, "do2015 (PD servo)": 29.2, "robustness": 20.7, "lau2015": 8.0,
         "sun2015": 5.3, "models": 0.3, "rate_dependence": 0.1}  # fmt: skip


def run_demo(
    out: Path,
    scale: float = 1.0,
    scenarios: list[str] | None = None,
    progress: Callable[[str], None] | None = None,
    seed: int = 0,
    robustness: bool = True,
    angle_unit: str = "deg",
    workers: int | None = None,
) -> dict:
    """Run the scenarios (all by default) and write the report; returns what was written.
    Without Plotly (the ``report`` extra) a MissingExtraError, before anything is run.

    The scenarios and studies are independent: they run on ``workers`` processes (default:
    one per core; 1: all in this process, one after the other), with the same results
    either way. ``timings``: each one's seconds of work (do2015's: its parts' together)."""
    from .._util.blas import one_blas_thread
    from .._util.jobs import cores, run_jobs
    from ..bench.scenarios import SCENARIOS

    check_angle_unit(angle_unit)
    require_plotly()
    names = list(SCENARIOS) if scenarios is None else scenarios
    unknown = [n for n in names if n not in SCENARIOS]
    if unknown:
        raise ValueError(f"unknown scenario(s) {unknown}; known: {list(SCENARIOS)}")
    if workers is not None and (isinstance(workers, bool) or int(workers) != workers
                                or workers < 1):  # fmt: skip
        raise ValueError(f"workers must be an integer >= 1 (got {workers!r})")
    out.mkdir(parents=True, exist_ok=True)
    workers = cores() if workers is None else int(workers)
    jobs = _jobs(names, SCENARIOS, out, scale, seed, robustness, angle_unit, split=workers > 1)
    with one_blas_thread():  # as in the jobs (run_jobs)
        done = run_jobs(jobs, workers, progress, preload=["tendonsheath.apps.demo"])
        return _write(out, names, done, scale, seed, robustness, angle_unit)


def _write(out, names, done, scale, seed, robustness, angle_unit) -> dict:
    """The report from the jobs' outcomes (``done``: key -> (value, seconds))."""
    from ..report.build import write

    results, timings = [], {}
    for name in names:
        if name == "do2015" and "do2015 (PD servo)" in done:
            from ..bench.scenarios import do

            start = time.perf_counter()
            lead, pd = done["do2015"][0], done["do2015 (PD servo)"][0]
            results.append(do.assemble(lead, {"pd": pd}, scale=scale, seed=seed))
            seconds = done["do2015"][1] + done["do2015 (PD servo)"][1]
            timings[name] = seconds + time.perf_counter() - start
        else:
            results.append(done[name][0])
            timings[name] = done[name][1]
    extra = []
    if robustness:
        extra.append(done["robustness"][0])
        timings["robustness"] = done["robustness"][1]
    rate_body, rate_metrics, rate_file = done["rate_dependence"][0]
    extra.append(
        ("rate_dependence", "Rate dependence of the realistic plant", rate_body, rate_metrics)
    )
    timings["rate_dependence"] = done["rate_dependence"][1]
    body, model_metrics, model_files = done["models"][0]
    extra.append(("models", "Hysteresis models on a standard input", body, model_metrics))
    population = population_section()
    if population is not None:
        extra.insert(0, ("population", "Over a population of drives", *population))
    written = write(out, results, extra, angle_unit=angle_unit)
    written["figures"] += [rate_file, *model_files]
    if robustness:
        written["figures"].append(out / "robustness_mse.png")
    written["timings"] = timings
    written["results"] = results
    return written


def _jobs(names, scenarios, out, scale, seed, robustness, angle_unit, split: bool):
    """The demo's independent jobs, in the order a serial run takes them. ``split``: the
    built-in do2015 as two jobs (the PID servo with what is designed on it, and the PD
    servo), which ``do.assemble`` puts together."""
    from .._util.jobs import Job
    from ..bench.scenarios import do

    common = {"scale": scale, "seed": seed}
    jobs = []
    for name in names:
        if name == "do2015" and split and scenarios[name] is do.do2015:
            jobs.append(Job(name, do.lead_study, common, _COST[name]))
            pd = {"servo": "pd", **common}
            jobs.append(Job("do2015 (PD servo)", do.servo_study, pd, _COST["do2015 (PD servo)"]))
        else:
            jobs.append(Job(name, scenarios[name], common, _COST.get(name, 1.0)))
    if robustness:
        runs = max(20, round(200 * min(scale, 1.0)))
        kwargs = {"out": out, "runs": runs, "seed": seed, "angle_unit": angle_unit,
                  "engine": "serial" if split else "local"}  # fmt: skip
        jobs.append(Job("robustness", _robustness_job, kwargs, _COST["robustness"]))
    jobs.append(
        Job("rate_dependence", _rate_job, {"out": out, "angle_unit": angle_unit},
            _COST["rate_dependence"])
    )  # fmt: skip
    jobs.append(Job("models", _models_job, {"out": out}, _COST["models"]))
    return jobs


def _robustness_job(out: Path, runs: int, seed: int, angle_unit: str, engine: str, progress):
    if progress:
        progress("robustness study")
    return robustness_section(out, runs=runs, seed=seed, angle_unit=angle_unit, engine=engine)


def _rate_job(out: Path, progress, angle_unit: str = "deg"):
    if progress:
        progress("rate dependence")
    return rate_section(out, angle_unit=angle_unit)


def _models_job(out: Path, progress):
    if progress:
        progress("hysteresis models")
    return model_section(out)


#: the population study's committed figures (benchmarks/population.py), read when the demo
#: runs from a checkout of the repository
POPULATION_JSON = Path("benchmarks") / "results" / "population.json"
#: the pipelines the report lists from it, with the issue's targets (median, worst member)
POPULATION_TARGETS = {
    "sensorless (encoder loop where it helps)": (60.0, 13.0),
    "TipLoop, 1 ms": (500.0, 190.0),
    "TipLoop, 5 ms": (100.0, None),
    "AdaptiveController, 1 ms": (190.0, None),
}


def population_section(path: Path | None = None) -> tuple[str, dict] | None:
    """The population study's headline (every pipeline over drawn drives, median over
    members and the worst member) from its committed JSON, or None when there is none (a
    demo run outside the repository: ``python benchmarks/population.py`` writes it)."""
    import json

    from ..report import html

    path = POPULATION_JSON if path is None else path
    if not path.is_file():
        return None
    data = json.loads(path.read_text())
    pull = data["pull_pull"]
    rows = []
    for name, (median, worst) in POPULATION_TARGETS.items():
        got = pull[name]["median"]
        met = got["median"] >= median and (worst is None or got["worst"] >= worst)
        rows.append({
            "pipeline": name,
            "median over members": f"{got['median']:.3g}x",
            "worst member": f"{got['worst']:.3g}x",
            "demo's plant": f"{data['demo_member'][name]['median']:.3g}x",
            "target": f">= {median:g}x" + (f", worst >= {worst:g}x" if worst else "")
            + (" (met)" if met else " (not met)"),
        })  # fmt: skip
    body = (
        f"<p>MSE reduction over the uncompensated drive on {data['members']} simulated "
        "pull-pull drives drawn from documented priors "
        "(<code>ts.presets.random_realistic_plant</code>), each calibrated from its own logs "
        f"and judged on its own tests; a member's figure is its median over "
        f"{data['route_seeds']} route seeds. Read from <code>{path}</code> "
        "(<code>python benchmarks/population.py</code>); the scenarios below are one plant.</p>"
        + html.table(rows)
    )
    return body, {"source": str(path), "members": data["members"]}


def rate_section(out: Path, frequencies=(0.1, 1.0, 5.0), angle_unit: str = "deg"):
    """Loops of the do2015 drive at 0.1, 1 and 5 Hz: the realistic plant (every effect of
    presets) beside the capstan-only pair, which draws the same loop at any rate; the widths
    in the report's ``angle_unit``."""
    from ..bench.rate_dependence import hysteresis_loops, loops_figure
    from ..bench.scenarios.do import _COMMON, NOMINAL, physics, servo_motor
    from ..plant import PullPullPlant
    from ..plant.motor import Motor
    from ..report import figures, html

    plants = {
        "realistic": PullPullPlant(route=NOMINAL, motor=servo_motor(), **physics()),
        "capstan only": PullPullPlant(route=NOMINAL, motor=Motor.position(60.0, 0.8), **_COMMON),
    }
    numbers: dict[str, Any] = {"frequencies_hz": list(frequencies)}
    rows = []
    loops = {}
    for name, plant in plants.items():
        loops[name] = hysteresis_loops(plant, frequencies=frequencies, amplitude=1.0)
        widths = {f: loop.width for f, loop in loops[name].items()}
        numbers[name] = {"loop_width_rad": {f"{f:g}": w for f, w in widths.items()}}
        rows.append({"plant": name, **{f"width at {f:g} Hz": w for f, w in widths.items()}})
    data = figures.png(loops_figure(loops["realistic"], title="Realistic do2015 drive"))
    path = out / "rate_dependence.png"
    write_bytes(path, data)
    body = (
        "<p>The do2015 drive driven by a 1 rad sine at each rate through its servo (motor "
        "encoder in, distal angle out, last of three periods). The capstan-only pair is rate "
        "independent; the realistic plant (viscous sheath friction, tendon creep, a dynamic "
        "distal joint, motor friction and gear backlash: <code>tendonsheath.plant.presets</code>) "
        "widens its loop with rate, as measured drives do.</p>"
        + html.table(
            rows_in_unit(rows, angle_unit, {f"width at {f:g} Hz": "rad" for f in frequencies})
        )
        + html.figure(data, "Input-output loops of the realistic plant at 0.1, 1 and 5 Hz.")
    )
    return body, numbers, path


def robustness_section(
    out: Path, runs: int = 200, seed: int = 0, angle_unit: str = "deg", engine: str = "local"
):
    """Each do2015 compensator's MSE over ``runs`` draws of friction (+/-30 %), pretension
    (+/-30 %) and route (random arcs, total angle within +/-50 % of pi), all calibrated on
    the nominal plant: robustness, not one lucky run. ``engine``: the sweep's ("local": a
    process per core; "serial": this process)."""
    from ..bench.scenarios.do import _COMMON, NOMINAL, robustness_run
    from ..report import html
    from ..report.units import convert, rows_in_unit, unit_after
    from ..sweep.studies import robustness_design, robustness_study
    from ..sweep.studies import robustness_section as study_figure

    design = robustness_design(
        friction=_COMMON["friction"],
        pretension=_COMMON["pretension"],
        route_angle=NOMINAL.curve_angle,
    )
    result = robustness_study(
        run=robustness_run,
        n=runs,
        seed=2015 + seed,
        design=design,
        progress=False,
        engine=engine,
    )
    numbers = study_figure(
        result, out, metric="mse", bound=1e-4, design=design, angle_unit=angle_unit
    )
    bound = convert(1e-4, "rad^2", angle_unit)
    within = f"share with MSE <= {bound:.3g} {unit_after('rad^2', angle_unit)}"
    rows = [
        {
            "compensator": k,
            "median MSE": v.get("median"),
            "MSE 5 %": v.get("q05"),
            "MSE 95 %": v.get("q95"),
            "worst MSE": v.get("max"),
            within: None if v.get("within_bound") is None else 100 * v["within_bound"],
            "share with a limit cycle": (
                None if v.get("limit_cycle_share") is None else 100 * v["limit_cycle_share"]
            ),
        }
        for k, v in numbers["compensators"].items()
    ]
    rows = rows_in_unit(rows, angle_unit, {within: "%", "share with a limit cycle": "%"})
    body = (
        "<p>The do2015 comparison over perturbed plants: friction and pretension within "
        "+/-30 % of the plant the compensators were calibrated on (by bench.calibrate, on its "
        "calibration route), and a random-arc route whose "
        f"total angle is within +/-50 % of pi ({numbers['runs']} draws, seed "
        f"{numbers['seed']}; 10 s each). The adaptive controller here has a fixed "
        "design (bandwidth 8 Hz, from the nominal fit), not the one designed from loop "
        "calibration; the last column counts the runs in which the tip oscillated on its "
        "own (a limit cycle).</p>"
        + html.table(rows)
        + html.figure(
            Path(numbers["figure"]).read_bytes(),
            "MSE per compensator over the perturbed plants (log scale).",
        )
    )
    return ("robustness", f"Robustness over {numbers['runs']} perturbed plants", body, numbers)


__all__ = [
    "DEMO_SCHEMA_VERSION",
    "demo_models",
    "model_section",
    "population_section",
    "rate_section",
    "robustness_section",
    "run_demo",
    "standard_input",
]
