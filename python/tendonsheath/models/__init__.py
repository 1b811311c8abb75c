"""Phenomenological hysteresis models of tendon-sheath transmissions."""

from .backlash import Backlash
from .base import HysteresisModel, load_model
from .bouc_wen import BoucWen
from .bouc_wen_backlash import BoucWenBacklash
from .chain import Chain
from .generalized_prandtl_ishlinskii import (
    GeneralizedPrandtlIshlinskii,
    GeneralizedPrandtlIshlinskiiInverse,
)
from .hysteretic_oscillator import HystereticOscillator
from .polynomial import Polynomial
from .prandtl_ishlinskii import PrandtlIshlinskii, PrandtlIshlinskiiInverse

__all__ = [
    "Backlash",
    "BoucWen",
    "BoucWenBacklash",
    "Chain",
    "GeneralizedPrandtlIshlinskii",
    "GeneralizedPrandtlIshlinskiiInverse",
    "HysteresisModel",
    "HystereticOscillator",
    "Polynomial",
    "PrandtlIshlinskii",
    "PrandtlIshlinskiiInverse",
    "load_model",
]
