"""tendonsheath: model, identify and compensate tendon-sheath mechanisms."""

from . import compensate, models
from .models import load_model

__version__ = "0.1.0"

__all__ = ["compensate", "load_model", "models", "__version__"]
