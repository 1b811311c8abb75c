"""Reading a saved JSON object (model or compensator) from a path, a JSON string or a dict."""

from __future__ import annotations

import json
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path


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
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{where}{what} file is not valid JSON: {exc}") from None
    except ValueError:  # an integer of more digits than Python converts (4300)
        raise ValueError(
            f"{where}{what} file holds a number too large to read (an integer of thousands of "
            "digits)"
        ) from None


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
