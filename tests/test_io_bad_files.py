"""read_log on the files users actually give it: each bad one gets a one-line error that
names the file and says what is wrong; the quirky but readable ones (a byte-order mark,
Windows-1252, semicolons, UTF-16) just work, with a note."""

import numpy as np
import pytest

from tendonsheath import io
from tendonsheath.io import _textread

GOOD = "t,x,y\n0,1,2\n1,2,3\n2,3,4\n"

BAD = [
    (
        "ros.bag",
        b"#ROSBAG V2.0\nE\x00\x00\x00\x05op=\x03\xb8\x01",
        r"ros.bag: cannot read it as a ROS 1 bag \(",
    ),
    ("ros.csv", b"#ROSBAG V2.0\nE\x00", r"a ROS 1 bag, not a data table.*name it .bag"),
    ("mcap.csv", b"\x89MCAP0\r\n\x00\x00", r"MCAP"),
    ("empty.csv", b"", r"the file is empty \(0 bytes\)"),
    ("blank.csv", b"\n \n\t\n", r"only blank lines"),
    ("header.csv", b"t,x,y\n", r"header names the columns \['t', 'x', 'y'\] but there are no data"),
    ("header_blank.csv", b"t,x,y\n\n\n", r"no data rows"),
    ("binary.dat", bytes(range(256)) * 8, r"a binary file, not a data table; supported: CSV"),
    ("zip.csv", b"PK\x03\x04rest", r"ZIP archive"),
    ("xls.csv", b"\xd0\xcf\x11\xe0\xa1\xb1", r"old Excel \.xls"),
    ("text.csv", b"t,x,y\n0,1,2\n1,2,3\n2,abc,4\n", r"column 'x', row 4: holds text 'abc'"),
    ("comma.csv", b"t;x;y\n0;1,5;2\n1;2;3\n2;3;4\n", r"row 2: holds text '1,5'.*decimal comma"),
    ("short.csv", b"t,x,y\n0,1,2\n1,2\n2,3,4\n", r"row 3 has 2 fields, the header has 3"),
    ("cyrillic.csv", "t,Время,y\n0,1,2\n".encode("cp1251"), r"not UTF-8 text \(byte 0xc2"),
    ("numbers.csv", b"0,1,2\n1,2,3\n2,3,4\n", r"header of column names \(got numbers\)"),
    ("dup.csv", b"t,x,x\n0,1,2\n1,2,3\n2,3,4\n", r"duplicate column names in the header: \['x'\]"),
    ("cut16.csv", GOOD.encode("utf-16")[:-1], r"not valid utf-16 text \(truncated data\)"),
    # a file whose suffix says one kind and whose content is another (Step 22: file kinds)
    ("json.csv", b'{"t": [0, 1], "x": [1, 2]}\n', r"this is JSON text, not a data table"),
    ("list.csv", b"[[0, 1, 2], [1, 2, 3]]\n", r"this is JSON text, not a data table"),
    ("text.npy", GOOD.encode(), r"this is text \(a CSV table\?\), not an NPY file; name it \.csv"),
    ("text.npz", GOOD.encode(), r"this is text \(a CSV table\?\), not an NPZ file"),
    ("text.h5", GOOD.encode(), r"this is text \(a CSV table\?\), not an HDF5 file"),
    ("text.xlsx", GOOD.encode(), r"this is text \(a CSV table\?\), not an Excel \(\.xlsx\)"),
    ("json.xlsx", b'{"a": 1}', r"this is JSON text, not an Excel \(\.xlsx\) workbook"),
    ("npy.h5", b"\x93NUMPY\x01\x00rest", r"this is a NumPy \.npy file, not an HDF5 file; name it"),
    ("h5.npy", b"\x89HDF\r\n\x1a\nrest", r"this is an HDF5 file, not an NPY file; name it \.h5"),
    ("pdf.xlsx", b"%PDF-1.4 rest", r"this is a PDF document, not an Excel"),
    ("empty.npy", b"", r"the file is empty \(0 bytes\), not an NPY file"),
    ("binary.npy", bytes(range(256)) * 8, r"this is not an NPY file"),
]


