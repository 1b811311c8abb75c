"""Inverses of identified models on a real tool: held in the identified range, and ranked.

    python benchmarks/inverse.py [--data ../shared/data/davinci_tool5]

The data (MRDLab's da Vinci tool 5: motor in, jaw out; ODbL/DbCL; read from its folder at run
time, never copied) is that of issue 23: the runs at 0.1 Hz / 10 % load, 0.3 Hz / 50 % and
0.5 Hz / 100 %.

1. ``ts.identify(PrandtlIshlinskii, recordings=...)`` on the three runs returns a Scaled PI whose
   weights nearly cancel. Its ``InverseFeedforward`` is asked for each run's recorded jaw angle
   (``tendonsheath.apps.inverse_error.offline_inverse``): without a range (``input_range=None``) and
   with the identified one (the default), the largest |command| and the share of cycles flagged
   out_of_range.
2. ``ts.compare_models`` on the three runs (leave one run out), its forward and inverse columns.

Writes benchmarks/results/inverse.json; without the data it says so and keeps the committed one.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import tendonsheath as ts
from _common import write_results
from tendonsheath.apps.inverse_error import desired_from_record
from tendonsheath.compensate import InverseFeedforward

RUNS = ("f0.10Hz_load010.csv", "f0.30Hz_load050.csv", "f0.50Hz_load100.csv")
DEFAULT = Path(__file__).resolve().parents[2] / "shared" / "data" / "davinci_tool5"


def _range_rows(model, logs) -> list[dict]:
    """Per run: the inverse's largest |command| without and with the identified range."""
    rows = []
    for name, log in zip(RUNS, logs, strict=True):
        desired = desired_from_record(log.t, log.y)
        row = {"run": name, "input_range": [float(log.x.min()), float(log.x.max())]}
        for label, setting in (("unbounded", None), ("identified", "identified")):
            ff = InverseFeedforward(model, smoothing=0.05, input_range=setting)
            u = ff.command(log.t, desired)
            flags = u.status
            row[label] = {
                "max_abs_command": float(np.max(np.abs(u))),
                "out_of_range_share": float(np.mean((flags & ts.Status.OUT_OF_RANGE) != 0)),
            }
        rows.append(row)
    return rows


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=DEFAULT)
    args = ap.parse_args()
    if not all((args.data / f).is_file() for f in RUNS):
        print(f"no tool-5 data in {args.data}: benchmarks/results/inverse.json kept")
        return 0
    warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
    logs = [ts.io.read_log(args.data / f, time="t", input="motor", output="jaw") for f in RUNS]
    fit = ts.identify(ts.models.PrandtlIshlinskii, recordings=logs, seed=0, progress=False)
    rows = _range_rows(fit.model, logs)
    start = time.perf_counter()
    names = ["backlash", "bwb", "pi", "gpi", "bwb+poly3"]
    cmp = ts.compare_models(logs, models=names, seed=0)
    seconds = time.perf_counter() - start
    for r in rows:
        print(f"{r['run']}: |command| <= {r['unbounded']['max_abs_command']:.3g} rad unbounded "
              f"({100 * r['unbounded']['out_of_range_share']:.0f} % flagged), "
              f"{r['identified']['max_abs_command']:.3g} rad in the identified range "
              f"({100 * r['identified']['out_of_range_share']:.0f} % flagged)")  # fmt: skip
    print(cmp.text())
    keys = ("model", "val_nrmse", "ratio_to_affine", "inv_nrmse", "inv_ratio_to_affine")
    table = [{k: r.get(k) for k in keys} for r in cmp.table if not r.get("error")]
    path = write_results(
        "inverse",
        {
            "data": "davinci_tool5: " + ", ".join(RUNS),
            "pi_model": fit.model.to_dict(),
            "range": rows,
            "compare": {"table": table, "winner": cmp.winner_name, "seconds": seconds},
        },
    )
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
