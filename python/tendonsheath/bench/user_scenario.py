"""User scenarios in TOML for ``tendonsheath bench scenario.toml``.

    title = "my bench"                  # optional
    seed = 0                            # optional: route-free runs are deterministic anyway

    [plant]                             # all keys optional
    type = "pull_pull"                  # or "continuum"
    friction = 0.1                      # mu
    stiffness = 5000.0                  # EA, N
    pretension = 20.0                   # T0, N
    proximal_radius = 0.01              # m
    distal_radius = 0.01                # m (pull_pull only)
    elements = 40                       # per sheath
    realistic = true                    # the realistic preset (tendonsheath.plant.presets): distal
                                        #   dynamics, sheath viscosity, creep, unequal pair,
                                        #   motor friction and gear backlash; false: ideal
    # continuum only: bending_stiffness, tendon_offset, backbone_length
    # or your own plant instead (tendonsheath.bench.user_plants): class = "module:Class" (or
    # file = "my_plant.py" and class = "MyPlant") and kwargs = { ... }, no other [plant] key

    [route]                             # the initial route: one of
    length = 1.2                        #   length + total_angle (uniform curvature)
    total_angle = 3.1416
    # arcs = [[0.5, 0.0], [0.7, 1.57]]  #   or (length m, bend angle rad) pieces

    [[route.changes]]                   # optional: the route changes at time t
    t = 5.0
    total_angle = 6.2832                # (same length) or arcs = [...]

    [load]                              # optional (pull_pull)
    type = "constant_torque"            # torque = N m
    # type = "torsional_spring"         # stiffness = N m/rad, preload = N m
    # type = "spring_damper"            # stiffness = N m/rad, damping = N m s/rad

    [motor]                             # position servo for none and the feedforwards
    bandwidth_hz = 60.0
    damping = 0.8
    [torque_motor]                      # for the adaptive controller
    inertia = 0.01
    viscous = 0.2
    max_torque = 5.0

    [sensor]
    noise_std = 2e-4
    resolution = 1e-4
    # delay = 0.005                     # latency, s (default 0); history = 1024 samples kept

    [reference]                         # sum of sines (amplitude rad, frequency Hz, phase rad)
    duration = 20.0
    rate = 1000.0
    sines = [[1.0, 0.25, 0.0], [0.3, 0.6, 0.0]]

    [calibration]                       # bench.calibrate: runs on calibration shapes
    duration = 20.0                     #   that differ from every test route
    amplitude = 1.2
    # angles = [1.26, 3.46, 5.34]       # calibration curve angles, rad (default: 0.4, 1.1
                                        #   and 1.7 pi, moved off any test route's angle)
    shape_noise = 0.05                  # shape sensing: noise std of the sensed curve angle
    shape_delay = 0.1                   #   (rad) and its delay (s)

    [compare]
    compensators = ["none", "inverse_feedforward", "curve_angle_feedforward", "adaptive"]

    [[compare.user]]                    # optional, repeatable: your own compensator
    class = "my_package.control:MyCompensator"   # module:Class, or file = "mine.py" and
    kwargs = { gain = 1.0 }                      #   class = "MyCompensator" (see
                                                 #   tendonsheath.bench.user_compensators)

Every table and key is checked; an unknown or ill-typed one is named in the error.
"""

from __future__ import annotations

import math
import re
import tomllib
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._util.units import JOINT_ANGLE, warn_if_unit_slip
from ..compensate import AdaptiveController
from ..io._textread import read_config_text
from ..plant import ContinuumPlant, PullPullPlant, loads, presets
from ..plant.motor import Motor
from ..plant.route import Route
from ..plant.sensor import Sensor
from .run import run
from .scenarios.common import ScenarioResult, piecewise_routes, ratio
from .user_compensators import UserCompensator, parse_user_compensators, told_by_user
from .user_plants import UserPlant, parse_user_plant

COMPENSATORS = ("none", "inverse_feedforward", "curve_angle_feedforward", "adaptive")

_KEYS: dict[str, dict[str, type | tuple]] = {
    "plant": {
        "type": str,
        "friction": float,
        "stiffness": float,
        "pretension": float,
        "proximal_radius": float,
        "distal_radius": float,
        "elements": int,
        "realistic": bool,
        "bending_stiffness": float,
        "tendon_offset": float,
        "backbone_length": float,
    },
    "route": {"length": float, "total_angle": float, "arcs": list, "changes": list},
    "load": {"type": str, "torque": float, "stiffness": float, "preload": float, "damping": float},
    "motor": {"bandwidth_hz": float, "damping": float, "max_speed": float, "max_accel": float},
    "torque_motor": {"inertia": float, "viscous": float, "max_torque": float},
    "sensor": {
        "noise_std": float,
        "resolution": float,
        "seed": int,
        "delay": float,
        "history": int,
    },
    "reference": {"duration": float, "rate": float, "sines": list},
    "calibration": {
        "duration": float,
        "amplitude": float,
        "angles": list,
        "shape_noise": float,
        "shape_delay": float,
    },
    "compare": {"compensators": list, "user": list},
}
_TOP = {"title": str, "seed": int, **{k: dict for k in _KEYS}}


