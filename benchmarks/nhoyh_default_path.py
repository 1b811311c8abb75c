"""The default path on the nhoyh bending joint: read_log with the load -> compare_models() ->
winner -> inverse, trained on some configurations and run on the others.

    python benchmarks/nhoyh_default_path.py [--data ../shared/data/nhoyh_vio_com]

The data (nhoyh / ViO-Com; licence unknown: read from its folder at run time only): the
commanded and measured bending angle of a tendon-sheath joint at ten sheath configurations
(config_XXXdeg.csv, 40 Hz, two periods of a 60 deg sine), read as a user would with every
column the log has for the drive: ``read_log(path, time="t", input="input", output="output",
degrees=True, load="tension_1")`` (tension_1: the load cell of one of the two pitch tendons;
a log's load is one column).

Training: configurations 0, 90, 180 and 270 deg; ``ts.compare_models(train)`` with every
default. Held out: the other six. The winner and the affine map (least squares on the
training runs) are run over each from its start, with the run's load where the winner takes
one, and scored from the input's first reversal on (forward: the predicted angle's rmse;
inverse: the commands the winner's inverse sends for the recorded angle against the input
that produced them; see ``_tool5.scores``). Zeros as recorded: the angle is the EM tracker's,
with no re-zeroing between the configurations. Figures: the winner's rmse over the affine
map's, median and worst over the six runs. Writes benchmarks/results/nhoyh_default_path.json.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np
from _tool5 import DEFAULT as TOOL5
from _tool5 import scores

import tendonsheath as ts
from _common import write_results

DEFAULT = TOOL5.parent / "nhoyh_vio_com"
TRAIN = (0, 90, 180, 270)
HELD_OUT = (30, 60, 120, 150, 210, 240)


def read(data: Path, config: int) -> ts.io.Log:
    return ts.io.read_log(
        data / f"config_{config:03d}deg.csv", time="t", input="input", output="output",
        degrees=True, load="tension_1",
    )  # fmt: skip


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=DEFAULT)
    args = ap.parse_args()
    if not (args.data / "config_000deg.csv").exists():
        print(f"no data at {args.data}: results/nhoyh_default_path.json kept as it is")
        return 0
    warnings.simplefilter("ignore")
    start = time.perf_counter()
    cmp = ts.compare_models([read(args.data, c) for c in TRAIN])
    seconds = time.perf_counter() - start
    print(cmp.text())
    per_run = {}
    for c in HELD_OUT:
        log = read(args.data, c)
        w, a = scores(cmp.winner, log), scores(cmp.fits["affine"], log)
        per_run[f"config_{c:03d}deg"] = {k: w[k] / a[k] for k in ("forward_abs", "inverse_abs")}
    summary = {
        key: {
            "median": float(np.median([r[key] for r in per_run.values()])),
            "worst": float(np.max([r[key] for r in per_run.values()])),
            "runs_worse_than_affine": int(sum(r[key] > 1 for r in per_run.values())),
        }
        for key in ("forward_abs", "inverse_abs")
    }
    print(summary)
    path = write_results(
        "nhoyh_default_path",
        {
            "train": [f"config_{c:03d}deg" for c in TRAIN],
            "winner": cmp.winner_name,
            "compare_seconds": seconds,
            "summary": summary,
            "per_run": per_run,
        },
    )
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
