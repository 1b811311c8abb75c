"""Pieces the built-in scenarios share: results, calibration runs, route schedules."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...route import Route
from ...sensor import Sensor
from ..frequency import FrequencyResponse
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

    def metrics(self) -> dict[str, dict[str, float]]:
        """compensator -> metric -> value, for metrics.json."""
        return {name: dict(result.metrics) for name, result in self.runs.items()}


def encoder(noise_std: float = 2e-4, resolution: float = 1e-4, seed: int = 1) -> Sensor:
    """The distal sensor of the scenarios: an encoder with Gaussian noise."""
    return Sensor(resolution=resolution, noise_std=noise_std, seed=seed)


def calibration_input(duration: float, amplitude: float, rate: float = 1000.0):
    """A calibration excitation unlike the test references: a 0.15 Hz sine whose amplitude
    sweeps from full to a third and back, plus a 0.9 Hz ripple (nested minor loops)."""
    t = np.arange(0.0, duration, 1.0 / rate)
    envelope = amplitude * (1.0 - (2.0 / 3.0) * np.sin(np.pi * t / duration))
    x = envelope * np.sin(2 * np.pi * 0.15 * t) + 0.08 * amplitude * np.sin(2 * np.pi * 0.9 * t)
    return t, x


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