class ScenarioError(ValueError):
    """A scenario file that cannot be run; the message names the file and the bad key."""


@dataclass
class UserScenario:
    title: str
    plant: dict[str, Any]
    route: dict[str, Any]
    load: dict[str, Any] | None
    motor: dict[str, Any]
    torque_motor: dict[str, Any]
    sensor: dict[str, Any]
    reference: dict[str, Any]
    calibration: dict[str, Any]
    compensators: list[str]
    seed: int = 0
    source: str = "<scenario>"
    route_changes: list[tuple[float, Route]] = field(default_factory=list)
    user_compensators: list[UserCompensator] = field(default_factory=list)
    user_plant: UserPlant | None = None  # [plant] class = ...: the user's own plant


def _check_type(where: str, key: str, value, kind):
    if kind is float and isinstance(value, int | float) and not isinstance(value, bool):
        if not math.isfinite(float(value)):
            raise ScenarioError(f"{where}: '{key}' must be a finite number (got {value!r})")
        return float(value)
    if kind is int and isinstance(value, int) and not isinstance(value, bool):
        if abs(value) >= 2**31 and key != "seed":  # counts are C ints; seeds are checked apart
            raise ScenarioError(f"{where}: '{key}' must be below 2**31 in size (got {value})")
        return value
    if kind not in (float, int) and isinstance(value, kind):
        return value
    name = {
        float: "a number",
        int: "an integer",
        str: "a string",
        bool: "true or false",
        list: "an array",
        dict: "a table",
    }[kind]
    raise ScenarioError(f"{where}: '{key}' must be {name} (got {value!r})")


def _section(data: dict, name: str, source: str) -> dict[str, Any]:
    table = data.get(name, {})
    where = f"{source} [{name}]"
    out = {}
    for key, value in table.items():
        if key not in _KEYS[name]:
            raise ScenarioError(f"{where}: unknown key '{key}' (known: {sorted(_KEYS[name])})")
        out[key] = _check_type(where, key, value, _KEYS[name][key])
    return out


def _sensor_table(table: dict[str, Any], source: str) -> dict[str, Any]:
    """The [sensor] table over its defaults, checked as the Sensor takes it: a bad value is
    named in one line."""
    sensor = {"noise_std": 2e-4, "resolution": 1e-4, "seed": 1, **table}
    try:
        Sensor(**sensor)
    except (TypeError, ValueError) as exc:
        raise ScenarioError(f"{source} [sensor]: {str(exc).removeprefix('Sensor: ')}") from None
    return sensor


def _route(spec: dict[str, Any], where: str, length: float | None = None) -> Route:
    both = sorted({"length", "total_angle"} & set(spec))
    if "arcs" in spec and both:
        raise ScenarioError(
            f"{where}: give arcs or {' and '.join(both)}, not both (the arcs set the route's "
            f"length and angle: {', '.join(both)} would be ignored)"
        )
    try:
        if "arcs" in spec:
            return Route.arcs([tuple(map(float, piece)) for piece in spec["arcs"]])
        total = float(spec.get("total_angle", math.pi))
        return Route.uniform(float(spec.get("length", length or 1.2)), total)
    except (TypeError, ValueError) as exc:
        raise ScenarioError(f"{where}: {exc}") from None


