"""Phenomenological hysteresis models of tendon-sheath transmissions."""

from .angle_dependent import AngleDependent
from .backlash import Backlash
from .base import HysteresisModel, load_model
from .bouc_wen import BoucWen
from .bouc_wen_backlash import BoucWenBacklash
from .curve_angle import CurveAngleModel
from .hysteretic_oscillator import HystereticOscillator
from .prandtl_ishlinskii import PrandtlIshlinskii, PrandtlIshlinskiiInverse

__all__ = [
    "AngleDependent",
    "Backlash",
    "BoucWen",
    "BoucWenBacklash",
    "CurveAngleModel",
    "HysteresisModel",
    "HystereticOscillator",
    "PrandtlIshlinskii",
    "PrandtlIshlinskiiInverse",
    "load_model",
]
