"""The closed-loop bench: equivalence with open-loop simulation, metrics, dropout, routes."""

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench import loop_width, tracking_metrics

T = np.arange(0.0, 6.0, 1e-3)
Y_D = 0.4 * np.sin(2 * np.pi * 0.5 * T)


def _plant(**kw):
    kw.setdefault("motor", ts.Motor.position(bandwidth_hz=15.0))
    return ts.PullPullPlant(route=ts.Route.uniform(1.2, np.pi), elements=30, **kw)


def test_feedforward_loop_equals_open_loop_simulation():
    plant = _plant()
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash(1.0, 1.0, 0.03, 0.03))
    result = ts.bench.run(plant, ff, T, Y_D)
    open_loop = plant.simulate(T, ff.command(T, Y_D))
    np.testing.assert_array_equal(result.output, open_loop)
    none = ts.bench.run(plant, None, T, Y_D)
    np.testing.assert_array_equal(none.output, plant.simulate(T, Y_D))


def test_metrics_match_their_definitions(rng):
    ref = np.sin(np.linspace(0, 20, 2000))
    out = ref + rng.normal(0, 0.01, ref.size)
    m = tracking_metrics(ref, out)
    e = out - ref
    assert m["mse"] == pytest.approx(np.mean(e**2))
    assert m["rmse"] == pytest.approx(np.sqrt(np.mean(e**2)))
    assert m["max_abs"] == pytest.approx(np.max(np.abs(e)))
    assert m["percent_error"] == pytest.approx(100 * np.mean(np.abs(e)) / np.ptp(ref))
    # a pure backlash of half-width b has a loop of height 2b
    x = np.sin(np.linspace(0, 6 * np.pi, 6000))
    y = ts.models.Backlash(1.0, 1.0, 0.1, 0.1).simulate(None, x)
    assert loop_width(x[2000:], y[2000:]) == pytest.approx(0.2, abs=2e-3)


def test_warmup_defaults_to_one_period_and_is_excluded():
    result = ts.bench.run(_plant(), None, T, Y_D)
    assert result.warmup == pytest.approx(2.0, rel=0.01)
    kept = result.scored
    assert abs(int(kept.sum()) - int(np.sum(T >= 2.0))) <= 1
    assert result.metrics["mse"] == pytest.approx(np.mean(result.error[kept] ** 2))


def test_adaptive_needs_a_torque_motor_and_falls_back_during_dropout():
    ctrl = ts.compensate.AdaptiveController.from_model(ts.models.Backlash(1, 1, 0.03, 0.03), 1e-5)
    with pytest.raises(ValueError, match="torque"):
        ts.bench.run(_plant(), ctrl, T, Y_D)
    plant = _plant(motor=ts.Motor.torque(inertia=1e-5, viscous=1e-4, max_torque=0.5))
    result = ts.bench.run(
        plant, ctrl, T, Y_D, dropout=[(3.0, 3.5)], noise=ts.Sensor(noise_std=1e-4)
    )
    in_window = (T >= 3.0) & (T < 3.5)
    assert np.all(np.isnan(result.measured[in_window]))
    # the controller sees each reading one cycle later
    assert np.all(result.fallback[in_window][1:]) and not np.any(result.fallback[T > 3.6])
    assert np.all(np.isfinite(result.command)) and np.max(np.abs(result.command)) <= 0.5


def test_curve_angle_controller_sees_route_changes():
    plant = _plant(motor=None)
    ff = ts.compensate.CurveAngleFeedforward(0.1, 2.4e4, 1.2, 10.0, curve_angle=0.1, smoothing=0.01)

    def routes(t):
        return ts.Route.uniform(1.2, np.pi if t < 3.0 else 2 * np.pi)

    result = ts.bench.run(plant, ff, T, Y_D, routes=routes)
    # it was told the true shape (pi, then 2 pi), not its constructor's 0.1 rad
    ff_pi = ts.compensate.CurveAngleFeedforward(
        0.1, 2.4e4, 1.2, 10.0, curve_angle=np.pi, smoothing=0.01
    )
    early = T < 3.0
    np.testing.assert_allclose(
        result.command[early], ff_pi.command(T, Y_D)[early], rtol=1e-12, atol=1e-15
    )
    assert result.metrics["rmse"] < ts.bench.run(plant, None, T, Y_D, routes=routes).metrics["rmse"]


def test_bad_input():
    with pytest.raises(ValueError, match="PullPullPlant"):
        ts.bench.run(object(), None, T, Y_D)
    with pytest.raises(TypeError, match="has no reset and no step"):
        ts.bench.run(_plant(), object(), T, Y_D)
    with pytest.raises(ValueError, match="not finite"):
        ts.bench.run(_plant(), None, T, np.where(T > 1, np.nan, Y_D))
    with pytest.raises(ValueError, match="start < stop"):
        ts.bench.run(_plant(), None, T, Y_D, dropout=[(2.0, 1.0)])