def parse(text: str, source: str = "<scenario>") -> UserScenario:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{source}: not valid TOML ({exc})") from None
    for key, value in data.items():
        if key not in _TOP:
            raise ScenarioError(f"{source}: unknown table or key '{key}' (known: {sorted(_TOP)})")
        _check_type(source, key, value, _TOP[key])
    if not data:
        raise ScenarioError(
            f"{source}: the scenario is empty (no table or key); give at least a [plant] or "
            "[route] table, or a title to run every default"
        )
    if not 0 <= data.get("seed", 0) < 2**32:
        raise ScenarioError(f"{source}: 'seed' must be in [0, 2**32) (got {data['seed']})")
    user_plant = _user_plant(data, source)
    s = {name: _section(data, name, source) for name in _KEYS if name != "plant" or not user_plant}
    s.setdefault("plant", {})
    plant_type = "user" if user_plant else s["plant"].get("type", "pull_pull")
    if plant_type not in ("pull_pull", "continuum", "user"):
        raise ScenarioError(f"{source} [plant]: 'type' must be 'pull_pull' or 'continuum'")
    route = _route(s["route"], f"{source} [route]")
    changes = []
    for i, change in enumerate(s["route"].get("changes", [])):
        where = f"{source} [[route.changes]] #{i + 1}"
        if not isinstance(change, dict) or "t" not in change:
            raise ScenarioError(f"{where}: each change needs a time 't'")
        unknown = set(change) - {"t", "total_angle", "arcs"}
        if unknown:
            raise ScenarioError(f"{where}: unknown key '{sorted(unknown)[0]}'")
        t = _check_type(where, "t", change["t"], float)
        changes.append((t, _route(change, where, route.length)))
    if any(b[0] <= a[0] for a, b in zip(changes, changes[1:], strict=False)):
        raise ScenarioError(f"{source} [[route.changes]]: times must increase")
    compensators, user = _compare_table(s["compare"], source)
    if user_plant is not None:
        compensators = _on_user_plant(s["compare"], compensators, source)
        if changes and not callable(getattr(user_plant.build(), "set_route", None)):
            raise ScenarioError(
                f"{source} [[route.changes]]: the plant {user_plant.origin} has no "
                "set_route(route) to take them"
            )
    motor = {"bandwidth_hz": 60.0, "damping": 0.8, **s["motor"]}
    reference = _reference_table(s["reference"], motor["bandwidth_hz"], source)
    load = s["load"] or None
    if load is not None and load.get("type") not in (
        "constant_torque",
        "torsional_spring",
        "spring_damper",
    ):
        raise ScenarioError(
            f"{source} [load]: 'type' must be constant_torque, torsional_spring or spring_damper"
        )
    sc = UserScenario(
        title=data.get("title", "user scenario"),
        plant={"type": plant_type, **s["plant"]}
        if user_plant is None
        else {"type": "user", "class": user_plant.origin, "kwargs": user_plant.kwargs},
        route={"initial": route},
        load=load,
        motor=motor,
        torque_motor={"inertia": 0.01, "viscous": 0.2, "max_torque": 5.0, **s["torque_motor"]},
        sensor=_sensor_table(s["sensor"], source),
        reference=reference,
        calibration={"duration": 20.0, "amplitude": 1.2, **s["calibration"]},
        compensators=list(compensators),
        seed=int(data.get("seed", 0)),
        source=source,
        route_changes=changes,
        user_compensators=user,
        user_plant=user_plant,
    )
    _check_calibration(sc, f"{source} [calibration]")
    return _checked(sc)


# the honesty panel refits a BoucWenBacklash (7 parameters, 3 samples each at the least) to
# every run, after its warm-up, decimated to at most this rate
_HONESTY_FIT_SAMPLES = 21
_HONESTY_FIT_RATE_HZ = 200.0


def _reference_table(table: dict[str, Any], bandwidth_hz: float, source: str) -> dict[str, Any]:
    """The [reference] table over its defaults, checked: sines of [amplitude, frequency,
    phase?] below half the rate, a rate at least twice the servo's bandwidth (the control
    loop runs at it), and enough samples after the warm-up for the honesty panel."""
    where = f"{source} [reference]"
    reference = {"duration": 20.0, "rate": 1000.0, "sines": [[1.0, 0.25, 0.0]], **table}
    for i, sine in enumerate(reference["sines"]):
        if (
            not isinstance(sine, list)
            or len(sine) not in (2, 3)
            or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in sine)
        ):
            raise ScenarioError(f"{where}: sines[{i}] must be [amplitude, frequency, phase?]")
        if not all(math.isfinite(v) for v in sine) or sine[1] < 0:
            raise ScenarioError(
                f"{where}: sines[{i}] must be finite with a frequency >= 0 (got {sine})"
            )
    if not reference["sines"]:
        raise ScenarioError(f"{where}: sines must list at least one sine")
    duration, rate = reference["duration"], reference["rate"]
    if not duration > 0 or not rate > 0:
        raise ScenarioError(f"{where}: duration and rate must be > 0")
    if rate < 2 * bandwidth_hz:
        raise ScenarioError(
            f"{where}: 'rate' {rate:g} Hz is below twice the servo's bandwidth ([motor] "
            f"bandwidth_hz = {bandwidth_hz:g} Hz): the control loop runs at this rate and "
            f"would not sample its own servo (give at least {2 * bandwidth_hz:g} Hz)"
        )
    for i, sine in enumerate(reference["sines"]):
        if abs(sine[1]) >= rate / 2:
            raise ScenarioError(
                f"{where}: sines[{i}] frequency {sine[1]:g} Hz is not below half the 'rate' "
                f"({rate / 2:g} Hz)"
            )
    _check_reference_samples(reference, where)
    return reference


