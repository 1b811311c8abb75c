"""Units of the numbers a report or a terminal table shows: one angle unit per report, chosen
by the user ("deg" or "rad"); every column header names its unit."""

from __future__ import annotations

import math
from typing import Any

ANGLE_UNITS = ("deg", "rad")

# column key -> unit of its values as computed (radians); checked in this order
_KEY_UNITS = (
    ("rmse_deg", "deg"),
    ("percent", "%"),
    ("improvement", "x"),
    ("ratio", "x"),
    ("_hz", "Hz"),
    ("nrmse", ""),  # a share of the output's range: no unit
    ("rmse", "rad"),
    ("mse", "rad^2"),
    ("max_abs", "rad"),
    ("loop_width", "rad"),
)


def check_angle_unit(unit: str) -> str:
    if unit not in ANGLE_UNITS:
        raise ValueError(f"angle unit must be 'deg' or 'rad' (got {unit!r})")
    return unit


def unit_of_key(key: str) -> str | None:
    k = key.lower()
    return next((unit for part, unit in _KEY_UNITS if part in k), None)


def convert(value, unit: str | None, angle_unit: str):
    """The value in the report's angle unit (see :func:`unit_after`); other units unchanged."""
    if unit not in ("rad", "rad^2", "deg") or isinstance(value, bool):
        return value
    if not isinstance(value, int | float):
        return value
    rad = math.radians(value) if unit == "deg" else value
    if angle_unit == "rad":
        return rad
    return rad * (180 / math.pi) ** 2 if unit == "rad^2" else math.degrees(rad)


def unit_after(unit: str | None, angle_unit: str) -> str | None:
    if unit in ("rad", "deg"):
        return angle_unit
    if unit == "rad^2":
        return f"{angle_unit}^2"
    return unit


def header(key: str, unit: str | None) -> str:
    name = key.removesuffix("_deg") if key.endswith("rmse_deg") else key
    return f"{name.replace('_', ' ')} [{unit}]" if unit else name.replace("_", " ")


def rows_in_unit(
    rows: list[dict[str, Any]], angle_unit: str, units: dict[str, str] | None = None
) -> list[dict[str, Any]]:
    """Table rows with every value in the report's angle unit and the unit in each header;
    ``units`` names the unit of columns whose key does not say it (e.g. one per compensator)."""
    out = []
    for row in rows:
        new = {}
        for key, value in row.items():
            unit = (units or {}).get(key) or unit_of_key(key)
            new[header(key, unit_after(unit, angle_unit))] = convert(value, unit, angle_unit)
        out.append(new)
    return out


__all__ = [
    "ANGLE_UNITS",
    "check_angle_unit",
    "convert",
    "header",
    "rows_in_unit",
    "unit_after",
    "unit_of_key",
]
