"""The status every cycle, through Python: streaming status(), the per-sample flags of the batch
calls (models, feedforwards, plants) and the bench's counts in metrics and the report."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.compensate import CommandLimits, InverseFeedforward
from tendonsheath.status import STATUS_FLAGS, Status, status_counts

T = np.linspace(0.0, 4.0, 4001)
SINE = 0.8 * np.sin(2 * np.pi * 0.5 * T)


def _models():
    return [
        ts.models.Backlash(c_r=1.1, c_l=0.9, B_r=0.05, B_l=0.08),
        ts.models.BoucWenBacklash(),
        ts.models.PrandtlIshlinskii(thresholds=[0.0, 0.1, 0.2], weights=[0.5, 0.3, 0.2]),
        ts.models.PrandtlIshlinskiiInverse(thresholds=[0.0, 0.1, 0.2], weights=[0.5, 0.3, 0.2]),
        ts.models.GeneralizedPrandtlIshlinskii(),
    ]


def test_status_counts_names_every_flag_and_counts_each_bit():
    flags = np.array([0, 1, 3, 32, 36, 0], dtype=np.uint8)
    counts = status_counts(flags)
    assert tuple(counts) == STATUS_FLAGS
    assert counts == {
        "held_nonfinite_input": 2,
        "input_clamped": 1,
        "not_converged": 1,
        "slack": 0,
        "fallback": 0,
        "saturated": 2,
        "out_of_range": 0,
    }
    with pytest.raises(ValueError, match="non-negative integers"):
        status_counts(np.array([0.5]))


@pytest.mark.parametrize("model", _models(), ids=lambda m: type(m).__name__)
def test_model_batch_flags_match_the_streaming_status(model):
    rng = np.random.default_rng(7)
    x = np.cumsum(rng.normal(0.0, 0.05, T.size))
    y_plain = model.simulate(T, x)
    y = model.simulate(T, x)
    flags = y.status
    assert isinstance(y_plain, np.ndarray)  # the default return type is unchanged
    np.testing.assert_array_equal(y, y_plain)
    assert flags.dtype == np.uint8 and flags.shape == x.shape
    model.reset()
    streamed = []
    for k in range(T.size):
        model.step(x[k], T[k] - T[k - 1] if k else 0.0)
        streamed.append(int(model.status()))
    np.testing.assert_array_equal(flags, streamed)


def test_a_held_nan_is_flagged_in_streaming_and_cleared_after():
    for model in _models():
        for k in range(20):
            model.step(0.01 * k)
        y = model.step(math.nan)
        assert model.status() == Status.HELD_NONFINITE_INPUT, type(model).__name__
        assert y == model.step(math.nan)
        model.step(0.3)
        assert not model.status() & Status.HELD_NONFINITE_INPUT


def test_pi_inverse_flags_an_unreachable_target_as_clamped():
    inv = ts.models.PrandtlIshlinskiiInverse(thresholds=[0.0, 0.1], weights=[0.6, 0.4])
    flags = inv.simulate(None, np.array([0.0, 0.5, 1e305, 0.2])).status
    assert [bool(f & Status.INPUT_CLAMPED) for f in flags] == [False, False, True, False]


@pytest.mark.parametrize("limit", [0.1, 0.3, 0.6])
def test_feedforward_flags_exactly_the_cycles_cut_to_the_limits(limit):
    ff = InverseFeedforward(ts.models.Backlash(), limits=CommandLimits(-limit, limit))
    u_plain = ff.command(T, SINE)
    u = ff.command(T, SINE)
    flags = u.status
    np.testing.assert_array_equal(u, u_plain)
    free = InverseFeedforward(ts.models.Backlash()).command(T, SINE)
    cut = np.abs(free) > limit
    assert cut.any() and not cut.all()
    np.testing.assert_array_equal((flags & Status.SATURATED) != 0, cut)
    assert status_counts(flags)["saturated"] == int(cut.sum())


def test_feedforward_streaming_status_reports_saturation():
    ff = ts.compensate.ContinuumFeedforward(limits=CommandLimits(-0.05, 0.05))
    ff.step(0.0, 1e-3)
    assert ff.status() == Status.OK
    ff.step(1.0, 1e-3)
    assert ff.status() & Status.SATURATED


def test_plant_simulate_reports_held_and_motor_saturation_per_sample():
    plant = ts.PullPullPlant(route=ts.Route.uniform(1.0, 2.0), elements=20)
    q_plain = plant.simulate(T, SINE)
    q = plant.simulate(T, SINE)
    flags = q.status
    np.testing.assert_array_equal(q, q_plain)
    assert not flags.any()  # a clean run flags nothing
    result = plant.simulate(T, SINE)
    np.testing.assert_array_equal(result.status, flags)
    slow = ts.PullPullPlant(
        route=ts.Route.uniform(1.0, 2.0), elements=20, motor=ts.Motor.position(max_speed=1.0)
    )
    counts = status_counts(slow.simulate(T, SINE).status)
    # the sine's peak speed is 0.8 * pi ~ 2.5 rad/s: the 1 rad/s limit cuts part of each cycle
    assert counts["saturated"] > 100
    assert counts["held_nonfinite_input"] == 0


def test_plant_streaming_status_includes_the_motor():
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(1.0, 2.0), elements=20, motor=ts.Motor.position(max_speed=1.0)
    )
    plant.step(0.0, 1e-3)
    assert plant.status() == Status.OK
    saturated = []
    for _ in range(300):  # the 1.5 Hz servo speeds up past 1 rad/s toward a 5 rad step
        plant.step(5.0, 1e-3)
        saturated.append(bool(plant.status() & Status.SATURATED))
    assert not saturated[0] and saturated[-1]
    plant.step(math.nan, 1e-3)
    assert plant.status() & Status.HELD_NONFINITE_INPUT


def _bench(limits=None, noise=None, dropout=None):
    plant = ts.PullPullPlant(route=ts.Route.uniform(1.0, 2.0), elements=20)
    ff = InverseFeedforward(ts.models.Backlash(B_r=0.02, B_l=0.02), limits=limits)
    return ts.bench.run(plant, ff, T, SINE, noise=noise, dropout=dropout)


def test_bench_counts_saturated_cycles_and_a_clean_run_shows_none():
    clean = _bench()
    assert clean.metrics["status"] == dict.fromkeys(STATUS_FLAGS, 0)
    saturating = _bench(limits=CommandLimits(-0.5, 0.5))
    counts = saturating.metrics["status"]
    # the command must reach about 0.8 rad; a 0.5 rad limit cuts a part of every half cycle
    assert counts["saturated"] > 200
    assert counts["saturated"] == int(np.count_nonzero(saturating.status & Status.SATURATED))
    assert np.all(np.abs(saturating.command[(saturating.status & Status.SATURATED) != 0]) == 0.5)


def test_bench_counts_the_adaptive_controllers_fallback_cycles():
    motor = ts.Motor.torque(inertia=1e-2, viscous=0.2, max_torque=5.0)
    plant = ts.PullPullPlant(route=ts.Route.uniform(1.0, 2.0), elements=20, motor=motor)
    ctrl = ts.compensate.AdaptiveController.from_model(
        ts.models.Backlash(), inertia=1e-2, viscous=0.2, max_torque=5.0
    )
    result = ts.bench.run(plant, ctrl, T, SINE, noise=1e-4, dropout=[(1.0, 1.5)])
    fallback = result.metrics["status"]["fallback"]
    assert fallback == int(result.fallback.sum())
    assert 450 <= fallback <= 510  # 0.5 s of dropout at 1 kHz (plus the cycle it is noticed)


def test_curve_angle_model_flags_slack_only_in_the_cycles_past_the_no_slack_bound():
    # spring load: the distal force grows with the output until it breaks the no-slack bound
    model = ts.models.CurveAngleModel(pretension=2.0, load_stiffness=4000.0, length=1.0)
    x = np.linspace(0.0, 3.0, 301)
    x = np.r_[x, x[::-1]]
    y = model.simulate(None, x, curve_angle=np.pi)
    flags = y.status
    np.testing.assert_array_equal(y, model.simulate(None, x, curve_angle=np.pi))
    slack = (flags & Status.SLACK) != 0
    assert slack.any() and not slack.all()
    # slack where |F| = |k x_out| is largest: every flagged output exceeds every clean one
    force = np.abs(y)
    assert force[slack].min() >= force[~slack].max() - 1e-12
    model.reset()
    for k, xk in enumerate(x):
        model.step(xk, 0.0, np.pi)
        assert int(model.status()) == flags[k]


def test_composite_models_report_their_parts_status():
    backlash = ts.models.Backlash(B_r=0.05, B_l=0.05)
    chain = ts.models.Chain(backlash, ts.models.SecondOrderLag())
    x = np.r_[SINE[:100], np.full(3, 1e12), SINE[100:200]]
    t = T[: x.size]
    y = chain.simulate(t, x)
    flags = y.status
    np.testing.assert_array_equal(y, chain.simulate(t, x))
    # the backlash reports (nothing to flag here); the linear block reports no status
    inner = backlash.simulate(t, x).status
    np.testing.assert_array_equal(flags, inner)
    with pytest.raises(TypeError, match="reports no status"):
        ts.models.SecondOrderLag().status()
    pi = ts.models.PrandtlIshlinskii(thresholds=[0.0, 0.1], weights=[0.6, 0.4])
    scaled = ts.models.Scaled(pi, input_scale=2.0, output_gain=-1.5)
    ys = scaled.simulate(None, np.array([0.0, 1.0, 1e305, 0.5]))
    fs = ys.status
    assert [bool(f & Status.INPUT_CLAMPED) for f in fs] == [False, False, True, False]
    np.testing.assert_array_equal(ys, scaled.simulate(None, np.array([0.0, 1.0, 1e305, 0.5])))
    scaled.step(1e305)
    assert scaled.status() == Status.INPUT_CLAMPED


def test_oscillator_flags_come_with_both_simulation_paths():
    osc = ts.models.HystereticOscillator()
    for periodic in (False, True):
        y = osc.simulate(T[:-1], SINE[:-1], periodic=periodic)
        flags = y.status
        np.testing.assert_array_equal(y, osc.simulate(T[:-1], SINE[:-1], periodic=periodic))
        assert flags.dtype == np.uint8 and not flags.any()
