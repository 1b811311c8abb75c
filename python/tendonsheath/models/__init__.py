"""Phenomenological hysteresis models of tendon-sheath transmissions."""

from .angle_dependent import AngleDependent
from .backlash import Backlash
from .base import HysteresisModel, load_model, register_models
from .bouc_wen import BoucWen
from .bouc_wen_backlash import BoucWenBacklash
from .chain import Chain
from .coupled import Coupled
from .curve_angle import CurveAngleModel
from .dead_zone import DeadZone
from .generalized_prandtl_ishlinskii import (
    GeneralizedPrandtlIshlinskii,
    GeneralizedPrandtlIshlinskiiInverse,
)
from .hysteretic_oscillator import HystereticOscillator
from .linear_block import FirstOrderLag, LinearBlock, SecondOrderLag
from .loaded import Loaded
from .plant_model import PlantModel
from .polynomial import Polynomial
from .prandtl_ishlinskii import PrandtlIshlinskii, PrandtlIshlinskiiInverse
from .scaled import Scaled

__all__ = [
    "AngleDependent",
    "Backlash",
    "BoucWen",
    "BoucWenBacklash",
    "Chain",
    "Coupled",
    "GeneralizedPrandtlIshlinskii",
    "GeneralizedPrandtlIshlinskiiInverse",
    "CurveAngleModel",
    "DeadZone",
    "FirstOrderLag",
    "LinearBlock",
    "Loaded",
    "PlantModel",
    "SecondOrderLag",
    "HysteresisModel",
    "HystereticOscillator",
    "Polynomial",
    "PrandtlIshlinskii",
    "PrandtlIshlinskiiInverse",
    "Scaled",
    "load_model",
]

# saved files, identify and compare name these classes (the models exported above)
register_models(*(globals()[name] for name in __all__))
