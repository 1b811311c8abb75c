"""read_log on real-life files: Excel, irregular sampling, gaps, missing values, bad files."""

import numpy as np
import openpyxl
import pytest
from _realdata_helpers import plant_log

from tendonsheath import io


def _xlsx(path, header, rows, sheet="log"):
    book = openpyxl.Workbook()
    ws = book.active
    ws.title = sheet
    ws.append(header)
    for r in rows:
        ws.append(list(r))
    book.save(path)
    return path


def test_excel_round_trip(tmp_path):
    t, x, y = plant_log(n=60)
    path = _xlsx(tmp_path / "run.xlsx", ["time", "motor", "tip"], zip(t, x, y, strict=True))
    log = io.read_log(path, time="time", input="motor", output="tip")
    assert np.allclose(log.t, t) and np.allclose(log.x, x) and np.allclose(log.y, y)
    assert io.columns(path) == ["time", "motor", "tip"]
    log2 = io.read_log(path, time="time", input="motor", output="tip", sheet="log")
    assert np.array_equal(log2.y, log.y)
    with pytest.raises(ValueError, match="no sheet 'other'"):
        io.read_log(path, input="motor", sheet="other")


def test_excel_errors_name_file_column_and_row(tmp_path):
    rows = [(0.0, 1.0, 2.0), (0.1, "abc", 3.0), (0.2, 3.0, 4.0), (0.3, 4.0, 5.0)]
    path = _xlsx(tmp_path / "bad.xlsx", ["t", "x", "y"], rows)
    with pytest.raises(ValueError, match=r"bad\.xlsx: column 'x', row 3: holds text 'abc'"):
        io.read_log(path, time="t", input="x", output="y")
    path = _xlsx(tmp_path / "nohead.xlsx", [0.0, 1.0, 2.0], [(1.0, 2.0, 3.0)] * 4)
    with pytest.raises(ValueError, match=r"nohead\.xlsx: row 1 must be a header"):
        io.read_log(path, input="1")
    path = _xlsx(tmp_path / "short.xlsx", ["t", "x"], [(0.0, 1.0), (1.0, 2.0)])
    with pytest.raises(ValueError, match=r"short\.xlsx: too few rows"):
        io.read_log(path, time="t", input="x")
    with pytest.raises(ValueError, match=r"short\.xlsx: unknown output column 'tip'"):
        io.read_log(path, time="t", input="x", output="tip")
    (tmp_path / "junk.xlsx").write_bytes(b"PK\x03\x04 not a workbook")  # a zip, broken
    with pytest.raises(ValueError, match=r"junk\.xlsx: not a readable Excel file"):
        io.read_log(tmp_path / "junk.xlsx", input="x")


def test_irregular_sampling_detected_and_resampled(tmp_path):
    rng = np.random.default_rng(1)
    t = np.cumsum(rng.choice([0.001, 0.002, 0.003], size=300))
    x = np.sin(2 * np.pi * t)
    io.write_csv(tmp_path / "irr.csv", {"t": t, "x": x, "y": 2 * x})
    log = io.read_log(tmp_path / "irr.csv", time="t", input="x", output="y")
    assert log.irregular and any("irregular sampling" in n for n in log.notes)
    r = io.read_log(tmp_path / "irr.csv", time="t", input="x", output="y", resample=500.0)
    assert not r.irregular and np.allclose(np.diff(r.t), 0.002)
    assert np.allclose(r.y, 2 * r.x) and np.allclose(r.x, np.interp(r.t, t, x))
    assert r.rows is None and any("resampled to 500 Hz" in n for n in r.notes)
    auto = io.read_log(tmp_path / "irr.csv", time="t", input="x", resample="auto")
    assert not auto.irregular
    with pytest.raises(ValueError, match=r"irr\.csv: resampling needs a time column"):
        io.read_log(tmp_path / "irr.csv", input="x", resample=100.0)
    regular = io.read_log(tmp_path / "irr.csv", input="x")  # no time column: sample index
    assert regular.t is None and np.array_equal(regular.index, np.arange(300.0))


