"""Reading logged data: CSV/TSV with a header, NPY (structured or 2-D), NPZ, HDF5 (the
``hdf5`` extra), Excel (the ``excel`` extra), and ROS bags (ROS 1 .bag; ROS 2 .db3, .mcap or a
bag folder; the ``ros`` extra). HDF5 or Excel without its extra is a MissingExtraError (an
ImportError) naming the extra.

``read_log(path, time=..., input=..., output=..., curve_angle=...)`` returns a :class:`Log`
with the named columns as float arrays. Every problem raises ValueError naming the file,
and where it applies the column and the row: unknown column, text in a number column,
NaN or empty cells, too few rows, time that goes backwards. Rows with a duplicate
timestamp are dropped, keeping the first (their row numbers are in ``Log.notes``), unless
the stamps are written too coarsely for the sampling: rounding made them equal, an error.
The time column may be in s, ms, us or ns (``time_unit``), absolute epoch stamps (kept
exact, time from 0 at the first row) or ISO-8601 text (see ``read_log`` and ``_timecol``).

Missing values (NaN or empty cells) are an error by default; ``missing="drop"`` drops those
rows and ``missing="interpolate"`` fills them linearly, and either way ``Log.notes`` lists
their row numbers. Gaps in time (steps above 3x the median step) and irregular sampling are
detected and reported in ``Log.notes``; ``resample=RATE`` (Hz) or ``resample="auto"``
(the median rate) puts the recording on a uniform grid by linear interpolation (for signals
logged as a zero-order hold, ``resample`` keeps their step shape only at rates below the
sensor's). Without a time column ``Log.t`` is None: rate-independent models then run on the
sample index (``Log.index``). ``degrees=True`` converts the input, the output and the curve
angle from degrees to radians; :func:`deg2rad` and :func:`rad2deg` convert arrays.

Row numbers are those of the file: for text and Excel files row 1 is the header.

In a ROS bag the input, output and curve angle are named "/topic:field" (e.g.
"/motor/joint_states:position[0]", "/tip/pose:pose.position.x"); ``time`` is None (header
stamps where a message has them, else the receive time), "header", "receive" or a
"/topic:field". The output topic's messages are the samples and the input is interpolated
at their times (see ``_rosbag`` for the rules; ``Log.notes`` says what was used); a row is
then a message number.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .._util.atomic import atomic_path
from .._util.extras import require
from .._util.typing import ArrayLike, FloatArray
from .._util.units import CURVE_ANGLE, warn_if_unit_slip
from ._rosbag import TIME_KEY, bag_columns, bag_path, read_bag
from ._textread import (
    Column,
    parse_cells,
    read_text_cells,
    read_text_header,
    read_text_table,
    sniff_kind,
)
from ._timecol import TimeColumn, check_unit, read_time

MIN_ROWS = 3
MAX_UPSAMPLING = 10  # resampling may multiply the samples by at most this


@dataclass
class Log:
    """Columns of one recording. ``t`` is None when no time column was asked for; ``y`` is
    None when no output column was; ``curve_angle`` is a per-sample array or None.

    Parameters
    ----------
    t : numpy.ndarray of float or None
        Sample times (s), or None without a time column.
    x : numpy.ndarray of float
        The input column.
    y : numpy.ndarray of float or None
        The output column, or None.
    curve_angle : numpy.ndarray of float, optional
        The curve angle of each sample (rad), or None.
    extra : dict of str to numpy.ndarray, optional
        The file's other numeric columns, by name.
    path : str, default ""
        The file it was read from.
    columns : list of str, optional
        All column names of the file.
    notes : list of str, optional
        Findings of the reader (dropped or filled rows, gaps, resampling, ...).
    rows : numpy.ndarray of int, optional
        The file row (bag: message number) of every sample; None once resampled.
    load : numpy.ndarray of float, optional
        A measured load per sample (the ``load=`` column: e.g. the jaw torque, N m), or None.
    """

    t: np.ndarray | None
    x: np.ndarray
    y: np.ndarray | None
    curve_angle: np.ndarray | None = None
    extra: dict[str, np.ndarray] = field(default_factory=dict)
    path: str = ""
    columns: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    rows: np.ndarray | None = None  # the file row (bag: message) of every sample; None resampled
    load: np.ndarray | None = None  # the measured load of every sample (read_log's load=)

    def __len__(self) -> int:
        return int(self.x.size)

    @property
    def index(self) -> np.ndarray:
        """The sample index 0, 1, 2, ... (the time base of rate-independent models)."""
        return np.arange(self.x.size, dtype=float)

    @property
    def sample_time(self) -> float | None:
        """The median time step (None without a time column)."""
        if self.t is None or self.t.size < 2:
            return None
        return float(np.median(np.diff(self.t)))

    @property
    def irregular(self) -> bool:
        """True when the time steps vary by more than 1 % of the median step."""
        return _irregular(self.t)

    def split(self, fraction: float) -> tuple[int, float | None]:
        """Sample index where the last ``fraction`` of the recording (in time, else in
        samples) begins, and its time.

        Parameters
        ----------
        fraction : float
            The held-out share, in (0, 1).

        Returns
        -------
        index : int
            First sample of the held-out part.
        time : float or None
            Its time (s); None without a time column.

        Raises
        ------
        ValueError
            fraction not in (0, 1).
        """
        if not 0.0 < fraction < 1.0:
            raise ValueError(f"the held-out fraction must be in (0, 1) (got {fraction})")
        if self.t is None:
            k = int(round((1.0 - fraction) * self.x.size))
            return k, None
        t_cut = self.t[0] + (1.0 - fraction) * (self.t[-1] - self.t[0])
        k = int(np.searchsorted(self.t, t_cut))
        return k, float(t_cut)

    def to_radians(self) -> Log:
        """A copy with x, y and the curve angle converted from degrees to radians.

        Returns
        -------
        Log
            The converted copy, with a note saying so.
        """
        return replace(
            self,
            x=deg2rad(self.x),
            y=None if self.y is None else deg2rad(self.y),
            curve_angle=None if self.curve_angle is None else deg2rad(self.curve_angle),
            notes=[*self.notes, "converted from degrees to radians"],
        )

    def resampled(self, rate: float) -> Log:
        """A copy on a uniform time grid at ``rate`` Hz (linear interpolation).

        Parameters
        ----------
        rate : float
            Sample rate (Hz), > 0.

        Returns
        -------
        Log
            The resampled copy (``rows`` None), with a note saying so.

        Raises
        ------
        ValueError
            No time column, a rate not > 0, fewer than 3 samples, or more than 10x upsampling.
        """
        if self.t is None:
            raise ValueError(f"{self.path}: resampling needs a time column")
        if not (np.isfinite(rate) and rate > 0):
            raise ValueError(f"{self.path}: the resampling rate must be > 0 Hz (got {rate})")
        n = int(np.floor((self.t[-1] - self.t[0]) * rate + 1e-9)) + 1
        if n < MIN_ROWS:
            raise ValueError(
                f"{self.path}: resampling at {rate:g} Hz leaves {n} samples (< {MIN_ROWS})"
            )
        if n > MAX_UPSAMPLING * self.x.size:  # interpolation invents nothing: a typo'd rate
            raise ValueError(
                f"{self.path}: resampling at {rate:g} Hz would make {n} samples from "
                f"{self.x.size} (more than {MAX_UPSAMPLING}x); give a rate near the recording's"
            )
        t = self.t[0] + np.arange(n) / rate

        def f(v):
            return None if v is None else np.interp(t, self.t, v)

        return replace(
            self,
            t=t,
            x=f(self.x),
            y=f(self.y),
            curve_angle=f(self.curve_angle),
            load=f(self.load),
            extra={k: f(v) for k, v in self.extra.items()},
            notes=[*self.notes, f"resampled to {rate:g} Hz ({self.x.size} -> {n} samples)"],
            rows=None,
        )


def deg2rad(values: ArrayLike) -> FloatArray:
    """Degrees to radians (arrays or numbers).

    Parameters
    ----------
    values : float or array_like of float
        Angles (deg).

    Returns
    -------
    numpy.ndarray of float
        Angles (rad), shaped as values.
    """
    return np.deg2rad(np.asarray(values, dtype=float))


def rad2deg(values: ArrayLike) -> FloatArray:
    """Radians to degrees (arrays or numbers).

    Parameters
    ----------
    values : float or array_like of float
        Angles (rad).

    Returns
    -------
    numpy.ndarray of float
        Angles (deg), shaped as values.
    """
    return np.rad2deg(np.asarray(values, dtype=float))


def _irregular(t) -> bool:
    if t is None or t.size < 3:
        return False
    dt = np.diff(t)
    med = float(np.median(dt))
    return bool(med > 0 and np.max(np.abs(dt - med)) > 0.01 * med)


def _ranges(rows) -> str:
    """Compact row list: 3, 5-9, 12 (at most 10 ranges, then a count)."""
    rows = [int(r) for r in rows]
    out, start, prev = [], None, 0
    for r in rows:
        if start is None:
            start = prev = r
        elif r == prev + 1:
            prev = r
        else:
            out.append(f"{start}" if start == prev else f"{start}-{prev}")
            start = prev = r
    if start is not None:
        out.append(f"{start}" if start == prev else f"{start}-{prev}")
    more = f" (+{len(out) - 10} more ranges)" if len(out) > 10 else ""
    return ", ".join(out[:10]) + more


class _Table:
    """Column name -> values: a :class:`Column` (text and Excel files: values with the first
    empty and first text cell) or a raw array (binary formats); the file row of every data
    row (``rows``), or of the first (``first_row``, rows then follow on)."""

    def __init__(
        self, path: Path, columns: dict, first_row: int, rows=None, notes=(), row_name="row"
    ):
        self.path = path
        self.text_cells: dict[str, list[str]] | None = None  # an Excel sheet's cells
        self.row_name = row_name  # "message" in a ROS bag
        self.columns = columns
        self.first_row = first_row
        self.rows = rows
        self.notes = list(notes)
        self._taken: set = set()

    def names(self) -> list[str]:
        return list(self.columns)

    def has(self, name) -> bool:
        return self.key(name) is not None

    def key(self, name):
        if name in self.columns:
            return name
        s = str(name)
        if s in self.columns:
            return s
        return None

    def cells(self, key) -> list[str] | None:
        """A column's cells as written (text files and Excel sheets), else None."""
        if self.text_cells is not None:
            return self.text_cells.get(key)
        if isinstance(self.columns.get(key), Column) and self.row_name == "row":
            return read_text_cells(self.path, key)
        return None

    def row(self, i: int) -> int:
        return int(self.rows[i]) if self.rows is not None else self.first_row + int(i)

    def row_numbers(self, n: int) -> np.ndarray:
        return np.asarray(self.rows) if self.rows is not None else self.first_row + np.arange(n)

    def numbers(self, name, role: str, allow_missing: bool = False) -> np.ndarray:
        key = self.key(name)
        if key is None:
            names = self.names()
            hint = ""
            if len(names) == 1 and re.search(r"[^\w .()\[\]/°µ-]", names[0]):
                hint = " (one column: the delimiter is none of , ; tab | or spaces?)"
            raise ValueError(f"{self.path}: unknown {role} column {name!r}; columns: {names}{hint}")
        raw = self.columns[key]
        if isinstance(raw, Column):
            where = f"{self.path}: column {key!r}, row"
            if raw.first_text is not None:
                row, cell = raw.first_text
                hint = " (a decimal comma? use a decimal point)" if _decimal_comma(cell) else ""
                raise ValueError(f"{where} {row}: holds text {cell!r}, not a number{hint}")
            if raw.first_empty is not None and not allow_missing:
                raise ValueError(f"{where} {raw.first_empty}: is empty, not a number")
            # the table is discarded after read_log: its arrays are handed over, once each
            out = raw.values.copy() if key in self._taken else raw.values
            self._taken.add(key)
        else:
            try:
                out = np.asarray(raw, dtype=np.float64).reshape(-1)
            except (TypeError, ValueError):
                raise ValueError(f"{self.path}: column {key!r} is not numeric") from None
        bad = np.flatnonzero(~np.isfinite(out))
        if allow_missing:
            bad = np.flatnonzero(np.isinf(out))
        if bad.size:
            i = int(bad[0])
            raise ValueError(
                f"{self.path}: column {key!r}, {self.row_name} {self.row(i)}: value {out[i]} "
                "is not a finite number"
            )
        return out

    def clean_numbers(self, name) -> np.ndarray | None:
        """A column's values if every cell is a number (for the extras), else None."""
        raw = self.columns[name]
        if isinstance(raw, Column):
            clean = raw.first_text is None and raw.first_empty is None
            return raw.values if clean else None
        try:
            return np.asarray(raw, dtype=np.float64)
        except (TypeError, ValueError):
            return None


