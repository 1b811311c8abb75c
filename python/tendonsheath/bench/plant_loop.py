"""The plant of a :func:`tendonsheath.bench.run`: any object with ``reset()`` and
``step(command, dt)`` (:class:`tendonsheath.protocols.SteppedPlant`), stepped in the one C++
closed loop; a closed loop needs neither :class:`~tendonsheath.protocols.Plant`'s ``params`` nor
its ``simulate``.

What else bench.run uses of a plant (everything optional has a default):

* ``_tendonsheath_plant()`` (optional): what the C++ loop steps at C++ speed: the shipped
  plants give themselves (each is its bound C++ plant; the loop steps a copy, without the
  motor), a compiled plant bound with
  ``tendonsheath_bind/plant.hpp`` a capsule. Without it the plant is a *Python plant*: the loop
  calls its ``step(command, dt)`` once per cycle (slower, the same loop otherwise), after
  ``reset()``; the plant object itself is stepped.
* ``motor`` (a :class:`~tendonsheath.Motor` or None; default None): the bench runs it between
  the controller's command and the plant, so ``step`` gets the pulley angle (the motor's output)
  and never runs that motor itself. A Python plant that wraps a shipped plant wraps one built
  without a motor and gives the motor here.
* ``sensor`` (a :class:`~tendonsheath.Sensor` or None): the default reading of the output.
* ``encoder`` (a :class:`~tendonsheath.Sensor` or None): the motor encoder's reading of the
  motor shaft (resolution, noise), what the controllers read as the motor position.
* ``kinematic_gain``, or ``distal_radius`` and ``proximal_radius``: the uncompensated command
  per unit of desired output (gain * reference; needed only for ``controller=None``).
* ``output()``, ``input()``: the output and input at rest (default 0); ``drive_reaction()``:
  the tendons' torque on the drive (default 0; a torque motor or a motor with inertia feels
  it); ``slack()`` (default False) and ``status()`` (Status flags, default ok), read after
  every step.
* ``set_route(route)`` (a Python plant) or ``route_schedule(t, routes)`` and
  ``node_angles(route)`` (a C++ engine): needed only with ``routes=`` (or a route-following
  controller, which also reads ``route``, the plant's route at rest).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..plant.coupled import CoupledPlant
from ..plant.motor import Motor
from ..plant.sensor import Sensor
from ..protocols import SteppedPlant, missing_members

# what a plant offers to the C++ loop, each read after every step (None: the default)
_OPTIONAL_CALLS = ("output", "input", "drive_reaction", "slack", "status")


class _PythonPlantSteps:
    """The members the C++ loop calls on a Python plant (bindings: bench_plant.hpp), each the
    plant's own or None (its default); ``set_route_index(i)`` sets the i-th scheduled route."""

    def __init__(self, plant, routes: list) -> None:
        self.name = type(plant).__name__
        self.reset, self.step = plant.reset, plant.step
        for name in _OPTIONAL_CALLS:
            member = getattr(plant, name, None)
            setattr(self, name, member if callable(member) else None)
        self._plant, self._routes = plant, routes
        self.set_route_index: Callable[[int], None] | None = None  # set by a scheduled route

    def _set_route(self, i: int) -> None:
        route = self._routes[i]
        if isinstance(route, tuple | list):
            self._plant.set_route(*route)
        else:
            self._plant.set_route(route)


