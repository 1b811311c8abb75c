"""The position servo's integral action (issue 23, item 3): closed forms, an independent ODE
solution, the preset's servo choice and the validation."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import tendonsheath as ts


def _random_servo(rng):
    """Bandwidth 3-60 Hz, damping 0.4-1.2, reflected inertia 1e-5-1e-3 kg m^2, viscous
    friction up to J w (so the damping term 2 zeta w + b / J stays <= 3.4 w)."""
    f = rng.uniform(3.0, 60.0)
    inertia = 10 ** rng.uniform(-5, -3)
    return {
        "bandwidth_hz": f,
        "damping": rng.uniform(0.4, 1.2),
        "inertia": inertia,
        "viscous_friction": inertia * 2 * math.pi * f * rng.uniform(0.0, 1.0),
    }


def _hold(motor, command, tau, duration, dt=1e-3):
    """Hold ``command`` under the constant torque ``tau`` for ``duration`` s; the last angle."""
    motor.step(command, 0.0, tau)
    for _ in range(int(duration / dt)):
        q = motor.step(command, dt, tau)
    return q


def test_pd_yields_tau_over_j_w2_and_pid_not_at_all(rng):
    """Under a constant torque tau the PD servo settles at q_cmd + tau / (J w^2); the PID one
    at q_cmd, its integral carrying the load (w^2 z / T_i = -tau / J)."""
    for _ in range(15):
        kw = _random_servo(rng)
        w = 2 * math.pi * kw["bandwidth_hz"]
        tau, command = rng.uniform(-0.3, 0.3), rng.uniform(-1, 1)
        yield_ = tau / (kw["inertia"] * w**2)
        # slowest decay: >= 0.26 w (PD) and >= 0.12 w (PID, T_i = 5 / w) for these dampings;
        # the durations leave < e^-30 of the transient; the backward-Euler rest state is the
        # continuous one exactly, so the errors are rounding: measured <= 3.2e-13 (PD),
        # 7.3e-15 (PID) and 8.4e-13 (integral) of the yield, bounded at 1e-11
        pd = ts.Motor.position(**kw)
        assert _hold(pd, command, tau, 120 / w + 0.1) - command == pytest.approx(
            yield_, rel=1e-11, abs=1e-14
        )
        pid = ts.Motor.position(**kw, integral_time=5 / w)
        assert _hold(pid, command, tau, 250 / w + 0.1) == pytest.approx(
            command, abs=1e-11 * abs(yield_) + 1e-14
        )
        assert pid.integral == pytest.approx(-yield_ * 5 / w, rel=1e-11)


def _third_order(kw, integral_time, command, tau, t):
    """q of q'' = w^2 [(u - q) + z / T_i] - (2 zeta w + b / J) q' + tau / J, z' = u - q,
    from rest at 0 (scipy, tight tolerances)."""
    w = 2 * math.pi * kw["bandwidth_hz"]
    c = 2 * kw["damping"] * w + kw["viscous_friction"] / kw["inertia"]

    def rhs(_, s):
        q, v, z = s
        return [
            v,
            w * w * ((command - q) + z / integral_time) - c * v + tau / kw["inertia"],
            command - q,
        ]

    sol = solve_ivp(
        rhs, (0.0, t[-1]), [0.0, 0.0, 0.0], t_eval=t, rtol=1e-11, atol=1e-13, method="Radau"
    )
    return sol.y[0]


def _step_error(kw, integral_time, tau, dt):
    """Largest |motor - ODE| over a unit command step under the torque tau, sampled at dt."""
    w = 2 * math.pi * kw["bandwidth_hz"]
    t = np.arange(0.0, 40.0 / w + 8 * integral_time, dt)
    motor = ts.Motor.position(**kw, integral_time=integral_time)
    motor.step(0.0, 0.0, tau)
    q = np.array([0.0] + [motor.step(1.0, dt, tau) for _ in t[1:]])
    assert q[-1] == pytest.approx(1.0, abs=1e-3)
    return np.abs(q - _third_order(kw, integral_time, 1.0, tau, t)).max()


def test_pid_step_response_matches_the_third_order_ode(rng):
    """Friction and limits off: a command step under a torque, against the linear ODE solved
    independently. The motor's backward-Euler sub-steps are first order in w dt: the error
    measured at most 0.59 w dt (times 1 + the load's deflection), bounded here by 1.0 w dt; and
    it halves with dt (a model that solved another ODE would not converge to this one)."""
    for _ in range(6):
        kw = _random_servo(rng)
        w = 2 * math.pi * kw["bandwidth_hz"]
        integral_time = rng.uniform(1.5, 10.0) / w  # near the bound (0.4-1.25 / w) and above
        if integral_time <= 1 / (2 * kw["damping"] * w):
            continue
        tau = rng.uniform(-0.2, 0.2) * kw["inertia"] * w**2  # a deflection of up to 0.2 rad
        scale = 1.0 + abs(tau / (kw["inertia"] * w**2))
        coarse = _step_error(kw, integral_time, tau, 2e-4)
        fine = _step_error(kw, integral_time, tau, 1e-4)
        assert coarse < 1.0 * w * 2e-4 * scale
        assert fine < 0.6 * coarse


def test_zero_integral_time_is_the_pd_servo_bit_for_bit(rng):
    t = np.arange(0.0, 3.0, 1e-3)
    u = np.sin(2 * np.pi * 1.3 * t) + (t > 1.5)
    for _ in range(5):
        kw = {**_random_servo(rng), "coulomb_friction": 0.01, "max_speed": 20.0, "max_accel": 2e3}
        a = ts.Motor.position(**kw).simulate(t, u)
        b = ts.Motor.position(**kw, integral_time=0.0).simulate(t, u)
        np.testing.assert_array_equal(a, b)


def test_the_preset_servo_choice():
    w = 2 * math.pi * 60.0
    pid = ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8)
    assert pid.params["integral_time"] == pytest.approx(
        ts.presets.REALISTIC["servo_integral_ratio"] / w
    )
    assert ts.presets.REALISTIC["servo_integral_ratio"] == 5.0
    pd = ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8, servo="pd")
    assert pd.params["integral_time"] == 0.0
    assert {k: v for k, v in pd.params.items() if k != "integral_time"} == {
        k: v for k, v in pid.params.items() if k != "integral_time"
    }
    explicit = ts.presets.realistic_motor(servo="pd", bandwidth_hz=10.0, integral_time=0.2)
    assert explicit.params["integral_time"] == 0.2
    # the Motor.position default bandwidth (1.5 Hz) when none is given
    assert ts.presets.realistic_motor().params["integral_time"] == pytest.approx(
        5.0 / (2 * math.pi * 1.5)
    )
    assert "integral_time" not in ts.presets.realistic_motor("torque").params
    assert "integral_time=" in repr(pid)


def test_the_realistic_pid_servo_holds_the_tendons_torque():
    """The preset servos on a constant 0.05 N m load: PD deflects by tau / (J w^2) within the
    Coulomb friction's band; PID returns to the command up to where friction sticks it (it
    stuck 3.1e-5 rad away, 2.5e-4 of the PD's yield; the bound is 1e-3 of it)."""
    tau, j, w = 0.05, ts.presets.REALISTIC["motor_inertia"], 2 * math.pi * 10.0
    pd = ts.presets.realistic_motor(bandwidth_hz=10.0, damping=0.8, servo="pd", gear_backlash=0.0)
    pid = ts.presets.realistic_motor(bandwidth_hz=10.0, damping=0.8, gear_backlash=0.0)
    band = ts.presets.REALISTIC["motor_coulomb_friction"] / (j * w**2)
    assert abs(_hold(pd, 0.0, tau, 3.0) - tau / (j * w**2)) <= band + 1e-9
    assert abs(_hold(pid, 0.0, tau, 3.0)) < 1e-3 * tau / (j * w**2)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: ts.Motor.position(10.0, 0.5, integral_time=-0.1), "integral_time must be >= 0"),
        (
            lambda: ts.Motor.position(10.0, 0.5, integral_time=0.01),
            r"Motor.position: integral_time must be 0 \(no integral action\) or > 1 / \(2 damping"
            r" w\) = 0.0159",
        ),
        (lambda: ts.presets.realistic_motor(servo="pi"), "servo must be 'pid' or 'pd'"),
        (lambda: ts.presets.realistic_motor(damping=0.05), "stable only for damping > 0.1"),
    ],
)
def test_servo_validation(make, message):
    with pytest.raises(ValueError, match=message):
        make()
    # the same damping without integral action is fine
    ts.presets.realistic_motor(damping=0.05, servo="pd")
