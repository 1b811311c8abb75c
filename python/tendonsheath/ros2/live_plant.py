"""A simulated drive stepped in real time, with no ROS in it: what the plant node runs.

Each step takes the last command (held between commands, as a servo amplifier holds its
set-point) and the real time since the previous step, runs the plant with its motor, and
reads it as a robot would: the motor encoder (its resolution and noise), the tip sensor (its
noise and latency) and the tendons' torque on the drive (the load a motor-current or torque
sensor reads). Where the plants come from: :func:`plant_source`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ..plant.motor import Motor
from ..plant.presets import random_realistic_plant, realistic_motor, realistic_plant
from ..plant.pull_pull import PullPullPlant
from ..plant.route import Route
from ..plant.sensor import Sensor
from ..status import Status

#: The presets :func:`plant_source` builds by name.
PRESETS = ("realistic", "ideal")


@dataclass
class Reading:
    """What the drive's sensors read after one step (and the truth, for a simulation).

    Parameters
    ----------
    tip : float
        The tip sensor's reading (rad; noise, resolution and latency included).
    motor : float
        The motor encoder's reading (rad).
    load : float
        The tendons' torque on the drive (N m).
    output : float
        The true output (rad): what no robot measures, for scoring a simulation.
    status : Status
        The plant's, motor's and sensors' flags.
    """

    tip: float
    motor: float
    load: float
    output: float
    status: Status


class LivePlant:
    """A plant (with its motor) and its sensors, stepped one real-time sample at a time.

    Parameters
    ----------
    plant : PullPullPlant, ContinuumPlant or SingleTendonPlant
        The drive, with its motor (``motor=``) and, optionally, its encoder (``encoder=``).
    tip_sensor : Sensor, optional
        The tip sensor (default the plant's own ``sensor``, else an exact reading).

    Raises
    ------
    TypeError
        A plant without the streaming members, or a sensor of the wrong kind.
    """

    def __init__(self, plant: Any, tip_sensor: Sensor | None = None):
        for member in ("reset", "step", "input", "output"):
            if not callable(getattr(plant, member, None)):
                raise TypeError(f"LivePlant: the plant {type(plant).__name__} has no {member}()")
        tip_sensor = tip_sensor if tip_sensor is not None else getattr(plant, "sensor", None)
        for what, sensor in (("tip_sensor", tip_sensor), ("encoder", plant.encoder)):
            if sensor is not None and not isinstance(sensor, Sensor):
                raise TypeError(f"LivePlant: {what} must be a tendonsheath.Sensor or None")
        self.plant = plant
        self.tip_sensor = tip_sensor
        self.reset()

    def reset(self) -> None:
        """Back to rest at a command of 0, the sensors' noise sequences restarted, and the
        sensors' first reading of the rest (:attr:`reading`), as bench.run reads it."""
        self.plant.reset()
        self.plant.step(0.0, 0.0)  # the rest state: at 0, so the first move crosses the play
        self._tip = self.tip_sensor.engine() if self.tip_sensor is not None else None
        enc = self.plant.encoder
        self._encoder = enc.engine() if enc is not None else None
        self.reading = self._read(float(self.plant.output()), 0.0, Status.OK)

    reading: Reading  # the last reading (of the rest after reset)

    def set_route(self, route: Route | float) -> None:
        """Bend the drive: a Route of the plant's length, or a curve angle (rad, a uniform
        bend of that length).

        Parameters
        ----------
        route : Route or float
            The new route, or its curve angle.

        Raises
        ------
        ValueError
            A negative or non-finite angle, or a route of another length.
        """
        if not isinstance(route, Route):
            angle = float(route)
            if not (math.isfinite(angle) and angle >= 0):
                raise ValueError(f"a curve angle must be finite and >= 0 rad (got {angle:g})")
            route = Route.uniform(self.plant.route.length, angle)
        self.plant.set_route(route)

    def step(self, command: float, dt: float) -> Reading:
        """One sample: ``command`` held for ``dt`` seconds.

        Parameters
        ----------
        command : float
            The command (rad; N m for a torque motor); NaN holds the output.
        dt : float
            Real time since the previous step (s), >= 0.

        Returns
        -------
        Reading
            The sensors' readings and the true output.
        """
        out = float(self.plant.step(float(command), float(dt)))
        self.reading = self._read(out, float(dt), Status(int(self.plant.status())))
        return self.reading

    def _read(self, out: float, dt: float, status: Status) -> Reading:
        """The sensors' readings of the plant now (``dt``: since their last reading)."""
        tip = out
        if self._tip is not None:
            tip = float(self._tip.measure(out, dt))
            status |= Status(int(self._tip.status()))
        shaft = getattr(self.plant, "motor_position", None)
        q = float(shaft() if callable(shaft) else self.plant.input())
        if self._encoder is not None:
            q = float(self._encoder.measure(q, dt))
        reaction = getattr(self.plant, "drive_reaction", None)
        load = float(reaction()) if callable(reaction) else math.nan
        return Reading(tip=tip, motor=q, load=load, output=out, status=status)


def plant_source(
    preset: str | None = None,
    member: int | None = None,
    scenario: str | None = None,
    latency: float = 0.0,
    noise: float | None = None,
    seed: int = 0,
    torque: bool = False,
) -> LivePlant:
    """A live plant from one source: a preset by name, a population member by seed, or the
    plant of a ``tendonsheath bench`` scenario file (TOML) (one of the three).

    Parameters
    ----------
    preset : {"realistic", "ideal"}, optional
        A pull-pull drive of the library's defaults on a 90-degree bend, with the realistic
        effects and drive train (``ts.presets``) or ideal (a 60 Hz servo).
    member : int, optional
        ``ts.presets.random_realistic_plant(member)``: its plant, encoder and tip sensor.
    scenario : str, optional
        A scenario file: its plant, motor and sensor.
    latency : float, default 0.0
        The tip sensor's latency (s).
    noise : float, optional
        The tip sensor's noise standard deviation (rad); default the source's own.
    seed : int, default 0
        Seed of the sensors' noise.
    torque : bool, default False
        A torque motor (for an AdaptiveController) instead of the position servo.

    Returns
    -------
    LivePlant
        The plant and its sensors.

    Raises
    ------
    ValueError
        None or more than one source, an unknown preset, or a bad file.
    """
    given = [s for s in (preset, member, scenario) if s is not None]
    if len(given) != 1:
        raise ValueError("give one plant source: a preset, a population member or a scenario")
    if member is not None:
        draw = random_realistic_plant(int(member))
        plant = draw.torque_plant(encoder_seed=seed) if torque else draw.plant(encoder_seed=seed)
        tip = draw.tip_sensor(latency, seed)
        if noise is not None:
            tip = Sensor(noise_std=noise, resolution=tip.resolution, delay=latency, seed=seed)
        return LivePlant(plant, tip)
    if scenario is not None:
        return _scenario_plant(scenario, latency, noise, seed, torque)
    if preset not in PRESETS:
        raise ValueError(f"unknown plant preset {preset!r}; known: {list(PRESETS)}")
    if preset == "realistic":  # the presets' example: a 60 Hz servo
        motor = realistic_motor("torque") if torque else realistic_motor(bandwidth_hz=60.0)
        physics = realistic_plant()
    elif torque:
        motor, physics = Motor.torque(), {}
    else:
        motor, physics = Motor.position(bandwidth_hz=60.0), {}
    route = Route.uniform(1.0, math.pi / 2)
    tip = Sensor(noise_std=noise or 0.0, delay=latency, seed=seed)
    encoder = Sensor(resolution=2 * math.pi / 4096, seed=seed)
    plant = PullPullPlant(route=route, motor=motor, encoder=encoder, **physics)
    return LivePlant(plant, tip)


def _scenario_plant(path: str, latency: float, noise: float | None, seed: int, torque: bool):
    from ..bench import user_scenario as us

    sc = us.load(path)
    motor = us._torque(sc) if torque else us._servo(sc)
    sensor = Sensor(noise_std=noise or 0.0, delay=latency, seed=seed)
    plant = us._plant(sc, motor, None)
    return LivePlant(plant, sensor)  # a scenario has no encoder: the motor is read exactly


__all__ = ["PRESETS", "LivePlant", "Reading", "plant_source"]
