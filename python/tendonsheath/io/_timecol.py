"""A file's time column read as seconds: numbers in a unit (s, ms, us, ns), absolute (epoch)
stamps kept exact, and ISO-8601 text; with the stamps' resolution, which tells stamps rounded
too coarsely for the sampling (duplicates, jitter) from a recording's own.

The rules (``read_log``'s doc states them for users):

- numbers are in ``unit`` (default s) and converted to seconds; a first stamp past the year
  5000 in that unit is refused, with the unit it would be an epoch time in (1.7e18 in s:
  "epoch time in ns? give time_unit='ns'");
- an absolute time (at least ``EPOCH_S`` s: after 1973, which no clock since boot reaches)
  starts at 0 at the first row, the first stamp in the notes; text cells are read exactly
  (decimal arithmetic, the first stamp subtracted before the conversion to float), so that
  integer nanoseconds (1.7e18) and epoch seconds with nine decimals keep every digit;
- ISO-8601 text (2024-05-01T12:00:00.125, a space for the T, an optional Z or +hh:mm
  offset): with an offset on every row, converted to UTC (a change of offset, daylight
  saving, is then no jump); with none on any, read as written (a clock change inside the
  recording would be a jump); offsets on some rows only are refused; time starts at 0;
- the resolution is the step of the stamps as written: 10^-d for d decimals of text, the
  float spacing of a binary float column (float32 epoch seconds: 128 s), 1 unit for
  integers, the last written field of an ISO time. ``read_log`` refuses repeated stamps
  (at three or more stamps, or in half the rows) when the resolution is above the mean
  step (more rows than distinct stamps: rounding, not rows logged twice).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from decimal import Decimal, InvalidOperation, localcontext

import numpy as np

from ._textread import Column

UNIT_NS = {"s": 1_000_000_000, "ms": 1_000_000, "us": 1_000, "ns": 1}
EPOCH_S = 1e8  # seconds: an absolute (epoch) time, after 1973-03-03
LATEST_S = 1e11  # seconds: past the year 5000, not a time in this unit
_ISO = re.compile(
    r"(\d{4}-\d{2}-\d{2}(?:[T ](\d{2}):(\d{2})(?::(\d{2})(?:\.(\d+))?)?)?)"
    r"(Z|[+-]\d{2}(?::?\d{2})?)?",
    re.IGNORECASE,
)


class TimeColumn:
    """Sample times (s) of a file's time column, the notes on how they were read, and the
    stamps' resolution (s) with its description, computed when first asked for."""

    def __init__(self, key, seconds: np.ndarray, notes: list[str], resolve: Callable):
        self.key = key
        self.seconds = seconds
        self.notes = notes
        self._resolve = resolve
        self._resolution: tuple[float, str] | None = None

    def resolution(self) -> tuple[float, str] | None:
        """(the stamps' step in s, what it comes from), or None where unknown."""
        if self._resolution is None:
            self._resolution = self._resolve()
        return self._resolution


def check_unit(unit) -> str:
    """``unit`` if it is one of s, ms, us, ns, else a one-line ValueError."""
    if unit not in UNIT_NS:
        raise ValueError(f"time_unit must be one of {', '.join(UNIT_NS)} (got {unit!r})")
    return unit