def _check_reference_samples(reference: dict[str, Any], where: str) -> None:
    """Enough samples after the bench's warm-up (the reference's dominant period, at most
    half the run) for the honesty panel's refits."""
    from .metrics import dominant_period

    duration, rate = reference["duration"], reference["rate"]
    if duration * rate > 1e8:
        raise ScenarioError(
            f"{where}: {duration:g} s at {rate:g} Hz is {duration * rate:.3g} samples: too many"
        )
    t, y_d = _reference_signal(reference)
    if t.size < 4:
        kept = 0
    else:
        warmup = min(dominant_period(t, y_d), 0.5 * float(t[-1] - t[0]))
        step = max(1, round(rate / _HONESTY_FIT_RATE_HZ))
        kept = int(np.count_nonzero(t >= t[0] + warmup)) // step
    if kept < _HONESTY_FIT_SAMPLES:
        raise ScenarioError(
            f"{where}: {duration:g} s at {rate:g} Hz leaves {kept} samples after the warm-up "
            f"(at most {_HONESTY_FIT_RATE_HZ:g} Hz); the bench needs {_HONESTY_FIT_SAMPLES}: "
            "a longer 'duration' or a higher 'rate'"
        )


def _check_calibration(sc: UserScenario, where: str) -> None:
    """The [calibration] duration (longer than twice the calibration's warm-up) and angles
    (a non-empty array of curve angles, each a route)."""
    import inspect

    from .calibration import calibrate

    warmup = inspect.signature(calibrate).parameters["warmup"].default
    duration = sc.calibration["duration"]
    if not duration >= 2 * warmup:
        raise ScenarioError(
            f"{where}: 'duration' must be >= {2 * warmup:g} s (got {duration:g}): the "
            f"calibration leaves out its first {warmup:g} s and fits at least as much"
        )
    angles = sc.calibration.get("angles")
    if angles is None:
        return
    if not angles:
        raise ScenarioError(f"{where}: 'angles' must list at least one curve angle (rad)")
    for i, angle in enumerate(angles):
        if isinstance(angle, bool) or not isinstance(angle, int | float):
            raise ScenarioError(f"{where}: angles[{i}] must be a number (got {angle!r})")
        try:
            Route.uniform(sc.route["initial"].length, float(angle))
        except (TypeError, ValueError) as exc:
            raise ScenarioError(f"{where}: angles[{i}]: {exc}") from None
    calibration_angles(sc)  # none is a test route's angle


def _user_plant(data: dict, source: str) -> UserPlant | None:
    """The user's own plant a [plant] table with 'class' names (None without one; see
    :mod:`tendonsheath.bench.user_plants`); the tables for the shipped plants ([load], [motor],
    [torque_motor]) are refused beside it."""
    table = data.get("plant", {})
    if "class" not in table and "file" not in table:
        return None
    given = [name for name in ("load", "motor", "torque_motor") if name in data]
    if given:
        raise ScenarioError(
            f"{source} [{given[0]}]: a user plant ([plant] class = ...) brings its own motor "
            "and load (its motor attribute); remove the table"
        )
    base = Path(source).parent if Path(source).is_file() else Path.cwd()
    try:
        return parse_user_plant(table, f"{source} [plant]", base)
    except ValueError as exc:
        raise ScenarioError(str(exc)) from None


def _on_user_plant(compare: dict, compensators: list[str], source: str) -> list[str]:
    """The shipped compensators run on a user plant: "none" only (the others are calibrated
    on the shipped plant's tension bench); by default "none"."""
    if "compensators" not in compare:
        return ["none"]
    calibrated = [name for name in compensators if name != "none"]
    if calibrated:
        raise ScenarioError(
            f"{source} [compare]: '{calibrated[0]}' is calibrated on the shipped plant's "
            "tension bench, which a user plant ([plant] class = ...) does not offer: compare "
            '"none" and your own [[compare.user]] compensators on it'
        )
    return compensators


def _compare_table(compare: dict, source: str) -> tuple[list[str], list[UserCompensator]]:
    """The [compare] table's shipped compensators (each known) and the user's own; not none."""
    compensators = compare.get("compensators", list(COMPENSATORS))
    user = _user_compensators(compare, source)
    if not compensators and not user:
        raise ScenarioError(
            f"{source} [compare]: 'compensators' is empty; name at least one of "
            f"{list(COMPENSATORS)}"
        )
    for name in compensators:
        if name not in COMPENSATORS:
            raise ScenarioError(
                f"{source} [compare]: unknown compensator '{name}' (known: {list(COMPENSATORS)})"
            )
    return compensators, user


