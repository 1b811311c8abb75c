"""A user's own plant in a ``tendonsheath bench`` scenario (``[plant] class = ...``).

    [plant]
    class = "my_package.plants:MyPlant"   # module:Class (importable), or
    # file = "my_plant.py"                #   a Python file (relative to the scenario)
    # class = "MyPlant"                   #   and the class in it
    kwargs = { half_width = 0.05 }        # optional: the constructor's keyword arguments

The class must meet :class:`tendonsheath.protocols.Plant` (``params``, ``reset()``,
``step(command, dt)``, ``simulate(t, command)``); what else :func:`tendonsheath.bench.run` reads
of it (its ``motor``, ``sensor``, ``kinematic_gain`` ...) is listed in
:mod:`tendonsheath.bench.plant_loop`. A compiled one bound with ``tendonsheath_bind/plant.hpp``
is stepped in the C++ loop, a Python one from Python. The plant brings its own motor (its
``motor`` attribute): the scenario's [motor], [torque_motor] and [load] tables are for the
shipped plants and are refused beside a user plant, and so is a compensator that needs the
calibration (which runs the shipped plant's tension bench): compare "none" and your own
``[[compare.user]]`` compensators on it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..protocols import Plant, missing_members
from .user_compensators import class_and_kwargs

_PLANT_KEYS = {"class", "file", "kwargs"}


@dataclass
class UserPlant:
    """The ``[plant]`` table of a scenario that names a user's class, its class resolved."""

    cls: type
    kwargs: dict[str, Any] = field(default_factory=dict)
    origin: str = ""

    def build(self):
        return self.cls(**self.kwargs)


def parse_user_plant(table: dict, where: str, base: Path) -> UserPlant:
    """The user plant a ``[plant]`` table with a 'class' names, its class imported and built
    once to check it (``base``: the scenario's folder)."""
    unknown = sorted(set(table) - _PLANT_KEYS)
    if unknown:
        raise ValueError(
            f"{where}: '{unknown[0]}' is a key of the shipped plants; a user plant ('class') "
            f"takes only {sorted(_PLANT_KEYS)}"
        )
    cls, origin, kwargs = class_and_kwargs(table, where, base)
    user = UserPlant(cls, dict(kwargs), origin)
    try:
        instance = user.build()
    except Exception as exc:  # the user's constructor: any error is theirs to see
        raise ValueError(f"{where}: {origin}(**kwargs) failed ({exc})") from None
    missing = missing_members(instance, Plant)
    if missing:
        raise ValueError(
            f"{where}: {origin} is not a plant: it has no {' and no '.join(missing)} (see "
            "tendonsheath.protocols.Plant)"
        )
    return user


__all__ = ["UserPlant", "parse_user_plant"]
