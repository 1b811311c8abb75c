"""How long the default path's model choice takes: ``compare_models`` with every default on
five recordings of 10^4 samples (issue 35 item 5: under 20 s on 2 cores).

    python benchmarks/compare_speed.py [--tool5 ../shared/data/davinci_tool5] [--repeat 3]

The recordings: five runs of the shared da Vinci tool 5 (its first session: 0.1 Hz at loads
10 %, 30 %, 50 %, 70 % and 90 %; ODbL/DbCL, read from its folder, never copied), read as a
user would with the jaw torque as the load (so the defaults include the load-aware
candidates), resampled to 500 Hz: 10 000 samples each. The call: ``ts.compare_models(logs)``,
every default (leave-one-recording-out cross-validation over the five, the winner refitted
on all of them). Wall seconds, the best and the median of ``--repeat`` calls, with the
machine's load average before each: the machine is shared, and the best call is the one
least disturbed by others. ``--before``: the folds' fits as before issue 35 item 5, on every
training sample (``compare.FOLD_THIN_ABOVE`` lifted). Writes
benchmarks/results/compare_speed.json (``--before``: compare_speed_before.json).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np
from _tool5 import DEFAULT, run_name

import tendonsheath as ts
from _common import write_results
from tendonsheath.apps import compare

RUNS = tuple(run_name(0.1, p) for p in (10, 30, 50, 70, 90))
RATE = 500.0  # Hz: 20 s runs of 10 000 samples


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tool5", type=Path, default=DEFAULT)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--before", action="store_true")
    args = ap.parse_args()
    if args.before:
        compare.FOLD_THIN_ABOVE = 10**12
    if not (args.tool5 / f"{RUNS[0]}.csv").exists():
        print(f"no data at {args.tool5}: results/compare_speed.json kept as it is")
        return 0
    warnings.simplefilter("ignore")
    logs = [
        ts.io.read_log(
            args.tool5 / f"{n}.csv",
            time="t",
            input="motor",
            output="jaw",
            load="jaw_torque",
            resample=RATE,
        )  # fmt: skip
        for n in RUNS
    ]
    samples = [int(log.x.size) for log in logs]
    calls = []
    for _ in range(args.repeat):
        load = os.getloadavg()[0]
        start = time.perf_counter()
        cmp = ts.compare_models(logs)
        calls.append({"seconds": time.perf_counter() - start, "load_average_before": load})
        print(f"compare_models: {calls[-1]['seconds']:.1f} s (load {load:.2f}); "
              f"winner {cmp.winner_name}")  # fmt: skip
    seconds = [c["seconds"] for c in calls]
    path = write_results(
        "compare_speed_before" if args.before else "compare_speed",
        {
            "runs": list(RUNS),
            "samples": samples,
            "cores": len(os.sched_getaffinity(0)),
            "candidates": [r["model"] for r in cmp.table],
            "winner": cmp.winner_name,
            "best_seconds": float(min(seconds)),
            "median_seconds": float(np.median(seconds)),
            "calls": calls,
            "per_candidate_seconds": {r["model"]: r.get("seconds") for r in cmp.table},
            "final_fit_seconds": next(
                (r["final_fit_seconds"] for r in cmp.table if r.get("final_fit_seconds")), None
            ),
        },
    )
    print(f"best {min(seconds):.1f} s, median {np.median(seconds):.1f} s; wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
