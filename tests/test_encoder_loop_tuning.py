"""tune_encoder_loop: MIGO gains with their margins, checked independently with python-control.

For random identified servos: the closed loop built by python-control from the servo and the
C++ loop's own difference equations is stable, its sensitivity peak is within the bound, the
margins obey the bounds Ms implies, ki is the largest the bound allows for its kp, and the gains
hold a simulated motor under the C++ EncoderLoop. A servo that cannot be closed is refused.
"""

import dataclasses
import math

import control as ct
import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.compensate.tuning import controller_polynomials, loop_plant, tune_encoder_loop
from tendonsheath.identify.servo import ServoFit


def _servo(frequency, damping, gain=1.0, delay=0, integral_time=0.0) -> ServoFit:
    return ServoFit(frequency, damping, gain, 0.0, delay, 1e-3, 0.0, 0.0, {}, integral_time)


def _closed_loop(design):
    """python-control's loop L = C G (in z) and its sensitivity, from the design's gains."""
    dt = design.dt
    c_num, c_den = controller_polynomials(design.kp, design.ki, design.kd,
                                          design.derivative_cutoff_hz, dt)  # fmt: skip
    g_num, g_den = loop_plant(design.servo, dt)
    num, den = np.convolve(c_num, g_num), np.convolve(c_den, g_den)
    n = max(num.size, den.size)
    L = ct.tf(np.pad(num, (0, n - num.size)), np.pad(den, (0, n - den.size)), dt)
    return L, ct.feedback(1, L)


SERVOS = [_servo(f, z, g, d, ti) for f, z, g, d, ti in
          [(60, 0.8, 1.0, 0, 0.0), (14, 2.2, 0.84, 0, 0.0), (25, 0.3, 1.1, 2, 0.0),
           (5, 0.7, 0.9, 5, 0.0), (120, 1.5, 1.0, 1, 0.0), (69, 1.1, 1.0, 0, 0.0135)]]  # fmt: skip


@pytest.mark.parametrize("servo", SERVOS, ids=lambda s: f"{s.frequency}Hz")
@pytest.mark.parametrize("derivative", [False, True])
def test_design_is_stable_within_its_sensitivity_bound(servo, derivative):
    design = tune_encoder_loop(servo, max_sensitivity=1.7, derivative=derivative)
    L, S = _closed_loop(design)
    assert np.all(np.abs(S.poles()) < 1.0)
    w = np.geomspace(1e-2, math.pi / design.dt, 4000)
    peak = np.max(np.abs(S(np.exp(1j * w * design.dt))))
    assert peak <= 1.7 * 1.01  # the design grid has 800 points: a hair of the peak may hide
    assert design.sensitivity_peak == pytest.approx(peak, rel=0.01)
    # what Ms <= 1.7 guarantees: GM >= Ms/(Ms-1) (7.7 dB) and PM >= 2 asin(1/(2 Ms)) (34 deg)
    assert design.gain_margin_db >= 20 * math.log10(1.7 / 0.7) - 0.2
    assert design.phase_margin_deg >= math.degrees(2 * math.asin(1 / 3.4)) - 0.5
    assert design.ki > 0 and design.kp >= 0


@pytest.mark.parametrize("servo", SERVOS[:3], ids=lambda s: f"{s.frequency}Hz")
def test_ki_is_the_largest_the_bound_allows(servo):
    design = tune_encoder_loop(servo, max_sensitivity=1.7)
    more = ts.compensate.tuning.EncoderLoopDesign(
        design.kp, 1.05 * design.ki, design.kd, design.derivative_cutoff_hz, 1.7, 0, 0, 0, 0,
        servo, design.dt,
    )  # fmt: skip
    _, S = _closed_loop(more)
    w = np.geomspace(1e-2, math.pi / design.dt, 4000)
    peak = np.max(np.abs(S(np.exp(1j * w * design.dt))))
    assert peak > 1.7 or np.any(np.abs(S.poles()) >= 1.0)


def test_a_tighter_bound_gives_more_margin_and_less_integral_gain():
    loose = tune_encoder_loop(SERVOS[0], max_sensitivity=2.0)
    tight = tune_encoder_loop(SERVOS[0], max_sensitivity=1.3)
    assert tight.ki < loose.ki
    assert tight.phase_margin_deg > loose.phase_margin_deg


