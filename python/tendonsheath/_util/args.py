"""Argument handling shared by the public constructors: saved files' old keys, number checks, the
C++ core's error messages under the Python caller's name (the core names each parameter as Python
does: one vocabulary, docs/vocabulary.md)."""

from __future__ import annotations

import numbers
import os
import re
import sys
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from types import FrameType
from typing import Any

import numpy as np


def renamed(who: str, values: dict[str, Any], renames: Mapping[str, str]) -> dict[str, Any]:
    """`values` (a saved file's keys) with each old key of `renames` (old -> new) moved to its
    new name: files written before a rename still load. Both names is a TypeError."""
    out = dict(values)
    for old, new in renames.items():
        if old not in out:
            continue
        if out.get(new) is not None:
            raise TypeError(f"{who}: give {new} or its old name {old}, not both")
        out[new] = out.pop(old)
    return out


# the package's folder (this file is in its _util/)
_PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep


def caller_outside_package() -> int:
    """The ``stacklevel`` for a warning raised by the caller of this function that points at
    the first frame outside the package: the user's line, for a warning raised some calls
    deep."""
    frame: FrameType | None = sys._getframe(1)  # the caller; warnings.warn itself is level 1
    level = 2
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    return level


def number(who: str, name: str, value: Any) -> float:
    """`value` as a float; a TypeError naming the argument and the type when it is no number
    (bool included: True where a number belongs is a mistake, not 1.0)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{who}: {name} must be a number (got {type(value).__name__} {value!r})")
    return float(value)


def is_format_version(value: Any, expected: int) -> bool:
    """Whether a saved file's ``"version"`` is the integer `expected`: JSON ``true`` is not 1
    (Python's ``True == 1`` would let it through), nor is ``1.0`` or ``"1"``."""
    return isinstance(value, int) and not isinstance(value, bool) and value == expected


def number_array(who: str, name: str, values: Any) -> np.ndarray:
    """`values` (numbers, any nesting) as a float array; a TypeError naming the argument when
    they are not numbers (a string, a dict, text inside)."""
    if isinstance(values, str | bytes | dict):
        raise TypeError(f"{who}: {name} must be numbers (got {type(values).__name__} {values!r})")
    try:
        return np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{who}: {name} must be numbers (got {values!r})") from None


def integer(who: str, name: str, value: Any) -> int:
    """`value` as an int; a TypeError naming the argument when it is not an integer."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{who}: {name} must be an integer (got {type(value).__name__} {value!r})")
    return int(value)


def as_caller(message: str, who: str) -> str:
    """A core error message ("CoreClass: smoothing must be > 0 (got 0)") under the name of the
    Python callable `who` ("InverseFeedforward: ..."); its words are kept, since the core's fields
    have the Python names (docs/vocabulary.md)."""
    body = message.split(": ", 1)[1] if re.match(r"^[\w.]+: ", message) else message
    return f"{who}: {body}"


@contextmanager
def core_errors_as(who: str) -> Iterator[None]:
    """Re-raise a ValueError of the C++ core (parameter validation) under `who`'s name."""
    try:
        yield
    except ValueError as err:
        raise ValueError(as_caller(str(err), who)) from None
