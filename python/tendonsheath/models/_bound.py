"""The C++ core as the models use it: the one module of this folder that imports
``tendonsheath._core`` (the nanobind extension); every other module takes the bound
names from here."""

from .._core import (  # noqa: F401 (re-exported)
    Backlash,
    BacklashParams,
    BoucWen,
    BoucWenBacklash,
    BoucWenBacklashParams,
    BoucWenParams,
    CurveAngleModel,
    CurveAngleParams,
    Envelope,
    GeneralizedPrandtlIshlinskii,
    GeneralizedPrandtlIshlinskiiInverse,
    GeneralizedPrandtlIshlinskiiParams,
    HystereticOscillator,
    HystereticOscillatorParams,
    Polynomial,
    PolynomialParams,
    PrandtlIshlinskii,
    PrandtlIshlinskiiInverse,
    PrandtlIshlinskiiParams,
    ShapeIntegrals,
)

__all__ = [
    "Backlash",
    "BacklashParams",
    "BoucWen",
    "BoucWenBacklash",
    "BoucWenBacklashParams",
    "BoucWenParams",
    "CurveAngleModel",
    "CurveAngleParams",
    "Envelope",
    "GeneralizedPrandtlIshlinskii",
    "GeneralizedPrandtlIshlinskiiInverse",
    "GeneralizedPrandtlIshlinskiiParams",
    "HystereticOscillator",
    "HystereticOscillatorParams",
    "Polynomial",
    "PolynomialParams",
    "PrandtlIshlinskii",
    "PrandtlIshlinskiiInverse",
    "PrandtlIshlinskiiParams",
    "ShapeIntegrals",
]
