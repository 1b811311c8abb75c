"""Identification: fit any model of the library to logged input/output data.

``identify(model_class, t, x, y, ...) -> Fit`` minimises the simulation error by differential
evolution (every generation evaluated in one batched, multi-threaded C++ call) followed by
least-squares refinement. :class:`Identifier` is the same as an object (settings stored,
``fit(recordings)``, ``clone()``), and :func:`cross_validate` scores it over recordings. See
:func:`identify`. :func:`detect_input_interpolation` says which input reconstruction between
samples (band-limited, held, linear) identify() picks for a HystereticOscillator by default.

The package itself is callable: ``tendonsheath.identify(...)`` is :func:`identify`, so
``ts.identify(Backlash, t, x, y)`` and ``ts.identify.identify_loop_dynamics(...)`` both read as
the docs write them (a function of the same name bound in ``tendonsheath`` would hide the
package, and ``import tendonsheath.identify`` would give the function).
"""

import inspect
import sys
import types

from .coupled import CoupledFit, identify_coupled
from .cross_validation import CrossValidation, cross_validate
from .diagnostics import Diagnostics, IdentifiabilityWarning
from .estimator import Identifier, NotFittedError, identify
from .fit import Fit, metrics
from .interpolation import detect_input_interpolation
from .loop_dynamics import (
    EmpiricalResponse,
    LoopDynamics,
    ResonanceOutOfBandWarning,
    empirical_response,
    identify_loop_dynamics,
)
from .servo import ServoFit, identify_servo

__all__ = [
    "CoupledFit",
    "CrossValidation",
    "Diagnostics",
    "EmpiricalResponse",
    "Fit",
    "IdentifiabilityWarning",
    "Identifier",
    "LoopDynamics",
    "ServoFit",
    "NotFittedError",
    "ResonanceOutOfBandWarning",
    "cross_validate",
    "detect_input_interpolation",
    "empirical_response",
    "identify",
    "identify_coupled",
    "identify_servo",
    "identify_loop_dynamics",
    "metrics",
]


class _CallablePackage(types.ModuleType):
    """This package, callable as :func:`identify` (its signature and docstring too)."""

    __call__ = staticmethod(identify)


sys.modules[__name__].__class__ = _CallablePackage
__signature__ = inspect.signature(identify)  # inspect would drop model_class as a "self"