def _checked(sc: UserScenario) -> UserScenario:
    """The scenario, once every value it runs with has passed the check of the class that
    takes it (the plant, the motors, the shape sensing, the routes: one rule, the same message
    as from Python), the route changes fall inside the run, and the angles look like radians."""
    src = sc.source
    _check_load(sc)
    _plant(sc, None)  # ScenarioError "[plant]: <the plant's message>"
    for table, build in (("motor", _servo), ("torque_motor", _torque)):
        try:
            build(sc)
        except (TypeError, ValueError) as exc:
            raise ScenarioError(f"{src} [{table}]: {exc}") from None
    duration = sc.reference["duration"]
    for t, _ in sc.route_changes:
        if not 0 < t < duration:
            raise ScenarioError(
                f"{src} [[route.changes]]: a change at t = {t:g} s is outside the run (0, "
                f"{duration:g}) s ([reference] duration): it would never happen"
            )
    _check_sines(sc.reference["sines"], src)
    _check_calibration_runs(sc)
    return sc


# the [load] keys each load type takes
_LOAD_KEYS = {
    "constant_torque": {"torque"},
    "torsional_spring": {"stiffness", "preload"},
    "spring_damper": {"stiffness", "damping"},
}
# the [load] keys under the names the load classes give their arguments (tendonsheath.plant.loads)
_LOAD_ARGUMENTS = {"tau": "torque", "k": "stiffness", "c": "damping"}


def _check_load(sc: UserScenario) -> None:
    """The [load] table as its load class takes it; the class's message with the table's key
    named (the classes call the stiffness k, the damping c and the torque tau). The continuum
    plant takes no load: a [load] table there is refused rather than ignored."""
    if sc.load is not None and sc.plant["type"] == "continuum":
        raise ScenarioError(
            f"{sc.source} [load]: the continuum plant takes no distal load (a [load] table "
            "applies to type = 'pull_pull'); remove the table or change the plant type"
        )
    if sc.load is not None:
        takes = _LOAD_KEYS.get(str(sc.load.get("type")), set())
        other = sorted(set(sc.load) - takes - {"type"})
        if takes and other:
            raise ScenarioError(
                f"{sc.source} [load]: a {sc.load['type']} load takes {sorted(takes)}, not "
                f"{other} (a key another load type takes would be ignored)"
            )
    try:
        _load_object(sc.load)
    except (TypeError, ValueError) as exc:
        message = str(exc)
        for arg, key in _LOAD_ARGUMENTS.items():
            message = re.sub(rf"\b{arg} must\b", f"'{key}' ({arg}) must", message)
        raise ScenarioError(f"{sc.source} [load]: {message}") from None


def _check_sines(sines: list, src: str) -> None:
    """An amplitude past a full turn of the joint warns (each sine was checked at parse)."""
    for i, sine in enumerate(sines):
        warn_if_unit_slip(sine[0], f"{src} [reference]", f"sines[{i}] amplitude", JOINT_ANGLE)


def _check_calibration_runs(sc: UserScenario) -> None:
    """The calibration runs as [calibration] describes them: duration > 0, the shape sensing
    valid, each angle a valid route's; a note when the test routes' angles lie outside the
    calibration angles (the curve-angle dependence is then extrapolated)."""
    src, cal = sc.source, sc.calibration
    if not cal["duration"] > 0 or not cal["amplitude"] > 0:
        raise ScenarioError(f"{src} [calibration]: duration and amplitude must be > 0")
    warn_if_unit_slip(cal["amplitude"], f"{src} [calibration]", "amplitude", JOINT_ANGLE)
    from .shape_sensing import ShapeSensing

    try:
        ShapeSensing(noise_std=cal.get("shape_noise", 0.05), delay=cal.get("shape_delay", 0.1))
    except (TypeError, ValueError) as exc:
        message = str(exc).removeprefix("ShapeSensing: ")
        for arg, key in (("noise_std", "shape_noise"), ("delay", "shape_delay")):
            message = re.sub(rf"^{arg}\b", f"'{key}' (ShapeSensing {arg})", message)
        raise ScenarioError(f"{src} [calibration]: {message}") from None
    given = cal.get("angles")
    if given is None:
        return  # each angle was checked by _check_calibration
    tests = [sc.route["initial"].curve_angle] + [r.curve_angle for _, r in sc.route_changes]
    if min(tests) < min(given) or max(tests) > max(given):
        warnings.warn(
            f"{src} [calibration]: the test routes' curve angles ({min(tests):.3g} to "
            f"{max(tests):.3g} rad) lie outside the calibration angles ({min(given):.3g} to "
            f"{max(given):.3g} rad): the curve-angle models extrapolate",
            UserWarning,
            stacklevel=4,
        )


