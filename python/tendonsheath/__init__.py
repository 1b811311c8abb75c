"""tendonsheath: model, identify and compensate tendon-sheath mechanisms."""

from . import io, models
from .identify import Fit, identify
from .models import load_model

__version__ = "0.1.0"

__all__ = ["Fit", "identify", "io", "load_model", "models", "__version__"]
