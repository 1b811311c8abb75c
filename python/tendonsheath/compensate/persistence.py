"""Compensators saved as JSON and loaded back, like models (format ``tendonsheath.compensator``).

A file holds the compensator's class name and its constructor settings; an
``InverseFeedforward`` (and a ``LoadCompensated``) embeds its model's own dict, a
``CoupledFeedforward`` its Coupled model's (format ``tendonsheath.coupled_model``). Unbounded
settings (infinite limits, ``max_correction_rate``) are written as ``null``, since JSON has no
infinity and the C++ loaders (``tendonsheath/io/json.hpp``, ``io/json_multi_input.hpp``) read
the same files.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeAlias, TypeVar

from .._util.args import is_format_version, renamed
from .._util.atomic import write_text
from .._util.json_source import naming_the_file, read_json_source
from ..models import Coupled, HysteresisModel

if TYPE_CHECKING:
    from .adaptive_controller import AdaptiveController
    from .base import Feedforward
    from .coupled_feedforward import CoupledFeedforward
    from .encoder_loop import EncoderLoop
    from .learned_feedforward import LearnedFeedforward
    from .load_compensated import LoadCompensated
    from .tip_loop import TipLoop

    Compensator: TypeAlias = (
        Feedforward
        | AdaptiveController
        | EncoderLoop
        | TipLoop
        | LearnedFeedforward
        | LoadCompensated
        | CoupledFeedforward
    )

FORMAT_NAME = "tendonsheath.compensator"
FORMAT_VERSION = 1

# settings that may be null (= unbounded) and the value null stands for
_UNBOUNDED = {"max_correction_rate": math.inf, "max_torque": math.inf, "max_correction": math.inf}
# settings saved as a model's own dict (null: no model)
_MODELS = ("model", "feedforward_model")
# settings saved as a compensator's own dict (the feedforward inside an EncoderLoop, a TipLoop
# or a LearnedFeedforward)
_COMPENSATORS = ("feedforward",)
_FLAGS = ("model_acceleration", "hold_last")
# settings saved as a list of numbers (a LearnedFeedforward's correction table)
_NUMBER_LISTS = ("table",)
_LIMIT_UNBOUNDED = {"min": -math.inf, "max": math.inf, "max_rate": math.inf}


def compensator_dict(name: str, settings: dict[str, Any]) -> dict[str, Any]:
    """The file contents for compensator class `name` built with `settings`."""
    out = {k: _finite_or_none(v) for k, v in settings.items() if k != "limits"}
    if "limits" in settings:
        lim = settings["limits"]
        out["limits"] = {k: _finite_or_none(getattr(lim, k)) for k in _LIMIT_UNBOUNDED}
    return {"format": FORMAT_NAME, "version": FORMAT_VERSION, "compensator": name, **out}


def to_json(data: dict[str, Any], path: str | Path | None) -> str:
    text = json.dumps(data, indent=2, allow_nan=False)
    if path is not None:
        write_text(path, text + "\n")
    return text


def _finite_or_none(value):
    if value is None or isinstance(value, str | bool):
        return value
    if isinstance(value, list | tuple):  # a range [lo, hi]
        return [_finite_or_none(v) for v in value]
    if hasattr(value, "to_dict"):  # a model
        return value.to_dict()
    value = float(value)  # numpy scalars too
    return None if math.isinf(value) else value


# the kinds of compensator file, by name: each class declaring its keys registers itself
# (compensate.base.SavedAsJson), so this module imports no compensator
_KINDS: dict[str, type[Compensator]] = {}


def register(*classes: Any) -> None:
    """Read files naming a class's ``__name__`` with that class (its ``_saved_settings`` and
    ``_from_saved``); a class that declares no file keys (a base, a helper) is skipped.

    Parameters
    ----------
    *classes : type
        Compensator classes.

    Returns
    -------
    None
    """
    for cls in classes:
        saved: tuple[str, ...] = getattr(cls, "_saved_settings", ())
        if isinstance(cls, type) and saved:
            _KINDS[cls.__name__] = cls


def compensator_from_dict(data: dict[str, Any]) -> Compensator:
    """Build the compensator a dict from ``to_dict`` describes; strict: every key checked."""
    if not isinstance(data, dict) or data.get("format") != FORMAT_NAME:
        raise ValueError(f"not a tendonsheath compensator file (missing format '{FORMAT_NAME}')")
    if not is_format_version(data.get("version"), FORMAT_VERSION):
        raise ValueError(
            f"unsupported compensator file version {data.get('version')!r} "
            f"(expected {FORMAT_VERSION})"
        )
    registry = _KINDS
    name = data.get("compensator")
    if name not in registry:
        raise ValueError(f"unknown compensator {name!r}; known: {sorted(registry)}")
    cls = registry[name]
    settings = {k: v for k, v in data.items() if k not in ("format", "version", "compensator")}
    settings = _upgraded(cls, settings)
    expected = cls._saved_settings
    unknown = sorted(set(settings) - set(expected))
    if unknown:
        raise ValueError(f"{name} file: unknown key(s) {unknown}; expected {list(expected)}")
    optional = getattr(cls, "_optional_settings", ())
    missing = [k for k in expected if k not in settings and k not in optional]
    if missing:
        raise ValueError(f"{name} file: key(s) {missing} missing")
    values = {k: _setting(name, k, v) for k, v in settings.items()}
    return cls._from_saved(values)


def _upgraded(cls: type[Compensator], settings: dict[str, Any]) -> dict[str, Any]:
    """Settings of a file written before the vocabulary (docs/vocabulary.md) under their new
    names (the class's ``_renamed_settings``, old -> new); such files load without a
    warning."""
    name = cls.__name__
    old_names = getattr(cls, "_renamed_settings", None)
    if old_names:
        try:
            return renamed(f"{name} file", settings, old_names)
        except TypeError as err:  # both names: a bad file
            raise ValueError(str(err)) from None
    if name in ("CurveAngleFeedforward", "ContinuumFeedforward") and "play" not in settings:
        settings = {**settings, "play": 0.0}  # written before the play was a setting
    if name == "CurveAngleFeedforward" and "compliance" in settings:
        out = dict(settings)
        compliance = _number(name, "'compliance'", out.pop("compliance"))
        if not compliance > 0:
            raise ValueError(f"{name} file: 'compliance' must be > 0 (got {compliance:g})")
        if "stiffness" in out or "length" in out:
            raise ValueError(f"{name} file: give stiffness and length or compliance, not both")
        return {**out, "stiffness": 1.0 / compliance, "length": 1.0}
    return settings


def _setting(name: str, key: str, value):
    if key == "limits":
        return _limits(name, value)
    if key in _MODELS:
        if name == "CoupledFeedforward":  # the joints' models and their coupling
            return Coupled.from_dict(value)
        return None if value is None else HysteresisModel.from_dict(value)
    if key in _COMPENSATORS:
        if not isinstance(value, dict):
            raise ValueError(f"{name} file: '{key}' must be a compensator object")
        inner = compensator_from_dict(value)
        if not hasattr(inner, "command"):
            raise ValueError(f"{name} file: '{key}' must hold a feedforward compensator")
        return inner
    if key in _NUMBER_LISTS:
        if not isinstance(value, list) or not value:
            got = json.dumps(value)[:60]
            raise ValueError(
                f"{name} file: '{key}' must be a non-empty list of numbers (got {got})"
            )
        return [_number(name, f"'{key}[{i}]'", v) for i, v in enumerate(value)]
    if key in _FLAGS:
        if not isinstance(value, bool):
            got = json.dumps(value)
            raise ValueError(f"{name} file: '{key}' must be true or false (got {got})")
        return value
    if key == "input_range":
        return _range(name, value)
    if key == "schedule":
        return _schedule(name, value)
    if key == "filter_hz" and value is None:
        return None
    if key == "mode":
        if not isinstance(value, str):
            raise ValueError(f"{name} file: 'mode' must be a string (got {json.dumps(value)})")
        return value
    if value is None and key in _UNBOUNDED:
        return _UNBOUNDED[key]
    return _number(name, f"'{key}'", value)


def _range(name: str, value) -> tuple[float, float] | None:
    """An input range: null (unbounded) or [lo, hi]."""
    if value is None:
        return None
    if not isinstance(value, list) or len(value) != 2:
        raise ValueError(
            f"{name} file: 'input_range' must be [lo, hi] or null (got {json.dumps(value)})"
        )
    lo, hi = (_number(name, "'input_range'", v) for v in value)
    return (lo, hi)


def _schedule(name: str, value) -> list[tuple[float, float]]:
    """A gain schedule: [[curve_angle, gain], ...]."""
    if not isinstance(value, list) or not all(isinstance(r, list) and len(r) == 2 for r in value):
        raise ValueError(
            f"{name} file: 'schedule' must be a list of [curve_angle, gain] pairs "
            f"(got {json.dumps(value)})"
        )
    return [(_number(name, "'schedule'", a), _number(name, "'schedule'", g)) for a, g in value]


def _limits(name: str, value) -> dict[str, float]:
    if not isinstance(value, dict):
        raise ValueError(f"{name} file: 'limits' must be an object (got {json.dumps(value)})")
    unknown = sorted(set(value) - set(_LIMIT_UNBOUNDED))
    if unknown:
        raise ValueError(f"{name} file: unknown key(s) {unknown} in 'limits'")
    return {
        k: _LIMIT_UNBOUNDED[k] if value.get(k) is None else _number(name, f"'limits.{k}'", value[k])
        for k in _LIMIT_UNBOUNDED
    }


def _number(name: str, what: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"{name} file: {what} must be a number (got {json.dumps(value)})")
    try:
        return float(value)
    except OverflowError:  # an integer beyond a double's range
        raise ValueError(
            f"{name} file: {what} is too large for a number (beyond 1.8e308)"
        ) from None


def load_compensator(source: str | Path | dict) -> Compensator:
    """Load a compensator saved with ``to_json``: a path, a JSON string or a dict.

    Parameters
    ----------
    source : str, Path or dict
        A path to a JSON file, JSON text, or the dict itself.

    Returns
    -------
    InverseFeedforward, CurveAngleFeedforward, ContinuumFeedforward, AdaptiveController,
    EncoderLoop, TipLoop, LearnedFeedforward, LoadCompensated or CoupledFeedforward
        The saved compensator.

    Raises
    ------
    ValueError
        An unreadable source or an invalid compensator file.
    """
    data = read_json_source(source, "compensator")
    with naming_the_file(source):
        return compensator_from_dict(data)


_C = TypeVar("_C")


def load_as(cls: type[_C], source: str | Path | dict) -> _C:
    """``cls.load(source)``: a saved compensator, which must be a ``cls``."""
    compensator = load_compensator(source)
    if not isinstance(compensator, cls):
        raise TypeError(
            f"{cls.__name__}.load: the file holds a {type(compensator).__name__}, "
            f"not a {cls.__name__} (tendonsheath.compensate.load reads any compensator)"
        )
    return compensator


__all__ = [
    "FORMAT_NAME",
    "FORMAT_VERSION",
    "compensator_dict",
    "compensator_from_dict",
    "load_as",
    "load_compensator",
    "to_json",
]