def _user_compensators(compare: dict, source: str) -> list[UserCompensator]:
    """The [[compare.user]] entries; a 'file' is relative to the scenario file's folder."""
    base = Path(source).parent if Path(source).is_file() else Path.cwd()
    shipped = {"none", "InverseFeedforward", "CurveAngleFeedforward", "AdaptiveController"}
    try:
        return parse_user_compensators(
            compare.get("user", []), f"{source} [compare]", base, shipped
        )
    except ValueError as exc:
        raise ScenarioError(str(exc)) from None


def run_user_compensators(sc: UserScenario, t, y_d, routes, sensor) -> tuple[dict, dict]:
    """Bench runs of the scenario's own compensators and what each was told: on the plant with
    the torque motor when it commands torque, else on the one with the position servo."""
    runs, told = {}, {}
    for user in sc.user_compensators:
        compensator = user.build()
        torque = getattr(compensator, "control_output", "x") == "torque"
        plant = _plant(sc, _torque(sc) if torque else _servo(sc))
        runs[user.name] = run(plant, compensator, t, y_d, routes=routes, noise=sensor)
        told[user.name] = told_by_user(user)
    return runs, told


def load(path: str | Path) -> UserScenario:
    path = Path(path)
    if not path.is_file():
        raise ScenarioError(f"scenario file not found: {path}")
    try:
        text = read_config_text(path, "a scenario file (TOML)")
    except ValueError as exc:
        raise ScenarioError(str(exc)) from None
    return parse(text, str(path))


def _load_object(spec):
    if spec is None:
        return None
    kind = spec["type"]
    if kind == "constant_torque":
        return loads.ConstantTorque(spec.get("torque", 0.0))
    if kind == "torsional_spring":
        return loads.TorsionalSpring(spec.get("stiffness", 0.0), spec.get("preload", 0.0))
    return loads.SpringDamper(spec.get("stiffness", 0.0), spec.get("damping", 0.0))


def _realistic(sc: UserScenario) -> bool:
    return bool(sc.plant.get("realistic", True))


def _servo(sc: UserScenario) -> Motor:
    if _realistic(sc):
        return presets.realistic_motor(**sc.motor)
    return Motor.position(**sc.motor)


def _torque(sc: UserScenario) -> Motor:
    if _realistic(sc):
        return presets.realistic_motor("torque", **sc.torque_motor)
    return Motor.torque(**sc.torque_motor)


def _plant(sc: UserScenario, motor: Motor | None, sensor: Sensor | None = None):
    if sc.user_plant is not None:  # it brings its own motor and sensor
        return _built_user_plant(sc)
    p = {k: v for k, v in sc.plant.items() if k not in ("type", "realistic")}
    if _realistic(sc):
        kind = ContinuumPlant if sc.plant["type"] == "continuum" else PullPullPlant
        import inspect

        defaults = inspect.signature(kind.__init__).parameters
        p.update(
            presets.realistic_plant(
                friction=p.pop("friction", defaults["friction"].default),
                stiffness=p.pop("stiffness", defaults["stiffness"].default),
            )
        )
    route = sc.route["initial"]
    try:
        if sc.plant["type"] == "continuum":
            return ContinuumPlant(route=route, motor=motor, sensor=sensor, **p)
        return PullPullPlant(
            route=route, load=_load_object(sc.load), motor=motor, sensor=sensor, **p
        )
    except (TypeError, ValueError) as exc:
        raise ScenarioError(f"{sc.source} [plant]: {exc}") from None


def _built_user_plant(sc: UserScenario):
    """The user's plant, on the scenario's initial route when it takes routes."""
    user = sc.user_plant
    if user is None:
        raise ScenarioError(f"{sc.source} [plant]: no user plant ('class') is named")
    plant = user.build()
    set_route = getattr(plant, "set_route", None)
    if callable(set_route):
        try:
            set_route(sc.route["initial"])
        except (TypeError, ValueError) as exc:
            raise ScenarioError(f"{sc.source} [route]: {exc}") from None
    return plant


def tension_bench_friction(plant) -> float:
    """Friction from a tension bench (spec B, identification): pull tendon 1 until it slips
    over its whole length, then mu = -ln(T_distal / T_proximal) / Theta between its first and
    last element (capstan, A1; the plant lumps the whole route's angle between them)."""
    plant.reset()
    travel = 20 * plant.pretension * plant.route.length / plant.stiffness / plant.proximal_radius
    for q in np.linspace(0.0, travel, 400):
        plant.step(float(q))
    tension = plant.tensions()[0]  # row 0: tendon 1, proximal to distal
    span = float(plant.route.curve_angle)
    plant.reset()
    if not span > 0:
        return 0.0
    return float(-math.log(tension[-1] / tension[0]) / span)


