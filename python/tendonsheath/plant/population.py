"""A population of realistic drives: every parameter drawn from documented priors.

A compensation figure measured on one plant says how well a design fits that plant. The
population says how it holds on drives it was never tuned on: ``random_realistic_plant(seed)``
draws a pull-pull drive (``random_continuum_plant`` and ``random_single_tendon_plant`` their
twins) whose every physical and sensing value comes from the priors below, and the draw also
gives the drive's calibration shapes, its route schedules and its test references, each from
its own seed. The demo's plant is one member (``bench.population.demo_draw``): every value
of it lies inside the priors' ranges.

The priors are ranges of the rigs such drives are built on, not measurements of one rig:

=========================  ===========================  =========================================
value                      prior                        provenance
=========================  ===========================  =========================================
sheath length              U(0.8, 2.5) m                flexible endoscopes and catheters 1-2.3 m
                                                        (Do et al. 1.5 m; Lau et al. 1 m)
route                      1-4 bends (straight lead-in  a colonoscope in the colon, a gastroscope
                           0-40 %), total U(90, 720)    in the stomach; Do et al. up to 2 pi
                           deg
friction mu                U(0.05, 0.2)                 PTFE-lined sheath 0.05-0.1, steel coil
                                                        0.1-0.2 (Kaneko; Palli & Melchiorri)
tendon stiffness EA        log-U(3e3, 3e4) N            polymer-coated steel rope 0.3-0.6 mm,
                                                        Dyneema (Do et al. 5e3 N)
pretension T0              U(8, 30) N                   Do et al. 20 N; Lau et al. 10 N
pulleys r_p, r_d/r_p       U(5, 20) mm, U(0.8, 1.25)    capstans of the seed rigs, unequal pairs
distal inertia J_d         log-U(5e-6, 8e-5) kg m^2     a 10-25 mm jaw or pulley with an encoder
distal damping c_d         log-U(5e-4, 5e-3) N m s/rad  joint bearings, grease
sheath viscosity           U(2, 15) N s/m^2             lubricated coils: 10-40 % of the Coulomb
                                                        friction at 1 Hz
creep                      U(3, 12) % of EA, tau        polymer-coated ropes (a standard linear
                           U(0.5, 3) s                  solid)
unequal pair               sheath 2 mu x U(0.85, 1.2),  manufacturing tolerances of two sheaths
                           tendon 2 EA x U(0.85, 1.15)  and two tendons
position servo             bandwidth U(30, 80) Hz,      servo amplifiers (Maxon EPOS, Faulhaber
                           damping U(0.6, 1.0), PID     MC, Copley): PID by default, some run a
                           (70 %) or PD (30 %)          PD position loop
motor                      J log-U(3e-5, 3e-4) kg m^2,  geared DC motors (Faulhaber 3863 14:1,
                           Coulomb U(0.004, 0.02) N m,  Maxon RE 25 with GP 32)
                           viscous log-U(3e-4, 3e-3)
gear play                  U(0.1, 1.0) deg              planetary gearheads' output play
motor encoder              512-16384 lines (x4          incremental encoders (Maxon MR, HEDL)
                           quadrature) on the rotor,    on the rotor of a gearhead; jitter of a
                           gear log-U(4, 66), noise     count
                           U(0, 0.5) counts
tip sensor                 noise U(1e-4, 5e-4) rad,     a distal encoder or an EM tracker's angle
                           resolution U(5e-5, 2e-4) rad (the latency is the study's: 1 or 5 ms)
shape sensing              noise U(0.02, 0.08) rad,     FBG / EM shape sensing of the sheath
                           delay U(0.05, 0.2) s, 6-12
                           arcs, 10 Hz
torque motor (adaptive)    J log-U(5e-3, 2e-2) kg m^2,  the torque-driven joint of Do et al.
                           b U(0.1, 0.3) N m s, |tau|   (J = 0.01, b = 0.2)
                           <= 5 N m
workspace                  U(0.7, 1.3) rad              the distal joint's range of use
test reference             main U(0.1, 0.18) or U(0.32, a sine at a main frequency off the
                           0.5) Hz, a second sine x     calibration's 0.25 Hz, and a faster one
                           U(2.2, 3.2) Hz at U(0.15,
                           0.35) of it
=========================  ===========================  =========================================

The continuum twin draws its segment too (EI log-U(2e-4, 1e-3) N m^2, r_t U(1.5, 3) mm,
l U(20, 45) mm) and a 5-25 Hz servo; the single-tendon twin a distal spring against a
preload instead of the second tendon. ``draw.values`` holds every value drawn (SI units).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .continuum import ContinuumPlant
from .loads import SpringPreload
from .motor import Motor
from .pull_pull import PullPullPlant
from .route import Route
from .sensor import Sensor
from .single_tendon import SingleTendonPlant

#: the kinds of drive a population draws
KINDS = ("pull-pull", "continuum", "single-tendon")
#: elements per sheath of a drawn plant (the demo's 40: enough for the distributed friction)
ELEMENTS = 40
#: the calibration shapes of a draw, as fractions of its nominal route's total angle
CALIBRATION_FRACTIONS = (0.55, 0.8, 1.25)

# name -> (distribution, low, high): "u" uniform, "log" log-uniform, "int" integers [low, high]
PRIORS: dict[str, tuple[str, float, float]] = {
    "length": ("u", 0.8, 2.5),
    "route_angle": ("u", math.radians(90.0), math.radians(719.0)),  # 4 pi: two coils
    "bends": ("int", 1, 4),
    "lead_in": ("u", 0.0, 0.4),
    "friction": ("u", 0.05, 0.2),
    "stiffness": ("log", 3e3, 3e4),
    "pretension": ("u", 8.0, 30.0),
    "proximal_radius": ("u", 5e-3, 20e-3),
    "radius_ratio": ("u", 0.8, 1.25),
    "distal_inertia": ("log", 5e-6, 8e-5),
    "distal_damping": ("log", 5e-4, 5e-3),
    "sheath_viscosity": ("u", 2.0, 15.0),
    "relaxation_fraction": ("u", 0.03, 0.12),
    "relaxation_time": ("u", 0.5, 3.0),
    "friction2_ratio": ("u", 0.85, 1.2),
    "stiffness2_ratio": ("u", 0.85, 1.15),
    "servo_bandwidth_hz": ("u", 30.0, 80.0),
    "servo_damping": ("u", 0.6, 1.0),
    "servo_pid": ("u", 0.0, 1.0),  # PID when below PID_SHARE
    "motor_inertia": ("log", 3e-5, 3e-4),
    "motor_coulomb": ("u", 0.004, 0.02),
    "motor_viscous": ("log", 3e-4, 3e-3),
    "gear_play": ("u", math.radians(0.1), math.radians(1.0)),
    "encoder_lines_log2": ("int", 9, 14),
    "gear_ratio": ("log", 4.0, 66.0),
    "encoder_noise_counts": ("u", 0.0, 0.5),
    "tip_noise": ("u", 1e-4, 5e-4),
    "tip_resolution": ("u", 5e-5, 2e-4),
    "shape_noise": ("u", 0.02, 0.08),
    "shape_delay": ("u", 0.05, 0.2),
    "shape_segments": ("int", 6, 12),
    "torque_inertia": ("log", 5e-3, 2e-2),
    "torque_viscous": ("u", 0.1, 0.3),
    "workspace": ("u", 0.7, 1.3),
}
#: the continuum twin's own priors (the segment and its slower servo)
CONTINUUM_PRIORS: dict[str, tuple[str, float, float]] = {
    "bending_stiffness": ("log", 2e-4, 1e-3),
    "tendon_offset": ("u", 1.5e-3, 3e-3),
    "backbone_length": ("u", 0.02, 0.045),
    "servo_bandwidth_hz": ("u", 5.0, 25.0),
    "proximal_radius": ("u", 3e-3, 8e-3),
}
#: the single-tendon twin's distal load: a spring against a preload
SINGLE_TENDON_PRIORS: dict[str, tuple[str, float, float]] = {
    "spring": ("log", 500.0, 5000.0),
    "preload": ("u", 5.0, 20.0),
    "workspace": ("u", 2e-3, 6e-3),  # m of distal stroke
}
#: the share of drives whose amplifier runs a PID position loop (the rest: PD)
PID_SHARE = 0.7
#: how much a drive drifts between calibration and test (relative, uniform +/-)
DRIFT = {
    "friction": 0.08,
    "stiffness": 0.05,
    "pretension": 0.08,
    "sheath_viscosity": 0.1,
    "servo_bandwidth_hz": 0.03,
}
#: the second tendon's frequencies and amplitudes of the test references
REFERENCE_BANDS = ((0.1, 0.18), (0.32, 0.5))
MAX_TORQUE = 5.0


def _draw(rng: np.random.Generator, priors: dict[str, tuple[str, float, float]]) -> dict:
    out: dict[str, float] = {}
    for name, (kind, low, high) in priors.items():
        if kind == "u":
            out[name] = float(rng.uniform(low, high))
        elif kind == "log":
            out[name] = float(math.exp(rng.uniform(math.log(low), math.log(high))))
        else:
            out[name] = int(rng.integers(int(low), int(high) + 1))
    return out


def _route(length: float, angle: float, bends: int, lead_in: float, rng) -> Route:
    """A lead-in straight part (``lead_in`` of the length) then ``bends`` arcs sharing the
    rest of the length and the total angle at random (Dirichlet(2) splits); a lead-in under
    1 mm is none (every route of a drive keeps its length)."""
    straight = lead_in * length
    straight = straight if straight > 1e-3 else 0.0
    lengths = rng.dirichlet(2.0 * np.ones(bends)) * (length - straight)
    angles = rng.dirichlet(2.0 * np.ones(bends)) * angle
    arcs = [(float(a), float(b)) for a, b in zip(lengths, angles, strict=True)]
    return Route.arcs(([(straight, 0.0)] if straight > 0.0 else []) + arcs)


@dataclass(frozen=True)
class PlantDraw:
    """One drive of the population: its drawn values and everything a study needs of it.

    Build its plants with :meth:`plant` (behind its position servo) and :meth:`torque_plant`
    (a torque motor, for the adaptive controller), its sensors with :meth:`tip_sensor` and
    :meth:`shape_sensing`; :attr:`calibration_routes` are the shapes it is calibrated on,
    :meth:`route_schedule` and :meth:`reference` its test conditions, each from a seed.

    Parameters
    ----------
    seed : int
        The draw's seed (None for a hand-made member such as :func:`demo_draw`).
    kind : {"pull-pull", "continuum", "single-tendon"}
        The drive.
    values : dict
        Every drawn value (SI units, angles in rad).
    nominal_route : Route
        The route the drive is laid along at rest (the fixed-route tests' route).
    calibration_routes : tuple of Route
        The shapes the drive is calibrated on (none of them a test route).
    """

    seed: int | None
    kind: str
    values: dict[str, Any]
    nominal_route: Route
    calibration_routes: tuple[Route, ...] = field(default=())

    @property
    def servo(self) -> str:
        """The position servo: "pid" (integral action) or "pd"."""
        return "pid" if self.values["servo_pid"] < PID_SHARE else "pd"

    @property
    def encoder_resolution(self) -> float:
        """One count of the motor encoder at the output shaft (rad): 2 pi over 4 x lines
        (quadrature) x the gear ratio (the encoder sits on the rotor); for a
        single tendon, whose input is a displacement, its arc on the proximal capstan (m)."""
        lines = 2 ** int(self.values["encoder_lines_log2"])
        count = 2.0 * math.pi / (4 * lines * self.values["gear_ratio"])
        return count * self._input_scale

    @property
    def _input_scale(self) -> float:
        """Metres of input per radian of motor for a single tendon (its capstan), else 1."""
        return self.values["proximal_radius"] if self.kind == "single-tendon" else 1.0

    def encoder(self, seed: int = 0) -> Sensor:
        """The motor encoder: its resolution and a noise of a fraction of a count.

        Parameters
        ----------
        seed : int, default 0
            Seed of its noise.

        Returns
        -------
        Sensor
            The encoder (attach it to a plant with ``encoder=``).
        """
        res = self.encoder_resolution
        return Sensor(
            resolution=res, noise_std=self.values["encoder_noise_counts"] * res, seed=int(seed)
        )

    def motor(self) -> Motor:
        """The position servo with the drive train's friction and gear play.

        Returns
        -------
        Motor
            A position motor: PID (integral time 5 / w_n) or PD, as drawn.
        """
        v = self.values
        w = 2.0 * math.pi * v["servo_bandwidth_hz"]
        integral = 5.0 / w if self.servo == "pid" else 0.0
        if self.kind == "single-tendon":  # a linear stage: the play as a stroke, no inertia
            return Motor.position(
                bandwidth_hz=v["servo_bandwidth_hz"],
                damping=v["servo_damping"],
                gear_backlash=v["gear_play"] * self._input_scale,
                integral_time=integral,
            )
        return Motor.position(
            bandwidth_hz=v["servo_bandwidth_hz"],
            damping=v["servo_damping"],
            inertia=v["motor_inertia"],
            coulomb_friction=v["motor_coulomb"],
            viscous_friction=v["motor_viscous"],
            gear_backlash=v["gear_play"],
            integral_time=integral,
        )

    def torque_motor(self) -> Motor:
        """The torque motor of the adaptive controller's joint.

        Returns
        -------
        Motor
            A torque motor (|tau| <= 5 N m) with the drawn inertia, damping and gear play.
        """
        v = self.values
        return Motor.torque(
            inertia=v["torque_inertia"],
            viscous=v["torque_viscous"],
            max_torque=MAX_TORQUE,
            coulomb_friction=v["motor_coulomb"],
            gear_backlash=v["gear_play"],
        )

    def physics(self) -> dict[str, Any]:
        """The plant's keyword arguments (without route, motor and sensors).

        Returns
        -------
        dict
            Keywords of the draw's plant class.
        """
        v = self.values
        common = {
            "friction": v["friction"],
            "stiffness": v["stiffness"],
            "elements": ELEMENTS,
            "sheath_viscosity": v["sheath_viscosity"],
            "relaxation_fraction": v["relaxation_fraction"],
            "relaxation_time": v["relaxation_time"],
        }
        if self.kind == "single-tendon":
            return common
        pair = {
            **common,
            "pretension": v["pretension"],
            "proximal_radius": v["proximal_radius"],
            "friction2": v["friction"] * v["friction2_ratio"],
            "stiffness2": v["stiffness"] * v["stiffness2_ratio"],
            "distal_inertia": v["distal_inertia"],
            "distal_damping": v["distal_damping"],
        }
        if self.kind == "continuum":
            return {
                **pair,
                **{k: v[k] for k in ("bending_stiffness", "tendon_offset", "backbone_length")},
            }
        return {**pair, "distal_radius": v["proximal_radius"] * v["radius_ratio"]}

    def plant(
        self, route: Route | None = None, *, encoder_seed: int = 0, motor: Motor | None = None
    ) -> PullPullPlant | ContinuumPlant | SingleTendonPlant:
        """The drive behind its position servo (or ``motor``), its motor encoder attached,
        laid along ``route`` (default the nominal route).

        Parameters
        ----------
        route : Route, optional
            The route (default the nominal one).
        encoder_seed : int, default 0
            Seed of the motor encoder's noise.
        motor : Motor, optional
            Another motor (default :meth:`motor`).

        Returns
        -------
        PullPullPlant or ContinuumPlant or SingleTendonPlant
            The plant of the draw's kind.
        """
        route = self.nominal_route if route is None else route
        motor = self.motor() if motor is None else motor
        enc = self.encoder(encoder_seed)
        if self.kind == "continuum":
            return ContinuumPlant(route=route, motor=motor, encoder=enc, **self.physics())
        if self.kind == "single-tendon":
            v = self.values
            load = SpringPreload(k=v["spring"], F0=v["preload"])
            return SingleTendonPlant(route, load=load, motor=motor, encoder=enc, **self.physics())
        return PullPullPlant(route=route, motor=motor, encoder=enc, **self.physics())

    def torque_plant(
        self, route: Route | None = None, *, encoder_seed: int = 0
    ) -> PullPullPlant | ContinuumPlant | SingleTendonPlant:
        """The drive on its torque motor (the adaptive controller's joint).

        Parameters
        ----------
        route : Route, optional
            The route (default the nominal one).
        encoder_seed : int, default 0
            Seed of the motor encoder's noise.

        Returns
        -------
        PullPullPlant or ContinuumPlant or SingleTendonPlant
            The plant on :meth:`torque_motor`.
        """
        return self.plant(route, encoder_seed=encoder_seed, motor=self.torque_motor())

    def tip_sensor(self, latency: float = 0.0, seed: int = 0) -> Sensor:
        """The tip sensor with its drawn noise and resolution, at ``latency`` (s).

        Parameters
        ----------
        latency : float, default 0.0
            The sensor's latency (s).
        seed : int, default 0
            Seed of its noise.

        Returns
        -------
        Sensor
            The tip sensor.
        """
        v = self.values
        return Sensor(
            noise_std=v["tip_noise"],
            resolution=v["tip_resolution"],
            delay=float(latency),
            seed=int(seed),
        )

    def shape_sensing(self, seed: int = 0) -> dict[str, Any]:
        """The drive's shape sensing as the keywords of ``bench.ShapeSensing`` (curvature
        profile in its drawn number of arcs, 10 Hz); ``bench.population`` builds it.

        Parameters
        ----------
        seed : int, default 0
            Seed of its noise.

        Returns
        -------
        dict
            noise_std, delay, rate_hz, segments and seed.
        """
        v = self.values
        return {
            "noise_std": v["shape_noise"],
            "delay": v["shape_delay"],
            "rate_hz": 10.0,
            "segments": int(v["shape_segments"]),
            "seed": int(seed),
        }

    @property
    def calibration_amplitude(self) -> float:
        """The calibration excitation's amplitude: the workspace with a 15 % margin (the
        calibrated range covers every reference), as a motor angle for the pulleys' ratio."""
        return 1.15 * self.values["workspace"] * self.kinematic_gain

    @property
    def kinematic_gain(self) -> float:
        """Motor angle per unit of output of the uncompensated drive (its pulleys' ratio; a
        continuum segment's r_t / r_p; a single tendon's 1 / r_p)."""
        v = self.values
        if self.kind == "continuum":
            return v["tendon_offset"] / v["proximal_radius"]
        if self.kind == "single-tendon":
            return 1.0
        return v["radius_ratio"]

    def route_schedule(self, duration: float, seed: int) -> tuple[list[float], list[Route]]:
        """Random route changes (mean 4 s apart) among shapes of this drive's length, 1-4
        bends and a total angle between half and 1.5 times the nominal one (90-720 deg);
        the nominal route first. Seed ``seed`` of this draw.

        Parameters
        ----------
        duration : float
            Length of the schedule (s).
        seed : int
            The route seed.

        Returns
        -------
        tuple of (list of float, list of Route)
            The change times (s, the first 0) and the routes from each on.
        """
        rng = np.random.default_rng([int(self.seed or 0), 7919, int(seed)])
        v = self.values
        times, routes = [0.0], [self.nominal_route]
        while True:
            nxt = times[-1] + rng.exponential(4.0) + 0.5
            if nxt >= duration:
                return times, routes
            angle = float(
                np.clip(
                    v["route_angle"] * rng.uniform(0.5, 1.5),
                    math.radians(90.0),
                    math.radians(719.0),
                )
            )
            times.append(nxt)
            routes.append(
                _route(
                    v["length"], angle, int(rng.integers(1, 5)), float(rng.uniform(0.0, 0.4)), rng
                )
            )

    def routes(self, duration: float, seed: int) -> Callable[[float], Route]:
        """:meth:`route_schedule` as the ``routes=`` callable of ``bench.run``.

        Parameters
        ----------
        duration : float
            Length of the schedule (s).
        seed : int
            The route seed.

        Returns
        -------
        callable
            t -> Route.
        """
        times, shapes = self.route_schedule(duration, seed)
        edges = np.asarray(times)

        def at(t: float) -> Route:
            return shapes[int(np.searchsorted(edges, t, side="right")) - 1]

        return at

    def reference(
        self, duration: float, seed: int = 0, rate: float = 1000.0, lead_in: float = 0.0
    ) -> tuple[np.ndarray, np.ndarray]:
        """A test reference (t, y_d): a sine at a main frequency off the calibration's 0.25 Hz
        plus a faster one, random phases, within the workspace; from ``seed`` of this draw.
        ``lead_in`` (s): the first seconds go from rest through a random excursion onto the
        reference, so the drive starts its scored part away from rest.

        Parameters
        ----------
        duration : float
            Length (s).
        seed : int, default 0
            The reference seed.
        rate : float, default 1000.0
            Sample rate (Hz).
        lead_in : float, default 0.0
            Seconds from rest through a random excursion onto the reference.

        Returns
        -------
        tuple of numpy.ndarray
            t (s) and the desired output (rad; m for a single tendon).
        """
        rng = np.random.default_rng([int(self.seed or 0), 104729, int(seed)])
        band = REFERENCE_BANDS[int(rng.integers(0, len(REFERENCE_BANDS)))]
        f1 = float(rng.uniform(*band))
        f2 = f1 * float(rng.uniform(2.2, 3.2))
        share = float(rng.uniform(0.15, 0.35))
        a1 = self.values["workspace"] / (1.0 + share)
        phase1, phase2 = rng.uniform(0.0, 2.0 * math.pi, 2)
        t = np.arange(0.0, duration, 1.0 / rate)
        y = a1 * np.sin(2 * np.pi * f1 * t + phase1) + share * a1 * np.sin(
            2 * np.pi * f2 * t + phase2
        )
        if lead_in > 0.0:  # from rest to an excursion, then onto the reference's start
            x = np.clip(t / lead_in, 0.0, 1.0)
            blend = x**3 * (10 - 15 * x + 6 * x**2)
            excursion = float(rng.uniform(-0.6, 0.6)) * self.values["workspace"]
            y = np.where(t < lead_in, blend * y + np.sin(np.pi * x) * excursion, y)
        return t, y

    def drifted(self, seed: int, scale: float = 1.0) -> PlantDraw:
        """The same drive a little later: friction, stiffness, pretension, viscosity and
        servo bandwidth each off by a few percent (uniform, +/- DRIFT x ``scale``), as between
        a calibration and a test session. Seed ``seed`` of this draw.

        Parameters
        ----------
        seed : int
            The drift's seed.
        scale : float, default 1.0
            Multiplies every drift.

        Returns
        -------
        PlantDraw
            The drifted drive (same routes and sensors).
        """
        rng = np.random.default_rng([int(self.seed or 0), 15485863, int(seed)])
        values = dict(self.values)
        for name, share in DRIFT.items():
            values[name] = values[name] * (1.0 + scale * share * float(rng.uniform(-1.0, 1.0)))
        return PlantDraw(self.seed, self.kind, values, self.nominal_route, self.calibration_routes)

    def describe(self) -> str:
        """One line: the drive's main values.

        Returns
        -------
        str
            Kind, seed, length, route, friction, stiffness and servo.
        """
        v = self.values
        return (
            f"{self.kind} draw {self.seed}: L {v['length']:.2f} m, "
            f"{math.degrees(v['route_angle']):.0f} deg in {int(v['bends'])} bend(s), "
            f"mu {v['friction']:.3f}, EA {v['stiffness']:.3g} N, {self.servo.upper()} servo "
            f"{v['servo_bandwidth_hz']:.0f} Hz"
        )


