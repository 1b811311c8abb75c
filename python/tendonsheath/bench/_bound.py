"""The C++ core as the closed loops use it: the one module of this folder that imports
``tendonsheath._core`` (the nanobind extension); every other module takes the bound
names from here."""

from .._core import (  # noqa: F401 (re-exported)
    AdaptiveController,
    BacklashInverseFeedforward,
    ContinuumFeedforward,
    CurveAngleFeedforward,
    EncoderLoop,
    LearnedCorrection,
    ModelInverse,
    PrandtlIshlinskiiFeedforward,
    TipLoop,
    bench_adaptive,
    bench_continuum,
    bench_curve_angle,
    bench_erased,
    bench_inverse,
    bench_model_inverse,
    bench_open_loop,
    bench_pi_inverse,
    bench_python,
)

__all__ = [
    "AdaptiveController",
    "BacklashInverseFeedforward",
    "ContinuumFeedforward",
    "CurveAngleFeedforward",
    "EncoderLoop",
    "LearnedCorrection",
    "ModelInverse",
    "PrandtlIshlinskiiFeedforward",
    "TipLoop",
    "bench_adaptive",
    "bench_continuum",
    "bench_curve_angle",
    "bench_erased",
    "bench_inverse",
    "bench_model_inverse",
    "bench_open_loop",
    "bench_pi_inverse",
    "bench_python",
]
