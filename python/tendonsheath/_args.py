"""Argument handling shared by the public constructors: renamed keywords, number checks, and the
C++ core's error messages under the Python caller's name (the core names each parameter as Python
does: one vocabulary, docs/vocabulary.md)."""

from __future__ import annotations

import functools
import numbers
import os
import re
import sys
import warnings
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from types import FrameType
from typing import Any

import numpy as np


def renamed(
    who: str,
    values: dict[str, Any],
    renames: Mapping[str, str],
    warn: bool = True,
) -> dict[str, Any]:
    """`values` with each old keyword of `renames` (old -> new) moved to its new name.

    With ``warn`` each old name found raises a DeprecationWarning naming the new one (saved
    files are read without one). Giving both names is a TypeError, as Python does for an
    argument given twice.
    """
    out = dict(values)
    for old, new in renames.items():
        if old not in out:
            continue
        if out.get(new) is not None:
            raise TypeError(f"{who}: give {new} or its old name {old}, not both")
        if warn:
            warn_renamed(who, old, new, caller_outside_package())
        out[new] = out.pop(old)
    return out


def warn_renamed(who: str, old: str, new: str, stacklevel: int | None = None) -> None:
    """The DeprecationWarning of an old name (argument or attribute) that names the new one,
    pointing at the user's line: the first frame outside the package unless `stacklevel` says."""
    if stacklevel is None:
        stacklevel = caller_outside_package() - 1  # counted from this function, not its caller
    warnings.warn(
        f"{who}: {old!r} is now called {new!r} (docs/vocabulary.md); {old!r} will be removed "
        "in the next release",
        DeprecationWarning,
        stacklevel=stacklevel,
    )


def warn_status_switch(who: str) -> None:
    """The DeprecationWarning of the old ``status=True`` switch (a ``(result, flags)`` tuple),
    naming the new form and pointing at the user's line."""
    warnings.warn(
        f"{who}(..., status=True) is deprecated: read .status on the result (each sample's "
        "Status flags, uint8; docs/status.md); status= will be removed in the next release",
        DeprecationWarning,
        stacklevel=caller_outside_package() - 1,
    )


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def caller_outside_package() -> int:
    """The ``stacklevel`` for :func:`warn_renamed`, called by the caller of this function, that
    points at the first frame outside the package: the user's line, for a warning raised some
    calls deep (identify's settings pass through the estimator first)."""
    frame: FrameType | None = sys._getframe(1)  # the caller; warn_renamed itself is level 1
    level = 2
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    return level


def accepts_old_names(who: str, renames: Mapping[str, str | Callable[[Any], dict[str, Any]]]):
    """Decorator: the function also takes the old keywords of `renames` for one release, each
    with a DeprecationWarning that names the new one. A rename maps an old name to its new name,
    or to a function of the old value that gives the new keywords (one old setting split in
    two). The signature (``inspect.signature``, the docs) shows only the new names."""

    def wrap(fn):
        @functools.wraps(fn)
        def call(*args, **kwargs):
            for old in sorted(renames.keys() & kwargs.keys()):
                kwargs = _new_keywords(who, old, renames[old], kwargs)
            return fn(*args, **kwargs)

        return call

    return wrap


def _new_keywords(who: str, old: str, new, kwargs: dict[str, Any]) -> dict[str, Any]:
    value = kwargs.pop(old)
    values = new(value) if callable(new) else {new: value}
    label = " and ".join(values)
    if set(values) & set(kwargs):
        raise TypeError(f"{who}: give {label} or its old name {old}, not both")
    warn_renamed(who, old, label, caller_outside_package())
    return {**kwargs, **values}


def reject_unknown(who: str, extra: Mapping[str, Any], old_names: Iterable[str]) -> None:
    """A TypeError for keywords that are neither parameters nor `old_names` (a renames map's
    keys, or a list)."""
    unknown = sorted(set(extra) - set(old_names))
    if unknown:
        raise TypeError(f"{who}: unexpected keyword argument(s) {unknown}")


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
