"""The C++ core as identification use it: the one module of this folder that imports
``tendonsheath._core`` (the nanobind extension); every other module takes the bound
names from here."""

from collections.abc import Callable
from typing import Any

from .._core import (  # noqa: F401 (re-exported)
    RecordingSet,
    bouc_wen_paths,
    features_BoucWen,
    features_BoucWenBacklash,
    features_GeneralizedPrandtlIshlinskii,
    features_PrandtlIshlinskii,
    model_kinds,
    oscillator_sensitivity_dense,
    reconstruct_bandlimited,
    separable_cost_BoucWen,
    separable_cost_BoucWenBacklash,
    separable_cost_GeneralizedPrandtlIshlinskii,
    separable_cost_PrandtlIshlinskii,
)

#: the batched C++ kernels of a direct problem by model class name, one per model of the core's
#: model list with a parameter vector (``model_kinds()``): (the population's costs, the
#: population's outputs)
POPULATION: dict[str, tuple[Callable[..., Any], Callable[..., Any]]] = {
    k["kind"]: (k["population_cost"], k["population_simulate"])
    for k in model_kinds()
    if k["param_vector"]
}

__all__ = [
    "POPULATION",
    "RecordingSet",
    "bouc_wen_paths",
    "features_BoucWen",
    "features_BoucWenBacklash",
    "features_GeneralizedPrandtlIshlinskii",
    "features_PrandtlIshlinskii",
    "oscillator_sensitivity_dense",
    "reconstruct_bandlimited",
    "separable_cost_BoucWen",
    "separable_cost_BoucWenBacklash",
    "separable_cost_GeneralizedPrandtlIshlinskii",
    "separable_cost_PrandtlIshlinskii",
]