def _decimal_comma(cell: str) -> bool:
    return bool(re.fullmatch(r"[-+]?\d+,\d+", cell))


def _read_text(path: Path) -> _Table:
    table = read_text_table(path)
    return _Table(path, table.columns, table.first_row, rows=table.rows, notes=table.notes)


def _read_npy(path: Path) -> _Table:
    sniff_kind(path, b"\x93NUMPY", "an NPY file")
    try:
        arr = np.load(path, allow_pickle=False)
    except ValueError as exc:
        raise ValueError(f"{path}: not a readable NPY file ({exc})") from None
    if arr.dtype.names:
        return _Table(path, {n: arr[n] for n in arr.dtype.names}, 0)
    if arr.ndim == 1:
        return _Table(path, {"0": arr}, 0)
    if arr.ndim != 2:
        raise ValueError(f"{path}: expected a structured or 2-D array (got shape {arr.shape})")
    return _Table(path, {str(i): arr[:, i] for i in range(arr.shape[1])}, 0)


def _read_npz(path: Path) -> _Table:
    sniff_kind(path, b"PK\x03\x04", "an NPZ file")
    try:
        with np.load(path, allow_pickle=False) as data:
            cols = {k: data[k] for k in data.files}
    except ValueError as exc:
        raise ValueError(f"{path}: not a readable NPZ file ({exc})") from None
    for k, v in cols.items():
        if v.ndim != 1:
            raise ValueError(f"{path}: array {k!r} must be 1-D (got shape {v.shape})")
    return _Table(path, cols, 0)


