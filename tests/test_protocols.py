"""Compensator and Plant protocols (issue 14 item 2): every shipped compensator and plant meets
them, every compensator round-trips through JSON, and bench.run runs any object that meets
the streaming protocol, in the same closed loop as the shipped ones."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest
from _bench_helpers import Y_D, T, bench_plant
from test_compensator_json import _random_compensator

import tendonsheath as ts
from tendonsheath.compensate import AdaptiveController
from tendonsheath.models import Backlash, BoucWenBacklash
from tendonsheath.protocols import (
    Compensator,
    FeedforwardCompensator,
    Plant,
    StreamingCompensator,
    missing_members,
)

EXAMPLE_09 = Path(__file__).resolve().parent.parent / "examples" / "09_user_compensator.py"


def _example_09():
    spec = importlib.util.spec_from_file_location("example_09", EXAMPLE_09)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _random_adaptive(rng) -> AdaptiveController:
    model = None
    if rng.uniform() < 0.7:
        c = dict(c_r=rng.uniform(0.6, 1.4), c_l=rng.uniform(0.6, 1.4))
        b = dict(B_r=rng.uniform(0, 0.2), B_l=rng.uniform(0, 0.2))
        model = Backlash(**c, **b) if rng.uniform() < 0.5 else BoucWenBacklash(**c, **b)
    if rng.uniform() < 0.5 and model is not None:
        return AdaptiveController.from_model(
            model,
            inertia=rng.uniform(1e-3, 0.05),
            viscous=rng.uniform(0, 0.3),
            bandwidth_hz=rng.uniform(1, 10),
            max_torque=float(rng.choice([math.inf, rng.uniform(1, 10)])),
            noise_std=rng.uniform(0, 1e-3),
            model_acceleration=bool(rng.uniform() < 0.5),
        )
    return AdaptiveController(
        model,
        smoothing=rng.uniform(0.01, 0.2),
        lambda_=rng.uniform(5, 40),
        k_s=rng.uniform(0.1, 3),
        sigma_phi=rng.uniform(0, 0.1),
        max_torque=float(rng.choice([math.inf, rng.uniform(1, 10)])),
    )


def _all_compensators(rng):
    return [_random_compensator(rng, k) for k in range(6)] + [_random_adaptive(rng)]


def _signals(rng, n):
    t = np.cumsum(rng.uniform(5e-4, 2e-3, n))
    y_d = 0.8 * np.sin(2 * np.pi * rng.uniform(0.2, 1.0) * t)
    y = y_d + rng.normal(0, 0.05, n)
    y[rng.uniform(size=n) < 0.05] = np.nan  # dropouts
    q = y_d + rng.normal(0, 0.05, n)
    return np.diff(t, prepend=t[0]), {"y_d": y_d, "y": y, "q": q}


def _stream(compensator, dts, signals):
    compensator.reset()
    names = getattr(compensator, "step_inputs", ("y_d",))
    rows = zip(*(signals[s] for s in names), dts, strict=True)
    return np.array([compensator.step(*row) for row in rows])


@pytest.mark.parametrize("seed", range(6))
def test_every_compensator_meets_the_protocol_and_round_trips(tmp_path, seed):
    rng = np.random.default_rng(seed)
    dts, signals = _signals(rng, 600)
    for c in _all_compensators(rng):
        assert isinstance(c, Compensator) and isinstance(c, StreamingCompensator)
        assert missing_members(c, Compensator) == []
        assert isinstance(c.params, dict) and c.params
        path = tmp_path / f"{type(c).__name__}.json"
        c.to_json(path)
        again = type(c).load(path)
        assert type(again) is type(c) and again.to_json() == c.to_json()
        assert ts.compensate.load(path).to_json() == c.to_json()
        u0, u1 = _stream(c, dts, signals), _stream(again, dts, signals)
        assert np.all(np.isfinite(u0))
        np.testing.assert_array_equal(u1, u0)  # the same settings: the same commands, bit for bit


def test_feedforwards_have_command_and_the_adaptive_controller_does_not():
    rng = np.random.default_rng(3)
    *feedforwards, adaptive = _all_compensators(rng)
    for ff in feedforwards:
        assert isinstance(ff, FeedforwardCompensator)
        t = np.arange(0.0, 1.0, 1e-3)
        y_d = np.sin(2 * np.pi * t)
        np.testing.assert_allclose(
            ff.command(t, y_d), _stream(ff, np.diff(t, prepend=0), {"y_d": y_d})
        )
    assert not isinstance(adaptive, FeedforwardCompensator)
    assert missing_members(adaptive, FeedforwardCompensator) == ["command"]


def test_load_refuses_another_class():
    saved = AdaptiveController().to_json()
    with pytest.raises(TypeError, match="holds a AdaptiveController, not a InverseFeedforward"):
        ts.compensate.InverseFeedforward.load(saved)


def _plants():
    route = ts.Route.uniform(0.8, 2.0)
    return [
        ts.PullPullPlant(route, friction=0.12, stiffness=4e3, pretension=15.0, elements=20),
        ts.ContinuumPlant(route, friction=0.08, elements=20),
        ts.SingleTendonPlant(route, friction=0.1, elements=20),
    ]


def test_every_plant_meets_the_protocol_and_its_params_rebuild_it():
    t = np.arange(0.0, 2.0, 1e-3)
    for plant in _plants():
        assert isinstance(plant, Plant) and missing_members(plant, Plant) == []
        scale = 1.0 if not isinstance(plant, ts.SingleTendonPlant) else 5e-3
        x = scale * np.sin(2 * np.pi * t)
        y = plant.simulate(t, x)
        plant.reset()
        streamed = [plant.step(xk, dt) for xk, dt in zip(x, np.diff(t, prepend=0), strict=True)]
        np.testing.assert_allclose(streamed, y, rtol=0, atol=1e-12)
        twin = type(plant)(**plant.params)
        np.testing.assert_array_equal(twin.simulate(t, x), y)
        assert plant.params["elements"] == 20


class _Delegate:
    """A shipped compensator seen only through the protocol: bench.run must step it from
    Python (no bench_engine), inside the same C++ loop."""

    def __init__(self, inner):
        self.inner = inner
        self.step_inputs = getattr(inner, "step_inputs", ("y_d",))
        self.control_output = getattr(inner, "control_output", "x")

    def reset(self):
        self.inner.reset()

    def step(self, *signals):
        return self.inner.step(*signals)

    def status(self):
        return self.inner.status()

    @property
    def in_fallback(self):
        return getattr(self.inner, "in_fallback", False)


@pytest.mark.parametrize("seed", range(3))
def test_python_path_equals_the_cpp_loop(seed):
    rng = np.random.default_rng(seed)
    model = BoucWenBacklash(c_r=1.0, c_l=0.95, B_r=rng.uniform(0.02, 0.1), B_l=0.05)
    servo = bench_plant(ts.Motor.position(60.0, 0.8))
    torque = bench_plant(ts.Motor.torque(inertia=0.01, viscous=0.2, max_torque=5.0))
    cases = [
        (servo, ts.compensate.InverseFeedforward(model, smoothing=rng.uniform(0.02, 0.1))),
        (torque, AdaptiveController.from_model(model, inertia=0.01, viscous=0.2, max_torque=5.0)),
    ]
    noise = ts.Sensor(noise_std=2e-4, seed=seed)
    bent = ts.Route.arcs([(0.5, 0.0), (0.6, rng.uniform(2.5, 4.0))])
    kw = dict(noise=noise, dropout=[(2.0, 2.3)])
    for plant, c in cases:
        kw["routes"] = lambda tk, first=plant.route: bent if tk >= 1.0 else first
        fast = ts.bench.run(plant, c, T, Y_D, **kw)
        slow = ts.bench.run(plant, _Delegate(c), T, Y_D, **kw)
        assert slow.controller == "_Delegate"
        for name in ("output", "measured", "command", "q_motor", "status", "fallback"):
            np.testing.assert_array_equal(getattr(slow, name), getattr(fast, name))
        assert fast.metrics["status"] == slow.metrics["status"]
        if isinstance(c, AdaptiveController):  # in fallback exactly after a NaN reading
            np.testing.assert_array_equal(fast.fallback[1:], np.isnan(fast.measured[:-1]))
            assert fast.fallback.sum() == np.isnan(fast.measured).sum() > 0


def test_user_compensator_is_what_a_hand_written_loop_gives():
    """bench.run of example 09's compensator against the loop written out in Python:
    controller from the last reading, then motor and plant (Plant.step), the sensor reading
    NaN in the dropout window."""
    pi = _example_09().PIFeedforward(gain=1.05, kp=0.8, ki=6.0, integral_limit=0.1)
    plant = bench_plant(ts.Motor.position(60.0, 0.8))
    dropout = (1.5, 1.8)
    result = ts.bench.run(plant, pi, T, Y_D, dropout=[dropout])
    plant.reset()
    pi.reset()
    measured, out, commands = 0.0, [], []
    for k, (tk, y_d) in enumerate(zip(T, Y_D, strict=True)):
        dt = 0.0 if k == 0 else tk - T[k - 1]
        u = pi.step(y_d, measured, dt)
        y = plant.step(u, dt)
        measured = math.nan if dropout[0] <= tk < dropout[1] else y
        out.append(y)
        commands.append(u)
    np.testing.assert_allclose(result.command, commands, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.output, out, rtol=0, atol=1e-12)
    assert np.isnan(result.measured[(T >= 1.5) & (T < 1.8)]).all()
    # and it tracks: the PI loop beats the uncompensated drive (a margin, not a tuned figure)
    plain = ts.bench.run(plant, None, T, Y_D)
    assert result.metrics["rmse"] < 0.8 * plain.metrics["rmse"]


class _NoStep:
    def reset(self):
        pass


class _Wordy:
    def reset(self):
        pass

    def step(self, y_d, dt):
        return "up"


class _Broken(_Wordy):
    def step(self, y_d, dt):
        raise ZeroDivisionError("inside the user's step")


class _Torque(_Wordy):
    control_output = "torque"


class _Moody:
    def reset(self):
        pass

    def step(self, y_d, dt):
        return y_d

    def status(self):
        return "fine"


class _BadInputs(_Wordy):
    step_inputs = ("y_d", "force")


def test_bench_names_what_a_compensator_lacks():
    plant = bench_plant(ts.Motor.position(60.0, 0.8))
    with pytest.raises(TypeError, match="_NoStep has no step"):
        ts.bench.run(plant, _NoStep(), T, Y_D)
    with pytest.raises(TypeError, match=r"_Wordy.step returned 'up', not a number"):
        ts.bench.run(plant, _Wordy(), T, Y_D)
    with pytest.raises(ZeroDivisionError, match="inside the user's step"):
        ts.bench.run(plant, _Broken(), T, Y_D)
    with pytest.raises(ValueError, match="_Torque commands torque"):
        ts.bench.run(plant, _Torque(), T, Y_D)
    with pytest.raises(TypeError, match=r"_Moody.status\(\) must return Status flags"):
        ts.bench.run(plant, _Moody(), T, Y_D)
    with pytest.raises(TypeError, match=r"step_inputs must name distinct signals"):
        ts.bench.run(plant, _BadInputs(), T, Y_D)