def calibration_angles(sc: UserScenario) -> list[float]:
    """The calibration curve angles: [calibration] angles, or 0.4, 1.1 and 1.7 pi, each
    moved off any test route's angle (by at least 0.1 rad)."""
    tests = [sc.route["initial"].curve_angle] + [r.curve_angle for _, r in sc.route_changes]
    given = sc.calibration.get("angles")
    if given is not None:
        angles = [float(a) for a in given]
        clash = [a for a in angles if any(abs(a - b) < 0.05 for b in tests)]
        if clash:
            raise ScenarioError(
                f"{sc.source} [calibration]: angles {clash} are test route angles; calibration "
                "and test routes must differ"
            )
        return angles
    angles = []
    for a in (0.4 * math.pi, 1.1 * math.pi, 1.7 * math.pi):
        while any(abs(a - b) < 0.1 for b in tests):
            a += 0.1
        angles.append(a)
    return angles


def run_user_scenario(sc: UserScenario, progress=None) -> ScenarioResult:
    """Calibrate with :func:`bench.calibrate` on calibration shapes that differ from every
    test route (the plant's logs alone), then run every compensator of [compare]."""
    from .scenarios.common import announce, honesty_panel
    from .shape_sensing import ShapeSensing

    servo_motor = _servo(sc)
    sensor = Sensor(**sc.sensor)
    announce(progress, "calibration")
    shape = ShapeSensing(
        noise_std=sc.calibration.get("shape_noise", 0.05),
        delay=sc.calibration.get("shape_delay", 0.1),
        seed=sc.seed,
    )
    angles = calibration_angles(sc)
    cal = _calibration(sc, shape, angles)
    t, y_d = _reference(sc)
    routes = None
    if sc.route_changes:
        times = [0.0] + [c[0] for c in sc.route_changes]
        shapes = [sc.route["initial"]] + [c[1] for c in sc.route_changes]
        routes = piecewise_routes(times, shapes)
    runs, told = _run_compensators(
        sc, cal, _plant(sc, servo_motor), t, y_d, routes, sensor, shape, progress
    )
    if sc.user_compensators:
        announce(progress, "user compensators")
    user_runs, user_told = run_user_compensators(sc, t, y_d, routes, sensor)
    runs.update(user_runs)
    told.update(user_told)
    announce(progress, "honesty panel")
    theta = (
        np.array([routes(tk).curve_angle for tk in t])
        if routes is not None
        else sc.route["initial"].curve_angle
    )
    honesty = honesty_panel(cal, runs, curve_angle=theta, told=told, seed=sc.seed)
    return _result(sc, cal, runs, honesty, angles, shape)


def _calibration(sc: UserScenario, shape, angles: list[float]):
    """bench.calibrate at the calibration ``angles``, of the models the scenario's
    compensators need (None when none needs one)."""
    from .calibration import calibrate

    wants = set(sc.compensators)
    model_names = []
    if {"inverse_feedforward", "adaptive"} & wants:
        model_names.append("BoucWenBacklash")
    if "curve_angle_feedforward" in wants:
        model_names.append("CurveAngleModel")
    if not model_names:
        return None
    sensed_initial = shape.static_reading(sc.route["initial"].curve_angle, 1.0, seed_offset=77)
    length = sc.route["initial"].length
    return calibrate(
        _plant(sc, _servo(sc)),
        [Route.uniform(length, a) for a in angles],
        models_=model_names,
        backlash_route=int(np.argmin([abs(a - sensed_initial) for a in angles])),
        spring=sc.plant["type"] == "continuum"
        or bool(sc.load and sc.load.get("type") != "constant_torque"),
        duration=sc.calibration["duration"],
        amplitude=sc.calibration["amplitude"],
        sensor=Sensor(**{**sc.sensor, "seed": sc.seed + 11}),
        shape=shape,
        seed=sc.seed,
        names=[f"curve angle {a:.3f} rad" for a in angles],
    )


def _reference(sc: UserScenario) -> tuple[np.ndarray, np.ndarray]:
    """The times and the reference (a sum of sines) of the [reference] table."""
    return _reference_signal(sc.reference)