def _read_hdf5(path: Path) -> _Table:
    h5py = require("h5py", extra="hdf5", feature=f"{path}: reading HDF5 files")

    sniff_kind(path, b"\x89HDF\r\n\x1a\n", "an HDF5 file")
    cols: dict[str, np.ndarray] = {}
    try:
        with h5py.File(path, "r") as f:

            def visit(name, obj):
                if isinstance(obj, h5py.Dataset) and obj.ndim == 1:
                    cols[name] = obj[()]

            f.visititems(visit)
    except OSError as exc:
        raise ValueError(f"{path}: not a readable HDF5 file ({exc})") from None
    return _Table(path, cols, 0)


def _read_excel(path: Path, sheet=None) -> _Table:
    openpyxl = require("openpyxl", extra="excel", feature=f"{path}: reading Excel files")
    sniff_kind(path, b"PK\x03\x04", "an Excel (.xlsx) workbook")
    try:
        book = openpyxl.load_workbook(path, read_only=True, data_only=True)
    except Exception as exc:  # openpyxl raises many types for a broken file
        raise ValueError(f"{path}: not a readable Excel file ({exc})") from None
    try:
        if sheet is None:
            ws = book.worksheets[0]
        elif isinstance(sheet, int):
            ws = book.worksheets[sheet]
        elif sheet in book.sheetnames:
            ws = book[sheet]
        else:
            raise ValueError(f"{path}: no sheet {sheet!r}; sheets: {book.sheetnames}")
        rows = [list(r) for r in ws.iter_rows(values_only=True)]
    finally:
        book.close()
    while rows and all(c is None for c in rows[-1]):
        rows.pop()
    if not rows:
        raise ValueError(f"{path}: the sheet is empty")
    width = max(len(r) for r in rows)
    while width > 0 and all(len(r) < width or r[width - 1] is None for r in rows):
        width -= 1
    header = rows[0][:width]
    if any(h is None or str(h).strip() == "" for h in header) or not header:
        raise ValueError(f"{path}: row 1 must be a header with a name for every column")
    if all(isinstance(h, int | float) for h in header):
        raise ValueError(f"{path}: row 1 must be a header of column names (got numbers)")
    names = [str(h).strip() for h in header]
    if len(set(names)) != len(names):
        raise ValueError(f"{path}: duplicate column names in the header")
    cells: dict[str, list[str]] = {h: [] for h in names}
    numbers: list[int] = []
    for number, r in enumerate(rows[1:], start=2):
        r = list(r[:width]) + [None] * (width - len(r))
        if all(c is None for c in r):
            continue
        numbers.append(number)
        for h, c in zip(names, r, strict=True):
            cells[h].append("" if c is None else str(c))
    row_array = np.asarray(numbers, dtype=np.int64)
    if not numbers:
        raise ValueError(f"{path}: the header names the columns {names} but there are no data rows")
    columns = {h: parse_cells(v, row_array) for h, v in cells.items()}
    table = _Table(path, columns, 2, rows=row_array)
    table.text_cells = cells
    return table