#: the priors a kind draws after PRIORS (in this order: the seed's draws follow it)
_KIND_PRIORS: dict[str, dict[str, tuple[str, float, float]]] = {
    "pull-pull": {},
    "continuum": CONTINUUM_PRIORS,
    "single-tendon": SINGLE_TENDON_PRIORS,
}


def _member(kind: str, seed: int) -> PlantDraw:
    rng = np.random.default_rng([int(seed), KINDS.index(kind)])
    values = _draw(rng, PRIORS)
    values.update(_draw(rng, _KIND_PRIORS[kind]))
    route = _route(
        values["length"], values["route_angle"], int(values["bends"]), values["lead_in"], rng
    )
    calibration = tuple(
        _route(
            values["length"],
            float(np.clip(values["route_angle"] * f, math.radians(60.0), math.radians(715.0))),
            int(rng.integers(1, 5)),
            float(rng.uniform(0.0, 0.4)),
            rng,
        )
        for f in CALIBRATION_FRACTIONS
    )
    return PlantDraw(int(seed), kind, values, route, calibration)


def random_realistic_plant(seed: int) -> PlantDraw:
    """A pull-pull drive of the population, every value drawn from :data:`PRIORS` by
    ``seed`` (the same draw on every machine).

    Parameters
    ----------
    seed : int
        The member's seed, >= 0.

    Returns
    -------
    PlantDraw
        The draw: its values, plants, sensors, calibration shapes, routes and references.
    """
    return _member("pull-pull", _checked_seed(seed))