def read_time(table, name, unit: str) -> TimeColumn:
    """The time column ``name`` of ``table`` (io's _Table) in seconds, by the module's rules."""
    key = table.key(name)
    raw = table.columns.get(key) if key is not None else None
    if isinstance(raw, Column) and raw.first_text is not None:
        cells = table.cells(key)
        if cells is not None and _ISO.fullmatch(raw.first_text[1]):
            return _iso_time(table, key, cells, unit)
    values = table.numbers(name, "time")  # the errors of a number column
    _check_magnitude(table.path, key, values, unit)
    per_s = per_second(unit)  # divided by, not multiplied by its inverse: exact for s
    if isinstance(raw, Column):
        return _text_time(table, key, values, unit)
    arr = np.asarray(raw).reshape(-1)
    if arr.dtype.kind in "iu":
        steps = (arr.astype(np.int64) - np.int64(arr[0])).astype(float) / per_s
        absolute = abs(float(arr[0])) / per_s >= EPOCH_S
        seconds = steps if absolute else arr.astype(float) / per_s
        first = int(arr[0]) * UNIT_NS[unit]
        return _maybe_shifted(key, seconds, absolute, first, _fixed(1 / per_s, "integers"))
    spacing = float(np.spacing(np.abs(arr).max().astype(arr.dtype))) / per_s
    absolute = abs(float(values[0])) / per_s >= EPOCH_S
    seconds = (values - values[0]) / per_s if absolute else values / per_s
    first = round(float(values[0]) * UNIT_NS[unit])
    return _maybe_shifted(key, seconds, absolute, first, _fixed(spacing, f"{arr.dtype} numbers"))


def per_second(unit: str) -> float:
    """How many ``unit`` make a second (1e3 for ms)."""
    return 1e9 / UNIT_NS[unit]


def _fixed(step: float, what: str) -> Callable:
    return lambda: (step, what)


def _check_magnitude(path, key, values: np.ndarray, unit: str) -> None:
    """A ValueError when the stamps are too large to be times in ``unit``."""
    top = float(np.abs(values).max()) if values.size else 0.0
    if top * UNIT_NS[unit] * 1e-9 < LATEST_S:
        return
    fits = [u for u in UNIT_NS if EPOCH_S <= top * UNIT_NS[u] * 1e-9 < LATEST_S]
    hint = (
        f"epoch time in {fits[0]}? give time_unit='{fits[0]}' (--time-unit {fits[0]})"
        if fits
        else "not a time in any of s, ms, us, ns"
    )
    raise ValueError(
        f"{path}: column {key!r}: a time of {top:.6g} {unit} is past the year 5000; {hint}"
    )


def _maybe_shifted(key, seconds, absolute: bool, first_ns: int, resolve) -> TimeColumn:
    notes = []
    if absolute:
        notes.append(
            f"time: column {key!r} holds absolute (epoch) stamps: time from 0 at the first "
            f"row ({_utc(first_ns)} UTC)"
        )
    return TimeColumn(key, seconds, notes, resolve)


def _utc(ns: int) -> str:
    """An instant in ns since 1970 as ISO-8601 (whole seconds, then all nine decimals: beyond
    the year 2262 too, where datetime64[ns] ends)."""
    ns = int(ns)
    return f"{np.datetime64(ns // 1_000_000_000, 's')}.{ns % 1_000_000_000:09d}"


def _text_time(table, key, values: np.ndarray, unit: str) -> TimeColumn:
    """A time column of text cells: exact (decimal) when the stamps are absolute."""
    per_s = per_second(unit)

    def resolve():
        cells = table.cells(key)
        return None if cells is None else _decimal_resolution(cells, unit)

    if abs(float(values[0])) / per_s < EPOCH_S:
        return TimeColumn(key, values / per_s if unit != "s" else values, [], resolve)
    cells = table.cells(key)
    if cells is None:  # pragma: no cover - every text table re-reads its cells
        return _maybe_shifted(key, (values - values[0]) / per_s, True, 0, resolve)
    seconds, first_ns = _exact_offsets(cells, unit)
    return _maybe_shifted(key, seconds, True, first_ns, resolve)


def _decimals(cells: list[str]) -> list[Decimal]:
    out = []
    for cell in cells:
        try:
            out.append(Decimal(cell.strip()))
        except InvalidOperation:  # pragma: no cover - the cell was read as a number
            out.append(Decimal(repr(float(cell))))
    return out


