"""Modules that moved into the layer folders: importing an old path fails with a
ModuleNotFoundError naming the new one (the public names on ``tendonsheath`` are unchanged)."""

from __future__ import annotations

import importlib.abc
import sys

MOVED = {
    "tendonsheath.motor": "tendonsheath.plant.motor",
    "tendonsheath.sensor": "tendonsheath.plant.sensor",
    "tendonsheath.loads": "tendonsheath.plant.loads",
    "tendonsheath.route": "tendonsheath.plant.route",
    "tendonsheath.presets": "tendonsheath.plant.presets",
    "tendonsheath.physics": "tendonsheath.plant.physics",
    "tendonsheath.plant_input": "tendonsheath.plant.input_interpolation",
    "tendonsheath.coupled_plant": "tendonsheath.plant.coupled",
}


class MovedModuleFinder(importlib.abc.MetaPathFinder):
    """Last on ``sys.meta_path``: asked only once no other finder has the module."""

    def find_spec(self, fullname, path, target=None):
        new = MOVED.get(fullname)
        if new is not None:
            raise ModuleNotFoundError(
                f"No module named {fullname!r}: it moved to {new!r} (tendonsheath.plant "
                "holds the plant layer)",
                name=fullname,
            )
        return None


def install() -> None:
    if not any(isinstance(f, MovedModuleFinder) for f in sys.meta_path):
        sys.meta_path.append(MovedModuleFinder())


__all__ = ["MOVED", "MovedModuleFinder", "install"]
