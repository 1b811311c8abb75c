"""Reading a delimited text table in chunks: bounded memory, and a clear one-line error for
every kind of file that is not one (binary formats, empty, header only, wrong encoding).

The file is checked first (its first block: known binary formats, NUL bytes, a UTF-16 or
UTF-8 byte-order mark), then read ``CHUNK_LINES`` lines at a time. A clean chunk is parsed
by numpy's C parser; a chunk with a problem (text or empty cells, a short row) is parsed
cell by cell, so that the problem's row and column can be named. Every column ends as a
float array (NaN for an empty cell) with the file row of its first empty cell and of its
first text cell, if any: whether those are an error depends on the column's use.
"""

from __future__ import annotations

import codecs
import csv
import re
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

CHUNK_LINES = 1 << 16
HEAD_BYTES = 1 << 16
DELIMITERS = (",", "\t", ";", "|")
SUPPORTED = (
    "CSV/TSV text with a header row, NPY, NPZ, HDF5 (.h5), Excel (.xlsx) or a ROS bag "
    "(.bag, .db3, .mcap)"
)

# (magic bytes at offset 0, what the file looks like, what to do)
_MAGIC = (
    # a bag is read by its suffix (that is how rosbags tells them apart)
    (b"#ROSBAG", "a ROS 1 bag", "name it .bag to read it as one"),
    (b"\x89MCAP", "an MCAP (ROS 2) bag", "name it .mcap to read it as one"),
    (
        b"SQLite format 3\x00",
        "an SQLite database (a ROS 2 .db3 bag?)",
        "if it is a ROS 2 bag, name it .db3",
    ),
    (b"PAR1", "a Parquet file", "convert it, e.g. pandas.read_parquet(...).to_csv(...)"),
    (b"\x89HDF\r\n\x1a\n", "an HDF5 file", "name it .h5"),
    (b"\x93NUMPY", "a NumPy .npy file", "name it .npy"),
    (
        b"PK\x03\x04",
        "a ZIP archive (an .xlsx workbook or an .npz?)",
        "name it .xlsx or .npz, or unpack it",
    ),
    (b"\x1f\x8b", "a gzip-compressed file", "decompress it first"),
    (b"\xd0\xcf\x11\xe0", "an old Excel .xls workbook", "save it as .xlsx or CSV"),
    (b"%PDF", "a PDF document", "export the data as CSV"),
    (b"\x89PNG", "a PNG image", "give the data file instead"),
    (b"\xff\xd8\xff", "a JPEG image", "give the data file instead"),
    (
        b"MATLAB 5.0 MAT-file",
        "a MATLAB .mat file",
        "save the signals as CSV (writematrix/writetable)",
    ),
)


@dataclass
class Column:
    """One column: values (NaN for empty cells), and the first empty and first text cell."""

    values: np.ndarray
    first_empty: int | None = None  # file row
    first_text: tuple[int, str] | None = None  # (file row, the cell)


@dataclass
class TextTable:
    columns: dict[str, Column]
    rows: np.ndarray | None  # file row of every data row (None: they follow on from first_row)
    first_row: int
    notes: list[str] = field(default_factory=list)


def _fail(path: Path, message: str) -> ValueError:
    return ValueError(f"{path}: {message}")


def sniff_binary(path: Path, head: bytes, expected: str = "") -> None:
    """A clear error for a binary file (a known format by its magic bytes, else any NUL)."""
    want = expected or f"a data table; supported: {SUPPORTED}"
    for magic, what, todo in _MAGIC:
        if head.startswith(magic):
            raise _fail(path, f"this is {what}, not {want}" + ("" if expected else f"; {todo}"))
    if b"\x00" in head:
        raise _fail(path, f"this is a binary file, not {want}")


def sniff_kind(path: Path, magic: bytes, what: str) -> None:
    """Before a binary reader (NPY, NPZ, HDF5, Excel) opens ``path``: a one-line error where
    its first bytes are not ``magic`` but another known format's, or text (a CSV table or
    JSON named with the wrong suffix), instead of the reader's own message about a broken
    file of its kind (NumPy's about pickled data, for a text file named .npy)."""
    if path.is_dir() or not path.exists():
        return  # the reader says so
    with open(path, "rb") as f:
        head = f.read(HEAD_BYTES)
    if not head:
        raise _fail(path, f"the file is empty (0 bytes), not {what}")
    # at 0, or (HDF5's user block) at 512, 1024, 2048, ... bytes
    if any(head[at:].startswith(magic) for at in (0, *(512 << k for k in range(8)))):
        return
    for other, kind, todo in _MAGIC:
        if head.startswith(other):
            raise _fail(path, f"this is {kind}, not {what}; {todo}")
    if b"\x00" not in head:
        text = head.lstrip(codecs.BOM_UTF8).lstrip()
        kind = "JSON text" if text[:1] in (b"{", b"[") else "text (a CSV table?)"
        todo = "" if kind == "JSON text" else "; name it .csv to read it as one"
        raise _fail(path, f"this is {kind}, not {what}{todo}")
    raise _fail(path, f"this is not {what} (its first bytes are not {what}'s)")


