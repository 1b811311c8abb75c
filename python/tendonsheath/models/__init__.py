"""Phenomenological hysteresis models of tendon-sheath transmissions."""

from .backlash import Backlash
from .base import HysteresisModel, load_model
from .bouc_wen import BoucWen
from .bouc_wen_backlash import BoucWenBacklash
from .hysteretic_oscillator import HystereticOscillator
from .prandtl_ishlinskii import PrandtlIshlinskii, PrandtlIshlinskiiInverse

__all__ = [
    "Backlash",
    "BoucWen",
    "BoucWenBacklash",
    "HysteresisModel",
    "HystereticOscillator",
    "PrandtlIshlinskii",
    "PrandtlIshlinskiiInverse",
    "load_model",
]
