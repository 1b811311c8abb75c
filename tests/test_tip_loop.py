"""TipLoop in Python: the bench runs it in C++ exactly as its Python step (the gain schedule
given the route's, or the sensed, curve angle), it saves and loads bit for bit, bad settings
are one-line errors, and on a realistic plant it improves on its feedforward."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench.run import run
from tendonsheath.bench.shape_sensing import ShapeSensing, sensed_route_schedule
from tendonsheath.compensate import (
    CurveAngleFeedforward,
    EncoderLoop,
    InverseFeedforward,
    TipLoop,
)
from tendonsheath.models import Backlash, BoucWenBacklash, Scaled
from tendonsheath.plant.presets import realistic_motor, realistic_plant

SCHEDULE = [(1.0, 0.5), (2.0, 1.0), (3.0, 2.0)]


def _plant():
    """A realistic pull-pull drive (presets) behind a PID position servo; 10 elements: quick."""
    return ts.PullPullPlant(
        route=ts.Route.uniform(1.0, math.pi / 2),
        pretension=20.0,
        proximal_radius=15e-3,
        distal_radius=15e-3,
        elements=10,
        motor=realistic_motor(servo="pid", bandwidth_hz=20.0),
        **realistic_plant(),
    )


class _UserFeedforward:
    """A feedforward written in Python: bench.run steps it from Python, the loop in C++."""

    def reset(self):
        pass

    def step(self, y_d, dt):
        return 1.05 * y_d


FEEDFORWARDS = {
    "inverse": lambda: InverseFeedforward(BoucWenBacklash(B_r=0.02, B_l=0.01), 0.03),
    "curve_angle": lambda: CurveAngleFeedforward(
        0.1, 2.4e4, 1.0, 20.0, curve_angle=math.pi / 2, proximal_radius=15e-3, distal_radius=15e-3
    ),
    "user": _UserFeedforward,
}


def _routes(t):
    # the route bends further at 1 s: the schedule's gain changes with it
    return ts.Route.uniform(1.0, math.pi / 2 if t < 1.0 else 2.6)


def _stepped(loop, result, angle_at):
    """The Python object stepped over the bench's measurements, told the curve angle (or
    route) where ``angle_at(k)`` gives one."""
    loop.reset()
    out = []
    for k in range(result.t.size):
        told = angle_at(k)
        if isinstance(told, ts.Route):
            loop.set_route(told)
        elif told is not None:
            loop.set_curve_angle(told)
        dt = 0.0 if k == 0 else result.t[k] - result.t[k - 1]
        # the measurement before this cycle: the sensor's reading of the last output (the
        # first cycle only primes the loop: its reading is not used)
        y = result.measured[k - 1] if k > 0 else 0.0
        out.append(loop.step(result.reference[k], y, dt))
    return np.array(out)


@pytest.mark.parametrize("name", sorted(FEEDFORWARDS))
def test_the_bench_runs_it_in_cpp_as_its_python_step(name):
    plant = _plant()
    t = np.arange(0.0, 2.0, 1e-3)
    y_d = 0.5 * np.sin(2 * np.pi * 0.5 * t)

    def make():
        return TipLoop(FEEDFORWARDS[name](), kp=0.5, ki=20.0, kd=0.002, schedule=SCHEDULE)

    result = run(
        plant, make(), t, y_d, routes=_routes, noise=ts.Sensor(noise_std=1e-3),
        dropout=[(0.5, 0.52)],
    )  # fmt: skip
    assert result.controller == "TipLoop"
    assert result.fallback[510] and not result.fallback[700]
    starts = {0, int(np.searchsorted(t, 1.0))}
    python = _stepped(make(), result, lambda k: _routes(t[k]) if k in starts else None)
    np.testing.assert_allclose(result.command, python, rtol=0, atol=1e-12)
    # the schedule mattered: without it the commands differ
    flat = _stepped(
        TipLoop(FEEDFORWARDS[name](), kp=0.5, ki=20.0, kd=0.002), result, lambda k: None
    )
    assert np.max(np.abs(flat - python)) > 1e-4


def test_the_schedule_gets_the_sensed_curve_angle():
    plant = _plant()
    t = np.arange(0.0, 1.5, 1e-3)
    y_d = 0.5 * np.sin(2 * np.pi * 0.5 * t)
    sensing = ShapeSensing(noise_std=0.2, delay=0.05, rate_hz=20.0, seed=4)
    loop = TipLoop(FEEDFORWARDS["inverse"](), kp=0.5, ki=20.0, schedule=SCHEDULE)
    result = run(plant, loop, t, y_d, noise=ts.Sensor(noise_std=1e-3), shape_sensing=sensing)
    idx, _, rows = sensed_route_schedule(sensing, t, lambda _t: plant.route, 0.0)
    told = {0: rows[0, 2], **{int(k): rows[j, 2] for j, k in enumerate(idx)}}
    assert len(set(told.values())) > 10  # noisy readings: the schedule's gain moves
    python = _stepped(loop, result, told.get)
    np.testing.assert_allclose(result.command, python, rtol=0, atol=1e-12)


def test_json_round_trip_and_the_loader(tmp_path):
    loop = TipLoop(
        InverseFeedforward(Scaled(Backlash(B_r=0.05, B_l=0.03), output_gain=1.1), 0.04),
        kp=0.7,
        ki=35.0,
        kd=0.001,
        derivative_cutoff_hz=80.0,
        max_correction=0.2,
        schedule={2.0: 1.5, 0.5: 0.8},
        limits=(-2.0, 2.0, 30.0),
    )
    assert loop.schedule == ((0.5, 0.8), (2.0, 1.5))
    loop.to_json(tmp_path / "loop.json")
    back = ts.compensate.load(tmp_path / "loop.json")
    assert isinstance(back, TipLoop)
    assert back.to_dict() == loop.to_dict()
    assert TipLoop.load(loop.to_json()).schedule == loop.schedule
    t = np.arange(0.0, 1.0, 1e-3)
    y_d, y = 0.5 * np.sin(3 * t), 0.45 * np.sin(3 * t - 0.05)
    loop.set_curve_angle(1.2), back.set_curve_angle(1.2)
    loop.reset(), back.reset()
    for k in range(t.size):
        dt = 0.0 if k == 0 else 1e-3
        assert loop.step(y_d[k], y[k], dt) == back.step(y_d[k], y[k], dt)


def test_a_dropout_falls_back_toward_the_feedforward():
    ff = InverseFeedforward(BoucWenBacklash())
    loop = TipLoop(ff, kp=1.0, ki=100.0)
    for k in range(100):
        loop.step(0.3, 0.2, 0.0 if k == 0 else 1e-3)
    before = loop.correction
    u = loop.step(0.3, math.nan, 1e-3)
    assert ts.Status.FALLBACK in loop.status()
    assert math.isfinite(u) and 0.0 < loop.correction < before  # the P term is gone


def test_from_design_takes_any_design():
    class Design:
        schedule = [(0.0, 1.0), (3.0, 2.0)]

        def gains(self):
            return {"kp": 0.4, "ki": 12.0, "kd": 0.0, "derivative_cutoff_hz": 40.0}

    design = Design()
    loop = TipLoop.from_design(InverseFeedforward(Backlash()), design, limits=(-1.0, 1.0))
    assert loop.design is design and loop.params["ki"] == 12.0
    assert loop.schedule == ((0.0, 1.0), (3.0, 2.0)) and loop.follows_route
    loop.set_curve_angle(1.5)
    assert loop.gain_scale == pytest.approx(1.5)
    assert TipLoop(InverseFeedforward(Backlash())).design is None
    with pytest.raises(TypeError, match="gains"):
        TipLoop.from_design(InverseFeedforward(Backlash()), object())


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"kp": -1.0}, ValueError, "kp"),
        ({"ki": math.nan}, ValueError, "ki"),
        ({"derivative_cutoff_hz": 0.0}, ValueError, "derivative_cutoff_hz"),
        ({"max_correction": 0.0}, ValueError, "max_correction"),
        ({"kd": "high"}, TypeError, "kd"),
        ({"gain": 1.0}, TypeError, "gain"),
        ({"schedule": [(0.0, 1.0), (0.0, 2.0)]}, ValueError, "schedule_angles"),
        ({"schedule": [(0.0, 1.0), (1.0, 0.0)]}, ValueError, "schedule_gains"),
        ({"schedule": [(0.0, 1.0, 2.0)]}, TypeError, "schedule entry 0"),
        ({"schedule": [(float(i), 1.0) for i in range(9)]}, ValueError, "at most 8"),
        ({"schedule": 3.0}, TypeError, "schedule"),
        ({"limits": (1.0, -1.0)}, ValueError, "min"),
    ],
)
def test_bad_settings_are_one_line_errors(kwargs, error, match):
    with pytest.raises(error, match=match):
        TipLoop(InverseFeedforward(BoucWenBacklash()), **kwargs)


def test_bad_feedforwards_and_curve_angles_are_refused():
    ff = InverseFeedforward(BoucWenBacklash())
    for inner in ("Backlash", EncoderLoop(ff), TipLoop(ff)):
        with pytest.raises(TypeError, match="feedforward"):
            TipLoop(inner)
    with pytest.raises(TypeError, match="feedforward"):
        EncoderLoop(TipLoop(ff))
    with pytest.raises(ValueError, match="curve_angle"):
        TipLoop(ff, schedule=SCHEDULE).set_curve_angle(-1.0)


def test_it_improves_on_its_feedforward_on_a_realistic_plant():
    """A hand-tuned loop (kp 0.5, ki 20/s) around an InverseFeedforward whose backlash guess
    is rough: measured MSE 1.7e-4 rad^2 for the feedforward alone, 4.4e-5 with the loop (3.9x);
    asserted: at least 2x."""
    plant = _plant()
    t = np.arange(0.0, 4.0, 1e-3)
    y_d = 0.6 * np.sin(2 * np.pi * 0.5 * t)
    sensor = ts.Sensor(noise_std=1e-3)
    ff = InverseFeedforward(Backlash(B_r=0.01, B_l=0.01), 0.03)
    alone = run(plant, ff, t, y_d, noise=sensor)
    looped = run(plant, TipLoop(ff, kp=0.5, ki=20.0), t, y_d, noise=sensor)
    assert alone.metrics["mse"] < run(plant, None, t, y_d, noise=sensor).metrics["mse"]
    assert looped.metrics["mse"] < 0.5 * alone.metrics["mse"]
