"""tendonsheath: model, identify and compensate tendon-sheath mechanisms."""

from typing import Any

# identify is the package, callable as identify.identify (identify/__init__.py says why)
from . import bench, compensate, identify, io, models, protocols
from ._util.extras import MissingExtraError
from .apps import session
from .apps.compare import Comparison, compare_models
from .apps.session import recalibrate, session_shift
from .identify import Fit, IdentifiabilityWarning, Identifier, identify_coupled
from .models import load_model
from .plant import (
    ContinuumPlant,
    CoupledPlant,
    CoupledSimulation,
    Motor,
    PullPullPlant,
    Route,
    Sensor,
    SingleTendonPlant,
    SlackWarning,
    UnitWarning,
    loads,
    physics,
    presets,
)
from .protocols import Compensator, Plant
from .simulation_result import SimulationResult
from .status import Status, status_counts
from .sweep import sweep


def __getattr__(name: str) -> Any:
    """``__version__``: pyproject.toml's version, as installed (one source), read when asked.

    importlib.metadata costs ~20 ms, a tenth of ``import tendonsheath``: read on first use.
    """
    if name == "__version__":
        from importlib.metadata import version

        return version("tendonsheath")
    raise AttributeError(f"module 'tendonsheath' has no attribute {name!r}")


__all__ = [
    "Comparison",
    "Compensator",
    "ContinuumPlant",
    "CoupledPlant",
    "CoupledSimulation",
    "Fit",
    "IdentifiabilityWarning",
    "Identifier",
    "MissingExtraError",
    "Motor",
    "Plant",
    "PullPullPlant",
    "Route",
    "Sensor",
    "SimulationResult",
    "SingleTendonPlant",
    "SlackWarning",
    "Status",
    "UnitWarning",
    "bench",
    "compare_models",
    "compensate",
    "identify",
    "identify_coupled",
    "io",
    "load_model",
    "loads",
    "models",
    "physics",
    "presets",
    "protocols",
    "recalibrate",
    "session",
    "session_shift",
    "status_counts",
    "sweep",
    "__version__",
]