class BenchPlant:
    """A plant as bench.run closes the loop around it: what the C++ loop steps (``engine``),
    its motor and sensor engines, its route schedule and its uncompensated gain."""

    def __init__(self, plant) -> None:
        check_plant(plant)
        self.plant = plant
        self.motor = _member_of_kind(plant, "motor", Motor)
        self.sensor = _member_of_kind(plant, "sensor", Sensor)
        self.encoder = _member_of_kind(plant, "encoder", Sensor)
        compiled = getattr(plant, "_tendonsheath_plant", None)
        self.compiled = callable(compiled)
        self._routes: list = []  # a Python plant's scheduled routes, by index
        self.engine: Any = (
            compiled() if callable(compiled) else _PythonPlantSteps(plant, self._routes)
        )

    @property
    def kinematic_gain(self) -> float:
        """The uncompensated command per unit of desired output."""
        plant = self.plant
        gain = getattr(plant, "kinematic_gain", None)
        if gain is not None:
            return float(gain)
        if hasattr(plant, "distal_radius") and hasattr(plant, "proximal_radius"):
            return float(plant.distal_radius) / float(plant.proximal_radius)
        raise ValueError(
            f"bench.run: the plant {type(plant).__name__} has no kinematic_gain and no "
            "distal_radius/proximal_radius: the uncompensated run (controller=None) needs the "
            "command per unit of desired output"
        )

    @property
    def route(self):
        """The plant's route at rest (what a route-following controller is told first)."""
        route = getattr(self.plant, "route", None)
        if route is None:
            raise ValueError(
                f"bench.run: the plant {type(self.plant).__name__} has no 'route': a "
                "controller that follows the route needs it (or give routes=)"
            )
        return route

    def schedule(self, ts: np.ndarray, routes) -> tuple[np.ndarray, np.ndarray]:
        """(sample indices, rows) of the route changes, as the C++ loop takes them."""
        if self.compiled:
            return self._compiled_call("route_schedule")(ts, routes)
        idx, rows, previous = [], [], object()
        for k, tk in enumerate(ts):
            route = routes(float(tk))
            if route is previous:
                continue
            previous = route
            idx.append(k)
            rows.append(self.angles_for(route))
        return np.asarray(idx, dtype=np.uint64), np.ascontiguousarray(np.vstack(rows))

    def angles_for(self, route) -> np.ndarray:
        """The row that sets ``route``: its node angles (a C++ engine), or its index among the
        routes the loop hands a Python plant's ``set_route``."""
        if self.compiled:
            return np.asarray(self._compiled_call("node_angles")(route), dtype=float)
        if not callable(getattr(self.plant, "set_route", None)):
            raise ValueError(
                f"bench.run: the plant {type(self.plant).__name__} has no set_route(route): "
                "routes= (or a route-following controller) needs it"
            )
        self._routes.append(route)
        self.engine.set_route_index = self.engine._set_route
        return np.array([float(len(self._routes) - 1)])

    def _compiled_call(self, name: str):
        member = getattr(self.plant, name, None)
        if not callable(member):
            raise ValueError(
                f"bench.run: the plant {type(self.plant).__name__} has no {name}(): routes= "
                "(or a route-following controller) needs route_schedule(t, routes) and "
                "node_angles(route)"
            )
        return member


def check_plant(plant) -> None:
    """Raise ValueError naming what ``plant`` lacks of
    :class:`~tendonsheath.protocols.SteppedPlant` (``reset`` and ``step``),
    or for a plant bench.run cannot close one loop around."""
    if isinstance(plant, CoupledPlant):
        raise ValueError(
            "bench.run closes one loop around a single-input plant; a CoupledPlant's step takes "
            "one command per joint: run each joint's plant (CoupledPlant.plants) on its own"
        )
    missing = missing_members(plant, SteppedPlant)
    if missing:
        raise ValueError(
            f"bench.run: the plant {type(plant).__name__} has no {' and no '.join(missing)}: a "
            "plant needs reset() and step(command, dt) (see "
            "tendonsheath.protocols.SteppedPlant; PullPullPlant, ContinuumPlant and "
            "SingleTendonPlant have them)"
        )


def _member_of_kind(plant, name: str, kind: type):
    member = getattr(plant, name, None)
    if member is not None and not isinstance(member, kind):
        raise TypeError(
            f"bench.run: the plant's {name} must be a tendonsheath.{kind.__name__} or None "
            f"(got {type(member).__name__})"
        )
    return member


__all__ = ["BenchPlant", "check_plant"]
