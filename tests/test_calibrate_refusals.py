"""bench.calibrate refuses a plant it cannot calibrate: a torque-driven joint (its command is a
torque, not the angle the calibration excitation is), with one line naming what to do."""

import pytest

from tendonsheath.bench import calibrate
from tendonsheath.bench.scenarios import do


def test_a_torque_motor_is_refused_with_what_to_do():
    servo_plant, torque_plant = do.plants("pid")
    route = do.CALIBRATION_ROUTES[0]
    with pytest.raises(ValueError, match="torque motor") as err:
        calibrate(torque_plant, [route], models_=("BoucWenBacklash",), duration=2.0)
    message = str(err.value)
    assert "\n" not in message and "Motor.position" in message
    assert "AdaptiveController.from_calibration" in message
    # the same robot behind its position servo is calibrated (short run, no model fitted)
    cal = calibrate(servo_plant, [route], models_=(), duration=2.0)
    assert len(cal.runs) == 1 and cal.logs[0].command.size == 2000
