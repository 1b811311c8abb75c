"""The C++ core as the closed loops use it: the one module of this folder that imports
``tendonsheath._core`` (the nanobind extension); every other module takes the bound
names from here."""

from .._core import (  # noqa: F401 (re-exported)
    CurveAngleFeedforward,
    EncoderLoop,
    LearnedCorrection,
    ModelInverse,
    TipLoop,
    bench_run,
)

__all__ = [
    "CurveAngleFeedforward",
    "EncoderLoop",
    "LearnedCorrection",
    "ModelInverse",
    "TipLoop",
    "bench_run",
]
