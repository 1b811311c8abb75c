"""Pieces the built-in scenarios share: results, calibration runs, route schedules."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...plant.route import Route
from ...plant.sensor import Sensor
from ..calibration import calibration_input  # noqa: F401 (re-exported)
from ..frequency import FrequencyResponse
from ..limit_cycle import describe
from ..run import Result


@dataclass
class ScenarioResult:
    """One scenario's outcome: the comparison runs, a metrics table with the paper's numbers
    beside ours, and what the report needs to show (routes, calibration, frequency response)."""

    name: str
    title: str
    summary: str
    conditions: dict[str, Any]
    runs: dict[str, Result]
    table: list[dict[str, Any]]
    paper: dict[str, Any]
    routes: dict[str, Route] = field(default_factory=dict)
    route_schedule: list[tuple[float, float]] = field(default_factory=list)
    calibration: dict[str, Any] = field(default_factory=dict)
    frequency: dict[str, FrequencyResponse] = field(default_factory=dict)
    extra: dict[str, Any] = field(default_factory=dict)
    protocol: str = ""  # how the compensators were calibrated and judged (the report's intro)
    honesty: dict[str, Any] = field(default_factory=dict)  # compensator -> honesty panel row
    identified: list[dict[str, Any]] = field(default_factory=list)  # identified groups, report
    # the paper's headline claims checked: {claim, target, measured, met}; a miss is reported
    targets: list[dict[str, Any]] = field(default_factory=list)
    table_title: str = "Results beside the paper"
    # unit of the table's columns whose key does not say it (e.g. one column per compensator)
    table_units: dict[str, str] = field(default_factory=dict)

    @property
    def metrics(self) -> dict[str, dict[str, Any]]:
        """compensator -> metric -> value, for metrics.json: each run's ``metrics`` field."""
        return {name: dict(result.metrics) for name, result in self.runs.items()}


def first_paragraph(doc: str) -> str:
    """A docstring's first paragraph as one line (the report's scenario summary)."""
    return " ".join(doc.strip().split("\n\n")[0].split())


def announce(progress: Callable[[str], Any] | None, step: str) -> None:
    """Tell ``progress`` (a callable, or None for silence) that ``step`` begins."""
    if progress:
        progress(step)


def calibrated(name: str, calibrate: Callable, scale: float, seed: int, progress=None):
    """A built-in scenario's calibration protocol ``calibrate(seed, budget)`` run at the
    identification budget of ``scale``: (calibration, budget)."""
    announce(progress, f"{name}: calibration")
    budget = identification_budget(scale)
    return calibrate(seed, budget), budget


#: the identified table's column of the simulated plant's own values
PLANT_VALUE = "the plant's value (never told)"


def scenario_result(
    scenario: Callable, cal, plant_values: dict[str, str] | None = None, **fields
) -> ScenarioResult:
    """A built-in scenario's result: named after its function, summarised by the first
    paragraph of its docstring, listing the groups ``cal`` identified; with ``plant_values``
    (group -> the simulated plant's value, as text) beside each group, and a model class's
    parameters marked as having none (the plant lies outside every model class). Only the
    report shows them: no compensator is built from them."""
    rows = cal.identified_rows()
    if plant_values:
        for row in rows:
            quantity = row["quantity"]
            row[PLANT_VALUE] = plant_values.get(quantity) or (
                "none: the plant is outside the model class" if quantity in cal_model_rows(cal)
                else "-"
            )  # fmt: skip
    return ScenarioResult(
        name=scenario.__name__,
        summary=first_paragraph(scenario.__doc__ or ""),
        identified=rows,
        **fields,
    )


def cal_model_rows(cal) -> set[str]:
    """The identified table's rows that are a model class's parameters (no plant value)."""
    return {f"{name} {k}" for name, fit in cal.fits.items() for k in fit.model.params}


def encoder(noise_std: float = 2e-4, resolution: float = 1e-4, seed: int = 1) -> Sensor:
    """The distal sensor of the scenarios: an encoder with Gaussian noise."""
    return Sensor(resolution=resolution, noise_std=noise_std, seed=seed)