_BINARY_SUFFIXES = (".xlsx", ".xlsm", ".xls", ".npy", ".npz", ".h5", ".hdf5", ".hdf")


def _is_text(path: Path) -> bool:
    return path.suffix.lower() not in _BINARY_SUFFIXES


def _check_readable(path: Path) -> None:
    if path.is_dir():
        raise ValueError(f"{path}: is a folder, not a data file")
    if not path.is_file():
        raise ValueError(f"data file not found: {path}")
    try:
        with open(path, "rb"):
            pass
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror or exc})") from None


def _open(path: Path, sheet=None) -> _Table:
    _check_readable(path)
    suffix = path.suffix.lower()
    if suffix in (".xlsx", ".xlsm"):
        return _read_excel(path, sheet)
    if suffix == ".xls":
        raise ValueError(f"{path}: old .xls workbooks are not supported; save it as .xlsx")
    if suffix == ".npy":
        return _read_npy(path)
    if suffix == ".npz":
        return _read_npz(path)
    if suffix in (".h5", ".hdf5", ".hdf"):
        return _read_hdf5(path)
    return _read_text(path)


def columns(path: str | Path, sheet: str | int | None = None) -> list[str]:
    """The column names of a data file (of a text file: from its header alone; of a ROS bag:
    every number its topics hold, as /topic:field).

    Parameters
    ----------
    path : str or Path
        A data file or ROS bag.
    sheet : str or int, optional
        The Excel sheet (default the first).

    Returns
    -------
    list of str
        The column names.

    Raises
    ------
    ValueError
        A file that cannot be read (the message names it).
    MissingExtraError
        An HDF5 or Excel file without h5py or openpyxl (the ``hdf5`` or ``excel`` extra).
    """
    path = Path(path)
    bag = bag_path(path)
    if bag is not None:
        return bag_columns(bag)
    if _is_text(path):
        _check_readable(path)
        return read_text_header(path)
    return _open(path, sheet).names()


