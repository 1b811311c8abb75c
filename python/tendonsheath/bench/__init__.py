"""The virtual bench: closed-loop runs on the physics plant, metrics, frequency response."""

from .calibration import (
    Calibration,
    ShapeSensing,
    calibrate,
    calibrate_load,
    honesty_entry,
    in_class_fit,
)
from .frequency import FrequencyResponse, frequency_response
from .loop_calibration import LoopCalibration, calibrate_loop, loop_calibration_input
from .metrics import loop_width, tracking_metrics
from .motor_calibration import (
    MotorCalibration,
    TorqueMotorCalibration,
    calibrate_servo,
    calibrate_torque_motor,
    motor_calibration_input,
)
from .run import Result, run
from .shape_sensing import sensed_route_schedule
from .trial import Choice, Trial, calibration_trial, choose, measured_mse

__all__ = [
    "Choice",
    "Trial",
    "choose",
    "TorqueMotorCalibration",
    "calibrate_torque_motor",
    "calibration_trial",
    "measured_mse",
    "Calibration",
    "ShapeSensing",
    "calibrate",
    "calibrate_load",
    "calibrate_loop",
    "LoopCalibration",
    "loop_calibration_input",
    "calibrate_servo",
    "MotorCalibration",
    "motor_calibration_input",
    "honesty_entry",
    "in_class_fit",
    "FrequencyResponse",
    "Result",
    "frequency_response",
    "loop_width",
    "run",
    "sensed_route_schedule",
    "tracking_metrics",
]
