"""The C++ core as the compensators use it: the one module of this folder that imports
``tendonsheath._core`` (the nanobind extension); every other module takes the bound
names from here. The compensators of the core's list (``compensator_list.hpp``,
``_core.compensator_kinds()``) and their parameter structs are re-exported by that list: a
compensator added there needs no line here."""

from typing import Any

from .._core import (  # noqa: F401 (re-exported)
    AdaptiveController,
    AdaptiveControllerParams,
    AngleLaws,
    BacklashInverseParams,
    CommandLimits,
    ContinuumFeedforward,
    ContinuumFeedforwardParams,
    ContinuumMode,
    CoupledFeedforward,
    CurveAngleFeedforward,
    CurveAngleFeedforwardParams,
    EncoderLoop,
    EncoderLoopParams,
    InputRange,
    InverseModel,
    InverseSettings,
    LagInverseParams,
    LearnedCorrection,
    LearnedFeedforwardParams,
    LoadPlayInverse,
    LoadTerms,
    ModelInverse,
    ModelPart,
    PlantModelParams,
    ScaledMap,
    TipLoop,
    TipLoopParams,
    compensator_classes,
    compensator_kinds,
    model_kinds,
)

__all__ = [
    "AdaptiveController",
    "AdaptiveControllerParams",
    "AngleLaws",
    "BacklashInverseParams",
    "CommandLimits",
    "ContinuumFeedforward",
    "ContinuumFeedforwardParams",
    "ContinuumMode",
    "CoupledFeedforward",
    "CurveAngleFeedforward",
    "CurveAngleFeedforwardParams",
    "EncoderLoop",
    "EncoderLoopParams",
    "InputRange",
    "InverseModel",
    "InverseSettings",
    "LagInverseParams",
    "LearnedCorrection",
    "LearnedFeedforwardParams",
    "LoadPlayInverse",
    "LoadTerms",
    "ModelInverse",
    "ModelPart",
    "PlantModelParams",
    "ScaledMap",
    "TipLoop",
    "TipLoopParams",
    "compensator_classes",
    "compensator_kinds",
    "model_kinds",
]

# the compensators of the core's list and their parameter structs, by name
_BY_LIST = compensator_classes()
__all__ += sorted(set(_BY_LIST) - set(__all__))


def __getattr__(name: str) -> Any:
    """A compensator of the core's list (or its parameter struct) by name."""
    try:
        return _BY_LIST[name]
    except KeyError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