def read_log(
    path: str | Path,
    time: str | int | None = None,
    input: str | int | None = None,  # noqa: A002 - the natural name of the column role
    output: str | int | None = None,
    curve_angle: str | int | float | None = None,
    *,
    resample: float | str | None = None,
    missing: str = "error",
    degrees: bool = False,
    sheet: str | int | None = None,
    gap_factor: float = 3.0,
    load: str | int | None = None,
    extra: dict[str, str | int] | None = None,
    time_unit: str = "s",
) -> Log:
    """Read one recording. Columns are names (or indices for a 2-D NPY array).

    ``load`` names a measured signal besides the input (a load: the jaw torque, a tendon
    tension, the motor's current), read into ``Log.load`` and checked like the input;
    ``extra={name: column}`` reads other signals into ``Log.extra[name]`` (in a ROS bag,
    "/topic:field" signals interpolated at the samples like the input). A file's other clean
    numeric columns are in ``Log.extra`` under their own names as well (not a bag's).

    ``curve_angle`` is a column name or a number (a constant curve angle, in the unit of the
    data: rad, or degrees with ``degrees=True``). ``output`` may be None (prediction only).
    ``time=None``: no time column, the models run on the sample index.

    ``missing``: "error" (default: a NaN or empty cell raises, naming column and row),
    "drop" (drop those rows) or "interpolate" (fill linearly in time or index).
    ``resample``: None, a rate in Hz or "auto" (the median rate; only if the sampling is
    irregular). ``degrees``: convert input, output and curve angle from degrees to radians.
    ``sheet``: the Excel sheet (name or index; default the first). Findings (duplicate
    timestamps, missing values, gaps, irregular sampling) are listed in ``Log.notes``.
    A ROS bag (.bag, .db3, .mcap, a bag folder): signals are "/topic:field" and ``time`` is
    None, "header", "receive" or "/topic:field" (see the module's doc).

    Time is read as it is meant or refused with the reason, never made into duplicates or
    jitter. ``time_unit`` ("s", "ms", "us" or "ns") is the unit of a numeric time column;
    ``Log.t`` is in seconds either way, so a dynamic model's time constants come out in
    seconds. A stamp past the year 5000 in that unit is refused, naming the unit it would
    be an epoch time in (1.7e18 read as seconds: "epoch time in ns? give time_unit='ns'").
    An absolute (epoch) time, 1e8 s or more, starts at 0 at the first row (its UTC date in
    the notes); its text is read exactly, the first stamp subtracted before the conversion
    to float, so integer nanoseconds and nine-decimal epoch seconds keep every digit.
    ISO-8601 text (2024-05-01T12:00:00.125, with an optional Z or +02:00) starts at 0 too:
    with an offset on every row the times are converted to UTC (a daylight-saving change is
    no jump); with none, they are read as written (a clock change would be a jump); an
    offset on some rows only is refused. A repeated stamp is dropped (first kept) as a row
    logged twice, unless the stamps are too coarse for the rows: when their resolution
    (10^-d for d decimals, a float column's spacing: 128 s for float32 epoch seconds) is
    above the mean step, the file holds more rows than distinct stamps, and repeats at
    three or more stamps, or in half the rows, are rounding's: refused, naming the column
    and the resolution. Steps that differ by no more than the resolution are noted as
    rounded.

    Parameters
    ----------
    path : str or Path
        A CSV/TSV, NPY, NPZ, HDF5 or Excel file, or a ROS bag.
    time : str or int, optional
        The time column (s); None: none, models run on the sample index.
    input : str or int
        The input column; required.
    output : str or int, optional
        The output column; None for prediction only.
    curve_angle : str, int or float, optional
        The curve-angle column, or a constant curve angle.
    resample : float or "auto", optional
        Resample to this rate (Hz), or to the median rate when irregular.
    missing : {"error", "drop", "interpolate"}, default "error"
        What to do with NaN or empty cells.
    degrees : bool, default False
        Convert input, output and curve angle from degrees to radians.
    sheet : str or int, optional
        The Excel sheet (default the first).
    gap_factor : float, default 3.0
        A time step above this many median steps is reported as a gap.
    load : str or int, optional
        The measured load column (a ROS bag: "/topic:field"), into ``Log.load``.
    extra : dict of str to str or int, optional
        Other signals to read, by the name they get in ``Log.extra``.
    time_unit : {"s", "ms", "us", "ns"}, default "s"
        The unit of a numeric time column (in a ROS bag: of a /topic:field time that is a
        number; stamps carry their own).

    Returns
    -------
    Log
        The recording.

    Raises
    ------
    ValueError
        Any problem with the file, naming the file and, where it applies, column and row.
    MissingExtraError
        An HDF5 or Excel file without h5py or openpyxl (the ``hdf5`` or ``excel`` extra).
    """
    if missing not in ("error", "drop", "interpolate"):
        raise ValueError(f"missing must be 'error', 'drop' or 'interpolate' (got {missing!r})")
    path = Path(path)
    unit: str | None = check_unit(time_unit)
    extra = _checked_extra(path, extra)
    bag = bag_path(path)
    if bag is not None:
        table = _read_bag(bag, time, (input, output, curve_angle), missing, load, extra, time_unit)
        time, unit = TIME_KEY, None  # a bag's time is in seconds already
    else:
        table = _open(path, sheet)
    if input is None:
        raise ValueError(f"{path}: name the input column; columns: {table.names()}")
    roles = (time, input, output, curve_angle)
    log, timecol = _log_columns(table, path, roles, missing != "error", unit)
    if load is not None or extra:
        log = _with_measured(log, table, load, extra, allow_missing=missing != "error")
    if log.t is not None:
        log = _drop_duplicate_times(log, table, time, timecol)
    if missing != "error":
        log = _treat_missing(log, table, missing)
    if log.x.size < MIN_ROWS:
        raise ValueError(
            f"{path}: too few {table.row_name}s ({log.x.size}); at least {MIN_ROWS} are needed"
        )
    if log.t is not None:
        assert log.rows is not None  # None only once resampled, below
        log.notes.extend(_timing_notes(log.t, log.rows, table.row_name, gap_factor, timecol))
    if resample is not None:
        log = _resample(log, resample)
    if degrees:
        log = log.to_radians()
    if log.curve_angle is not None and log.curve_angle.size:
        top = float(np.max(np.abs(log.curve_angle)))
        warn_if_unit_slip(top, f"read_log({path.name})", "curve_angle (largest)", CURVE_ANGLE)
    return log


