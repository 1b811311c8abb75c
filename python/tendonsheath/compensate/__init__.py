"""Compensators: turn a desired distal trajectory into motor commands."""

from .adaptive_controller import AdaptiveController
from .continuum_feedforward import ContinuumFeedforward
from .curve_angle_feedforward import CurveAngleFeedforward, shape_of
from .inverse_feedforward import InverseFeedforward
from .limits import CommandLimits

__all__ = [
    "AdaptiveController",
    "CommandLimits",
    "ContinuumFeedforward",
    "CurveAngleFeedforward",
    "InverseFeedforward",
    "shape_of",
]
