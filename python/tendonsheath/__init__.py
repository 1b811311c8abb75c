"""tendonsheath: model, identify and compensate tendon-sheath mechanisms."""

from importlib.metadata import version as _version

from . import bench, compensate, io, loads, models, physics, presets, protocols
from ._extras import MissingExtraError
from .compare import Comparison, compare_models
from .coupled_plant import CoupledPlant, CoupledSimulation
from .identify import Fit, IdentifiabilityWarning, Identifier, identify, identify_coupled
from .models import load_model
from .motor import Motor
from .plant import (
    ContinuumPlant,
    PullPullPlant,
    SingleTendonPlant,
    SlackWarning,
)
from .protocols import Compensator, Plant
from .route import Route, UnitWarning
from .sensor import Sensor
from .simulation_result import SimulationResult
from .status import Status, status_counts
from .sweep import sweep

# one source: pyproject.toml's version, as installed
__version__ = _version("tendonsheath")

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
    "status_counts",
    "sweep",
    "__version__",
]
