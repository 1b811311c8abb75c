"""The default path on a real tool: read_log with the load -> compare_models() -> winner -> inverse.

    python benchmarks/tool5_default_path.py [--data ../shared/data/davinci_tool5]

The data (MRDLab's da Vinci tool 5; ODbL/DbCL; read from its folder at run time, never copied):
50 runs of a 30 deg sine at 0.1-0.5 Hz against ten resistive torque levels. Every run is read
as a user would, with every column the log has for the drive: ``read_log(path, time="t",
input="motor", output="jaw", load="jaw_torque")``.

Training: the runs at 0.1 Hz / 10 %, 0.3 Hz / 50 % and 0.5 Hz / 100 % (issue 35); the choice
is ``ts.compare_models(train)`` with every default (its cross-validation over the three runs,
its default candidates, its choice rule). Nothing is named by hand.

Held out: the other 47 runs. The winner (fitted on the three runs by compare_models) and the
affine map y = a x + b (least squares on the three runs, the table's baseline) are run over
each from its start, with the run's measured load where the winner takes one, and scored
from the input's first reversal on (compare_models' own rule: before it the output depends
on the unknown initial state). Per run:

- forward: the rmse of the predicted jaw angle (rad);
- inverse: the rmse between the commands the model's inverse sends for the recorded jaw angle
  (``tendonsheath.apps.inverse_error.offline_inverse``, the figure compare_models ranks by for
  ``objective="compensation"``: InverseFeedforward, or LoadCompensated with the run's load for
  a Loaded model; the affine map's the same) and the motor angle that produced it (rad).

Each as the winner's rmse over the affine map's on the same run: the median and the worst over
the 47 runs. Encoder zeros: the jaw encoder is relative (its zero is arbitrary; it jumps in
blocks of runs, as if zeroed anew per recording session) and the motor's zero jumps between
sessions too. The figures are given three ways: ``abs`` (the plain rmse, zeros as recorded:
what a user of the default path sees who never re-calibrates), ``zero_free`` (each run's
mean error removed, for the winner and the affine map alike: the error of the loop's shape,
whatever zero the encoders had) and ``recalibrated`` (what a user sees who runs
``ts.session.recalibrate`` at the start of each session: the winner and the affine map alike
refitted on the first two cycles of the session's first run, the sessions as ``_tool5.sessions``
finds them, and the plain rmse scored on the run, after that cycle for the first run).

Also: compare_models' wall time on the three training runs.

Writes benchmarks/results/tool5_default_path.json; without the data it says so and keeps the
old one.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np
from _tool5 import DEFAULT, NAMES, first_cycle, read_all, scores, sessions

import tendonsheath as ts
from _common import write_results
from tendonsheath.apps.session import recalibrate

TRAIN = ("f0.10Hz_load010", "f0.30Hz_load050", "f0.50Hz_load100")
FIGURES = ("forward_abs", "forward_zero_free", "inverse_abs", "inverse_zero_free",
           "forward_recalibrated", "inverse_recalibrated")  # fmt: skip


def recalibrated_scores(models: dict, logs: dict, blocks: list[list[str]]) -> dict:
    """name -> {model key -> (forward, inverse) rmse}: each model re-calibrated at the start
    of each held-out run's session (the first two cycles of the session's first run) and
    scored on the run (the first run after those cycles)."""
    out: dict[str, dict] = {}
    for block in blocks:
        first = logs[block[0]]
        cal, load, n = first_cycle(first, 2.0 / float(block[0][1:5]))  # two cycles
        recal = {key: recalibrate(m, cal, load=load).model for key, m in models.items()}
        for name in block:
            if name in TRAIN:
                continue
            start = n if name == block[0] else None
            out[name] = {}
            for key, m in recal.items():
                s = scores(m, logs[name], start)
                out[name][key] = (s["forward_abs"], s["inverse_abs"])
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=DEFAULT)
    ap.add_argument("--out", default="tool5_default_path", help="results file name (no .json)")
    args = ap.parse_args()
    if not (args.data / f"{TRAIN[0]}.csv").exists():
        print(f"no data at {args.data}: results/tool5_default_path.json kept as it is")
        return 0
    warnings.simplefilter("ignore")
    names = NAMES
    logs = read_all(args.data)
    train = [logs[n] for n in TRAIN]
    start, load_before = time.perf_counter(), os.getloadavg()
    cmp = ts.compare_models(train)
    seconds = time.perf_counter() - start
    print(cmp.text())
    print(f"compare_models on the 3 training runs: {seconds:.1f} s wall")
    affine = cmp.fits["affine"]  # least squares on the three runs
    winner = cmp.winner
    blocks = sessions(logs)
    recal = recalibrated_scores({"winner": winner, "affine": affine}, logs, blocks)
    per_run = {}
    for n in names:
        if n in TRAIN:
            continue
        w, a = scores(winner, logs[n]), scores(affine, logs[n])
        per_run[n] = {k: w[k] / a[k] for k in w} | {f"winner_{k}": v for k, v in w.items()}
        per_run[n] |= {f"affine_{k}": v for k, v in a.items()}
        for i, fig in enumerate(("forward_recalibrated", "inverse_recalibrated")):
            per_run[n][fig] = recal[n]["winner"][i] / recal[n]["affine"][i]
            per_run[n][f"winner_{fig}"] = recal[n]["winner"][i]
            per_run[n][f"affine_{fig}"] = recal[n]["affine"][i]
    summary = {}
    for fig in FIGURES:
        r = np.array([p[fig] for p in per_run.values()])
        summary[fig] = {
            "median": float(np.median(r)),
            "worst": float(np.max(r)),
            "runs_worse_than_affine": int(np.sum(r > 1.0)),
        }
        print(
            f"{fig:18s} winner/affine over the {r.size} held-out runs: median "
            f"{summary[fig]['median']:.3f}, worst {summary[fig]['worst']:.3f}, "
            f"{summary[fig]['runs_worse_than_affine']} worse than affine"
        )
    path = write_results(
        args.out,
        {
            "data": "MRDLab da Vinci tool 5 (ODbL/DbCL): motor in, jaw out, jaw_torque as load",
            "train": list(TRAIN),
            "winner": cmp.winner_name,
            "winner_model": repr(winner),
            "compare_seconds": seconds,
            "load_average_before": list(load_before),
            "cores": os.cpu_count(),
            "table": [
                {
                    k: r.get(k)
                    for k in (
                        "model",
                        "val_nrmse",
                        "ratio_to_affine",
                        "inv_ratio_to_affine",
                        "excluded",
                        "range_flag",
                        "seconds",
                        "final_fit_seconds",
                        "error",
                    )
                }
                for r in cmp.table
            ],
            "sessions": blocks,
            "summary": summary,
            "per_run": per_run,
        },
    )
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