def test_the_gains_hold_a_simulated_servo_under_a_load():
    """The C++ EncoderLoop with the designed gains around the C++ motor (which the design only
    knew through its identified lag) settles on the target under a load torque."""
    servo = _servo(40.0, 0.7)
    design = tune_encoder_loop(servo)
    motor = ts.Motor.position(bandwidth_hz=40.0, damping=0.7, inertia=1e-4)
    loop = ts.compensate.EncoderLoop(ts.compensate.InverseFeedforward(ts.models.Backlash(
        B_r=0.0, B_l=0.0)), **design.gains())  # fmt: skip
    engine = motor.engine()  # the bare C++ motor (its position() reads the angle)
    q, errors = 0.0, []
    for k in range(3000):
        target = 0.5 if k > 100 else 0.0
        u = loop.step(target, q, 0.0 if k == 0 else 1e-3)
        q = engine.step(u, 1e-3, 0.2)  # 0.2 N m of tendon pull: a PD servo yields 0.032 rad
        errors.append(target - engine.position())
    assert abs(errors[-1]) < 1e-4
    assert max(abs(e) for e in errors[-500:]) < 1e-3


def test_a_servo_that_cannot_be_closed_is_refused():
    # a sign error in the encoder's wiring: no positive gains can close this loop
    with pytest.raises(ValueError, match="cannot be closed"):
        tune_encoder_loop(_servo(40.0, 0.7, gain=-1.0))


@pytest.mark.parametrize(
    ("kwargs", "match"), [({"dt": 0.0}, "dt"), ({"max_sensitivity": 1.0}, "max_sensitivity")]
)
def test_bad_settings_name_themselves(kwargs, match):
    with pytest.raises(ValueError, match=match):
        tune_encoder_loop(SERVOS[0], **kwargs)


def test_summary_states_the_margins():
    text = tune_encoder_loop(SERVOS[0]).summary()
    for word in ("kp", "ki", "Ms", "gain margin", "phase margin", "crossover"):
        assert word in text


def test_a_servo_with_its_own_integral_is_in_the_design_and_may_be_left_alone():
    """The servo's integral is in the loop the design closes (the double integrator's margins
    are the design's) and the design's note says so; servo_integral_only leaves the loop out
    around it (gains 0), never around a PD servo."""
    pid, pd = SERVOS[5], SERVOS[0]
    design = tune_encoder_loop(pid)
    assert design.ki > 0 and "double integrator" in design.note
    assert "T_i 0.0135 s" in design.summary()
    # the same gains without the servo's integral are a different design: it was not ignored
    bare = tune_encoder_loop(dataclasses.replace(pid, integral_time=0.0))
    assert (bare.kp, bare.ki) != (design.kp, design.ki) and not bare.note
    alone = tune_encoder_loop(pid, servo_integral_only=True)
    assert (alone.kp, alone.ki, alone.kd) == (0.0, 0.0, 0.0) and alone.target_met
    assert "no loop" in alone.summary() and "no loop" in alone.as_dict()["note"]
    assert tune_encoder_loop(pd, servo_integral_only=True).ki > 0
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash(B_r=0.0, B_l=0.0))
    loop = ts.compensate.EncoderLoop.from_calibration(ff, pid, servo_integral_only=True)
    assert loop.params["ki"] == 0.0 and loop.params["kp"] == 0.0
    assert ts.compensate.EncoderLoop.from_calibration(ff, pid).params["ki"] == pytest.approx(
        design.ki
    )


def test_a_design_states_its_target_beside_what_it_reached():
    design = tune_encoder_loop(SERVOS[0], max_sensitivity=1.7)
    out = design.as_dict()
    assert out["target"]["sensitivity_peak"] == 1.7
    # Ms = 1.7 guarantees GM >= 1.7 / 0.7 (7.71 dB) and PM >= 2 asin(1 / 3.4) (34.2 deg)
    assert out["target"]["gain_margin_db"] == pytest.approx(20 * math.log10(1.7 / 0.7))
    assert out["target"]["phase_margin_deg"] == pytest.approx(math.degrees(2 * math.asin(1 / 3.4)))
    assert out["reached"]["sensitivity_peak"] == design.sensitivity_peak
    assert out["target_met"] is True and "target <= 1.7: met" in design.summary()
    # a design above its bound (as a hand-set or refined one may be) says so
    over = dataclasses.replace(design, sensitivity_peak=2.4)
    assert not over.target_met and over.as_dict()["target_met"] is False
    assert "2.4 reached (target <= 1.7: NOT met)" in over.summary()
