"""Trials: run a candidate compensator on the robot and score it on what the sensors measure.

A tuner chooses among designs by running them; so does a user comparing two compensators on
their robot. Either way the score must come from the sensors (the tip sensor's reading, with
its noise and latency), never from the simulator's true output, which no robot gives::

    trial = ts.bench.calibration_trial(plant, calibration_routes, sensor, amplitude=1.0)
    trial(candidate)          # the measured mean squared error (inf: diverged or saturated)
    trial.run(candidate)      # the whole bench Result

:class:`Trial` holds one experiment (plant, reference, routes, sensor);
:func:`calibration_trial` is the tuners' one: the calibration excitation while the robot is
switched among its calibration shapes, never a test route.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._util.units import DELAY, warn_if_unit_slip
from ..plant.route import Route
from ..plant.sensor import Sensor
from .calibration import calibration_input
from .run import Result, run

#: seconds between the calibration shapes of a calibration trial
SWITCH_EVERY = 2.5


def measured_mse(result: Result, delay: float = 0.0) -> float:
    """The mean squared error the sensor shows: its reading against the reference as it was
    ``delay`` seconds before (the reading's latency), over the scored samples; NaN readings
    (dropouts) left out.

    Parameters
    ----------
    result : Result
        A bench run.
    delay : float, default 0.0
        The sensor's latency (s), >= 0.

    Returns
    -------
    float
        The measured MSE (the sensor's noise included: it is what a robot sees).
    """
    if not (delay >= 0.0 and math.isfinite(delay)):
        raise ValueError(f"measured_mse: delay must be finite and >= 0 (got {delay})")
    warn_if_unit_slip(delay, "measured_mse", "delay", DELAY)
    t, reference = result.t, result.reference
    shifted = np.interp(t - delay, t, reference)
    err = (result.measured - shifted)[result.scored]
    err = err[np.isfinite(err)]
    if err.size == 0:
        return math.inf
    return float(np.mean(err**2))


@dataclass
class Trial:
    """One trial experiment on ``plant``: ``reference`` at times ``t`` with the route changes
    ``routes`` (None: the plant's route), read by ``sensor``; a compensator that follows the
    route is told the sensed shape (``shape_sensing``). Calling it runs a candidate and
    returns its measured MSE (:func:`measured_mse`), inf when the loop diverged or the
    command saturated (a trial that needs the limits has failed).

    Parameters
    ----------
    plant : Plant
        The robot (with its motor).
    t, reference : numpy.ndarray
        The trial's reference.
    sensor : Sensor
        The sensor the score reads (its latency is compensated for in the score).
    routes : callable, optional
        t -> Route.
    shape_sensing : ShapeSensing, optional
        What a route-following candidate is told of the shape.
    warmup : float, optional
        Seconds left out of the score (default: bench.run's).
    """

    plant: Any
    t: np.ndarray
    reference: np.ndarray
    sensor: Sensor
    routes: Any = None
    shape_sensing: Any = None
    warmup: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.sensor, Sensor):
            raise TypeError(
                f"Trial: sensor must be a tendonsheath.Sensor (got {type(self.sensor).__name__})"
                ": a trial is scored on what a sensor measures"
            )

    def run(self, candidate: Any) -> Result:
        """The bench run of ``candidate`` (None: uncompensated).

        Parameters
        ----------
        candidate : compensator or None
            What to run.

        Returns
        -------
        Result
            The whole bench run (its metrics are on the true output: the score is not).
        """
        sensing = self.shape_sensing if getattr(candidate, "follows_route", False) else None
        return run(
            self.plant,
            candidate,
            self.t,
            self.reference,
            routes=self.routes,
            noise=self.sensor,
            shape_sensing=sensing,
            warmup=self.warmup,
        )

    def score(self, candidate: Any) -> float:
        """The measured MSE of ``candidate``; inf when it diverged or saturated.

        Parameters
        ----------
        candidate : compensator or None
            What to run.

        Returns
        -------
        float
            :func:`measured_mse` of the run (rad^2), or inf.
        """
        try:
            result = self.run(candidate)
        except RuntimeError:  # the closed loop produced a non-finite output
            return math.inf
        if result.metrics["status"]["saturated"]:
            return math.inf
        return measured_mse(result, self.sensor.delay)

    __call__ = score


def calibration_trial(
    plant: Any,
    routes: Sequence[Route],
    sensor: Sensor,
    *,
    duration: float = 20.0,
    amplitude: float = 1.0,
    switch_every: float = SWITCH_EVERY,
    shape_sensing: Any = None,
    speed: float = 1.0,
) -> Trial:
    """The tuners' trial: the calibration excitation (:func:`calibration_input`, ``duration``
    s at ``amplitude``) while the robot switches among its calibration shapes ``routes`` every
    ``switch_every`` s, read by ``sensor``.

    Parameters
    ----------
    plant : Plant
        The robot.
    routes : sequence of Route
        The calibration shapes (never a test route).
    sensor : Sensor
        The tip sensor the trial is scored on.
    duration : float, default 20.0
        Length of the trial (s).
    amplitude : float, default 1.0
        The excitation's amplitude (rad, as the reference).
    switch_every : float, default 2.5
        Seconds between shape changes.
    shape_sensing : ShapeSensing, optional
        What a route-following candidate is told of the shape.
    speed : float, default 1.0
        The excitation played this many times faster (its 0.25 Hz at 0.25 x speed Hz), > 0:
        a second trial at another speed tells a part that helps at one rate only.

    Returns
    -------
    Trial
        Call it with a candidate for its measured MSE.
    """
    routes = list(routes)
    if not routes:
        raise ValueError("calibration_trial: give at least one calibration shape")
    if not (switch_every > 0.0 and math.isfinite(switch_every)):
        raise ValueError(f"calibration_trial: switch_every must be > 0 s (got {switch_every})")
    if not (speed > 0.0 and math.isfinite(speed)):
        raise ValueError(f"calibration_trial: speed must be > 0 (got {speed})")
    t, reference = calibration_input(duration, amplitude)
    if speed != 1.0:  # the same excitation, time-compressed, on the same 1 kHz grid
        t_full, full = calibration_input(duration * speed, amplitude)
        reference = np.interp(t * speed, t_full, full)
    edges = np.arange(0.0, duration, switch_every)
    shapes = [routes[i % len(routes)] for i in range(edges.size)]

    def route_at(time: float) -> Route:
        return shapes[int(np.searchsorted(edges, time, side="right")) - 1]

    return Trial(plant, t, reference, sensor, routes=route_at, shape_sensing=shape_sensing)


#: a richer candidate is chosen only when its trial error is below this share of the simpler
#: one's (a gain smaller than the trials' own spread is no gain)
KEEP_BELOW = 0.95


@dataclass
class Choice:
    """What :func:`choose` chose, and why.

    Parameters
    ----------
    name : str
        The chosen candidate's name.
    chosen : object
        The chosen candidate.
    scores : dict of str to float
        Each candidate's trial error (rad^2; inf: diverged or saturated).
    reason : str
        One line: the scores and the rule.
    all_scores : list of dict, optional
        Each trial's errors, by candidate.
    """

    name: str
    chosen: Any
    scores: dict[str, float]
    reason: str
    all_scores: list[dict[str, float]] = field(default_factory=list)


def choose(candidates: dict[str, Any], trials: Any, keep_below: float = KEEP_BELOW) -> Choice:
    """The simplest candidate that no richer one beats on the trials: candidates are given
    simplest first (e.g. the feedforward alone, then inside an EncoderLoop); a later one is
    chosen only when its error is below ``keep_below`` times the chosen one's so far on
    *every* trial (one trial is one excitation; a part that helps on one and hurts on another
    is not shown to help). A part that does not help on calibration trials is thus left out,
    and the reason says so.

    Parameters
    ----------
    candidates : dict of str to compensator
        Name -> candidate, simplest first.
    trials : callable or sequence of callables
        candidate -> its measured error (a :class:`Trial`), one or several.
    keep_below : float, default 0.95
        The share of the simpler candidate's error a richer one must get below, in (0, 1].

    Returns
    -------
    Choice
        The chosen candidate, its scores (each candidate's worst ratio is decided on every
        trial; ``scores`` holds the first trial's errors, ``all_scores`` every trial's) and
        the reason.
    """
    if not candidates:
        raise ValueError("choose: give at least one candidate")
    if not 0.0 < keep_below <= 1.0:
        raise ValueError(f"choose: keep_below must be in (0, 1] (got {keep_below})")
    trials = list(trials) if isinstance(trials, list | tuple) else [trials]
    if not trials:
        raise ValueError("choose: give at least one trial")
    table = [{name: float(trial(c)) for name, c in candidates.items()} for trial in trials]
    best = next(iter(candidates))
    for name in list(candidates)[1:]:
        if all(row[name] < keep_below * row[best] for row in table):
            best = name
    listed = "; ".join(", ".join(f"{n} {v:.3g}" for n, v in row.items()) for row in table)
    left_out = [n for n in candidates if n != best]
    every = " on every trial" if len(table) > 1 else ""
    reason = (
        f"trial error (rad^2): {listed}; chosen: {best} (a richer candidate must get below "
        f"{keep_below:g} x the simpler one's{every})"
        + (f"; left out: {', '.join(left_out)}" if left_out else "")
    )
    return Choice(best, candidates[best], table[0], reason, table)


__all__ = [
    "KEEP_BELOW",
    "SWITCH_EVERY",
    "Choice",
    "Trial",
    "calibration_trial",
    "choose",
    "measured_mse",
]