def _log_columns(
    table: _Table, path: Path, roles, allow_missing: bool, time_unit: str | None
) -> tuple[Log, TimeColumn | None]:
    """The named columns of ``table`` as a Log (no row dropped yet), with every other clean
    number column in ``extra``; ``roles`` are the time, input, output and curve angle names;
    the time column as read (``_timecol``; None for a bag's, in seconds already)."""
    time, input_, output, curve_angle = roles
    _distinct_roles(table, path, roles)
    x = table.numbers(input_, "input", allow_missing)
    n = x.size
    timecol = read_time(table, time, time_unit) if time is not None and time_unit else None
    t = timecol.seconds if timecol is not None else None
    if time is not None and timecol is None:
        t = table.numbers(time, "time")
    y = table.numbers(output, "output", allow_missing) if output is not None else None
    theta = None
    if curve_angle is not None:
        theta = _curve_angle_values(table, path, curve_angle, n, allow_missing)
    for name, arr in (("time", t), ("output", y), ("curve angle", theta)):
        if arr is not None and arr.size != n:
            raise ValueError(f"{path}: the {name} column has {arr.size} rows, the input has {n}")
    used = {table.key(c) for c in roles if c is not None}
    extra = {}
    for name in table.names():
        if name in used:
            continue
        values = table.clean_numbers(name)
        if values is not None and values.shape == (n,):
            extra[name] = values
    rows = table.row_numbers(n)
    notes = list(table.notes) + (timecol.notes if timecol is not None else [])
    return Log(t, x, y, theta, extra, str(path), table.names(), notes, rows), timecol


def _distinct_roles(table: _Table, path: Path, roles) -> None:
    """One column per role: the same column as input and output would make every fit the
    identity (and as time and a signal, a ramp)."""
    seen: dict = {}
    for role, column in zip(("time", "input", "output", "curve angle"), roles, strict=True):
        if column is None or (role == "curve angle" and not isinstance(column, str)):
            continue  # a curve angle may be a constant number
        key = table.key(column)
        if key is None:
            continue  # not a column: numbers() names it
        if key in seen:
            raise ValueError(
                f"{path}: column {column!r} is named as both the {seen[key]} and the {role}; "
                "each needs its own column"
            )
        seen[key] = role


def _checked_extra(path: Path, extra) -> dict | None:
    """``extra`` as {name: column}, or an error naming what is wrong with it."""
    if extra is None:
        return None
    if not isinstance(extra, dict):
        raise ValueError(
            f"{path}: extra must be a dict {{name: column}} (got {type(extra).__name__})"
        )
    for name, column in extra.items():
        if not isinstance(name, str) or not name:
            raise ValueError(f"{path}: extra's names must be non-empty strings (got {name!r})")
        if column is None:
            raise ValueError(f"{path}: extra {name!r} names no column")
    return dict(extra)


