"""bench.run closes one loop around any plant with reset() and step(command, dt)
(protocols.SteppedPlant): a plant written in Python (stepped from Python) runs as the shipped
plant it wraps, to the last bit; a compiled user plant (examples/cpp/user_plant,
tendonsheath_bind/plant.hpp) as its pure-Python twin and as the closed form of a play; the
SingleTendonPlant, its reference the distal displacement (m), as its capstan closed form; and a
plant that lacks a member is named."""

import importlib
import importlib.machinery
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app

ROOT = Path(__file__).resolve().parent.parent
T = np.arange(0.0, 2.0, 1e-3)
Y_D = 0.6 * np.sin(2 * np.pi * 1.0 * T) + 0.1 * np.sin(2 * np.pi * 2.3 * T)
ROUTE = ts.Route.arcs([(0.5, 0.0), (0.6, 2.0)])
ROUTE_2 = ts.Route.uniform(1.1, 3.5)

PLAY_PLANT = '''
import numpy as np
import tendonsheath as ts


class PlayPlant:
    """A play (backlash) of half-width h: the twin of examples/cpp/user_plant's PlayPlant."""

    kinematic_gain = 1.0

    def __init__(self, half_width=0.05):
        self.h = float(half_width)
        self.reset()

    @property
    def params(self):
        return {"half_width": self.h}

    def reset(self):
        self.x = self.y = 0.0

    def step(self, command, dt=0.0):
        self.x = float(command)
        if self.x - self.y > self.h:
            self.y = self.x - self.h
        if self.y - self.x > self.h:
            self.y = self.x + self.h
        return self.y

    def output(self):
        return self.y

    def input(self):
        return self.x

    def simulate(self, t, command):
        twin = PlayPlant(self.h)
        return ts.SimulationResult(np.array([twin.step(c) for c in command]), t=t)
'''
_namespace: dict = {}
exec(compile(PLAY_PLANT, "play_plant.py", "exec"), _namespace)  # also written for the CLI
PlayPlant = _namespace["PlayPlant"]


class Wrapped:
    """A user's Python plant: a shipped plant built without a motor, stepped from Python, its
    motor and sensor given beside it (bench.run runs them as for the shipped plant)."""

    def __init__(self, inner, motor=None, sensor=None):
        self.inner, self.motor, self.sensor = inner, motor, sensor

    @property
    def params(self):
        return self.inner.params

    @property
    def route(self):
        return self.inner.route

    @property
    def kinematic_gain(self):
        return self.inner.kinematic_gain

    def reset(self):
        self.inner.reset()

    def step(self, command, dt=0.0):
        return self.inner.step(command, dt)

    def simulate(self, t, command):
        return self.inner.simulate(t, command)

    def output(self):
        return self.inner.output()

    def input(self):
        return self.inner.input()

    def slack(self):
        return self.inner.slack()

    def status(self):
        return self.inner.status()

    def set_route(self, *routes):
        self.inner.set_route(*routes)


def _pair(motor=None, sensor=None):
    return ts.PullPullPlant(
        ROUTE,
        friction=0.1,
        stiffness=5e3,
        pretension=20.0,
        proximal_radius=0.015,
        distal_radius=0.012,
        elements=20,
        motor=motor,
        sensor=sensor,
        distal_inertia=2e-5,
        distal_damping=2e-3,
    )


def _assert_same_run(a, b):
    for name in ("output", "measured", "command", "q_motor"):
        np.testing.assert_allclose(getattr(a, name), getattr(b, name), rtol=0, atol=1e-12)
    assert np.array_equal(a.slack, b.slack) and np.array_equal(a.status, b.status)
    assert a.metrics["mse"] == pytest.approx(b.metrics["mse"], rel=1e-12)


