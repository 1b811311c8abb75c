"""Reading logged data: CSV/TSV with a header, NPY (structured or 2-D), NPZ, HDF5.

``read_log(path, time=..., input=..., output=..., curve_angle=...)`` returns a :class:`Log`
with the named columns as float arrays. Every problem raises ValueError naming the file,
and where it applies the column and the row: unknown column, text in a number column,
NaN or empty cells, too few rows, time that goes backwards. Rows with a duplicate
timestamp are dropped, keeping the first.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

MIN_ROWS = 3


@dataclass
class Log:
    """Columns of one recording. ``t`` is None when no time column was asked for; ``y`` is
    None when no output column was; ``curve_angle`` is a per-sample array or None."""

    t: np.ndarray | None
    x: np.ndarray
    y: np.ndarray | None
    curve_angle: np.ndarray | None = None
    extra: dict[str, np.ndarray] = field(default_factory=dict)
    path: str = ""
    columns: list[str] = field(default_factory=list)

    def __len__(self) -> int:
        return int(self.x.size)


class _Table:
    """Column name -> raw values (strings for text files, arrays otherwise), with the row
    number of the first data row in the file (for messages)."""

    def __init__(self, path: Path, columns: dict, first_row: int, text: bool):
        self.path = path
        self.columns = columns
        self.first_row = first_row
        self.text = text

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

    def numbers(self, name, role: str) -> np.ndarray:
        key = self.key(name)
        if key is None:
            raise ValueError(
                f"{self.path}: unknown {role} column {name!r}; columns: {self.names()}"
            )
        raw = self.columns[key]
        if self.text:
            out = np.empty(len(raw))
            for i, cell in enumerate(raw):
                cell = cell.strip()
                try:
                    out[i] = float(cell)
                except ValueError:
                    what = "is empty" if cell == "" else f"holds text {cell!r}"
                    raise ValueError(
                        f"{self.path}: column {key!r}, row {self.first_row + i}: {what}, "
                        "not a number"
                    ) from None
        else:
            try:
                out = np.asarray(raw, dtype=np.float64).reshape(-1)
            except (TypeError, ValueError):
                raise ValueError(f"{self.path}: column {key!r} is not numeric") from None
        bad = np.flatnonzero(~np.isfinite(out))
        if bad.size:
            i = int(bad[0])
            raise ValueError(
                f"{self.path}: column {key!r}, row {self.first_row + i}: value {out[i]} "
                "is not a finite number"
            )
        return out


def _read_text(path: Path) -> _Table:
    text = path.read_text()
    lines = text.splitlines()
    if not lines:
        raise ValueError(f"{path}: the file is empty")
    if path.suffix.lower() in (".tsv", ".tab"):
        delimiter = "\t"
    elif path.suffix.lower() == ".csv":
        delimiter = ","
    else:
        try:
            delimiter = csv.Sniffer().sniff(lines[0], delimiters=",\t; ").delimiter
        except csv.Error:
            delimiter = ","
    reader = csv.reader(lines, delimiter=delimiter)
    header = [h.strip() for h in next(reader)]
    if not header or any(h == "" for h in header):
        raise ValueError(f"{path}: row 1 must be a header with a name for every column")
    try:
        [float(h) for h in header]
    except ValueError:
        pass
    else:
        raise ValueError(f"{path}: row 1 must be a header of column names (got numbers)")
    if len(set(header)) != len(header):
        raise ValueError(f"{path}: duplicate column names in the header")
    columns: dict[str, list[str]] = {h: [] for h in header}
    for row_number, row in enumerate(reader, start=2):
        if not row or all(c.strip() == "" for c in row):
            continue
        if len(row) != len(header):
            raise ValueError(
                f"{path}: row {row_number} has {len(row)} fields, the header has {len(header)}"
            )
        for h, cell in zip(header, row, strict=True):
            columns[h].append(cell)
    return _Table(path, columns, 2, text=True)


def _read_npy(path: Path) -> _Table:
    try:
        arr = np.load(path, allow_pickle=False)
    except ValueError as exc:
        raise ValueError(f"{path}: not a readable NPY file ({exc})") from None
    if arr.dtype.names:
        return _Table(path, {n: arr[n] for n in arr.dtype.names}, 0, text=False)
    if arr.ndim == 1:
        return _Table(path, {"0": arr}, 0, text=False)
    if arr.ndim != 2:
        raise ValueError(f"{path}: expected a structured or 2-D array (got shape {arr.shape})")
    return _Table(path, {str(i): arr[:, i] for i in range(arr.shape[1])}, 0, text=False)


def _read_npz(path: Path) -> _Table:
    try:
        with np.load(path, allow_pickle=False) as data:
            cols = {k: data[k] for k in data.files}
    except ValueError as exc:
        raise ValueError(f"{path}: not a readable NPZ file ({exc})") from None
    for k, v in cols.items():
        if v.ndim != 1:
            raise ValueError(f"{path}: array {k!r} must be 1-D (got shape {v.shape})")
    return _Table(path, cols, 0, text=False)


def _read_hdf5(path: Path) -> _Table:
    import h5py

    cols: dict[str, np.ndarray] = {}
    try:
        with h5py.File(path, "r") as f:

            def visit(name, obj):
                if isinstance(obj, h5py.Dataset) and obj.ndim == 1:
                    cols[name] = obj[()]

            f.visititems(visit)
    except OSError as exc:
        raise ValueError(f"{path}: not a readable HDF5 file ({exc})") from None
    return _Table(path, cols, 0, text=False)


def _open(path: Path) -> _Table:
    if not path.is_file():
        raise ValueError(f"data file not found: {path}")
    suffix = path.suffix.lower()
    if suffix == ".npy":
        return _read_npy(path)
    if suffix == ".npz":
        return _read_npz(path)
    if suffix in (".h5", ".hdf5", ".hdf"):
        return _read_hdf5(path)
    return _read_text(path)


def columns(path: str | Path) -> list[str]:
    """The column names of a data file."""
    return _open(Path(path)).names()


def read_log(
    path: str | Path,
    time=None,
    input=None,  # noqa: A002 - the natural name of the column role
    output=None,
    curve_angle=None,
) -> Log:
    """Read one recording. Columns are names (or indices for a 2-D NPY array).

    ``curve_angle`` is a column name or a number (a constant curve angle, rad).
    ``output`` may be None (prediction only).
    """
    path = Path(path)
    table = _open(path)
    if input is None:
        raise ValueError(f"{path}: name the input column; columns: {table.names()}")
    x = table.numbers(input, "input")
    n = x.size
    t = table.numbers(time, "time") if time is not None else None
    y = table.numbers(output, "output") if output is not None else None
    theta = None
    if curve_angle is not None:
        if table.has(curve_angle):
            theta = table.numbers(curve_angle, "curve angle")
        else:
            try:
                value = float(curve_angle)
            except (TypeError, ValueError):
                raise ValueError(
                    f"{path}: unknown curve angle column {curve_angle!r} (nor a number); "
                    f"columns: {table.names()}"
                ) from None
            if not np.isfinite(value):
                raise ValueError(f"{path}: curve angle {curve_angle!r} is not finite")
            theta = np.full(n, value)
    for name, arr in (("time", t), ("output", y), ("curve angle", theta)):
        if arr is not None and arr.size != n:
            raise ValueError(f"{path}: the {name} column has {arr.size} rows, the input has {n}")
    used = {table.key(c) for c in (time, input, output, curve_angle) if c is not None}
    extra = {}
    for name in table.names():
        if name in used:
            continue
        try:
            values = np.asarray(
                [float(v) for v in table.columns[name]] if table.text else table.columns[name],
                dtype=np.float64,
            )
        except (TypeError, ValueError):
            continue
        if values.shape == (n,):
            extra[name] = values
    if t is not None:
        keep = np.r_[True, np.diff(t) != 0]
        back = np.flatnonzero(np.diff(t) < 0)
        if back.size:
            i = int(back[0]) + 1
            raise ValueError(
                f"{path}: column {table.key(time)!r}, row {table.first_row + i}: time goes "
                f"backwards ({t[i]} after {t[i - 1]})"
            )
        if not keep.all():
            t, x = t[keep], x[keep]
            y = y[keep] if y is not None else None
            theta = theta[keep] if theta is not None else None
            extra = {k: v[keep] for k, v in extra.items()}
    if x.size < MIN_ROWS:
        raise ValueError(f"{path}: too few rows ({x.size}); at least {MIN_ROWS} are needed")
    return Log(t, x, y, theta, extra, str(path), table.names())


def write_csv(path: str | Path, columns: dict[str, np.ndarray]) -> Path:
    """Write equal-length columns as a CSV with a header."""
    path = Path(path)
    names = list(columns)
    data = np.column_stack([np.asarray(columns[k], dtype=float) for k in names])
    np.savetxt(path, data, delimiter=",", header=",".join(names), comments="", fmt="%.10g")
    return path