def _with_measured(log: Log, table: _Table, load, extra, allow_missing: bool) -> Log:
    """``log`` with its load (``load=``) and the named extra signals (``extra=``) read."""
    n = log.x.size
    values = None
    if load is not None:
        values = table.numbers(load, "load", allow_missing)
        if values.size != n:
            raise ValueError(f"{log.path}: the load column has {values.size} rows, the input {n}")
        log.extra.pop(str(table.key(load)), None)
    named = {}
    for name, column in (extra or {}).items():
        arr = table.numbers(column, f"extra {name!r}")
        if arr.size != n:
            raise ValueError(f"{log.path}: extra {name!r} has {arr.size} rows, the input {n}")
        named[name] = arr
    return replace(log, load=values, extra={**log.extra, **named})


def _curve_angle_values(table: _Table, path: Path, curve_angle, n: int, allow_missing: bool):
    """The curve angle column, or ``n`` copies of a constant curve angle given as a number."""
    if table.has(curve_angle):
        return table.numbers(curve_angle, "curve angle", allow_missing)
    try:
        value = float(curve_angle)
    except (TypeError, ValueError):
        raise ValueError(
            f"{path}: unknown curve angle column {curve_angle!r} (nor a number); "
            f"columns: {table.names()}"
        ) from None
    if not np.isfinite(value):
        raise ValueError(f"{path}: curve angle {curve_angle!r} is not finite")
    return np.full(n, value)


def _keep_rows(log: Log, keep: np.ndarray) -> Log:
    """The samples of ``log`` where ``keep`` is True (notes kept as they are)."""

    def f(v):
        return None if v is None else v[keep]

    return replace(
        log,
        t=f(log.t),
        x=log.x[keep],
        y=f(log.y),
        curve_angle=f(log.curve_angle),
        load=f(log.load),
        extra={k: v[keep] for k, v in log.extra.items()},
        rows=f(log.rows),
    )


def _drop_duplicate_times(log: Log, table: _Table, time, timecol: TimeColumn | None) -> Log:
    """Raise where time goes backwards; drop samples with a duplicate timestamp (first kept),
    unless the stamps are rounded too coarsely for the sampling (then raise, saying so)."""
    t = log.t
    assert t is not None and log.rows is not None  # a time column, not resampled yet
    back = np.flatnonzero(np.diff(t) < 0)
    if back.size:
        i = int(back[0]) + 1
        raise ValueError(
            f"{log.path}: column {table.key(time)!r}, row {table.row(i)}: time goes "
            f"backwards ({t[i]} after {t[i - 1]})"
        )
    keep = np.r_[True, np.diff(t) != 0]
    if keep.all():
        return log
    copies = ~keep & np.r_[False, _same_as_before(log)]
    if copies[~keep].all():  # rows logged twice (time and values): not a rounding of the stamps
        log.notes.append(
            f"{int((~keep).sum())} {table.row_name}(s) that repeat the one before (time and "
            f"values) dropped: {table.row_name}s {_ranges(log.rows[~keep])}"
        )
        return _keep_rows(log, keep)
    if timecol is not None:
        _refuse_rounded(log, timecol, int((~keep).sum()))
    log.notes.append(
        f"{int((~keep).sum())} {table.row_name}(s) with a duplicate timestamp dropped "
        f"(first kept): {table.row_name}s {_ranges(log.rows[~keep])}"
    )
    return _keep_rows(log, keep)


def _same_as_before(log: Log) -> np.ndarray:
    """Per row after the first: the same input, output and curve angle as the row before."""
    same = np.diff(log.x) == 0
    for values in (log.y, log.curve_angle):
        if values is not None:
            same &= np.diff(values) == 0
    return same


def _refuse_rounded(log: Log, timecol: TimeColumn, repeats: int) -> None:
    """A ValueError when repeated stamps come from rounding: the stamps' resolution above
    the mean step, so that the rows outnumber the distinct stamps, and repeats throughout
    (at three or more stamps, or in half the rows). A stamp or two repeated, or repeats in
    a finer time base, are rows logged twice: only dropped."""
    assert log.t is not None
    same = np.diff(log.t) == 0
    stamps = int(np.count_nonzero(same[1:] & ~same[:-1])) + int(same[0])  # repeated ones
    if stamps < 3 and 2 * repeats < log.t.size:
        return
    resolution = timecol.resolution()
    mean = float(log.t[-1] - log.t[0]) / (log.t.size - 1)
    if resolution is None or resolution[0] <= mean:
        return
    step, what = resolution
    raise ValueError(
        f"{log.path}: column {timecol.key!r}: {repeats} row(s) repeat the time before them: "
        f"the stamps are written to {step:.3g} s ({what}), coarser than the sampling "
        f"({mean:.3g} s a row on average), so rounding made them equal; write the time "
        "with more digits, or read without a time column (a rate-independent model)"
    )


