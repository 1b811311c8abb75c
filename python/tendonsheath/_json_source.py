"""Reading a saved JSON object (model or compensator) from a path, a JSON string or a dict."""

from __future__ import annotations

import json
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
