"""How long each default candidate of ``compare_models`` takes, and how well it predicts, on
three runs of MRDLab's da Vinci tool 5 (issue 17 item 7: the slowest default candidate
budgeted).

    python benchmarks/compare_candidates_time.py [--tool5 ../shared/data/davinci_tool5]
                                                 [--before] [--resample HZ]
                                                 [--models bwb+lag2,...] [--out FILE]

Leave-one-run-out cross-validation of the default candidates (seed 0, default settings) on
f0.10Hz_load010, f0.30Hz_load050 and f0.50Hz_load100 (motor in, jaw out, rad; 4000 samples
each at 200 Hz; ODbL/DbCL, read from its folder, never copied). Prints each candidate's wall
and CPU seconds over its three folds and its pooled held-out rmse over the affine map's.
``--before``: the settings before that item: the dynamic chains' global search on every
sample (identify.data.MAX_DECIMATION = 1) and the full least-squares polish in every fold
(compare.FOLD_REFINE_EVALUATIONS = None). ``--resample 750``: the runs resampled to 750 Hz
(15k samples each, as long recordings); ``--models``: these candidates only.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import tendonsheath as ts
from tendonsheath.apps import compare
from tendonsheath.identify import data as identify_data

RUNS = ("f0.10Hz_load010.csv", "f0.30Hz_load050.csv", "f0.50Hz_load100.csv")


def main() -> None:
    here = Path(__file__).resolve().parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tool5", type=Path, default=here.parents[1] / "shared/data/davinci_tool5")
    parser.add_argument("--before", action="store_true")
    parser.add_argument("--resample", type=float, default=None)
    parser.add_argument("--models", default=None)
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args()
    if args.before:
        identify_data.MAX_DECIMATION = 1
        compare.FOLD_REFINE_EVALUATIONS = None
    columns = {"time": "t", "input": "motor", "output": "jaw", "resample": args.resample}
    logs = [ts.io.read_log(args.tool5 / name, **columns) for name in RUNS]
    models = args.models.split(",") if args.models else None
    start = time.perf_counter()
    cmp = ts.compare_models(logs, models=models)
    total = time.perf_counter() - start
    rows = [
        {
            "model": r["model"],
            "n_params": r.get("n_params"),
            "seconds": r.get("seconds"),
            "cpu_seconds": r.get("cpu_seconds"),
            "val_rmse": r.get("val_rmse"),
            "ratio_to_affine": r.get("ratio_to_affine"),
            "eligible": r.get("eligible"),
        }
        for r in cmp.table
    ]
    print(f"{'model':<28} {'params':>6} {'wall s':>8} {'CPU s':>8} {'val rmse':>10} {'/affine':>8}")
    for r in rows:
        print(
            f"{r['model']:<28} {r['n_params'] or 0:>6} {r['seconds'] or 0:>8.1f} "
            f"{r['cpu_seconds'] or 0:>8.1f} {r['val_rmse'] or 0:>10.5f} "
            f"{r['ratio_to_affine'] or 0:>8.3f}"
        )
    print(f"winner: {cmp.winner_name}; total {total:.1f} s (final fit included)")
    if args.out is not None:
        result = {
            "before": args.before,
            "resample": args.resample,
            "total_seconds": total,
            "rows": rows,
        }
        args.out.write_text(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
