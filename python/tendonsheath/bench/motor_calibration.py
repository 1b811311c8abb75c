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
    from ..plant import ContinuumPlant, PullPullPlant, SingleTendonPlant
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
    plant: PullPullPlant | ContinuumPlant | SingleTendonPlant,
    route: Route | None,
    t: np.ndarray,
    command: np.ndarray,
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
    plant: PullPullPlant | ContinuumPlant | SingleTendonPlant,
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


@dataclass
class TorqueMotorCalibration:
    """A torque motor identified from its torque command and encoder logs: inertia J and
    viscous damping b at the shaft (and the rest of the regression: Coulomb friction, the
    tendons' mean stiffness and an offset), with their standard errors.

    Parameters
    ----------
    inertia, viscous : float
        J (kg m^2) and b (N m s/rad) identified.
    inertia_se, viscous_se : float
        Their standard errors.
    coulomb, stiffness : float
        The Coulomb friction (N m) and the tendons' stiffness seen at the shaft (N m/rad).
    t, torque, encoder : numpy.ndarray
        The logs.
    """

    inertia: float
    viscous: float
    inertia_se: float
    viscous_se: float
    coulomb: float
    stiffness: float
    t: np.ndarray
    torque: np.ndarray
    encoder: np.ndarray

    def summary(self) -> str:
        """One line: the identified J and b with their standard errors.

        Returns
        -------
        str
            The summary.
        """
        return (
            f"torque motor identified from a torque chirp: J = {self.inertia:.3g} +/- "
            f"{self.inertia_se:.2g} kg m^2, b = {self.viscous:.3g} +/- {self.viscous_se:.2g} "
            "N m s/rad"
        )


def torque_calibration_input(
    duration: float = 6.0,
    amplitude: float = 2.0,
    f_start: float = 1.0,
    f_stop: float = 15.0,
    rate: float = 1000.0,
) -> tuple[np.ndarray, np.ndarray]:
    """A torque chirp (N m): ``amplitude`` from ``f_start`` to ``f_stop`` Hz (logarithmic)."""
    from scipy.signal import chirp

    t = np.arange(0.0, duration, 1.0 / rate)
    return t, amplitude * chirp(t, f_start, duration, f_stop, method="logarithmic")


def calibrate_torque_motor(
    plant: PullPullPlant | ContinuumPlant,
    route: Route | None = None,
    *,
    duration: float = 6.0,
    amplitude: float = 2.0,
) -> TorqueMotorCalibration:
    """Drive ``plant`` through its torque motor with a torque chirp
    (:func:`torque_calibration_input`), log the torque and the motor encoder, and identify the
    shaft's inertia and damping by least squares on
    tau = J q'' + b q' + c sgn(q') + k q + d, the encoder's derivatives from a
    Savitzky-Golay filter (the tendons act as the spring k and part of c). Nothing is read
    from the plant but its logs.

    Parameters
    ----------
    plant : PullPullPlant or ContinuumPlant
        The robot, with a torque motor.
    route : Route, optional
        The calibration shape (default the plant's route).
    duration : float, default 6.0
        Length of the run (s).
    amplitude : float, default 2.0
        The chirp's amplitude (N m).

    Returns
    -------
    TorqueMotorCalibration
        J and b with their standard errors, and the logs.

    Raises
    ------
    ValueError
        The plant has no torque motor, or the logs do not determine J and b.
    """
    from scipy.signal import savgol_filter

    motor = getattr(plant, "motor", None)
    if motor is None or motor.kind != "torque":
        raise ValueError("calibrate_torque_motor needs a plant driven by a torque motor")
    t, torque = torque_calibration_input(duration, amplitude)
    encoder = _encoder(_drive(plant, route, t, torque))
    dt = float(t[1] - t[0])
    window = 41  # 41 ms: smooths a count's steps, far below the chirp's 15 Hz top
    q = savgol_filter(encoder, window, 3)
    qd = savgol_filter(encoder, window, 3, deriv=1, delta=dt)
    qdd = savgol_filter(encoder, window, 3, deriv=2, delta=dt)
    keep = slice(window, -window)
    a = np.column_stack([qdd, qd, np.tanh(qd / 1e-2), q, np.ones_like(q)])[keep]
    b = torque[keep]
    coef, *_ = np.linalg.lstsq(a, b, rcond=None)
    resid = b - a @ coef
    dof = max(b.size - a.shape[1], 1)
    cov = np.linalg.pinv(a.T @ a) * float(resid @ resid) / dof
    se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    if not (coef[0] > 0.0 and coef[0] > 3.0 * se[0]):
        raise ValueError(
            f"calibrate_torque_motor: the logs do not determine the inertia (J = {coef[0]:.3g} "
            f"+/- {se[0]:.2g}): use a longer run or a larger amplitude"
        )
    return TorqueMotorCalibration(
        inertia=float(coef[0]),
        viscous=float(max(coef[1], 0.0)),
        inertia_se=float(se[0]),
        viscous_se=float(se[1]),
        coulomb=float(coef[2]),
        stiffness=float(coef[3]),
        t=t,
        torque=torque,
        encoder=encoder,
    )


__all__ = [
    "MotorCalibration",
    "TorqueMotorCalibration",
    "calibrate_servo",
    "calibrate_torque_motor",
    "motor_calibration_input",
    "torque_calibration_input",
]
