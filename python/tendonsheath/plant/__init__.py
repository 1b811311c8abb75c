"""The plant layer: the simulated drives and what they are made of.

The plants (:class:`PullPullPlant`, :class:`ContinuumPlant`, :class:`SingleTendonPlant`,
:class:`CoupledPlant`), their motor, tip sensor, route and distal loads, the capstan closed
forms (:mod:`~tendonsheath.plant.physics`) and the realistic presets
(:mod:`~tendonsheath.plant.presets`). Nothing here imports a model, a compensator or the bench.
"""

from . import input_interpolation, loads, physics, presets
from .base import SlackWarning
from .continuum import ContinuumPlant
from .coupled import CoupledPlant, CoupledSimulation
from .motor import Motor
from .pull_pull import PullPullPlant
from .route import Route, UnitWarning
from .sensor import Sensor
from .single_tendon import SingleTendonPlant

__all__ = [
    "ContinuumPlant",
    "CoupledPlant",
    "CoupledSimulation",
    "Motor",
    "PullPullPlant",
    "Route",
    "Sensor",
    "SingleTendonPlant",
    "SlackWarning",
    "UnitWarning",
    "input_interpolation",
    "loads",
    "physics",
    "presets",
]
