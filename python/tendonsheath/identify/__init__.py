"""Identification: fit any model of the library to logged input/output data.

``identify(model_class, t, x, y, ...) -> Fit`` minimises the simulation error by differential
evolution (every generation evaluated in one batched, multi-threaded C++ call) followed by
least-squares refinement. See :func:`identify`.
"""

from .core import identify
from .diagnostics import Diagnostics, IdentifiabilityWarning
from .fit import Fit, metrics

__all__ = ["Diagnostics", "Fit", "IdentifiabilityWarning", "identify", "metrics"]
