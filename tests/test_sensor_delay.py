"""The sensor's latency (issue 23, item 6): a delayed reading is the true signal shifted by the
delay, noise is unchanged, a short history is flagged, and the bench feeds the controller the
delayed reading."""

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench.user_scenario import ScenarioError, parse


def test_a_ramp_is_shifted_by_the_delay(rng):
    """Linear interpolation is exact on a ramp, at any (jittered) rate; before the delay has
    passed the reading is the first sample."""
    for _ in range(30):
        rate, delay = rng.uniform(100.0, 5000.0), rng.uniform(0.0, 0.2)
        t = 0.3 + np.cumsum(rng.uniform(0.7, 1.3, 2000) / rate)
        slope, offset = rng.uniform(-5, 5), rng.uniform(-1, 1)
        x = offset + slope * t
        y = ts.Sensor(delay=delay, history=4096).measure(x, t=t)
        expected = offset + slope * np.maximum(t - delay, t[0])
        np.testing.assert_allclose(y, expected, rtol=0, atol=1e-11 * (1 + np.abs(x).max()))


def test_an_integer_sample_delay_is_a_shift(rng):
    for _ in range(20):
        dt, m = rng.uniform(1e-4, 1e-2), int(rng.integers(1, 50))
        x = rng.normal(size=600)
        t = np.arange(600) * dt
        sensor = ts.Sensor(delay=m * dt, history=m + 2)  # +1: t - delay rounded below a sample
        y = sensor.measure(x, t=t)
        np.testing.assert_allclose(y[m:], x[:-m], rtol=0, atol=1e-9)
        assert np.all(y[:m] == x[0])
        assert sensor.status() == ts.Status.OK


def test_noise_and_quantisation_apply_to_the_delayed_value_unchanged():
    """The same seed draws the same noise with or without a delay: reading minus the delayed
    true value is the undelayed sensor's noise, sample for sample."""
    t = np.arange(20000) * 1e-3
    x = np.sin(2 * np.pi * 0.3 * t)
    plain = ts.Sensor(noise_std=0.01, seed=42)
    delayed = ts.Sensor(noise_std=0.01, seed=42, delay=0.05)
    noise = plain.measure(x, t=t) - x
    shifted = np.r_[np.full(50, x[0]), x[:-50]]
    np.testing.assert_allclose(delayed.measure(x, t=t) - shifted, noise, rtol=0, atol=1e-12)
    assert noise.std() == pytest.approx(0.01, rel=0.03)
    step = 2 * np.pi / 4096
    quantised = ts.Sensor(resolution=step, delay=0.05).measure(x, t=t)
    np.testing.assert_allclose(np.round(quantised / step) * step, quantised, rtol=0, atol=1e-15)
    assert np.abs(quantised - shifted).max() <= step / 2 + 1e-15


def test_a_history_too_short_is_flagged():
    """A 10.5 ms delay at 1 kHz needs 12 samples: with fewer the oldest kept is read and
    INPUT_CLAMPED set once a sample has been dropped; with enough, never."""
    for history, flagged in ((5, True), (11, True), (12, False), (50, False)):
        sensor = ts.Sensor(delay=10.5e-3, history=history)
        flags = []
        for k in range(40):
            y = sensor.measure(float(k), dt=0.0 if k == 0 else 1e-3)
            flags.append(bool(sensor.status() & ts.Status.INPUT_CLAMPED))
        assert flags[-1] is flagged
        assert not any(flags[:history])  # nothing dropped yet: the first sample, no flag
        assert y == pytest.approx(40 - history if flagged else 39 - 10.5, abs=1e-12)