def test_gap_and_missing_values_reported_with_rows(tmp_path):
    t = np.r_[np.arange(10) * 0.01, 0.5 + np.arange(10) * 0.01]  # gap before the 11th sample
    x = np.sin(t)
    lines = ["t,x,y"] + [f"{a},{b},{2 * b}" for a, b in zip(t, x, strict=True)]
    lines[4] = f"{t[3]},,{2 * x[3]}"  # file row 5: empty input cell
    lines[7] = f"{t[6]},{x[6]},nan"  # file row 8: NaN output
    (tmp_path / "g.csv").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"g\.csv: column 'x', row 5: is empty"):
        io.read_log(tmp_path / "g.csv", time="t", input="x", output="y")
    log = io.read_log(tmp_path / "g.csv", time="t", input="x", output="y", missing="drop")
    assert len(log) == 18
    assert any("2 row(s) with a missing value dropped: rows 5, 8" in n for n in log.notes)
    assert any("gap(s)" in n and "before rows 12" in n for n in log.notes)
    log = io.read_log(tmp_path / "g.csv", time="t", input="x", output="y", missing="interpolate")
    assert len(log) == 20 and np.all(np.isfinite(log.y))
    assert np.isclose(log.x[3], 0.5 * (x[2] + x[4]), rtol=1e-3)
    assert any("interpolated: rows 5, 8" in n for n in log.notes)
    with pytest.raises(ValueError, match="missing must be"):
        io.read_log(tmp_path / "g.csv", input="x", missing="ignore")


def test_duplicate_timestamps_reported(tmp_path):
    (tmp_path / "d.csv").write_text("t,x,y\n0,1,10\n0.1,2,20\n0.1,3,30\n0.1,5,50\n0.2,4,40\n")
    log = io.read_log(tmp_path / "d.csv", time="t", input="x", output="y")
    assert log.x.tolist() == [1.0, 2.0, 4.0]
    assert log.rows.tolist() == [2, 3, 6]
    assert any("2 row(s) with a duplicate timestamp" in n and "rows 4-5" in n for n in log.notes)


def test_degrees_and_helpers(tmp_path):
    t, x, y = plant_log(n=50, saturate=False)
    io.write_csv(tmp_path / "deg.csv", {"t": t, "x": np.degrees(x), "y": np.degrees(y)})
    log = io.read_log(
        tmp_path / "deg.csv", time="t", input="x", output="y", curve_angle=90, degrees=True
    )
    assert np.allclose(log.x, x) and np.allclose(log.y, y)
    assert np.allclose(log.curve_angle, np.pi / 2)
    assert np.isclose(io.deg2rad(180.0), np.pi) and np.isclose(io.rad2deg(np.pi / 2), 90.0)
    assert np.allclose(io.rad2deg(io.deg2rad([1.0, -30.0])), [1.0, -30.0])


@pytest.mark.parametrize(
    ("text", "kwargs", "pattern"),
    [
        ("t,x,y\n0,1,2\n1,2,3\n2,3,4\n", {"output": "tip"}, r"unknown output column 'tip'"),
        ("t,x,y\n0,1,2\n1,2,3\n2,3,oops\n", {}, r"column 'y', row 4: holds text 'oops'"),
        ("t,x,y\n0,1,2\n1,2,3\n", {}, r"too few rows \(2\)"),
        ("1,2,3\n0,1,2\n1,2,3\n2,3,4\n", {}, r"row 1 must be a header"),
    ],
)
def test_malformed_text_files(tmp_path, text, kwargs, pattern):
    path = tmp_path / "mal.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=pattern) as info:
        io.read_log(path, **{"time": "t", "input": "x", "output": "y", **kwargs})
    assert "mal.csv" in str(info.value)
