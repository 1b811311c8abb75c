"""The virtual bench: closed-loop runs on the physics plant, metrics, frequency response."""

from .frequency import FrequencyResponse, frequency_response
from .metrics import loop_width, tracking_metrics
from .run import Result, run

__all__ = [
    "FrequencyResponse",
    "Result",
    "frequency_response",
    "loop_width",
    "run",
    "tracking_metrics",
]