def random_continuum_plant(seed: int) -> PlantDraw:
    """A continuum segment bent through a pull-pull drive, drawn as
    :func:`random_realistic_plant` with the segment's priors (:data:`CONTINUUM_PRIORS`).

    Parameters
    ----------
    seed : int
        The member's seed, >= 0.

    Returns
    -------
    PlantDraw
        The draw.
    """
    return _member("continuum", _checked_seed(seed))


def random_single_tendon_plant(seed: int) -> PlantDraw:
    """A single tendon against a distal spring and preload, drawn as
    :func:`random_realistic_plant` with :data:`SINGLE_TENDON_PRIORS`.

    Parameters
    ----------
    seed : int
        The member's seed, >= 0.

    Returns
    -------
    PlantDraw
        The draw.
    """
    return _member("single-tendon", _checked_seed(seed))


def _checked_seed(seed: int) -> int:
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise ValueError(f"a population seed is an integer >= 0 (got {seed!r})")
    return int(seed)


def in_priors(draw: PlantDraw) -> list[str]:
    """The values of ``draw`` outside the priors of its kind (empty: a member)."""
    priors = PRIORS | _KIND_PRIORS[draw.kind]
    out = []
    for name, (_, low, high) in priors.items():
        value = draw.values[name]
        if not low - 1e-12 <= value <= high + 1e-12:
            out.append(f"{name} = {value:g} outside [{low:g}, {high:g}]")
    return out


__all__ = [
    "CONTINUUM_PRIORS",
    "DRIFT",
    "KINDS",
    "PRIORS",
    "PlantDraw",
    "SINGLE_TENDON_PRIORS",
    "in_priors",
    "random_continuum_plant",
    "random_realistic_plant",
    "random_single_tendon_plant",
]
