"""EncoderLoop in Python: the bench runs it in C++ exactly as its Python step, it saves and
loads bit for bit around each shipped feedforward, it makes a yielding servo follow its
feedforward, and bad settings are one-line errors."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench.run import run
from tendonsheath.compensate import (
    ContinuumFeedforward,
    CurveAngleFeedforward,
    EncoderLoop,
    InverseFeedforward,
)
from tendonsheath.models import BoucWenBacklash, PrandtlIshlinskii, Scaled


def _yielding_plant(route=None):
    """A pull-pull drive behind a PD servo that yields to the tendons (no integral action)."""
    route = route or ts.Route.arcs([(0.5, 0.0), (0.5, math.pi / 2), (0.5, math.pi / 2)])
    return ts.PullPullPlant(
        route=route,
        pretension=20.0,
        proximal_radius=15e-3,
        distal_radius=15e-3,
        elements=20,
        friction=0.1,
        stiffness=5e3,
        motor=ts.Motor.position(bandwidth_hz=10.0, damping=0.8, inertia=1e-4),
    )


class _Stepped:
    """The same compensator stepped from Python by the bench (its Python path)."""

    step_inputs = ("y_d", "q")

    def __init__(self, inner):
        self.inner = inner

    def reset(self):
        self.inner.reset()

    def step(self, y_d, q, dt):
        return self.inner.step(y_d, q, dt)


FEEDFORWARDS = {
    "bouc_wen_backlash": lambda: InverseFeedforward(BoucWenBacklash(B_r=0.12, B_l=0.1), 0.05),
    "scaled": lambda: InverseFeedforward(Scaled(BoucWenBacklash(), output_gain=-1.0), 0.05),
    "prandtl_ishlinskii": lambda: InverseFeedforward(PrandtlIshlinskii.uniform(0.3, 5)),
    "curve_angle": lambda: CurveAngleFeedforward(
        0.1, 5e3, 1.5, 20.0, curve_angle=math.pi, proximal_radius=15e-3, distal_radius=15e-3
    ),
    "continuum": lambda: ContinuumFeedforward(mode="exact"),
}


@pytest.mark.parametrize("name", sorted(FEEDFORWARDS))
def test_the_bench_runs_it_in_cpp_as_its_python_step(name):
    # a uniform route of the curve-angle feedforward's angle: the C++ path tells it the route's
    # shape, the Python path (no route) keeps the angle it was built with; both the same here
    plant = _yielding_plant(ts.Route.uniform(1.5, math.pi))
    t = np.arange(0.0, 3.0, 1e-3)
    y_d = 0.6 * np.sin(2 * np.pi * 0.5 * t)
    fast = run(plant, EncoderLoop(FEEDFORWARDS[name](), kp=1.0, ki=200.0), t, y_d)
    slow = run(plant, _Stepped(EncoderLoop(FEEDFORWARDS[name](), kp=1.0, ki=200.0)), t, y_d)
    assert fast.controller == "EncoderLoop"
    np.testing.assert_array_equal(fast.command, slow.command)
    np.testing.assert_array_equal(fast.status, slow.status)


@pytest.mark.parametrize("name", sorted(FEEDFORWARDS))
def test_json_round_trip_is_bit_for_bit(name, tmp_path):
    rng = np.random.default_rng(len(name))
    loop = EncoderLoop(
        FEEDFORWARDS[name](),
        kp=rng.uniform(0, 3),
        ki=rng.uniform(0, 500),
        kd=rng.uniform(0, 0.01),
        derivative_cutoff_hz=rng.uniform(10, 200),
        max_correction=rng.choice([math.inf, 0.3]),
        limits=(-2.0, 2.0, 30.0),
    )
    loop.to_json(tmp_path / "loop.json")
    back = ts.compensate.load(tmp_path / "loop.json")
    assert isinstance(back, EncoderLoop)
    assert back.to_dict() == loop.to_dict()
    t = np.arange(0.0, 2.0, 1e-3)
    y_d, q = 0.5 * np.sin(3 * t), 0.45 * np.sin(3 * t - 0.05)
    for a, b in ((loop, back),):
        a.reset(), b.reset()
        for k in range(t.size):
            dt = 0.0 if k == 0 else 1e-3
            assert a.step(y_d[k], q[k], dt) == b.step(y_d[k], q[k], dt)


def test_it_makes_a_yielding_servo_follow_its_feedforward():
    """The encoder follows the feedforward's command: the PD servo alone misses it by the
    tendons' pull over its stiffness (tens of mrad here); the loop removes most of that."""
    plant = _yielding_plant()
    t = np.arange(0.0, 8.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.25 * t)
    ff = InverseFeedforward(BoucWenBacklash(B_r=0.05, B_l=0.05), 0.05)
    alone = run(plant, ff, t, y_d)
    looped = run(plant, EncoderLoop(ff, kp=1.0, ki=150.0), t, y_d)
    keep = t > 2.0
    miss_alone = np.sqrt(np.mean((alone.q_motor - alone.command)[keep] ** 2))
    target = ff.command(t, y_d)
    miss_looped = np.sqrt(np.mean((looped.q_motor - target)[keep] ** 2))
    assert miss_alone > 0.01
    # measured: 0.024 rad alone against 0.0016 rad with the loop (the servo's lag remains)
    assert miss_looped < 0.2 * miss_alone