def read_config_text(path: Path, what: str = "a TOML file") -> str:
    """The text of a small UTF-8 configuration file, or a one-line ValueError saying why
    not (a folder, a binary file, not UTF-8)."""
    if path.is_dir():
        raise _fail(path, f"is a folder, not {what}")
    data = path.read_bytes()
    sniff_binary(path, data[:HEAD_BYTES], what)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise _fail(
            path, f"not UTF-8 text (byte 0x{data[exc.start]:02x} on line {line}); save it as UTF-8"
        ) from None


def _first_bad_utf8(path: Path) -> tuple[int, int, int] | None:
    """(line, byte offset, the byte) of the first byte that is not UTF-8, or None."""
    decoder = codecs.getincrementaldecoder("utf-8")()
    offset, line = 0, 1
    with open(path, "rb") as f:
        while block := f.read(1 << 20):
            try:
                decoder.decode(block)
            except UnicodeDecodeError as exc:
                at = exc.start
                return line + block.count(b"\n", 0, at), offset + at, block[at]
            line += block.count(b"\n")
            offset += len(block)
    return None


def _western_8bit(path: Path) -> bool:
    """True when the file reads unambiguously as Windows-1252/Latin-1: every non-ASCII byte
    is defined there and stands alone (degree signs, micro signs, accented letters). Runs of
    three or more non-ASCII bytes are what Cyrillic, Greek or East Asian encodings produce."""
    run = re.compile(rb"[\x80-\xff]{3,}|[\x81\x8d\x8f\x90\x9d]")
    with open(path, "rb") as f:
        tail = b""
        while block := f.read(1 << 20):
            if run.search(tail + block):
                return False
            tail = block[-2:]
    return True


def choose_encoding(path: Path, head: bytes) -> tuple[str, str | None]:
    """The encoding to read with, and a note when it is not UTF-8."""
    if head.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return "utf-16", "read as UTF-16 text (byte-order mark)"
    bad = _first_bad_utf8(path)
    if bad is None:
        return "utf-8-sig", None  # -sig: Excel's "CSV UTF-8" starts with a byte-order mark
    line, offset, byte = bad
    if _western_8bit(path):
        return "cp1252", f"not UTF-8 (byte 0x{byte:02x} on line {line}): read as Windows-1252"
    raise _fail(
        path,
        f"not UTF-8 text (byte 0x{byte:02x} at offset {offset}, line {line}), and not "
        "unambiguously Windows-1252/Latin-1 either; save it as UTF-8 (Excel: CSV UTF-8)",
    )


def _split_header(line: str) -> tuple[str | None, list[str]]:
    """The delimiter that splits the header into the most names (None: whitespace)."""
    best, fields = ",", next(csv.reader([line], delimiter=","), [])
    for d in DELIMITERS[1:]:
        cand = next(csv.reader([line], delimiter=d), [])
        if len(cand) > len(fields):
            best, fields = d, cand
    if len(fields) <= 1 and len(line.split()) > 1:
        return None, line.split()
    return best, fields


def _check_header(path: Path, header: list[str]) -> list[str]:
    names = [h.strip().strip('"').strip() for h in header]
    if not names or any(h == "" for h in names):
        raise _fail(path, "row 1 must be a header with a name for every column")
    try:
        [float(h) for h in names]
    except ValueError:
        pass
    else:
        raise _fail(path, "row 1 must be a header of column names (got numbers)")
    dup = sorted({h for h in names if names.count(h) > 1})
    if dup:
        raise _fail(path, f"duplicate column names in the header: {dup}")
    return names


def _cells(lines: list[str], delimiter: str | None) -> list[list[str]]:
    if delimiter is None:
        return [ln.split() for ln in lines]
    return list(csv.reader(lines, delimiter=delimiter))


def parse_cells(cells: list[str], rows: np.ndarray) -> Column:
    """Cell by cell: empty -> NaN (first one recorded); text -> the first one recorded."""
    out = np.empty(len(cells))
    empty, text = None, None
    for i, cell in enumerate(cells):
        s = cell.strip()
        if s == "":
            out[i] = np.nan
            empty = empty if empty is not None else int(rows[i])
            continue
        try:
            out[i] = float(s)
        except ValueError:
            out[i] = np.nan
            text = text if text is not None else (int(rows[i]), s)
    return Column(out, empty, text)