def _exact_offsets(cells: list[str], unit: str) -> tuple[np.ndarray, int]:
    """Seconds from the first stamp, every digit of the text kept, and the first stamp (ns)."""
    with localcontext() as ctx:
        ctx.prec = 60
        numbers = _decimals(cells)
        first = numbers[0]
        per_unit = Decimal(UNIT_NS[unit]) / Decimal(10**9)
        seconds = np.array([float((d - first) * per_unit) for d in numbers])
        first_ns = int((first * UNIT_NS[unit]).to_integral_value())
    return seconds, first_ns


def _decimal_resolution(cells: list[str], unit: str) -> tuple[float, str]:
    """The step of the stamps as written: 10^-d for the most decimals d (1 for integers)."""
    exponent = min(int(d.as_tuple().exponent) for d in _decimals(cells))
    step = 10.0**exponent / per_second(unit)
    if exponent < 0:
        what = f"{-exponent} decimal(s) of {unit}"
    else:
        what = f"whole {unit}" if exponent == 0 else f"multiples of 1e{exponent} {unit}"
    return step, what


def _iso_time(table, key, cells: list[str], unit: str) -> TimeColumn:
    """ISO-8601 text: UTC when every row has an offset, as written when none has."""
    if unit != "s":
        raise ValueError(
            f"{table.path}: column {key!r} holds ISO-8601 times: time_unit does not apply "
            f"(got {unit!r})"
        )
    matches = []
    for i, cell in enumerate(cells):
        m = _ISO.fullmatch(cell.strip())
        if m is None:
            raise ValueError(
                f"{table.path}: column {key!r}, {table.row_name} {table.row(i)}: {cell.strip()!r} "
                "is not an ISO-8601 time (like 2024-05-01T12:00:00.125+02:00)"
            )
        matches.append(m)
    zoned = [m[6] is not None for m in matches]
    if any(zoned) and not all(zoned):
        with_, without = zoned.index(True), zoned.index(False)
        raise ValueError(
            f"{table.path}: column {key!r}: {table.row_name} {table.row(with_)} has a UTC "
            f"offset ({cells[with_].strip()!r}), {table.row_name} {table.row(without)} has "
            f"none ({cells[without].strip()!r}); give an offset on every row or on none"
        )
    try:
        stamps = np.array([m[1].replace(" ", "T") for m in matches], dtype="datetime64[ns]")
    except ValueError as exc:  # a date that does not exist (2024-02-30)
        raise ValueError(f"{table.path}: column {key!r}: not an ISO-8601 time ({exc})") from None
    ns = stamps.view(np.int64) - np.array([_offset_ns(m[6]) for m in matches], dtype=np.int64)
    notes = [f"time: column {key!r} holds ISO-8601 times: time from 0 at the first row"]
    if all(zoned):
        offsets = sorted({_offset_ns(m[6]) for m in matches})
        changed = " (the offset changes within the column)" if len(offsets) > 1 else ""
        notes[0] += f" ({_utc(ns[0])} UTC); offsets converted to UTC{changed}"
    else:
        notes[0] += (
            f" ({_utc(ns[0])}, no UTC offset: read as written; a clock change inside the "
            "recording would be a jump)"
        )
    seconds = (ns - ns[0]).astype(float) * 1e-9
    return TimeColumn(key, seconds, notes, _fixed(*_iso_resolution(matches)))


def _offset_ns(zone: str | None) -> int:
    if zone is None or zone.upper() == "Z":
        return 0
    digits = zone[1:].replace(":", "")
    minutes = int(digits[:2]) * 60 + (int(digits[2:]) if len(digits) > 2 else 0)
    return (1 if zone[0] == "+" else -1) * minutes * 60 * 1_000_000_000


def _iso_resolution(matches) -> tuple[float, str]:
    """The finest field written: a fraction of a second, seconds, minutes or days."""
    decimals = max((len(m[5]) for m in matches if m[5] is not None), default=None)
    if decimals is not None:
        return 10.0**-decimals, f"{decimals} decimal(s) of a second"
    if any(m[4] is not None for m in matches):
        return 1.0, "whole seconds"
    if any(m[3] is not None for m in matches):
        return 60.0, "whole minutes"
    return 86400.0, "dates without a time"
