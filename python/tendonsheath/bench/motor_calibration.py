"""The motor calibration run: the servo's own dynamics from its command and encoder logs.

A motor-encoder loop (:class:`~tendonsheath.compensate.EncoderLoop`) is tuned on the servo it
closes around, tendons attached. The run drives the servo with a chirp on a slow ramp
(:func:`motor_calibration_input`) so that the tendons keep slipping one way (no dead-zone
crossing: the chirp's speed stays below the ramp's) while the command sweeps the servo's
bandwidth; only the command and the motor encoder are logged, and the servo is identified from
them (:func:`tendonsheath.identify.servo.identify_servo`). Nothing is read from the plant.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..identify.servo import ServoFit, identify_servo
from ..plant.sensor import Sensor

if TYPE_CHECKING:
    from ..plant import ContinuumPlant, PullPullPlant
    from ..plant.route import Route


def motor_calibration_input(
    duration: float = 10.0,
    span: float = 1.0,
    f_start: float = 1.0,
    f_stop: float = 100.0,
    speed_ratio: float = 0.8,
    rate: float = 1000.0,
) -> tuple[np.ndarray, np.ndarray]:
    """A logarithmic chirp from ``f_start`` to ``f_stop`` Hz on a ramp from -span to +span rad.

    The chirp's amplitude falls as 1/f so that its speed amplitude is ``speed_ratio`` times the
    ramp's speed: the command never reverses, so the tendons never cross their dead zone.

    Parameters
    ----------
    duration : float, default 10.0
        Length of the run (s), > 0.
    span : float, default 1.0
        The ramp goes from -span to +span (rad), > 0.
    f_start : float, default 1.0
        First frequency of the chirp (Hz), > 0.
    f_stop : float, default 100.0
        Last frequency (Hz), > f_start and below half the rate.
    speed_ratio : float, default 0.8
        Chirp speed amplitude over ramp speed, in (0, 1) to keep the command monotonic.
    rate : float, default 1000.0
        Samples per second.

    Returns
    -------
    t, command : numpy.ndarray of float
        Sample times (s) and the motor command (rad).

    Raises
    ------
    ValueError
        A value out of its range.
    """
    values = (duration, span, f_start, f_stop, speed_ratio, rate)
    if not all(math.isfinite(v) and v > 0 for v in values):
        raise ValueError(f"motor_calibration_input: every argument must be > 0 (got {values})")
    if not (f_stop > f_start and f_stop < 0.5 * rate and speed_ratio < 1.0):
        raise ValueError(
            "motor_calibration_input: needs f_start < f_stop < rate/2 and speed_ratio < 1"
        )
    t = np.arange(0.0, duration, 1.0 / rate)
    speed = 2.0 * span / duration
    growth = (f_stop / f_start) ** (1.0 / duration)  # frequency f_start growth^t
    frequency = f_start * growth**t
    phase = 2.0 * math.pi * f_start * (growth**t - 1.0) / math.log(growth)
    chirp = speed_ratio * speed / (2.0 * math.pi * frequency) * np.sin(phase)
    return t, -span + speed * t + chirp


@dataclass(frozen=True)
class MotorCalibration:
    """A motor calibration run and the servo identified from it.

    Parameters
    ----------
    servo : ServoFit
        The identified servo.
    t : numpy.ndarray of float
        Sample times (s).
    command : numpy.ndarray of float
        The commands sent (rad).
    encoder : numpy.ndarray of float
        The motor encoder (rad).
    """

    servo: ServoFit
    t: np.ndarray
    command: np.ndarray
    encoder: np.ndarray


def calibrate_servo(
    plant: PullPullPlant | ContinuumPlant,
    route: Route | None = None,
    *,
    duration: float = 10.0,
    span: float = 1.0,
    f_stop: float = 100.0,
) -> MotorCalibration:
    """Drive ``plant`` (the robot, bent into ``route``) through its own motor with
    :func:`motor_calibration_input`, log the command and the motor encoder, and identify the
    servo from those logs alone.

    Parameters
    ----------
    plant : PullPullPlant or ContinuumPlant
        The robot, with a position motor (only driven and logged, never read).
    route : Route, optional
        The calibration shape (default the plant's route).
    duration : float, default 10.0
        Length of the run (s).
    span : float, default 1.0
        The ramp's half span (rad).
    f_stop : float, default 100.0
        Highest chirp frequency (Hz).

    Returns
    -------
    MotorCalibration
        The logs and the identified servo.

    Raises
    ------
    ValueError
        The plant has no position motor.
    """
    motor = getattr(plant, "motor", None)
    if motor is None or motor.kind != "position":
        raise ValueError("calibrate_servo needs a plant driven by a position motor")
    t, command = motor_calibration_input(duration, span, f_stop=f_stop)
    encoder = _encoder(_drive(plant, route, t, command))
    return MotorCalibration(identify_servo(t, command, encoder), t, command, encoder)


def _drive(
    plant: PullPullPlant | ContinuumPlant, route: Route | None, t: np.ndarray, command: np.ndarray
) -> Any:
    """Simulate ``plant`` bent into ``route`` (default its own) driven by ``command``; the
    plant's route is restored."""
    previous = plant.route
    if route is not None:
        plant.set_route(route)
    try:
        return plant.simulate(t, command)
    finally:
        plant.set_route(previous)


def _encoder(sim: Any) -> np.ndarray:
    """The motor encoder: the motor shaft angle (q_motor on plants that model gear play)."""
    return np.asarray(getattr(sim, "q_motor", sim.q_in), dtype=float)


def run_experiment(
    plant: PullPullPlant | ContinuumPlant,
    route: Route | None,
    t: np.ndarray,
    command: np.ndarray,
    sensor: Sensor | None,
    seed: int,
) -> tuple[np.ndarray, np.ndarray]:
    """One calibration experiment on the robot bent into ``route``; returns (encoder, distal
    reading). The distal reading is the rig's sensor (a fresh copy of ``sensor`` with its own
    seed, reading the output with its latency, quantisation and noise), or the plant's own
    sensor."""
    sim = _drive(plant, route, t, command)
    if sensor is not None:
        rig = Sensor(sensor.resolution, sensor.noise_std, seed, sensor.delay, sensor.history)
        reading = rig.measure(sim.q_out, t=t) if sensor.delay > 0 else rig.measure(sim.q_out)
    else:
        reading = sim.measured
    return _encoder(sim), np.asarray(reading, dtype=float)


__all__ = ["MotorCalibration", "calibrate_servo", "motor_calibration_input"]