@pytest.mark.parametrize(("name", "content", "pattern"), BAD, ids=[b[0] for b in BAD])
def test_bad_files_get_one_line_errors(tmp_path, name, content, pattern):
    path = tmp_path / name
    path.write_bytes(content)
    with pytest.raises(ValueError, match=pattern) as info:
        io.read_log(path, time="t", input="x", output="y")
    message = str(info.value)
    assert str(path) in message and "\n" not in message


def test_a_folder_and_an_unreadable_file(tmp_path):
    with pytest.raises(ValueError, match="is a folder, not a data file"):
        io.read_log(tmp_path, input="x")


def _read(path, **kw):
    return io.read_log(path, time="t", input=kw.pop("input", "x"), output="y", **kw)


def test_excel_csv_utf8_byte_order_mark_just_works(tmp_path):
    path = tmp_path / "bom.csv"
    path.write_bytes(("\ufeff" + GOOD).encode("utf-8"))
    log = _read(path)
    assert log.x.tolist() == [1.0, 2.0, 3.0] and log.notes == []


def test_windows_1252_header_is_read_with_a_note(tmp_path):
    path = tmp_path / "latin.csv"
    path.write_bytes("t,Winkel (°),y\n0,1,2\n1,2,3\n2,3,4\n".encode("cp1252"))
    log = _read(path, input="Winkel (°)")
    assert log.x.tolist() == [1.0, 2.0, 3.0]
    assert any("Windows-1252" in n for n in log.notes)


def test_utf16_with_byte_order_mark_and_semicolons(tmp_path):
    path = tmp_path / "u16.txt"
    path.write_bytes(GOOD.replace(",", "\t").encode("utf-16"))
    assert _read(path).y.tolist() == [2.0, 3.0, 4.0]
    path = tmp_path / "semi.csv"
    path.write_text(GOOD.replace(",", ";"))
    log = _read(path)
    assert log.y.tolist() == [2.0, 3.0, 4.0]
    assert any("separated by ';'" in n for n in log.notes)


def test_blank_lines_keep_the_file_row_numbers(tmp_path):
    path = tmp_path / "gaps.csv"
    path.write_text("t,x,y\n0,1,2\n\n1,2,3\n\n2,x,4\n")
    with pytest.raises(ValueError, match=r"row 6: holds text 'x'"):
        _read(path)


def test_chunked_reading_matches_one_chunk(tmp_path, monkeypatch):
    """Many chunks (some clean, one with an empty cell far down) give the same arrays and
    the right row numbers."""
    rng = np.random.default_rng(3)
    n = 1000
    t = np.arange(n) * 0.01
    x, y = rng.normal(size=n), rng.normal(size=n)
    io.write_csv(tmp_path / "a.csv", {"t": t, "x": x, "y": y})
    monkeypatch.setattr(_textread, "CHUNK_LINES", 37)
    log = _read(tmp_path / "a.csv")
    assert np.allclose(log.x, x, rtol=1e-9) and np.allclose(log.t, t)
    lines = (tmp_path / "a.csv").read_text().splitlines()
    lines[900] = lines[900].split(",")[0] + ",," + lines[900].split(",")[2]
    (tmp_path / "b.csv").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"column 'x', row 901: is empty"):
        _read(tmp_path / "b.csv")
    log = _read(tmp_path / "b.csv", missing="drop")
    assert len(log) == n - 1 and any(
        "row(s) with a missing value dropped: rows 901" in s for s in log.notes
    )


def test_columns_reads_the_header_alone(tmp_path, monkeypatch):
    path = tmp_path / "big.csv"
    path.write_text(GOOD + "3,oops,5\n")

    def no_data(*args, **kwargs):
        raise AssertionError("columns() parsed the data rows")

    monkeypatch.setattr(_textread, "_parse_chunk", no_data)
    assert io.columns(path) == ["t", "x", "y"]