def target(
    claim: str, target: str, measured: float, met: bool, unit: str = "", seen: str = ""
) -> dict:
    """One paper claim checked on this run (a row of the report's "Paper targets" table);
    ``seen``: what the runs also show that the figure does not (a limit cycle, saturation)."""
    return {
        "claim": claim,
        "target": target,
        "measured": float(measured),
        "unit": unit,
        "met": bool(met),
        "seen": seen,
    }


def runs_seen(runs: list) -> dict[str, Any]:
    """What a controller's runs show besides their error: ``seen``, its limit cycles (the
    strongest named) and saturated cycles as one phrase; ``limit_cycle``, whether any run had
    one; ``limit_cycle_runs`` and ``runs``, how many had one of how many; and
    ``saturated_cycles``, their saturated cycles together."""
    cycles = [r.metrics["limit_cycle"] for r in runs if r.metrics["limit_cycle"]["detected"]]
    saturated = int(sum(r.metrics["status"]["saturated"] for r in runs))
    parts = []
    if cycles:
        worst = max(cycles, key=lambda c: c["output_reversals"])
        parts.append(f"{describe(worst)} in {len(cycles)} of {len(runs)} runs")
    if saturated:
        cycles_total = sum(r.t.size for r in runs)
        parts.append(f"command saturated on {saturated} of {cycles_total} cycles")
    return {
        "seen": "; ".join(parts),
        "limit_cycle": bool(cycles),
        "limit_cycle_runs": len(cycles),
        "runs": len(runs),
        "saturated_cycles": saturated,
    }


def honesty_panel(
    cal,
    runs: dict[str, Result],
    *,
    curve_angle=None,
    load: str | None = "calibrated",
    told: dict[str, dict[str, tuple[Any, str]]] | None = None,
    seed: int = 0,
    budget: dict | None = None,
    calibrations: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """compensator -> what it was told (and where from), parameters at their bounds, and the
    best in-class fit on its own test run next to the output range. ``calibrations``: the
    calibration a compensator was built from, where it is not ``cal``."""
    from ..calibration import honesty_entry

    panel = {}
    for name, result in runs.items():
        declared = dict((told or {}).get(name, {}))
        own = (calibrations or {}).get(name, cal)
        if name == "none" or own is None:  # None: only user compensators, nothing calibrated
            rows = [{"quantity": k, "value": v, "source": src} for k, (v, src) in declared.items()]
            bounds = []
        else:
            rows = own.told(name, load=load, **declared)
            bounds = own.bounds_of(name)
        panel[name] = honesty_entry(
            name, result, rows, bounds, curve_angle=curve_angle, seed=seed, budget=budget
        )
    return panel


def kinematic_told(plant) -> dict[str, tuple[Any, str]]:
    """The uncompensated drive's only input: the kinematic ratio of its pulleys (a plant
    without pulley radii: its kinematic_gain)."""
    if not (hasattr(plant, "distal_radius") and hasattr(plant, "proximal_radius")):
        from ..plant_loop import BenchPlant

        gain = (
            BenchPlant(plant).kinematic_gain,
            "the plant's kinematic_gain (the uncompensated command)",
        )
        return {"kinematic gain": gain}
    return {
        "kinematic gain r_d/r_p": (
            plant.distal_radius / plant.proximal_radius,
            "design ratio of the pulleys (the uncompensated command)",
        )
    }


def piecewise_routes(times: list[float], routes: list[Route]) -> Callable[[float], Route]:
    """A route schedule: routes[i] from times[i] on (times[0] must be the start)."""
    edges = np.asarray(times, dtype=float)

    def at(t: float) -> Route:
        return routes[int(np.searchsorted(edges, t, side="right")) - 1]

    return at


def ratio(a: float, b: float) -> float:
    return float(a / b) if b > 0 else float("inf")


def identification_budget(scale: float) -> dict[str, int]:
    """Differential-evolution budget of the calibrations: the default for full runs, a
    smaller search for shortened ones (tests)."""
    return {} if scale >= 1.0 else {"maxiter": 40, "popsize": 10}


__all__ = [
    "PLANT_VALUE",
    "ScenarioResult",
    "announce",
    "cal_model_rows",
    "calibrated",
    "encoder",
    "first_paragraph",
    "honesty_panel",
    "identification_budget",
    "kinematic_told",
    "piecewise_routes",
    "ratio",
    "runs_seen",
    "scenario_result",
    "target",
]
