"""read_log: every supported format, duplicate timestamps, and clear errors."""

import h5py
import numpy as np
import pytest

from tendonsheath import io


def _columns(n=10):
    t = np.arange(n) * 0.01
    return t, np.sin(t), np.cos(t), np.full(n, 1.5)


def test_csv_and_tsv(tmp_path):
    t, x, y, th = _columns()
    io.write_csv(tmp_path / "a.csv", {"time": t, "motor": x, "tip": y, "angle": th})
    log = io.read_log(
        tmp_path / "a.csv", time="time", input="motor", output="tip", curve_angle="angle"
    )
    assert np.allclose(log.t, t) and np.allclose(log.x, x) and np.allclose(log.y, y)
    assert np.allclose(log.curve_angle, th)
    lines = ["time\tmotor\ttip\tnote"] + [
        f"{a}\t{b}\t{c}\tok" for a, b, c in zip(t, x, y, strict=True)
    ]
    (tmp_path / "b.tsv").write_text("\n".join(lines) + "\n")
    log = io.read_log(
        tmp_path / "b.tsv", time="time", input="motor", output="tip", curve_angle="3.0"
    )
    assert np.allclose(log.x, x) and np.all(log.curve_angle == 3.0)
    assert "note" not in log.extra  # text column kept out of the numeric extras


def test_npy_npz_hdf5(tmp_path):
    t, x, y, _ = _columns()
    rec = np.zeros(t.size, dtype=[("t", float), ("u", float), ("v", float)])
    rec["t"], rec["u"], rec["v"] = t, x, y
    np.save(tmp_path / "s.npy", rec)
    log = io.read_log(tmp_path / "s.npy", time="t", input="u", output="v")
    assert np.allclose(log.y, y)
    np.save(tmp_path / "m.npy", np.column_stack([t, x, y]))
    log = io.read_log(tmp_path / "m.npy", time=0, input=1, output="2")
    assert np.allclose(log.x, x) and np.allclose(log.y, y)
    np.savez(tmp_path / "z.npz", time=t, motor=x, tip=y)
    log = io.read_log(tmp_path / "z.npz", time="time", input="motor", output="tip")
    assert np.allclose(log.t, t)
    with h5py.File(tmp_path / "h.h5", "w") as f:
        f["time"] = t
        f["robot/motor"] = x
        f["robot/tip"] = y
    log = io.read_log(tmp_path / "h.h5", time="time", input="robot/motor", output="robot/tip")
    assert np.allclose(log.y, y)


def test_duplicate_timestamps_keep_the_first(tmp_path):
    (tmp_path / "d.csv").write_text("t,x,y\n0,1,10\n0.1,2,20\n0.1,3,30\n0.2,4,40\n")
    log = io.read_log(tmp_path / "d.csv", time="t", input="x", output="y")
    assert log.t.tolist() == [0.0, 0.1, 0.2]
    assert log.x.tolist() == [1.0, 2.0, 4.0]
    assert log.y.tolist() == [10.0, 20.0, 40.0]


@pytest.mark.parametrize(
    ("text", "kwargs", "pattern"),
    [
        ("t,x,y\n0,1,2\n1,2,3\n2,3,4\n", {"input": "motor"}, r"unknown input column 'motor'"),
        ("t,x,y\n0,1,2\n1,nan,3\n2,3,4\n", {}, r"column 'x', row 3: value nan"),
        ("t,x,y\n0,1,2\n1,abc,3\n2,3,4\n", {}, r"column 'x', row 3: holds text 'abc'"),
        ("t,x,y\n0,1,2\n1,,3\n2,3,4\n", {}, r"column 'x', row 3: is empty"),
        ("t,x,y\n0,1,2\n1,2,3\n", {}, r"too few rows"),
        ("t,x,y\n0,1,2\n2,2,3\n1,3,4\n", {}, r"row 4: time goes backwards"),
        ("t,x,y\n0,1,2\n1,2\n2,3,4\n", {}, r"row 3 has 2 fields"),
        ("0,1,2\n0,1,2\n1,2,3\n2,3,4\n", {}, r"header"),
        ("t,x,y\n0,1,2\n1,2,3\n2,3,4\n", {"curve_angle": "theta"}, r"unknown curve angle"),
    ],
)
def test_clear_errors_name_file_column_and_row(tmp_path, text, kwargs, pattern):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    args = {"time": "t", "input": "x", "output": "y", **kwargs}
    with pytest.raises(ValueError, match=pattern) as info:
        io.read_log(path, **args)
    assert "bad.csv" in str(info.value)


def test_missing_file_and_bad_binary(tmp_path):
    with pytest.raises(ValueError, match="not found"):
        io.read_log(tmp_path / "none.csv", input="x")
    np.save(tmp_path / "nan.npy", np.array([[0.0, 1.0], [1.0, np.nan], [2.0, 1.0]]))
    with pytest.raises(ValueError, match=r"column '1', row 1"):
        io.read_log(tmp_path / "nan.npy", time=0, input=1)