def test_scalar_calls_and_the_old_api():
    sensor = ts.Sensor(delay=0.01, history=8)
    assert sensor.measure(1.0) == 1.0
    assert sensor.measure(2.0) == 2.0  # dt 0: no time passes, the sample is replaced
    assert sensor.measure(3.0, dt=0.02) == 2.5
    assert "delay=0.01, history=8" in repr(sensor)
    assert (sensor.delay, sensor.history) == (0.01, 8)
    assert repr(ts.Sensor()) == "Sensor(resolution=0, noise_std=0, seed=0)"
    # delay 0: t is optional and changes nothing
    x = np.linspace(0, 1, 50)
    np.testing.assert_array_equal(ts.Sensor().measure(x), ts.Sensor().measure(x, t=x))


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: ts.Sensor(delay=-0.1), "Sensor: delay must be >= 0"),
        (lambda: ts.Sensor(delay=float("inf")), "Sensor: delay"),
        (lambda: ts.Sensor(history=0), r"Sensor: history must be in \[1, 16777216\]"),
        (lambda: ts.Sensor(delay=0.1).measure(np.zeros(3)), "needs the sample times t"),
        (lambda: ts.Sensor().measure(1.0, t=[0.0]), "a scalar x takes dt"),
        (lambda: ts.Sensor().measure([1.0, 2.0], t=[0.0]), "different sizes"),
        (lambda: ts.Sensor().measure([1.0, 2.0], t=[1.0, 0.0]), "strictly increasing"),
        (lambda: ts.Sensor().measure(1.0, dt=-1.0), "dt must be"),
    ],
)
def test_bad_values(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_history_must_be_an_integer():
    with pytest.raises(TypeError, match="history must be an integer"):
        ts.Sensor(history=10.5)


T = np.arange(0.0, 4.0, 1e-3)
Y_D = 0.4 * np.sin(2 * np.pi * 0.5 * T)


def _adaptive_run(noise):
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(1.2, np.pi),
        elements=30,
        motor=ts.Motor.torque(inertia=0.01, viscous=0.2, max_torque=5.0),
    )
    ctrl = ts.compensate.AdaptiveController.from_model(
        ts.models.Backlash(1, 1, 0.03, 0.03), inertia=0.01, viscous=0.2, max_torque=5.0
    )
    return ts.bench.run(plant, ctrl, T, Y_D, noise=noise)


def test_the_bench_feeds_the_controller_the_delayed_reading():
    exact = _adaptive_run(ts.Sensor())
    np.testing.assert_array_equal(exact.measured, exact.output)
    late = _adaptive_run(ts.Sensor(delay=0.005))
    # the reading at k is the output at k - 5 (1 kHz)
    np.testing.assert_allclose(late.measured[5:], late.output[:-5], rtol=0, atol=1e-9)
    # the controller acted on it: 5 ms of latency raised the MSE 11x (2.0e-6 -> 2.2e-5) and
    # moved the commands by up to 1.2 N m; the bounds sit well below both
    assert late.metrics["mse"] > 3 * exact.metrics["mse"]
    assert np.abs(late.command - exact.command).max() > 0.1
    # delay 0 is the plain sensor, bit for bit (and the sensor before the latency existed:
    # checked against main's build when this was written)
    zero = _adaptive_run(ts.Sensor(delay=0.0, history=1))
    np.testing.assert_array_equal(zero.command, exact.command)
    np.testing.assert_array_equal(zero.output, exact.output)


def test_a_plant_sensor_with_a_delay():
    route = ts.Route.uniform(1.0, np.pi)
    plant = ts.PullPullPlant(route=route, elements=30, sensor=ts.Sensor(delay=0.01))
    t = np.arange(0.0, 2.0, 1e-3)
    res = plant.simulate(t, 0.5 * np.sin(2 * np.pi * t))
    np.testing.assert_allclose(res.measured[10:], res.q_out[:-10], rtol=0, atol=1e-9)


SCENARIO = """
[sensor]
noise_std = 1e-4
{extra}
"""


def test_a_scenario_sensor_takes_a_delay():
    sc = parse(SCENARIO.format(extra="delay = 0.005\nhistory = 64"))
    assert sc.sensor["delay"] == 0.005 and sc.sensor["history"] == 64
    assert ts.Sensor(**sc.sensor).delay == 0.005


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("delay = -0.005", r"<scenario> \[sensor\]: delay must be >= 0 \(got -0.005\)"),
        ("delay = 'soon'", r"<scenario> \[sensor\]: 'delay' must be a number"),
        ("history = 0", r"<scenario> \[sensor\]: history must be in \[1, 16777216\]"),
        ("history = 1.5", r"<scenario> \[sensor\]: 'history' must be an integer"),
        ("seed = -1", r"<scenario> \[sensor\]: seed must be >= 0"),
    ],
)
def test_a_scenario_sensor_with_a_bad_value_is_named_in_one_line(extra, message):
    with pytest.raises(ScenarioError, match=message) as err:
        parse(SCENARIO.format(extra=extra))
    assert "\n" not in str(err.value)
