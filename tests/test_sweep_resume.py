"""An interrupted sweep keeps its finished runs (stored as they finish) and resumes from them:
the resumed table equals an uninterrupted one, and only the missing runs are run again."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app
from tendonsheath.sweep import Relative, Uniform

DESIGN = {"a": Uniform(0.0, 1.0), "b": Relative(2.0, 0.3)}
N = 12


def metric(params):
    return {"m": params["a"] * params["b"], "k": params["a"] - params["b"]}


class StopAfter:
    """Ctrl-C (a KeyboardInterrupt from inside a run) after ``k`` runs."""

    def __init__(self, k):
        self.k, self.calls = k, []

    def __call__(self, params):
        if len(self.calls) == self.k:
            raise KeyboardInterrupt
        self.calls.append(params)
        return metric(params)


def test_an_interrupted_sweep_resumes_with_only_the_missing_runs(tmp_path):
    ck = tmp_path / "runs.jsonl"
    full = ts.sweep(metric, DESIGN, n=N, seed=5, engine="serial")
    with pytest.raises(KeyboardInterrupt):
        ts.sweep(StopAfter(5), DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)
    assert len(ck.read_text().splitlines()) == 1 + 5  # header + the 5 finished runs
    rest = StopAfter(10**9)
    res = ts.sweep(rest, DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)
    assert len(rest.calls) == N - 5 and res.engine["resumed_runs"] == 5
    pd.testing.assert_frame_equal(res.table, full.table)
    # a resume of a finished sweep runs nothing at all
    again = StopAfter(0)
    res = ts.sweep(again, DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)
    assert again.calls == [] and res.engine["resumed_runs"] == N
    pd.testing.assert_frame_equal(res.table, full.table)


def test_a_line_cut_off_by_the_interruption_is_dropped(tmp_path):
    ck = tmp_path / "runs.jsonl"
    with pytest.raises(KeyboardInterrupt):
        ts.sweep(StopAfter(4), DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)
    with open(ck, "a") as f:
        f.write('{"i": 7, "params": {"a": 0.')  # killed mid-line
    rest = StopAfter(10**9)
    res = ts.sweep(rest, DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)
    assert len(rest.calls) == N - 4
    full = ts.sweep(metric, DESIGN, n=N, seed=5, engine="serial")
    pd.testing.assert_frame_equal(res.table, full.table)
    assert all(json.loads(line) for line in ck.read_text().splitlines())


@pytest.mark.parametrize(
    ("kwargs", "what"), [({"seed": 6}, "seed"), ({"n": N + 1}, "runs"), ({"tag": "x"}, "tag")]
)
def test_another_sweeps_runs_are_never_mixed_in(tmp_path, kwargs, what):
    ck = tmp_path / "runs.jsonl"
    ts.sweep(metric, DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)
    args = {"n": N, "seed": 5, "checkpoint_tag": kwargs.pop("tag", None), **kwargs}
    with pytest.raises(ValueError, match=rf"holds the runs of another sweep \(its {what} differ"):
        ts.sweep(metric, DESIGN, engine="serial", checkpoint=ck, **args)


def test_edited_parameters_in_the_file_are_detected(tmp_path):
    ck = tmp_path / "runs.jsonl"
    ts.sweep(metric, DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)
    lines = ck.read_text().splitlines()
    rec = json.loads(lines[3])
    rec["params"]["a"] += 1e-9
    lines[3] = json.dumps(rec)
    ck.write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"run \d+ had other parameters"):
        ts.sweep(metric, DESIGN, n=N, seed=5, engine="serial", checkpoint=ck)


TOML = """
[run]
function = "reference.stand_in_study:compensator_study"

[sweep]
design = "random"
n = 400
seed = 3
workers = 2

[parameters]
friction = { relative = [0.1, 0.3] }
pretension = { relative = [10.0, 0.3] }
route_seed = { seed = true }
route_pieces = 2
elements = 12
samples = 150
"""


def test_ctrl_c_on_a_local_sweep_keeps_the_finished_runs_and_resumes(tmp_path):
    cfg = tmp_path / "sweep.toml"
    cfg.write_text(TOML)
    out = tmp_path / "out"
    runs = out / "runs.jsonl"
    # PYTHONPATH: the stand-in study (tests/reference/)
    env = {**os.environ, "PYTHONUNBUFFERED": "1", "PYTHONPATH": str(Path(__file__).parent)}
    main = "from tendonsheath.apps.cli import main; main()"
    cmd = [sys.executable, "-c", main, "sweep", str(cfg), "--out", str(out), "--no-figures"]
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)  # fmt: skip
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if runs.is_file() and len(runs.read_text().splitlines()) > 3:
            break
        time.sleep(0.05)
    assert proc.poll() is None, "the sweep finished before it could be interrupted"
    os.killpg(proc.pid, signal.SIGINT)  # as a terminal's Ctrl-C: workers get it too
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stdout + stderr
    assert "Traceback" not in stdout + stderr
    assert "interrupted (Ctrl-C): sweep stopped; its finished runs are kept in" in stderr
    assert not (out / "table.csv").exists()
    kept = len(runs.read_text().splitlines()) - 1
    assert 3 <= kept < 400

    result = CliRunner().invoke(app, ["sweep", str(cfg), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    assert f"({kept} more stored by an earlier call)" in " ".join(result.output.split())
    fresh = tmp_path / "fresh"
    result = CliRunner().invoke(app, ["sweep", str(cfg), "--out", str(fresh), "--no-figures"])
    assert result.exit_code == 0, result.output
    pd.testing.assert_frame_equal(
        pd.read_parquet(out / "table.parquet"), pd.read_parquet(fresh / "table.parquet")
    )
