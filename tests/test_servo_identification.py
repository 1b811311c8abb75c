"""identify_servo: a position servo from its command and motor encoder.

Checked against data simulated independently (SciPy's continuous-time lsim of the transfer
function, the command held between samples), against the C++ motor's own lag, and on the
tendon-loaded drive of the do2015 bench, whose frequency response (Welch) it must match.
"""

import math

import numpy as np
import pytest
from scipy.signal import csd, lsim, lti, welch

import tendonsheath as ts
from tendonsheath.bench.motor_calibration import calibrate_servo, motor_calibration_input
from tendonsheath.bench.scenarios import do
from tendonsheath.identify.servo import identify_servo


def _lsim_servo(t, u, frequency, damping, gain, delay):
    """The servo simulated in continuous time: the command of sample k held over (t_k-1, t_k]
    (the motor steps with it), delayed by ``delay`` samples."""
    w = 2 * math.pi * frequency
    system = lti([gain * w * w], [1.0, 2 * damping * w, w * w])
    held = np.concatenate([np.full(delay, u[0]), u[: u.size - delay]])
    fine = np.linspace(t[0], t[-1], 20 * (t.size - 1) + 1)
    index = np.minimum(np.searchsorted(t, fine, side="left"), t.size - 1)
    _, y, _ = lsim(system, held[index] - u[0], fine)  # linear between the fine points
    return y[::20] + gain * u[0]


@pytest.mark.parametrize("seed", range(4))
def test_recovers_random_servos_simulated_independently(seed):
    rng = np.random.default_rng(seed)
    f, z = rng.uniform(5.0, 80.0), rng.uniform(0.3, 2.0)
    g, d = rng.uniform(0.7, 1.2), int(rng.integers(0, 4))
    t, u = motor_calibration_input(6.0, 0.5, f_stop=150.0)
    q = _lsim_servo(t, u, f, z, g, d) + rng.normal(0.0, 1e-5, t.size)
    fit = identify_servo(t, u, q)
    assert fit.delay == d
    # lsim ramps the held command over 1/20 of a sample at each step (a 25 us shift): with the
    # noise, up to 1.4 % at 10x oversampling and 80 Hz, under 1 % at 20x
    assert fit.frequency == pytest.approx(f, rel=0.02)
    assert fit.damping == pytest.approx(z, rel=0.03)
    assert fit.gain == pytest.approx(g, rel=0.01)
    assert fit.standard_errors["frequency"] < 0.01 * f


def test_recovers_the_cpp_motor_lag():
    t, u = motor_calibration_input(8.0, 1.0)
    q = ts.Motor.position(bandwidth_hz=40.0, damping=0.7).simulate(t, u)
    fit = identify_servo(t, u, q)
    # the motor integrates with backward Euler on sub-steps of w h <= 0.1, which damps a little
    assert fit.frequency == pytest.approx(40.0, rel=0.02)
    assert fit.damping == pytest.approx(0.7, rel=0.06)
    assert fit.delay == 0
    assert fit.integral_time == 0.0  # a PD servo: the integral does not pay its parameter


@pytest.mark.parametrize("integral_time", [0.01, 0.03])
def test_recovers_the_integral_time_of_a_pid_servo(integral_time):
    """A PID servo (integral action) is told from a PD one, and its integral time recovered."""
    t, u = motor_calibration_input(8.0, 1.0)
    motor = ts.Motor.position(bandwidth_hz=40.0, damping=0.7, integral_time=integral_time)
    fit = identify_servo(t, u, motor.simulate(t, u))
    assert fit.integral_time == pytest.approx(integral_time, rel=0.1)  # measured: within 6 %
    assert fit.frequency == pytest.approx(40.0, rel=0.03)
    assert "PID" in fit.summary()


def test_the_loaded_drive_matches_its_measured_frequency_response():
    """On the realistic do2015 drive (tendons attached, friction, gear play), behind either
    servo, the fit must reproduce the command-to-encoder response where the chirp excites it
    (Welch estimate)."""
    from tendonsheath.bench.scenarios import do

    for servo in (do.plants("pid")[0], do.plants("pd")[0]):
        _check_response(calibrate_servo(servo, do.CALIBRATION_ROUTE, duration=20.0))


def _check_response(motor):
    t, u, q = motor.t, motor.command, motor.encoder
    detrend = [x - np.polyval(np.polyfit(t, x, 1), t) for x in (u, q)]
    f, puq = csd(detrend[0], detrend[1], fs=1000.0, nperseg=2048)
    _, puu = welch(detrend[0], fs=1000.0, nperseg=2048)
    measured = puq / puu
    num, den = motor.servo.discrete()
    band = (f > 3.0) & (f < 60.0)
    zinv = np.exp(-2j * np.pi * f[band] / 1000.0)
    model = np.polyval(num[::-1], zinv) / np.polyval(den[::-1], zinv)
    error = np.abs(model - measured[band]) / np.abs(measured[band])
    assert np.median(error) < 0.05  # measured: about 1-2 %


@pytest.mark.parametrize(
    ("t", "u", "q", "match"),
    [
        (np.array([0.0, 1e-3, 3e-3] * 30), None, None, "uniform"),
        (np.arange(100) * 1e-3, np.ones(100), np.ones(100), "does not move"),
        (np.arange(100) * 1e-3, np.r_[np.nan, np.arange(99.0)], np.arange(100.0), "finite"),
        (np.arange(10) * 1e-3, np.arange(10.0), np.arange(10.0), "at least 64"),
    ],
)
def test_bad_records_are_one_line_errors(t, u, q, match):
    u = np.arange(t.size, dtype=float) if u is None else u
    q = u if q is None else q
    with pytest.raises(ValueError, match=match):
        identify_servo(t, u, q)


def test_bad_options_name_themselves():
    t, u = motor_calibration_input(2.0, 0.5)
    with pytest.raises(ValueError, match="max_delay"):
        identify_servo(t, u, u, max_delay=-1)
    with pytest.raises(ValueError, match="highpass_hz"):
        identify_servo(t, u, u, highpass_hz=1e4)
    with pytest.raises(ValueError, match="f_start < f_stop"):
        motor_calibration_input(2.0, 0.5, f_start=50.0, f_stop=10.0)


def test_the_servo_kind_says_whether_integral_action_was_identified():
    """On the demo's drive (tendons attached) the PD servo's slowly varying load fitted an
    integral at T_i ~ 0.8 s (a 0.2 Hz corner, below the 1 Hz band the dynamics are fitted in),
    and the PD servo was named PID: such an integral is not identified. The PID servo's
    (T_i 13.5 ms, a 12 Hz corner) still is."""
    pd = calibrate_servo(do.plants("pd")[0], do.CALIBRATION_ROUTES[0]).servo
    assert pd.integral_time == 0.0 and "(PD)" in pd.summary()
    pid = calibrate_servo(do.plants("pid")[0], do.CALIBRATION_ROUTES[0]).servo
    assert pid.integral_time == pytest.approx(0.0135, rel=0.1) and "PID" in pid.summary()
