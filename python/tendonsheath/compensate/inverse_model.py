"""A model as the C++ inverse (``ModelInverse``) takes it: its parts' parameter structs, the
Chain's order and a Scaled model's map. The C++ loader (``tendonsheath/io/json.hpp``) builds
the same description from the model's JSON, so Python's and C++'s commands agree."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from ..models import (
    AngleDependent,
    Chain,
    CurveAngleModel,
    FirstOrderLag,
    HysteresisModel,
    PlantModel,
    Polynomial,
    Scaled,
    SecondOrderLag,
)
from ..models.base import _REGISTRY
from . import _bound as core

#: the C++ part member of each model class of the core's model list (``model_kinds()``, from
#: include/tendonsheath/models/model_list.hpp): where its parameter struct is copied as it is
_STRUCT_MEMBERS = {k["kind"]: k["member"] for k in core.model_kinds()}
#: the ModelPart members the inverse of each kind reads (what ``export --cpp`` writes): the
#: model list's, and a lag's LagInverseParams
PART_MEMBERS: dict[str, tuple[str, ...]] = {
    **{kind: (member,) for kind, member in _STRUCT_MEMBERS.items()},
    "FirstOrderLag": ("lag",),
    "SecondOrderLag": ("lag",),
}
#: AngleDependent bases with a real-time inverse (the core's ``angle_dependent_base``)
ANGLE_BASES = tuple(k["kind"] for k in core.model_kinds() if k["angle_dependent_base"])
_LAW_CODES = {"constant": 0, "linear": 1, "tanh": 2}

#: the model classes (and Chains of them) InverseFeedforward inverts, for messages
INVERTIBLE = (
    "Backlash, BoucWenBacklash, PrandtlIshlinskii, GeneralizedPrandtlIshlinskii, BoucWen, "
    "Polynomial, PlantModel, HystereticOscillator, CurveAngleModel, AngleDependent (over "
    "Backlash, BoucWenBacklash, BoucWen or HystereticOscillator), FirstOrderLag, "
    "SecondOrderLag, Chain(model, Polynomial | lag), Chain(lag, model), and Scaled around them"
)


def describe(model: HysteresisModel) -> Any:
    """The ``core.InverseModel`` of `model` (TypeError for a model without an inverse)."""
    desc = core.InverseModel()
    if isinstance(model, Scaled):
        mp = core.ScaledMap()
        for key, value in model.map.items():
            setattr(mp, key, float(value))
        desc.map = mp
        model = model.inner
    if isinstance(model, Chain):
        _check_chain(model)
        desc.parts = [part(model.first), part(model.second)]
    else:
        desc.parts = [part(model)]
    return desc


def _check_chain(chain: Chain) -> None:
    """A Chain has an inverse when its second part is a Polynomial or a lag, or its first a lag."""
    lags = (FirstOrderLag, SecondOrderLag)
    if isinstance(chain.second, Polynomial | FirstOrderLag | SecondOrderLag):
        return
    if isinstance(chain.first, lags):
        return
    raise TypeError(
        "InverseFeedforward: a Chain is inverted when its second part is a Polynomial or a lag "
        f"(Hammerstein), or its first a lag (Wiener); got {type(chain.first).__name__} then "
        f"{type(chain.second).__name__}"
    )


def part(model: HysteresisModel) -> Any:
    """The ``core.ModelPart`` of one plain model."""
    name = type(model).__name__
    builder = _BUILDERS.get(type(model))
    if builder is None and type(model) is _REGISTRY.get(name) and name in _STRUCT_MEMBERS:
        builder = _struct_part
    if builder is None:
        raise TypeError(
            f"InverseFeedforward: no real-time inverse for a {name} in this place; it inverts "
            f"{INVERTIBLE}"
        )
    p = core.ModelPart()
    p.kind = name
    builder(p, model)
    return p


def _struct_part(p, model) -> None:
    setattr(p, _STRUCT_MEMBERS[type(model).__name__], model.params_struct())


def _plant_part(p, model: PlantModel) -> None:
    s = core.PlantModelParams()
    for key, value in model.params.items():
        setattr(s, key, float(value))
    s.elements = int(model.options["elements"])
    p.plant_model = s


def _lag_part(p, model) -> None:
    s = core.LagInverseParams()
    if isinstance(model, FirstOrderLag):
        s.order, s.time_constant = 1, float(model.params["time_constant"])
    else:
        s.order = 2
        s.frequency, s.damping = (float(model.params[k]) for k in ("frequency", "damping"))
    p.lag = s


def _angle_part(p, model: AngleDependent) -> None:
    base = model.base.__name__
    if base not in ANGLE_BASES:
        raise TypeError(
            f"InverseFeedforward: no real-time inverse of an AngleDependent {base}; its base "
            f"must be one of {', '.join(ANGLE_BASES)}"
        )
    params = model.params
    laws = core.AngleLaws()
    mu = params["angle_friction"]
    laws.angle_friction = 0.0 if mu is None else float(mu)
    for name in model.base.param_names:
        c = params["coefficients"][name]
        laws.append(
            _LAW_CODES[params["laws"][name]], float(c[0]), float(c[1]) if len(c) > 1 else 0.0
        )
    p.base = base
    p.laws = laws
    theta0 = math.pi if "tanh" in params["laws"].values() else 0.0
    setattr(p, _STRUCT_MEMBERS[base], model.at(theta0).params_struct())


_BUILDERS: dict[type, Callable[[Any, Any], None]] = {
    PlantModel: _plant_part,
    FirstOrderLag: _lag_part,
    SecondOrderLag: _lag_part,
    AngleDependent: _angle_part,
}


def follows_route(model: HysteresisModel) -> bool:
    """Whether the inverse of `model` follows the route (CurveAngleModel, AngleDependent)."""
    inner = model.inner if isinstance(model, Scaled) else model
    parts = (inner.first, inner.second) if isinstance(inner, Chain) else (inner,)
    return any(isinstance(m, CurveAngleModel | AngleDependent) for m in parts)


def route_friction(model: HysteresisModel) -> float | None:
    """The friction coefficient of the route's shape integrals: a CurveAngleModel's friction or
    an AngleDependent's angle_friction (0 without a tanh law); None when it does not follow."""
    inner = model.inner if isinstance(model, Scaled) else model
    parts = (inner.first, inner.second) if isinstance(inner, Chain) else (inner,)
    for m in parts:
        if isinstance(m, CurveAngleModel):
            return float(m.params["friction"])
        if isinstance(m, AngleDependent):
            mu = m.params["angle_friction"]
            return 0.0 if mu is None else float(mu)
    return None


__all__ = [
    "ANGLE_BASES",
    "INVERTIBLE",
    "PART_MEMBERS",
    "describe",
    "follows_route",
    "part",
    "route_friction",
]