def _reference_signal(ref: dict[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """The times and the sum of sines of a [reference] table."""
    t = np.arange(0.0, ref["duration"], 1.0 / ref["rate"])
    y_d = sum(
        (
            float(s[0]) * np.sin(2 * np.pi * float(s[1]) * t + (float(s[2]) if len(s) > 2 else 0.0))
            for s in ref["sines"]
        ),
        np.zeros_like(t),  # the start: the sum is an array
    )
    return t, y_d


def _run_compensators(sc: UserScenario, cal, servo, t, y_d, routes, sensor, shape, progress):
    """Build every compensator of [compare] from the calibration and run it: (name -> run
    result, name -> what it was told beyond the calibration)."""
    from .scenarios.common import announce, kinematic_told

    runs = {}
    told: dict[str, dict] = {"none": kinematic_told(servo)}
    for name in sc.compensators:
        announce(progress, name)
        if name == "none":
            runs[name] = run(servo, None, t, y_d, routes=routes, noise=sensor)
        elif name == "inverse_feedforward":
            ff = cal.inverse_feedforward(smoothing=0.03)
            runs["InverseFeedforward"] = run(servo, ff, t, y_d, routes=routes, noise=sensor)
        elif name == "curve_angle_feedforward":
            ff = cal.curve_angle_feedforward(smoothing=0.03)
            runs["CurveAngleFeedforward"] = run(
                servo, ff, t, y_d, routes=routes, noise=sensor, shape_sensing=shape
            )
        else:
            torque = _plant(sc, _torque(sc))
            ctrl = AdaptiveController.from_model(
                cal.backlash_model,
                inertia=sc.torque_motor["inertia"],
                viscous=sc.torque_motor["viscous"],
                max_torque=sc.torque_motor["max_torque"],
                noise_std=sc.sensor["noise_std"],
            )
            told["AdaptiveController"] = {
                f"torque motor {k}": (v, "declared by the user ([torque_motor])")
                for k, v in sc.torque_motor.items()
            }
            told["AdaptiveController"]["sensor noise std"] = (
                sc.sensor["noise_std"],
                "declared by the user ([sensor])",
            )
            runs["AdaptiveController"] = run(torque, ctrl, t, y_d, routes=routes, noise=sensor)
    return runs, told


def _result(sc: UserScenario, cal, runs: dict, honesty: dict, angles, shape) -> ScenarioResult:
    """The user scenario's result: the metrics table, the conditions and the calibration."""
    base = runs["none"].metrics["mse"] if "none" in runs else float("nan")
    table = [
        {
            "compensator": k,
            "mse": r.metrics["mse"],
            "rmse": r.metrics["rmse"],
            "percent_error": r.metrics["percent_error"],
            "improvement": ratio(base, r.metrics["mse"]),
        }
        for k, r in runs.items()
    ]
    at_angles = ", ".join(f"{a:.3f}" for a in angles)
    shapes = {"initial": sc.route["initial"]}
    shapes.update({f"t = {tc:g} s": r for tc, r in sc.route_changes})
    return ScenarioResult(
        name="user",
        title=sc.title,
        summary=f"User scenario from {sc.source}.",
        conditions=_conditions(sc, at_angles, shape),
        runs=runs,
        table=table,
        table_title="Results",
        paper={},
        routes=shapes,
        route_schedule=[(0.0, sc.route["initial"].curve_angle)]
        + [(tc, r.curve_angle) for tc, r in sc.route_changes],
        calibration=cal.to_dict() if cal is not None else {},
        protocol=f"{sc.title}: compensators calibrated by bench.calibrate from the plant's "
        f"logs at curve angles {at_angles} rad and judged on the scenario's own routes and "
        "reference; the plant's parameters are never copied (what each compensator was told "
        "is listed below).",
        honesty=honesty,
        identified=cal.identified_rows() if cal is not None else [],
    )


def _conditions(sc: UserScenario, at_angles: str, shape) -> dict[str, str]:
    """The report's conditions table: the scenario's tables in words."""
    ref = sc.reference
    return {
        "plant": ", ".join(f"{k} = {v}" for k, v in sc.plant.items()),
        "load": str(sc.load or "none"),
        "motor": ", ".join(f"{k} = {v}" for k, v in sc.motor.items()),
        "sensor": ", ".join(f"{k} = {v}" for k, v in sc.sensor.items()),
        "reference": f"{ref['sines']} (amplitude rad, Hz, phase) for {ref['duration']} s "
        f"at {ref['rate']} Hz",
        "calibration": f"bench.calibrate: {sc.calibration['duration']} s runs, amplitude "
        f"{sc.calibration['amplitude']} rad, at curve angles {at_angles} rad (no test route "
        "takes them), from the motor encoder, the noisy distal sensor and a "
        f"{shape.describe()}",
    }


__all__ = [
    "COMPENSATORS",
    "ScenarioError",
    "UserScenario",
    "calibration_angles",
    "load",
    "parse",
    "run_user_compensators",
    "run_user_scenario",
    "tension_bench_friction",
]
