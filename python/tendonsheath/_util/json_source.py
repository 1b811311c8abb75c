"""Reading a saved JSON object (model or compensator) from a path, a JSON string or a dict."""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any


def read_json_source(source: str | Path | dict, what: str) -> dict:
    """The object in ``source``: a dict as it is, else JSON text or a path to a JSON file.
    ``what`` ("model", "compensator") names the file in the one-line errors."""
    if isinstance(source, dict):
        return source
    text, where = str(source), ""
    if not text.lstrip().startswith("{"):
        path = Path(source)
        if not path.is_file():
            raise ValueError(f"{what} file not found: {path}")
        where = f"{path}: "
        try:
            text = path.read_text(encoding="utf-8-sig")
        except UnicodeDecodeError:
            raise ValueError(f"{where}not a {what} JSON file (binary, not UTF-8 text)") from None
    try:
        return json.loads(
            text,
            parse_constant=_Unreadable,
            parse_float=_not_finite_float,
            object_pairs_hook=_checked_object,
        )
    except _NotFinite as exc:  # one rule with the C++ loader (tendonsheath/io/json.hpp)
        raise ValueError(f"{where}{what} file: {exc}") from None
    except json.JSONDecodeError as exc:
        raise ValueError(f"{where}{what} file is not valid JSON: {exc}") from None
    except ValueError:  # an integer of more digits than Python converts (4300)
        raise ValueError(
            f"{where}{what} file holds a number too large to read (an integer of thousands of "
            "digits)"
        ) from None


class _NotFinite(Exception):
    """A number JSON cannot hold (NaN, Infinity, or beyond a double's range)."""


class _Unreadable(str):
    """A number read as NaN or +-inf: kept as its text until its key is known."""


def _not_finite_float(text: str) -> float | _Unreadable:
    value = float(text)
    return _Unreadable(text) if value in (math.inf, -math.inf) else value


def _found(value: Any) -> _Unreadable | None:
    """The unreadable number in value (a list's, at any depth), if any."""
    if isinstance(value, _Unreadable):
        return value
    if isinstance(value, list):
        return next((u for u in map(_found, value) if u is not None), None)
    return None


def _checked_object(pairs: list[tuple[str, Any]]) -> dict:
    """An object whose numbers are all finite, else the key of the one that is not."""
    for key, value in pairs:
        bad = _found(value)
        if bad is None:
            continue
        if bad in ("NaN", "Infinity", "-Infinity"):
            why = "is not JSON (a number must be finite; null stands for an unbounded setting)"
        else:
            why = "is out of range (beyond 1.8e308)"
        raise _NotFinite(f"key '{key}': {bad} {why}")
    return dict(pairs)


@contextmanager
def naming_the_file(source) -> Iterator[None]:
    """A ValueError from reading ``source``'s object names the file (when ``source`` is a path
    and the message does not already start with it); a number too large for a float
    (OverflowError) is such an error too."""
    where = None
    if isinstance(source, Path) or (
        isinstance(source, str) and not source.lstrip().startswith("{")
    ):
        where = str(source)
    try:
        yield
    except (ValueError, OverflowError) as exc:
        message = str(exc)
        if isinstance(exc, OverflowError):
            message = f"a number is too large ({message})"
        if where is None or message.startswith(where):
            if isinstance(exc, ValueError):
                raise
            raise ValueError(message) from None
        raise ValueError(f"{where}: {message}") from None
