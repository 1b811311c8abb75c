"""The table of docs/bad-inputs.md: every bad input tried, with the one-line error (or the
result) it gets today. Each case is run here, so the table is what the code says.

    .venv/bin/python tools/bad_inputs_table.py > /tmp/table.md
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

import tendonsheath as ts

GOOD = "t,x,y\n0,1,2\n1,2,3\n2,3,4\n"

FILES = [
    ("a cut-off ROS 1 bag", "run.bag", b"#ROSBAG V2.0\nE\x00\x00\x00op=\x03\xb8\x01"),
    ("a cut-off MCAP (ROS 2) bag", "run.mcap", b"\x89MCAP0\r\n\x00"),
    ("a cut-off ROS 2 .db3 bag", "run.db3", b"SQLite format 3\x00\x10\x00"),
    ("a ROS 1 bag named .csv", "run.csv", b"#ROSBAG V2.0\nE\x00\x00\x00op=\x03\xb8\x01"),
    ("a Parquet file", "run.csv", b"PAR1\x15\x04"),
    ("a ZIP (an .xlsx renamed .csv)", "run.csv", b"PK\x03\x04\x14\x00"),
    ("gzip-compressed CSV", "run.csv.gz", b"\x1f\x8b\x08\x00"),
    ("an old .xls saved as .csv", "run.csv", b"\xd0\xcf\x11\xe0\xa1\xb1"),
    ("a MATLAB .mat", "run.mat", b"MATLAB 5.0 MAT-file, Platform: GLNXA64"),
    ("random binary", "run.dat", bytes(range(256)) * 4),
    ("an empty file", "run.csv", b""),
    ("only blank lines", "run.csv", b"\n  \n\t\n"),
    ("a header only", "run.csv", b"t,x,y\n"),
    ("numbers where the header should be", "run.csv", b"0,1,2\n1,2,3\n2,3,4\n"),
    ("a duplicate column name", "run.csv", b"t,x,x\n0,1,2\n1,2,3\n2,3,4\n"),
    ("an empty column name", "run.csv", b"t,,y\n0,1,2\n1,2,3\n2,3,4\n"),
    ("text in a number column", "run.csv", b"t,x,y\n0,1,2\n1,2,3\n2,abc,4\n"),
    ("a decimal comma", "run.csv", b"t;x;y\n0;1,5;2\n1;2;3\n2;3;4\n"),
    ("an empty cell", "run.csv", b"t,x,y\n0,1,2\n1,,3\n2,3,4\n"),
    ("NaN in a cell", "run.csv", b"t,x,y\n0,1,2\n1,nan,3\n2,3,4\n"),
    ("a short row", "run.csv", b"t,x,y\n0,1,2\n1,2\n2,3,4\n"),
    ("wrong delimiter, one column", "run.csv", b"t:x:y\n0:1:2\n1:2:3\n2:3:4\n"),
    ("time going backwards", "run.csv", b"t,x,y\n0,1,2\n2,2,3\n1,3,4\n"),
    (
        "epoch nanoseconds read as seconds",
        "run.csv",
        b"t,x,y\n1700000000000000000,1,2\n1700000000001000000,2,3\n1700000000002000000,3,4\n",
    ),
    (
        "epoch seconds rounded coarser than the sampling",
        "run.csv",
        b"t,x,y\n1700000000.1,1,2\n1700000000.1,2,3\n1700000000.1,3,4\n1700000000.2,4,5\n",
    ),
    (
        "ISO-8601 times, an offset on some rows only",
        "run.csv",
        b"t,x,y\n2024-05-01T12:00:00+02:00,1,2\n2024-05-01T12:00:01,2,3\n2024-05-01T12:00:02,3,4\n",
    ),
    ("two data rows", "run.csv", b"t,x,y\n0,1,2\n1,2,3\n"),
    ("Cyrillic in cp1251 (not UTF-8)", "run.csv", "t,x,y,Время\n0,1,2,3\n".encode("cp1251")),
    ("UTF-16 without a byte-order mark", "run.csv", GOOD.encode("utf-16-le")),
    ("UTF-16 cut off mid-character", "run.csv", GOOD.encode("utf-16")[:-1]),
    ("a folder", "folder", None),
    ("a missing file", "missing.csv", False),
]

WORKS = [
    ("Excel's CSV UTF-8 (a byte-order mark)", "run.csv", ("\ufeff" + GOOD).encode()),
    (
        "Windows-1252 (a degree sign in the header)",
        "run.csv",
        "t,x,y,Winkel (°)\n0,1,2,3\n1,2,3,4\n2,3,4,5\n".encode("cp1252"),
    ),
    (
        "UTF-16 with a byte-order mark (Excel's Unicode text)",
        "run.txt",
        GOOD.replace(",", "\t").encode("utf-16"),
    ),
    ("semicolons in a .csv", "run.csv", GOOD.replace(",", ";").encode()),
    ("whitespace-separated", "run.txt", GOOD.replace(",", " ").encode()),
    ("blank lines between rows", "run.csv", b"t,x,y\n0,1,2\n\n1,2,3\n\n2,3,4\n"),
    ("Windows line ends", "run.csv", GOOD.replace("\n", "\r\n").encode()),
    (
        "epoch seconds with six decimals",
        "run.csv",
        b"t,x,y\n1700000000.000001,1,2\n1700000000.001002,2,3\n1700000000.002003,3,4\n",
    ),
    (
        "ISO-8601 times with a UTC offset",
        "run.csv",
        b"t,x,y\n2024-05-01T12:00:00.000+02:00,1,2\n2024-05-01T12:00:00.010+02:00,2,3\n"
        b"2024-05-01T12:00:00.020+02:00,3,4\n",
    ),
]


def _message(fn) -> str:
    try:
        out = fn()
    except (ValueError, TypeError) as exc:
        return f"{type(exc).__name__}: {exc}"
    return f"works: {out}"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _file_rows(cases) -> list[str]:
    rows = []
    for what, name, content in cases:
        path = Path(name)
        if content is None:
            path.mkdir(exist_ok=True)
        elif content is not False:
            path.write_bytes(content)

        def read(path=path):
            log = ts.io.read_log(path, time="t", input="x", output="y")
            return f"{len(log)} rows" + (f"; note: {'; '.join(log.notes)}" if log.notes else "")

        rows.append(f"| {what} | {_cell(_message(read))} |")
        if content not in (None, False):
            path.unlink()
    return rows


def _toml_rows() -> list[str]:
    from tendonsheath.bench.user_scenario import load
    from tendonsheath.sweep.toml import read_sweep_file

    rows = []
    for what, content in [
        ("a ROS 1 bag as the TOML file", b"#ROSBAG V2.0\n\xb8"),
        ("a non-UTF-8 TOML file", b'[run]\nscenario = "\x80"\n'),
    ]:
        Path("scenario.toml").write_bytes(content)
        for label, fn in (("bench", load), ("sweep", read_sweep_file)):
            msg = _cell(_message(lambda fn=fn: fn(Path("scenario.toml"))))
            rows.append(f"| {label}: {what} | {msg} |")
    Path("model.json").write_bytes(b"\x89PNG\r\n\x1a\n\x00")
    msg = _cell(_message(lambda: ts.load_model("model.json")))
    rows.append(f"| predict: a binary model file | {msg} |")
    return rows


def _api_rows() -> list[str]:
    t = np.arange(20) * 0.01
    x = np.sin(7 * t)
    cases = [
        ("identify: y shorter than x", lambda: ts.identify("Backlash", t, x, x[:10])),
        ("identify: NaN in x", lambda: ts.identify("Backlash", t, np.r_[x[:-1], np.nan], x)),
        ("identify: time going backwards", lambda: ts.identify("Backlash", t[::-1], x, x)),
        ("identify: 2-D x", lambda: ts.identify("Backlash", t, np.c_[x, x], x)),
        ("identify: two samples", lambda: ts.identify("Backlash", t[:2], x[:2], x[:2])),
        (
            "FirstOrderLag(time_constant=None) (Hypothesis; was a bare TypeError)",
            lambda: ts.models.FirstOrderLag(time_constant=None),
        ),
        (
            "FirstOrderLag(time_constant='1') (Hypothesis; was accepted as 1.0)",
            lambda: ts.models.FirstOrderLag(time_constant="1"),
        ),
        (
            "BoucWenBacklash(B_l=None) (Hypothesis; was a bare TypeError)",
            lambda: ts.models.BoucWenBacklash(B_l=None),
        ),
        (
            "BoucWenBacklash(B_r=2.2e-313, B_l=0) (Hypothesis; was 'rho must be > 0 (got inf)')",
            lambda: ts.models.BoucWenBacklash(B_r=2.2250738585e-313, B_l=0.0),
        ),
        ("Backlash(B_r=nan)", lambda: ts.models.Backlash(B_r=float("nan"))),
        ("BoucWen(n=-1)", lambda: ts.models.BoucWen(n=-1.0)),
        ("Backlash(B_l=None): None means the default", lambda: ts.models.Backlash(B_l=None).params),
    ]
    return [f"| {what} | {_cell(_message(fn))} |" for what, fn in cases]


def _write_bag(path: Path) -> None:
    """A real ROS 1 bag: /motor/joint_states (JointState, header stamps) at 100 Hz, /tip
    (Float64, no header) at 50 Hz with a NaN in message 4, /late (Float64) after both."""
    from rosbags.rosbag1 import Writer
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS1_NOETIC)
    ty = store.types
    t0 = 1_700_000_000 * 10**9

    def joint_state(ns, k):
        stamp = ty["builtin_interfaces/msg/Time"](sec=ns // 10**9, nanosec=ns % 10**9)
        header = ty["std_msgs/msg/Header"](seq=k, stamp=stamp, frame_id="")
        pos = np.array([np.sin(k / 10), 0.0])
        zero = np.zeros(0)
        return ty["sensor_msgs/msg/JointState"](
            header=header, name=["m0", "m1"], position=pos, velocity=zero, effort=zero
        )

    def float64(value):
        return ty["std_msgs/msg/Float64"](data=float(value))

    with Writer(path) as w:
        conns = {
            name: w.add_connection(name, msgtype, typestore=store)
            for name, msgtype in (
                ("/motor/joint_states", "sensor_msgs/msg/JointState"),
                ("/tip", "std_msgs/msg/Float64"),
                ("/late", "std_msgs/msg/Float64"),
            )
        }
        stream = [
            (t0 + k * 10**7, "/motor/joint_states", joint_state(t0 + k * 10**7, k))
            for k in range(100)
        ]
        stream += [
            (t0 + k * 2 * 10**7 + 1, "/tip", float64(np.nan if k == 3 else k)) for k in range(50)
        ]
        stream += [(t0 + 2 * 10**9 + k * 10**7, "/late", float64(k)) for k in range(10)]
        for ns, topic, msg in sorted(stream, key=lambda item: item[0]):
            w.write(conns[topic], ns, store.serialize_ros1(msg, msg.__msgtype__))


def _bag_rows() -> list[str]:
    import sys

    path = Path("run.bag")
    _write_bag(path)
    motor = "/motor/joint_states:position[0]"
    cases = [
        ("no input named", {"input": None}),
        ("a topic the bag lacks", {"input": "/motor:position[0]"}),
        ("a field the message lacks", {"input": "/motor/joint_states:pos"}),
        ("an index past the array's end", {"input": "/motor/joint_states:position[5]"}),
        ("an array without an index", {"input": "/motor/joint_states:position"}),
        ("a nested message, not a number", {"input": "/motor/joint_states:header.stamp"}),
        ("a text field", {"input": "/motor/joint_states:name[0]"}),
        ("a topic with several numbers named alone", {"input": "/motor/joint_states"}),
        ("not a field path", {"input": "/motor/joint_states:position[0"}),
        ("a CSV time column name", {"input": motor, "time": "t"}),
        ("header time on a topic without a header", {"input": "/late", "time": "header"}),
        ("a NaN in a message", {"input": motor, "output": "/tip"}),
        ("topics that do not overlap in time", {"input": motor, "output": "/late"}),
        (
            "works: NaN dropped (missing='drop')",
            {"input": motor, "output": "/tip", "missing": "drop"},
        ),
    ]
    rows = []
    for what, kwargs in cases:

        def read(kwargs=kwargs):
            log = ts.io.read_log(path, **kwargs)
            return f"{len(log)} samples; notes: {'; '.join(log.notes)}"

        rows.append(f"| {what} | {_cell(_message(read))} |")
    saved = sys.modules.get("rosbags.highlevel")
    sys.modules["rosbags.highlevel"] = None  # as if the ros extra were not installed
    try:
        msg = _message(lambda: ts.io.read_log(path, input=motor))
    finally:
        sys.modules["rosbags.highlevel"] = saved
    rows.append(f"| the rosbags library not installed | {_cell(msg)} |")
    return rows


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        print("| bad input | what you get |\n| --- | --- |")
        print("\n".join(_file_rows(FILES) + _toml_rows() + _api_rows()))
        print("\n| unusual but readable | what you get |\n| --- | --- |")
        print("\n".join(_file_rows(WORKS)))
        print("\n| ROS bag (run.bag, written by the script) | what you get |\n| --- | --- |")
        print("\n".join(_bag_rows()))


if __name__ == "__main__":
    main()