def _treat_missing(log: Log, table: _Table, missing: str) -> Log:
    """Drop (``missing="drop"``) or fill linearly (``"interpolate"``) the samples where the
    input, output, curve angle or load is missing, and say which rows in the notes."""
    signals = [a for a in (log.x, log.y, log.curve_angle, log.load) if a is not None]
    bad = np.zeros(log.x.size, dtype=bool)
    for arr in signals:
        bad |= ~np.isfinite(arr)
    if not bad.any():
        return log
    assert log.rows is not None  # None only once resampled, after this
    rows = f"{table.row_name}s {_ranges(log.rows[bad])}"
    if missing == "drop":
        log.notes.append(
            f"{int(bad.sum())} {table.row_name}(s) with a missing value dropped: {rows}"
        )
        return _keep_rows(log, ~bad)
    if bad.all():
        raise ValueError(f"{log.path}: every row has a missing value")
    base = log.t if log.t is not None else log.index
    for arr in signals:
        m = ~np.isfinite(arr)
        if m.any():
            arr[m] = np.interp(base[m], base[~m], arr[~m])
    log.notes.append(
        f"{int(bad.sum())} {table.row_name}(s) with a missing value interpolated: {rows}"
    )
    return log


def _timing_notes(
    t: np.ndarray, rows: np.ndarray, row_name: str, gap_factor: float, timecol=None
) -> list[str]:
    """Notes on gaps in time (steps over ``gap_factor`` x the median) and irregular sampling
    (said to be rounding where the steps differ by no more than the stamps' resolution)."""
    notes = []
    dt = np.diff(t)
    med = float(np.median(dt))
    gaps = np.flatnonzero(dt > gap_factor * med)
    if gaps.size:
        notes.append(
            f"{gaps.size} gap(s) in time longer than {gap_factor:g}x the median step "
            f"({med:.4g}): before {row_name}s {_ranges(rows[gaps + 1])} "
            f"(longest {float(dt.max()):.4g})"
        )
    if _irregular(t):
        notes.append(
            f"irregular sampling: steps from {float(dt.min()):.4g} to {float(dt.max()):.4g} "
            f"(median {med:.4g}); consider resample="
        )
        if timecol is not None and not gaps.size:
            notes.extend(_rounding_note(dt, timecol))
    return notes


def _rounding_note(dt: np.ndarray, timecol: TimeColumn) -> list[str]:
    """A note when irregular steps differ by no more than the stamps' resolution."""
    resolution = timecol.resolution()
    if resolution is None or dt.max() - dt.min() > 1.5 * resolution[0]:
        return []
    step, what = resolution
    return [
        f"the steps differ by the stamps' resolution ({step:.3g} s, {what}): rounded "
        f"stamps, jitter of up to {step:.3g} s that the recording may not have; "
        "consider resample="
    ]


def _resample(log: Log, resample: float | str) -> Log:
    """``log`` at a rate in Hz, or with ``"auto"`` at its median rate where it is irregular."""
    if log.t is None:
        raise ValueError(f"{log.path}: resampling needs a time column")
    if resample == "auto":
        step = log.sample_time
        return log.resampled(1.0 / step) if log.irregular and step is not None else log
    try:
        rate = float(resample)
    except (TypeError, ValueError):
        raise ValueError(
            f"{log.path}: resample must be a rate in Hz or 'auto' (got {resample!r})"
        ) from None
    return log.resampled(rate)


def _read_bag(  # noqa: PLR0913 - the roles of a bag's signals
    bag: Path, time, roles, missing, load=None, extra=None, time_unit: str = "s"
) -> _Table:
    """A ROS bag's named signals (``roles``: input, output, curve angle), aligned
    (``_rosbag``), as a table of columns."""
    input_, output, curve_angle = roles
    specs = {"input": input_, "output": output}
    if curve_angle is not None and not _is_number(curve_angle):
        specs["curve angle"] = curve_angle
    if load is not None:
        specs["load"] = load
    for name, spec in (extra or {}).items():
        specs[f"extra {name}"] = spec
    data = read_bag(bag, time, specs, missing, time_unit)
    return _Table(bag, data.columns, 1, rows=data.rows, notes=data.notes, row_name="message")


def _is_number(value) -> bool:
    try:
        float(value)
    except (TypeError, ValueError):
        return False
    return True


def write_csv(path: str | Path, columns: dict[str, np.ndarray]) -> Path:
    """Write equal-length columns as a CSV with a header.

    Parameters
    ----------
    path : str or Path
        The file to write (atomically).
    columns : dict of str to array_like
        Column name -> values, all of one length.

    Returns
    -------
    Path
        The file written.
    """
    path = Path(path)
    names = list(columns)
    data = np.column_stack([np.asarray(columns[k], dtype=float) for k in names])
    with atomic_path(path) as tmp:
        np.savetxt(tmp, data, delimiter=",", header=",".join(names), comments="", fmt="%.10g")
    return path


__all__ = [
    "Log",
    "MAX_UPSAMPLING",
    "MIN_ROWS",
    "columns",
    "deg2rad",
    "rad2deg",
    "read_log",
    "write_csv",
]
