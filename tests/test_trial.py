"""Trials scored on what the sensors measure, and the torque motor identified from its logs."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench import calibrate_torque_motor, calibration_trial, measured_mse
from tendonsheath.bench.calibration import calibration_input


def _result(t, reference, measured, warmup=0.0):
    n = t.size
    z = np.zeros(n)
    return ts.bench.Result(
        "x", t, reference, z, measured, z, z, z.astype(bool), z.astype(bool), warmup
    )


@pytest.mark.parametrize("case", range(20))
def test_measured_mse_compares_the_reading_with_the_reference_as_it_was(case):
    rng = np.random.default_rng(case)
    t = np.arange(0.0, 5.0, 1e-3)
    # whole periods in the 4 s scored: the lag's mean square is then exact
    f = int(rng.integers(1, 12)) / 4.0
    delay, offset = rng.uniform(0.0, 0.02), rng.uniform(-0.1, 0.1)
    reference = np.sin(2 * np.pi * f * t)
    # a sensor reading the reference exactly, late by `delay`, plus a constant error
    measured = np.interp(t - delay, t, reference) + offset
    r = _result(t, reference, measured, warmup=1.0)
    assert measured_mse(r, delay) == pytest.approx(offset**2, rel=1e-6, abs=1e-12)
    # scored as if it had no latency, the lag counts as error: sin(w t - w d) - sin(w t) has
    # the mean square 2 sin^2(w d / 2)
    lagged = _result(t, reference, measured - offset, warmup=1.0)
    lag_power = 2.0 * math.sin(math.pi * f * delay) ** 2
    assert measured_mse(lagged, 0.0) == pytest.approx(lag_power, rel=0.02, abs=1e-9)


def test_measured_mse_leaves_dropouts_out_and_rejects_a_bad_delay():
    t = np.arange(0.0, 1.0, 1e-3)
    measured = np.full(t.size, 0.1)
    measured[::3] = np.nan
    r = _result(t, np.zeros(t.size), measured)
    assert measured_mse(r) == pytest.approx(0.01)
    with pytest.raises(ValueError, match="delay"):
        measured_mse(r, -1.0)
    assert measured_mse(_result(t, np.zeros(t.size), np.full(t.size, np.nan))) == math.inf


def test_a_trial_scores_on_the_sensor_not_on_the_truth():
    d = ts.presets.random_realistic_plant(1)
    noise = 3e-3  # far above the tracking error's size: the score must show it
    sensor = ts.Sensor(noise_std=noise, seed=5)
    trial = calibration_trial(d.plant(), d.calibration_routes, sensor, duration=6.0, amplitude=0.3)
    r = trial.run(None)
    true = r.metrics["mse"]
    assert trial(None) == pytest.approx(true + noise**2, rel=0.1)
    # the routes switch among the calibration shapes only
    shapes = {id(trial.routes(s)) for s in np.arange(0.0, 6.0, 0.1)}
    assert len(shapes) == len(d.calibration_routes)


def test_a_trial_needs_a_sensor_and_shapes():
    d = ts.presets.random_realistic_plant(1)
    with pytest.raises(TypeError, match="scored on what a sensor measures"):
        ts.bench.Trial(d.plant(), np.arange(3.0), np.zeros(3), sensor=1e-3)
    with pytest.raises(ValueError, match="at least one calibration shape"):
        calibration_trial(d.plant(), [], ts.Sensor())


def test_a_diverging_or_saturating_candidate_scores_inf():
    d = ts.presets.random_realistic_plant(2)
    plant = ts.PullPullPlant(
        route=d.nominal_route, **d.physics(), motor=ts.Motor.torque(max_torque=0.01)
    )

    class Saturating:
        control_output = "torque"

        def reset(self):
            pass

        def step(self, y_d, dt):
            return 10.0

    trial = calibration_trial(plant, d.calibration_routes, ts.Sensor(), duration=2.0)
    assert trial(Saturating()) == math.inf


@pytest.mark.parametrize("seed", range(4))
def test_the_torque_motor_is_identified_from_its_logs(seed):
    d = ts.presets.random_realistic_plant(seed)
    c = calibrate_torque_motor(d.torque_plant(), d.calibration_routes[0])
    # the tendons' hysteresis and the sheath's viscosity sit in the regression's residual and
    # in b: measured within 18 % on J and +45 % on b over seeds 0-9
    assert c.inertia == pytest.approx(d.values["torque_inertia"], rel=0.25)
    assert d.values["torque_viscous"] * 0.8 < c.viscous < d.values["torque_viscous"] * 1.8
    assert 0.0 < c.inertia_se < 0.1 * c.inertia


def test_torque_calibration_needs_a_torque_motor():
    d = ts.presets.random_realistic_plant(0)
    with pytest.raises(ValueError, match="torque motor"):
        calibrate_torque_motor(d.plant())


@pytest.mark.parametrize("case", range(30))
def test_choose_keeps_a_richer_candidate_only_when_it_helps(case):
    rng = np.random.default_rng(case)
    scores = {f"c{i}": float(rng.choice([rng.uniform(0.5, 2.0), math.inf])) for i in range(3)}
    choice = ts.bench.choose({k: k for k in scores}, lambda c: scores[c], keep_below=0.9)
    # the rule replayed: walk simplest first, move on only below 0.9 x the current one
    best = "c0"
    for name in ("c1", "c2"):
        if scores[name] < 0.9 * scores[best]:
            best = name
    assert choice.name == best and choice.chosen == best
    assert choice.scores == scores
    assert f"chosen: {best}" in choice.reason


def test_choose_leaves_out_a_part_that_does_not_help_and_says_so():
    choice = ts.bench.choose({"alone": 1, "with loop": 2}, lambda c: {1: 1.0, 2: 0.97}[c])
    assert choice.name == "alone" and "left out: with loop" in choice.reason
    with pytest.raises(ValueError, match="at least one candidate"):
        ts.bench.choose({}, lambda c: 0.0)
    with pytest.raises(ValueError, match="keep_below"):
        ts.bench.choose({"a": 1}, lambda c: 0.0, keep_below=0.0)


def test_choose_needs_a_richer_candidate_to_help_on_every_trial():
    first = {"a": 1.0, "b": 0.5}
    second = {"a": 1.0, "b": 0.99}  # b helps on one trial only
    choice = ts.bench.choose({"a": "a", "b": "b"}, [first.get, second.get])
    assert choice.name == "a" and "on every trial" in choice.reason
    assert choice.all_scores == [first, second]
    assert ts.bench.choose({"a": "a", "b": "b"}, [first.get, first.get]).name == "b"


def test_a_faster_trial_plays_the_same_excitation_faster():
    d = ts.presets.random_realistic_plant(0)
    slow = calibration_trial(d.plant(), d.calibration_routes, ts.Sensor(), duration=8.0)
    fast = calibration_trial(d.plant(), d.calibration_routes, ts.Sensor(), duration=8.0, speed=2.0)
    np.testing.assert_array_equal(slow.t, fast.t)
    np.testing.assert_array_equal(slow.reference, calibration_input(8.0, 1.0)[1])
    # twice as fast: a 16 s excitation played in 8 s, every other sample of it
    np.testing.assert_allclose(fast.reference, calibration_input(16.0, 1.0)[1][::2], atol=1e-12)
    with pytest.raises(ValueError, match="speed"):
        calibration_trial(d.plant(), d.calibration_routes, ts.Sensor(), speed=0.0)