def test_a_dropout_of_the_encoder_is_reported_and_held():
    loop = EncoderLoop(InverseFeedforward(BoucWenBacklash()), kp=1.0, ki=100.0)
    for k in range(100):
        loop.step(0.3, 0.2, 0.0 if k == 0 else 1e-3)
    held = loop.correction
    u = loop.step(0.3, math.nan, 1e-3)
    assert ts.Status.FALLBACK in loop.status()
    assert loop.correction == held and math.isfinite(u)


def test_to_control_takes_the_desired_output_and_the_encoder():
    loop = EncoderLoop(InverseFeedforward(BoucWenBacklash()), ki=100.0)
    sys = loop.to_control(1e-3)
    assert [sys.input_labels, sys.output_labels] == [["y_d", "q"], ["x"]]
    t = np.arange(0.0, 0.2, 1e-3)
    y_d, q = 0.3 * np.sin(10 * t), 0.25 * np.sin(10 * t)
    import control as ct

    resp = ct.input_output_response(sys, t, np.vstack([y_d, q]))
    loop.reset()
    dts = np.r_[0.0, np.full(t.size - 1, 1e-3)]
    direct = [loop.step(a, b, dt) for a, b, dt in zip(y_d, q, dts, strict=True)]
    np.testing.assert_allclose(np.ravel(resp.outputs), direct, rtol=0, atol=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"ki": -1.0}, ValueError, "ki"),
        ({"derivative_cutoff_hz": 0.0}, ValueError, "derivative_cutoff_hz"),
        ({"max_correction": 0.0}, ValueError, "max_correction"),
        ({"kp": "high"}, TypeError, "kp"),
        ({"gain": 1.0}, TypeError, "gain"),
    ],
)
def test_bad_settings_are_one_line_errors(kwargs, error, match):
    with pytest.raises(error, match=match):
        EncoderLoop(InverseFeedforward(BoucWenBacklash()), **kwargs)


def test_what_is_not_a_feedforward_is_refused():
    with pytest.raises(TypeError, match="feedforward"):
        EncoderLoop(BoucWenBacklash.__name__)
    inner = EncoderLoop(InverseFeedforward(BoucWenBacklash()))
    with pytest.raises(TypeError, match="feedforward"):
        EncoderLoop(inner)


def test_a_user_feedforward_runs_but_cannot_be_saved():
    class Gain:
        def reset(self):
            pass

        def step(self, y_d, dt):
            return 1.1 * y_d

    loop = EncoderLoop(Gain(), ki=50.0)
    plant = _yielding_plant()
    t = np.arange(0.0, 1.0, 1e-3)
    result = run(plant, loop, t, 0.3 * np.sin(4 * t))
    assert np.isfinite(result.metrics["rmse"])
    with pytest.raises(TypeError, match="cannot be saved"):
        loop.to_json()