def _parse_chunk(path, lines, rows, names, delimiter) -> list[Column]:
    """numpy's C parser on a clean chunk; cell by cell where it refuses."""
    if delimiter is not None and len(names) > 1:
        try:
            arr = np.loadtxt(
                lines, delimiter=delimiter, quotechar='"', dtype=float, ndmin=2, comments=None
            )
            if arr.shape == (len(lines), len(names)):
                # copies, not views of arr: each column's memory is released on its own
                return [Column(arr[:, j].copy()) for j in range(len(names))]
        except ValueError:
            pass
    table = _cells(lines, delimiter)
    for k, cells in enumerate(table):
        if len(cells) != len(names):
            hint = "" if len(names) > 1 else " (is the delimiter one of , ; tab |?)"
            raise _fail(
                path,
                f"row {int(rows[k])} has {len(cells)} fields, the header has {len(names)}{hint}",
            )
    return [parse_cells([r[j] for r in table], rows) for j in range(len(names))]


def _merge(parts: list[list[Column | None]], n_cols: int) -> list[Column]:
    """One Column per column from the chunks' columns; each chunk's piece is released as soon
    as its column is joined, so the peak is the data plus one column, not twice the data."""
    merged = []
    for j in range(n_cols):
        cols = [c for c in (p[j] for p in parts) if c is not None]  # None: a joined column
        for p in parts:
            p[j] = None
        values = np.concatenate([c.values for c in cols]) if cols else np.empty(0)
        empty = next((c.first_empty for c in cols if c.first_empty is not None), None)
        text = next((c.first_text for c in cols if c.first_text is not None), None)
        del cols
        merged.append(Column(values, empty, text))
    return merged


def _join_rows(row_parts: list[np.ndarray]) -> np.ndarray | None:
    """The file row of every data row, or None when they follow on without a gap."""
    first, last = int(row_parts[0][0]), int(row_parts[-1][-1])
    if last - first + 1 == sum(r.size for r in row_parts):
        return None
    return np.concatenate(row_parts)


def _data_lines(f, first_row: int):
    """Chunks of (non-blank lines, their file rows)."""
    lines: list[str] = []
    rows: list[int] = []
    for number, line in enumerate(f, start=first_row):
        if line.strip():
            lines.append(line)
            rows.append(number)
            if len(lines) == CHUNK_LINES:
                yield lines, np.asarray(rows)
                lines, rows = [], []
    if lines:
        yield lines, np.asarray(rows)


@contextmanager
def _past_header(path: Path):
    """Yields (the file positioned after its header, column names, delimiter, the header's
    row, notes), after the checks that need no data (binary, empty, encoding, header)."""
    with open(path, "rb") as f:
        head = f.read(HEAD_BYTES)
    if not head:
        raise _fail(path, "the file is empty (0 bytes)")
    if not head.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        sniff_binary(path, head)
    if head.lstrip(codecs.BOM_UTF8).lstrip()[:1] in (b"{", b"["):
        raise _fail(path, "this is JSON text, not a data table (CSV/TSV with a header row)")
    encoding, note = choose_encoding(path, head)
    notes = [note] if note else []
    try:
        with open(path, encoding=encoding, newline="") as f:
            header_line, first = "", 0
            for first, line in enumerate(f, start=1):  # noqa: B007 - first: the header's row
                if line.strip():
                    header_line = line
                    break
            if not header_line.strip():
                raise _fail(path, "the file holds only blank lines: no header, no data")
            delimiter, header = _split_header(header_line.rstrip("\r\n"))
            names = _check_header(path, header)
            yield f, names, delimiter, first, notes
    except UnicodeDecodeError as exc:  # UTF-16 cut off in a character, say
        raise _fail(path, f"not valid {encoding} text ({exc.reason})") from None


def read_text_header(path: Path) -> list[str]:
    """The column names of a text table (reads the header only)."""
    with _past_header(path) as (_, names, *_rest):
        return names


def read_text_table(path: Path) -> TextTable:
    """Read a delimited text table with a header row (see the module's doc)."""
    with _past_header(path) as (f, names, delimiter, first, notes):
        parts: list[list[Column | None]] = []
        row_parts = []
        for lines, rows in _data_lines(f, first + 1):
            parts.append(
                list(_parse_chunk(path, lines, rows, names, delimiter))
            )  # of Column | None
            row_parts.append(rows)
    if not parts:
        raise _fail(path, f"the header names the columns {names} but there are no data rows")
    suffix = path.suffix.lower()
    expected = {".csv": ",", ".tsv": "\t", ".tab": "\t"}.get(suffix)
    if expected is not None and delimiter != expected and len(names) > 1:
        shown = {None: "whitespace", "\t": "tab"}.get(delimiter, repr(delimiter))
        notes.append(f"columns separated by {shown}, not the {suffix} file's usual one")
    columns = dict(zip(names, _merge(parts, len(names)), strict=True))
    return TextTable(columns, _join_rows(row_parts), int(row_parts[0][0]), notes)


def read_text_cells(path: Path, name: str) -> list[str]:
    """The cells of one column as written, in the order of ``read_text_table``'s rows (for
    the time column: its exact digits and its ISO-8601 text)."""
    with _past_header(path) as (f, names, delimiter, first, _notes):
        j = names.index(name)
        out: list[str] = []
        for lines, _rows in _data_lines(f, first + 1):
            out.extend(cells[j] for cells in _cells(lines, delimiter))
    return out
