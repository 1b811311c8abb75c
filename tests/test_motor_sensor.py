import math

import numpy as np
import pytest

import tendonsheath as ts


def test_position_motor_is_a_second_order_lag():
    fn, zeta = 2.0, 0.7
    m = ts.Motor.position(bandwidth_hz=fn, damping=zeta)
    t = np.arange(0, 3.0, 1e-3)
    q = m.simulate(t, np.r_[0.0, np.ones(t.size - 1)])
    assert q[-1] == pytest.approx(1.0, abs=1e-4)
    overshoot = q.max() - 1
    expected = math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2))
    assert overshoot == pytest.approx(expected, rel=0.05)
    # gain at the natural frequency of a 2nd-order lag: 1 / (2 zeta)
    t = np.arange(0, 10.0, 1e-3)
    y = m.simulate(t, np.sin(2 * np.pi * fn * t))
    tail = t > 5
    gain = np.ptp(y[tail]) / 2
    assert gain == pytest.approx(1 / (2 * zeta), rel=0.03)


def test_position_motor_limits():
    m = ts.Motor.position(bandwidth_hz=5.0, damping=1.0, max_speed=0.5, max_accel=2.0)
    t = np.arange(0, 4.0, 1e-3)
    q = m.simulate(t, np.r_[0.0, np.ones(t.size - 1)])
    v = np.diff(q) / 1e-3
    assert np.abs(v).max() <= 0.5 + 1e-9
    assert np.abs(np.diff(v) / 1e-3).max() <= 2.0 + 1e-6
    assert q[-1] == pytest.approx(1.0, abs=1e-3)


def test_torque_motor_reaches_torque_over_viscous_speed():
    m = ts.Motor.torque(inertia=0.01, viscous=0.2, max_torque=0.1)
    t = np.arange(0, 2.0, 1e-3)
    q = m.simulate(t, np.full(t.size, 1.0))  # saturated to 0.1 N m
    v = np.diff(q)[-1] / 1e-3
    assert v == pytest.approx(0.1 / 0.2, rel=1e-3)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: ts.Motor.position(bandwidth_hz=0.0), "bandwidth_hz must be > 0"),
        (lambda: ts.Motor.position(damping=-1.0), "damping must be > 0"),
        (lambda: ts.Motor.position(max_speed=0.0), "max_speed must be > 0"),
        (lambda: ts.Motor.torque(inertia=0.0), "inertia must be > 0"),
        (lambda: ts.Motor.torque(max_torque=-1.0), "max_torque must be > 0"),
        (lambda: ts.Sensor(resolution=-1.0), "resolution must be >= 0"),
        (lambda: ts.Sensor(noise_std=float("nan")), "noise_std"),
        (lambda: ts.Sensor(seed=-3), "seed must be >= 0"),
    ],
)
def test_bad_motor_and_sensor_parameters(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_sensor_quantisation_noise_and_seed():
    s = ts.Sensor(resolution=2 * np.pi / 4096)
    x = np.linspace(-1, 1, 1001)
    y = s.measure(x)
    assert np.abs(y - x).max() <= np.pi / 4096 + 1e-15
    np.testing.assert_allclose(np.round(y / (2 * np.pi / 4096)) * (2 * np.pi / 4096), y)
    noisy = ts.Sensor(noise_std=0.01, seed=42)
    r1 = noisy.measure(np.zeros(20000))
    assert r1.std() == pytest.approx(0.01, rel=0.03)
    assert abs(r1.mean()) < 3e-4
    noisy.reset()
    np.testing.assert_array_equal(noisy.measure(np.zeros(20000)), r1)
    other = ts.Sensor(noise_std=0.01, seed=43).measure(np.zeros(100))
    assert not np.array_equal(other, r1[:100])
    assert s.measure(0.5) == pytest.approx(0.5, abs=np.pi / 4096)


def test_plant_with_position_motor_and_sensor():
    t = np.arange(0, 6.0, 1e-3)
    q = 0.5 * np.sin(2 * np.pi * 1.0 * t)
    route = ts.Route.uniform(1.0, np.pi)
    bare = ts.PullPullPlant(route=route, elements=40)
    motor = ts.Motor.position(bandwidth_hz=1.2, damping=0.7, max_speed=5.0)
    sensor = ts.Sensor(resolution=1e-4, noise_std=1e-4, seed=1)
    plant = ts.PullPullPlant(route=route, elements=40, motor=motor, sensor=sensor)
    res = plant.simulate(t, q)
    # the command went through the motor: the plant input lags and is attenuated
    assert np.ptp(res.q_in[t > 3]) < 0.9 * np.ptp(q[t > 3])
    np.testing.assert_allclose(res.q_out, bare.simulate(t, res.q_in), atol=1e-12)
    assert np.abs(res.measured - res.q_out).max() < 1e-3
    assert not np.array_equal(res.measured, res.q_out)
    # the same run twice gives the same sensor noise (seeded, reset per simulate)
    np.testing.assert_array_equal(plant.simulate(t, q).measured, res.measured)
    # streaming goes through the motor too
    plant.reset()
    ys = [plant.step(q[0], 0.0)] + [plant.step(q[k], 1e-3) for k in range(1, len(q))]
    np.testing.assert_allclose(ys, res.q_out, atol=1e-12)


def test_torque_motor_feels_the_tendon_load():
    t = np.arange(0, 2.0, 1e-3)
    route = ts.Route.uniform(1.0, np.pi)
    kw = dict(route=route, elements=30, pretension=30.0)
    free = ts.PullPullPlant(motor=ts.Motor.torque(0.01, 0.2), **kw)
    loaded = ts.PullPullPlant(
        motor=ts.Motor.torque(0.01, 0.2), load=ts.loads.TorsionalSpring(0.5), **kw
    )
    tau = np.full(t.size, 0.2)
    q_free = free.simulate(t, tau).q_in
    q_loaded = loaded.simulate(t, tau).q_in
    # sheath friction alone costs r_p (T1p - T2p) of the torque; the rest drives the motor
    assert 0.2 < q_free[-1] < 0.2 / 0.2 * 2.0
    assert q_loaded[-1] < 0.5 * q_free[-1]  # the spring at the far end holds the motor back
