"""The loop calibration run: a tip-feedback loop's dynamics from command, encoder and tip logs.

A controller closed on a tip sensor is tuned on the servo, the distal resonance and the
sensor's delay (:class:`~tendonsheath.identify.loop_dynamics.LoopDynamics`). The run is the
motor calibration's chirp on a ramp (:func:`~tendonsheath.bench.motor_calibration.
motor_calibration_input`) made faster and wider: the ramp's speed bounds the chirp's amplitude
(the command must stay monotonic so the tendons never reverse through their dead zone), and the
tip's response around the distal resonance must stand well above the tip sensor's noise. The
robot is driven through its own position motor; the command, the motor encoder and the tip
sensor (its latency, quantisation and noise) are logged, and the dynamics are identified from
those logs alone (:func:`~tendonsheath.identify.loop_dynamics.identify_loop_dynamics`).
Nothing is read from the plant.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..identify.loop_dynamics import (
    EmpiricalResponse,
    LoopDynamics,
    empirical_response,
    identify_loop_dynamics,
)
from ..plant.sensor import Sensor
from .motor_calibration import motor_calibration_input, run_experiment

if TYPE_CHECKING:
    from ..plant import ContinuumPlant, PullPullPlant
    from ..plant.route import Route


def loop_calibration_input(
    duration: float = 5.0,
    span: float = 1.5,
    f_start: float = 5.0,
    f_stop: float = 120.0,
    speed_ratio: float = 0.9,
    rate: float = 1000.0,
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`~tendonsheath.bench.motor_calibration.motor_calibration_input` with the loop's
    defaults: a logarithmic chirp from 5 to 120 Hz on a ramp from -1.5 to +1.5 rad in 5 s.

    The chirp's amplitude is ``speed_ratio`` times the ramp's speed over 2 pi f (the most a
    monotonic command allows): with these defaults 0.9 * 0.6 / (2 pi 40) = 2.1e-3 rad at 40 Hz,
    11 times a 2e-4 rad tip sensor's noise (more at a resonance), 1.4e-3 rad at 60 Hz. A faster
    ramp (``span`` / ``duration``) buys amplitude at every frequency; the span is kept within
    a joint's usual range (+-1.5 rad), the duration gives the fit about 5000 samples.

    Parameters
    ----------
    duration : float, default 5.0
        Length of the run (s), > 0.
    span : float, default 1.5
        The ramp goes from -span to +span (rad), > 0.
    f_start : float, default 5.0
        First frequency of the chirp (Hz), > 0.
    f_stop : float, default 120.0
        Last frequency (Hz), > f_start and below half the rate.
    speed_ratio : float, default 0.9
        Chirp speed amplitude over ramp speed, in (0, 1): the command stays monotonic.
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
    return motor_calibration_input(duration, span, f_start, f_stop, speed_ratio, rate)


@dataclass(frozen=True)
class LoopCalibration:
    """A loop calibration run and the dynamics identified from it.

    Parameters
    ----------
    dynamics : LoopDynamics
        The identified loop.
    t : numpy.ndarray of float
        Sample times (s).
    command : numpy.ndarray of float
        The commands sent (rad).
    encoder : numpy.ndarray of float
        The motor encoder (rad).
    tip : numpy.ndarray of float
        The tip sensor's reading (rad).
    """

    dynamics: LoopDynamics
    t: np.ndarray
    command: np.ndarray
    encoder: np.ndarray
    tip: np.ndarray

    def empirical(self, nperseg: int | None = None) -> EmpiricalResponse:
        """The empirical command -> tip response of the logs (H1 with coherence, see
        :func:`~tendonsheath.identify.loop_dynamics.empirical_response`): the check of
        ``dynamics.frequency_response`` where the coherence is high.

        Parameters
        ----------
        nperseg : int, optional
            Samples per Welch segment (default a second's worth).

        Returns
        -------
        EmpiricalResponse
            Frequencies, H1 and coherence.
        """
        return empirical_response(self.t, self.command, self.tip, nperseg)


def calibrate_loop(
    plant: PullPullPlant | ContinuumPlant,
    route: Route | None = None,
    sensor: Sensor | None = None,
    *,
    duration: float = 5.0,
    span: float = 1.5,
    f_start: float = 5.0,
    f_stop: float = 120.0,
    seed: int = 0,
    max_delay: int = 20,
    highpass_hz: float = 2.0,
) -> LoopCalibration:
    """Drive ``plant`` (bent into ``route``) through its own position motor with
    :func:`loop_calibration_input`, log the command, the motor encoder and the tip ``sensor``,
    and identify the loop's dynamics from those logs alone.

    Parameters
    ----------
    plant : PullPullPlant or ContinuumPlant
        The robot, with a position motor (only driven and logged, never read).
    route : Route, optional
        The calibration shape (default the plant's route).
    sensor : Sensor, optional
        The tip sensor (latency, resolution, noise); a fresh copy seeded with ``seed`` reads
        the output. Default the plant's own sensor.
    duration : float, default 5.0
        Length of the run (s).
    span : float, default 1.5
        The ramp's half span (rad).
    f_start : float, default 5.0
        First chirp frequency (Hz).
    f_stop : float, default 120.0
        Last chirp frequency (Hz).
    seed : int, default 0
        Seed of the sensor's noise.
    max_delay : int, default 20
        The largest distal delay tried (samples).
    highpass_hz : float, default 2.0
        The dynamics are fitted above this frequency (Hz).

    Returns
    -------
    LoopCalibration
        The logs and the identified dynamics; a resonance only within the chirp's band
        (``f_start`` to ``f_stop``): a drive with no mode there gets none (``resonance_hz``
        inf, and a ResonanceOutOfBandWarning).

    Raises
    ------
    ValueError
        The plant has no position motor, or the logs cannot identify the loop (a distal mode
        below ``f_start`` included).
    """
    motor = getattr(plant, "motor", None)
    if motor is None or motor.kind != "position":
        raise ValueError("calibrate_loop needs a plant driven by a position motor")
    if sensor is not None and not isinstance(sensor, Sensor):
        raise ValueError("calibrate_loop: sensor must be a tendonsheath.Sensor or None")
    t, command = loop_calibration_input(duration, span, f_start, f_stop)
    encoder, tip = run_experiment(plant, route, t, command, sensor, seed)
    dynamics = identify_loop_dynamics(
        t, command, encoder, tip, max_delay, highpass_hz, band_hz=(f_start, f_stop)
    )
    return LoopCalibration(dynamics, t, command, encoder, tip)


__all__ = ["LoopCalibration", "calibrate_loop", "loop_calibration_input"]