def _pi_feedforward(**settings):
    spec = importlib.util.spec_from_file_location(
        "example_09_plants", ROOT / "examples" / "09_user_compensator.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.PIFeedforward(**{"gain": 0.8, **settings})


def _routes(t):
    return ROUTE if t < 1.0 else ROUTE_2


@pytest.mark.parametrize(
    "controller, routes",
    [
        (None, None),
        (ts.compensate.InverseFeedforward(ts.models.Backlash(0.8, 0.8, 0.03, 0.03)), _routes),
        ("python PI", None),
    ],
    ids=["uncompensated", "shipped-feedforward-with-routes", "python-compensator"],
)
def test_a_python_plant_runs_as_the_shipped_plant_it_wraps(controller, routes):
    """The erased path (a Python plant stepped from C++) gives the shipped plant's run."""
    if controller == "python PI":
        controller = _pi_feedforward()
    motor, sensor = ts.Motor.position(40.0, 0.8), ts.Sensor(noise_std=1e-4, seed=3)
    shipped = ts.bench.run(_pair(motor, sensor), controller, T, Y_D, routes=routes)
    user = ts.bench.run(Wrapped(_pair(), motor, sensor), controller, T, Y_D, routes=routes)
    _assert_same_run(user, shipped)
    assert not np.array_equal(shipped.output, Y_D)  # a real run (the plant's play shows)


def test_a_python_continuum_plant_runs_as_the_shipped_one():
    def continuum(motor=None):
        return ts.ContinuumPlant(ROUTE, elements=20, stiffness=5e3, pretension=20.0, motor=motor)

    motor = ts.Motor.position(40.0, 0.8)
    reference = 0.5 * Y_D
    shipped = ts.bench.run(continuum(motor), None, T, reference)
    _assert_same_run(ts.bench.run(Wrapped(continuum(), motor), None, T, reference), shipped)


def _single(motor=None):
    return ts.SingleTendonPlant(
        ts.Route.uniform(1.0, 2.0),
        friction=0.1,
        stiffness=2e4,
        elements=60,
        load=ts.loads.ConstantForce(10.0),
        motor=motor,
    )


def test_single_tendon_plant_tracks_as_its_capstan_closed_form():
    """Reference: the distal displacement (m); uncompensated command: the same displacement at
    the proximal end. Pulled past the dead zone, the tendon lags by the stretch the capstan
    tension profile T(s) = F0 exp(mu Theta s / L) adds: F0 L / EA ((e^a - 1) / a - 1),
    a = mu Theta."""
    t = np.arange(0.0, 1.0, 1e-3)
    reference = 2e-3 * t  # a slow pull, m
    result = ts.bench.run(_single(), None, t, reference, warmup=0.0)
    assert result.controller == "none"
    a = 0.1 * 2.0
    lag = 10.0 * 1.0 / 2e4 * ((math.exp(a) - 1) / a - 1)
    pulled = t > 0.5  # past the dead zone (about 0.1 mm at 2 mm/s)
    # 60 lumped elements approximate the continuous profile: measured 5e-5 relative, so 1e-3
    np.testing.assert_allclose(-result.error[pulled], lag, rtol=1e-3)
    # its Python twin (the same plant stepped from Python) runs it the same
    twin = ts.bench.run(Wrapped(_single()), None, t, reference, warmup=0.0)
    _assert_same_run(twin, result)


def _play(reference, h):
    out, y = np.empty_like(reference), 0.0
    for k, x in enumerate(reference):
        y = min(max(y, x - h), x + h)
        out[k] = y
    return out


@pytest.fixture(scope="module")
def cpp_plants():
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    found = sorted(
        ROOT.glob(f"build/*/examples/cpp/user_plant/user_plants{suffix}"),
        key=lambda p: p.stat().st_mtime,
    )
    assert found, "the example module is built by `make install` (CMakeLists.txt); run it first"
    sys.path.insert(0, str(found[-1].parent))
    try:
        return importlib.import_module("user_plants")
    finally:
        sys.path.pop(0)


def test_a_compiled_user_plant_runs_as_its_python_twin_and_the_play_closed_form(cpp_plants):
    h = 0.05
    compiled = cpp_plants.PlayPlant(half_width=h)
    assert isinstance(compiled, ts.protocols.Plant) and compiled.params == {"half_width": h}
    python = ts.bench.run(PlayPlant(h), None, T, Y_D)
    native = ts.bench.run(compiled, None, T, Y_D)
    _assert_same_run(native, python)
    np.testing.assert_allclose(native.output, _play(Y_D, h), rtol=0, atol=1e-15)
    # past the first turn the output lags the reference by the half-width, never more
    assert np.max(np.abs(native.error)) <= h + 1e-15
    assert np.max(np.abs(native.error[native.scored])) == pytest.approx(h, rel=1e-12)
    # with a feedback compensator and a motor too
    motor = ts.Motor.position(40.0, 0.8)
    twin, native_plant = PlayPlant(h), cpp_plants.PlayPlant(half_width=h)
    twin.motor = native_plant.motor = motor
    pi = {"gain": 1.0, "kp": 2.0, "ki": 20.0}
    a = ts.bench.run(twin, _pi_feedforward(**pi), T, Y_D)
    b = ts.bench.run(native_plant, _pi_feedforward(**pi), T, Y_D)
    _assert_same_run(b, a)
    # the feedback closes the play's lag: measured rmse 0.014 rad against 0.061 uncompensated
    assert b.metrics["rmse"] < 0.5 * ts.bench.run(native_plant, None, T, Y_D).metrics["rmse"]
    # simulate: from rest, on a copy
    np.testing.assert_allclose(native_plant.simulate(T, Y_D), _play(Y_D, h), atol=1e-15)


class _NoStep:
    def reset(self):
        pass


class _Fails(PlayPlant):
    def step(self, command, dt=0.0):
        if dt > 0 and command > 0.3:
            raise RuntimeError("the user's plant broke")
        return super().step(command, dt)


class _NotANumber(PlayPlant):
    def step(self, command, dt=0.0):
        return "far"


def test_a_plant_that_lacks_a_member_or_fails_is_named():
    with pytest.raises(ValueError, match=r"_NoStep has no step: a plant needs reset\(\) and"):
        ts.bench.run(_NoStep(), None, T, Y_D)
    with pytest.raises(ValueError, match="object has no reset and no step"):
        ts.bench.run(object(), None, T, Y_D)
    no_gain = PlayPlant()
    no_gain.kinematic_gain = None
    with pytest.raises(ValueError, match="no kinematic_gain and no distal_radius"):
        ts.bench.run(no_gain, None, T, Y_D)
    with pytest.raises(ValueError, match=r"no set_route\(route\)"):
        ts.bench.run(PlayPlant(), None, T, Y_D, routes=_routes)
    with pytest.raises(RuntimeError, match="the user's plant broke"):
        ts.bench.run(_Fails(), None, T, Y_D)
    with pytest.raises(TypeError, match=r"_NotANumber.step returned 'far', not a number"):
        ts.bench.run(_NotANumber(), None, T, Y_D)
    bad_motor = PlayPlant()
    bad_motor.motor = "servo"
    with pytest.raises(TypeError, match="motor must be a tendonsheath.Motor"):
        ts.bench.run(bad_motor, None, T, Y_D)
    with pytest.raises(ValueError, match="CoupledPlant's step takes one command per joint"):
        ts.bench.run(ts.CoupledPlant([_pair(), _pair()], np.zeros((2, 2))), None, T, Y_D)


SCENARIO = """
[plant]
file = "play_plant.py"
class = "PlayPlant"
kwargs = { half_width = 0.04 }
[reference]
duration = 2.0
sines = [[0.6, 1.0, 0.0]]
[sensor]
noise_std = 0.0
resolution = 0.0
"""


def test_bench_command_runs_a_user_plant(tmp_path):
    (tmp_path / "play_plant.py").write_text(PLAY_PLANT)
    scenario = tmp_path / "s.toml"
    scenario.write_text(SCENARIO)
    result = CliRunner().invoke(app, ["bench", str(scenario), "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    runs = json.loads((tmp_path / "out" / "metrics.json").read_text())["scenarios"]["user"]
    assert set(runs) == {"none"}
    # the uncompensated play lags by its half-width once moving: rmse just under 0.04 rad
    assert 0.02 < runs["none"]["rmse"] <= 0.04
    # a table for the shipped plants beside a user plant is refused, naming it
    scenario.write_text(SCENARIO + "[motor]\nbandwidth_hz = 30.0\n")
    refused = CliRunner().invoke(app, ["bench", str(scenario), "--out", str(tmp_path / "o2")])
    assert refused.exit_code == 2 and "brings its own motor" in refused.output
