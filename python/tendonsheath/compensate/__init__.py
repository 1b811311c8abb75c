"""Compensators: turn a desired distal trajectory into motor commands."""

from .adaptive_controller import AdaptiveController
from .continuum_feedforward import ContinuumFeedforward
from .coupled_feedforward import CoupledFeedforward
from .curve_angle_feedforward import CurveAngleFeedforward, shape_of
from .dead_band_inverse import DeadBandInverse
from .encoder_loop import EncoderLoop
from .inverse_feedforward import InverseFeedforward
from .iterative_learning import IterativeLearning, LearningDesign, TrialRecord
from .learned_feedforward import LearnedFeedforward
from .limits import CommandLimits
from .load_compensated import LoadCompensated
from .persistence import load_compensator, register
from .tip_loop import TipLoop
from .tuning import EncoderLoopDesign, tune_encoder_loop

load = load_compensator

__all__ = [
    "AdaptiveController",
    "CommandLimits",
    "ContinuumFeedforward",
    "CoupledFeedforward",
    "CurveAngleFeedforward",
    "DeadBandInverse",
    "EncoderLoop",
    "EncoderLoopDesign",
    "InverseFeedforward",
    "IterativeLearning",
    "LearnedFeedforward",
    "LearningDesign",
    "LoadCompensated",
    "TipLoop",
    "TrialRecord",
    "load",
    "load_compensator",
    "shape_of",
    "tune_encoder_loop",
]

# the files compensate.load reads: those of the compensators exported above
register(*(globals()[name] for name in __all__))
