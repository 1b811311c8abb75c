"""What kind of object each compensator's constructor takes, refused in one line otherwise.

A forward model and a compensator both have ``reset()`` and ``step(x, dt)``, so a duck-typed
check lets ``EncoderLoop(ts.models.Backlash())`` through, and the loop would then run the
forward model as its feedforward: the hysteresis applied twice instead of undone. These
checks name the kind wanted and, for the kinds a user is likely to hand over by mistake (a
model, a model class, a Fit, a plant, a sensor, a compensator where its model belongs, a
dict), what to give instead.
"""

from __future__ import annotations

from typing import Any

from ..identify.fit import Fit
from ..identify.loop_dynamics import LoopDynamics
from ..identify.servo import ServoFit
from ..models import Coupled, HysteresisModel, Loaded
from ..plant.motor import Motor
from ..plant.sensor import Sensor


def _kind(obj: Any) -> str:
    """The object's kind in words, with what to do about it where that is known."""
    name = type(obj).__name__
    if isinstance(obj, type):
        return f"the class {obj.__name__}, not an object of it: call it, {obj.__name__}(...)"
    if isinstance(obj, Fit):
        return "a Fit: its identified model is fit.model"
    if isinstance(obj, Sensor | Motor):
        return f"a {name}, a part of a plant"
    if hasattr(obj, "simulate") and hasattr(obj, "motor") and not isinstance(obj, HysteresisModel):
        return f"a plant ({name})"
    return name


def _inverse_of(model: object) -> str:
    """The compensator that inverts ``model``."""
    if isinstance(model, Loaded):
        return "LoadCompensated(model)"
    if isinstance(model, Coupled):
        return "CoupledFeedforward(model)"
    return "InverseFeedforward(model)"


def require_feedforward(who: str, obj: Any, param: str = "feedforward") -> None:
    """``obj`` is a feedforward compensator (``reset()`` and ``step(y_d, dt)``), not a forward
    model, a class or another kind; TypeError naming ``who`` and ``param`` otherwise."""
    if isinstance(obj, HysteresisModel):
        raise TypeError(
            f"{who}: {param} must be a compensator, not the forward model "
            f"{type(obj).__name__} (it maps commands to outputs; the feedforward is its "
            f"inverse: {_inverse_of(obj)})"
        )
    missing = [m for m in ("reset", "step") if not callable(getattr(obj, m, None))]
    if isinstance(obj, type) or missing:
        raise TypeError(
            f"{who}: {param} must be a feedforward compensator with reset() and step(y_d, dt) "
            f"(got {_kind(obj)})"
        )


def require_model(
    who: str, obj: Any, kind: type | tuple[type, ...] = HysteresisModel, param: str = "model"
) -> None:
    """``obj`` is a model object of ``kind`` (a class or a tuple of them); TypeError naming
    ``who``, ``param`` and what to give instead otherwise (a Loaded model to LoadCompensated,
    a Coupled one to CoupledFeedforward)."""
    if isinstance(obj, kind) and not isinstance(obj, type):
        if kind is HysteresisModel and isinstance(obj, Loaded | Coupled):
            more = "its measured load" if isinstance(obj, Loaded) else "the other joints' angles"
            raise TypeError(
                f"{who}: {param} is a {type(obj).__name__} model, which takes {more} besides "
                f"the input every cycle: use {_inverse_of(obj)}"
            )
        return
    kinds = kind if isinstance(kind, tuple) else (kind,)
    wanted = "a tendonsheath model"
    if kind is not HysteresisModel:
        wanted = f"a {' or '.join(k.__name__ for k in kinds)} model"
    got = _kind(obj)
    if isinstance(obj, HysteresisModel):
        got = f"a {type(obj).__name__} model"
    elif hasattr(obj, "model") and callable(getattr(obj, "step", None)):
        got = f"the compensator {type(obj).__name__}: give the model it inverts (.model)"
    raise TypeError(f"{who}: {param} must be {wanted} (got {got})")


def require_dynamics(who: str, dynamics: Any) -> list[LoopDynamics]:
    """``dynamics`` as a list of LoopDynamics (one, or a list or tuple of them); TypeError
    naming the first item of another kind."""
    items = list(dynamics) if isinstance(dynamics, list | tuple) else [dynamics]
    for i, d in enumerate(items):
        if not isinstance(d, LoopDynamics):
            where = "" if not isinstance(dynamics, list | tuple) else f" (item {i})"
            hint = "; a LoopCalibration's is its .dynamics" if hasattr(d, "dynamics") else ""
            raise TypeError(
                f"{who}: dynamics must be a LoopDynamics (identify_loop_dynamics, "
                f"calibrate_loop(...).dynamics) or a list of them{where} (got {_kind(d)}){hint}"
            )
    return items


def require_servo(who: str, servo: Any) -> ServoFit:
    """``servo`` is a ServoFit; TypeError naming what it is otherwise."""
    if not isinstance(servo, ServoFit):
        hint = (
            "; a LoopDynamics holds its servo as .servo" if isinstance(servo, LoopDynamics) else ""
        )
        raise TypeError(
            f"{who}: servo must be a ServoFit (identify_servo, a motor calibration's .servo) "
            f"(got {_kind(servo)}){hint}"
        )
    return servo


__all__ = ["require_dynamics", "require_feedforward", "require_model", "require_servo"]
