"""The C++ core as the models use it: the one module of this folder that imports
``tendonsheath._core`` (the nanobind extension); every other module takes the bound
names from here.

Every model of the core's list (``_core.model_kinds()``, from
``include/tendonsheath/models/model_list.hpp``) is re-exported by name: its parameter struct
and, where the core binds one, its model class. A new model of the list is here without an
edit. The names beside the list (the GPI's envelopes, the PI models' exact inverses, the
shape and the lag inverse's parameters) are imported by hand.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._core import (  # noqa: F401 (re-exported)
    Envelope,
    GeneralizedPrandtlIshlinskiiInverse,
    LagInverseParams,
    PrandtlIshlinskiiInverse,
    ShapeIntegrals,
    model_kinds,
)

_BESIDE_THE_LIST = [
    "Envelope",
    "GeneralizedPrandtlIshlinskiiInverse",
    "LagInverseParams",
    "PrandtlIshlinskiiInverse",
    "ShapeIntegrals",
]


def _list_names() -> dict[str, Any]:
    """The bound classes of every model of the list, by their Python names."""
    out: dict[str, Any] = {}
    for entry in model_kinds():
        out[entry["params"].__name__] = entry["params"]
        if entry["model"] is not None:
            out[entry["model"].__name__] = entry["model"]
    return out


globals().update(_list_names())

if TYPE_CHECKING:  # the type checker reads the classes from the stub the build writes
    from .._core import *  # noqa: F403


__all__ = sorted([*_list_names(), *_BESIDE_THE_LIST])
