"""The commands that take data files: a bad file is one line and exit 2 (no traceback);
the data-quality notes are printed; Ctrl-C stops with one line and exit 130."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app

runner = CliRunner()
COLS = ["--input", "x", "--output", "y", "--time", "t"]


def _good(path, n=400, jitter=False):
    t = np.arange(n) * 0.01
    if jitter:  # irregular sampling and a gap: read_log notes both
        t = t + np.random.default_rng(1).uniform(0, 0.004, n)
        t[n // 2 :] += 0.2
    x = np.sin(2 * np.pi * 0.5 * t)
    ts.io.write_csv(path, {"t": t, "x": x, "y": ts.models.Backlash(B_r=0.05).simulate(t, x)})
    return path


BAD = {
    "ros.bag": (b"#ROSBAG V2.0\nE\x00\x00\x00op=\x03\xb8\x01", "a ROS 1 bag"),
    "empty.csv": (b"", "the file is empty"),
    "header.csv": (b"t,x,y\n", "no data rows"),
    "text.csv": (b"t,x,y\n0,1,2\n1,oops,3\n2,3,4\n3,4,5\n", "column 'x', row 3: holds text"),
    "cyr.csv": ("t,x,y,Время\n0,1,2,3\n".encode("cp1251"), "not UTF-8 text"),
}


def _one_line_error(result, expected):
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    text = " ".join(result.output.split())  # rich wraps long lines on a narrow terminal
    assert "error:" in text and expected in text


@pytest.mark.parametrize("name", sorted(BAD))
def test_identify_predict_compare_name_the_bad_file(tmp_path, name):
    content, expected = BAD[name]
    bad = tmp_path / name
    bad.write_bytes(content)
    good = _good(tmp_path / "good.csv")
    model = tmp_path / "m.json"
    ts.models.Backlash(B_r=0.05).to_json(model)
    for args in (
        ["identify", str(bad), "--model", "Backlash", *COLS, "-o", str(tmp_path / "o.json")],
        ["identify", str(good), "--model", "Backlash", *COLS, "--validate", str(bad)],
        ["predict", str(model), str(bad), *COLS, "-o", str(tmp_path / "p.csv")],
        ["compare", str(good), str(bad), *COLS, "--models", "backlash"],
    ):
        _one_line_error(runner.invoke(app, args), expected)
    assert not (tmp_path / "o.json").exists() and not (tmp_path / "p.csv").exists()


def test_predict_names_a_binary_model_file(tmp_path):
    model = tmp_path / "m.json"
    model.write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff")
    result = runner.invoke(app, ["predict", str(model), str(_good(tmp_path / "g.csv")), *COLS])
    _one_line_error(result, "not a model JSON file")


def test_identify_and_predict_print_the_data_quality_notes(tmp_path):
    data = _good(tmp_path / "jittery.csv", jitter=True)
    out = tmp_path / "m.json"
    args = ["identify", str(data), "--model", "Backlash", *COLS, "--maxiter", "5", "-o", str(out)]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "gap(s) in time" in text and "irregular sampling" in text
    assert "consider --resample RATE (Hz)" in text  # the command line's words
    result = runner.invoke(app, ["predict", str(out), str(data), "-o", str(tmp_path / "p.csv")])
    assert result.exit_code == 0, result.output
    assert "irregular sampling" in " ".join(result.output.split())


def _interrupt(args, cwd, ready: str, timeout=120.0):
    """Run the CLI in its own process group, wait for ``ready`` on stdout, then Ctrl-C the
    group (as a terminal does: every process of the command gets SIGINT)."""
    env = {**os.environ, "PYTHONUNBUFFERED": "1", "COLUMNS": "200"}
    cmd = [sys.executable, "-c", "from tendonsheath.apps.cli import main; main()", *args]
    proc = subprocess.Popen(
        cmd,
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    seen, deadline = [], time.monotonic() + timeout
    while time.monotonic() < deadline:
        line = proc.stdout.readline()
        seen.append(line)
        if ready in line or not line:
            break
    assert any(ready in s for s in seen), "".join(seen) + proc.stderr.read()
    time.sleep(1.0)
    os.killpg(proc.pid, signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    return proc.returncode, "".join(seen) + out, err


def test_ctrl_c_stops_identify_cleanly_and_writes_nothing(tmp_path):
    data = _good(tmp_path / "jittery.csv", n=3000, jitter=True)
    out = tmp_path / "out" / "model.json"
    out.parent.mkdir()
    args = [
        "identify",
        str(data),
        "--model",
        "BoucWenBacklash",
        *COLS,
        "--maxiter",
        "100000",
        # the fit alone can end within the second before Ctrl-C; a million bootstrap re-fits
        # after it cannot, so the interrupt always lands in the work
        "--standard-errors",
        "bootstrap",
        "--resamples",
        "1000000",
        "-o",
        str(out),
    ]
    rc, stdout, stderr = _interrupt(args, tmp_path, ready="irregular sampling")
    assert rc == 130, stdout + stderr
    assert "Traceback" not in stderr + stdout
    assert [ln for ln in stderr.splitlines() if ln.strip()] == [
        "interrupted (Ctrl-C): identify stopped; no output file is left half-written"
    ]
    assert list(Path(out.parent).iterdir()) == []


def test_ctrl_c_stops_demo_cleanly(tmp_path):
    out = tmp_path / "demo"
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    cmd = [sys.executable, "-c", "from tendonsheath.apps.cli import main; main()", "demo",
           "--out", str(out), "--scale", "0.2"]  # fmt: skip
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)  # fmt: skip
    deadline = time.monotonic() + 120
    while not out.is_dir() and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.05)  # the folder is made once the command runs (past the imports)
    time.sleep(1.0)
    assert proc.poll() is None, "the demo finished before it could be interrupted"
    os.killpg(proc.pid, signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stdout + stderr
    assert "Traceback" not in stdout + stderr
    assert [ln for ln in stderr.splitlines() if ln.strip()] == [
        "interrupted (Ctrl-C): demo stopped; no output file is left half-written"
    ]
    assert not [p for p in out.iterdir() if ".tmp" in p.name]
    assert not (out / "report.html").exists()


@pytest.mark.parametrize(
    ("content", "expected"),
    [
        (b"#ROSBAG V2.0\n\xb8\x00", "this is a ROS 1 bag, not a"),
        (b'[run]\nscenario = "\x80\xff"\n', "not UTF-8 text (byte 0x80 on line 2)"),
        (bytes(range(256)), "this is a binary file, not a"),
    ],
)
@pytest.mark.parametrize("command", ["bench", "sweep"])
def test_bench_and_sweep_name_a_bad_toml_file(tmp_path, command, content, expected):
    path = tmp_path / "scenario.toml"
    path.write_bytes(content)
    result = runner.invoke(app, [command, str(path), "--out", str(tmp_path / "o")])
    _one_line_error(result, expected)
