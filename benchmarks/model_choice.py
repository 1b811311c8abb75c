"""Model choice that never misleads, checked on unseen runs of two real tendon drives.

    python benchmarks/model_choice.py [--nhoyh ../shared/data/nhoyh_vio_com]
                                      [--tool5 ../shared/data/davinci_tool5] [--maxiter 100]

The data (not part of this repository: read from its folders at run time, never copied):
nhoyh / ViO-Com bending joint (commanded and measured angle, deg) and MRDLab's da Vinci tool 5
(motor in, jaw out, rad; ODbL/DbCL).

Each split selects a model by ``ts.compare_models`` cross-validated on its training runs only
(leave one run out, default candidates and settings, seed 0), once ranked by the held-out
error (``objective="prediction"``) and once by the inverse error (``"compensation"``). The
winner, fitted on all the training runs, then predicts runs it never saw, and so does the affine
map y = a x + b fitted on the same runs: ``compare_models(train, models=[winner],
validate=unseen)`` scores both on every unseen run (from its first input reversal on). A
winner is *misleading* when its error (forward, or the inverse's for "compensation") on any
unseen run exceeds the affine map's. The candidate that the pooled held-out error alone would
have picked (the rule before this check) is scored the same way, for comparison.

Splits (nhoyh files resampled to 50 Hz, as in realdata.py):

- amp60 -> amp50/70: train conf0_amp60 and conf0_amp60_run2, unseen conf0_amp50, conf0_amp70
- conf0 amp50/60 -> amp70: train conf0_amp50, conf0_amp60; unseen conf0_amp70 (a longer stroke)
- conf90 amp50/60 -> amp70: the same at configuration 90
- configs: train config_000/090/180/270deg, unseen config_030/060/120/150/210/240deg
- tool 5, three rotations: train two of f0.10Hz_load010, f0.30Hz_load050, f0.50Hz_load100;
  unseen the third

Writes benchmarks/results/model_choice.json.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import tendonsheath as ts  # noqa: E402
from _common import write_results  # noqa: E402
from tendonsheath._util import eligibility as eligibility  # noqa: E402

HERE = Path(__file__).resolve().parents[2] / "shared" / "data"
RATE = 50.0  # Hz, resampling of the confX_ampY files (realdata.py's)
TOOL5 = ("f0.10Hz_load010", "f0.30Hz_load050", "f0.50Hz_load100")


def nhoyh(data: Path, name: str) -> ts.io.Log:
    rate = None if name.startswith("config_") else RATE
    return ts.io.read_log(
        data / f"{name}.csv", time="t", input="input", output="output", resample=rate
    )


def tool5(data: Path, name: str) -> ts.io.Log:
    return ts.io.read_log(data / f"{name}.csv", time="t", input="motor", output="jaw")


def splits(nh: Path, t5: Path) -> list[tuple[str, list, list]]:
    out = []
    if (nh / "conf0_amp60.csv").is_file():

        def read(*names):
            return [nhoyh(nh, n) for n in names]

        cfg = [f"config_{c:03d}deg" for c in (0, 90, 180, 270)]
        unseen = [f"config_{c:03d}deg" for c in (30, 60, 120, 150, 210, 240)]
        out += [
            (
                "nhoyh amp60 -> amp50/70",
                read("conf0_amp60", "conf0_amp60_run2"),
                read("conf0_amp50", "conf0_amp70"),
            ),
            (
                "nhoyh conf0 amp50/60 -> amp70",
                read("conf0_amp50", "conf0_amp60"),
                read("conf0_amp70"),
            ),
            (
                "nhoyh conf90 amp50/60 -> amp70",
                read("conf90_amp50", "conf90_amp60"),
                read("conf90_amp70"),
            ),
            ("nhoyh configs 0/90/180/270 -> others", read(*cfg), read(*unseen)),
        ]
    if all((t5 / f"{n}.csv").is_file() for n in TOOL5):
        for k, held in enumerate(TOOL5):
            train = [tool5(t5, n) for j, n in enumerate(TOOL5) if j != k]
            out.append((f"tool5 -> {held}", train, [tool5(t5, held)]))
    return out


def unseen_score(train, unseen, name: str, maxiter: int) -> dict:
    """``name`` and the affine map fitted on ``train``, scored on every unseen run: the ratios
    of their forward and inverse errors per run."""
    if name == "affine":
        ones = [1.0] * len(unseen)
        return {"model": name, "forward_ratios": ones, "inverse_ratios": ones}
    cmp = ts.compare_models(train, models=[name], validate=unseen, refit=False, maxiter=maxiter)
    row, affine = cmp.row(name), cmp.row("affine")
    if row.get("error"):
        return {"model": name, "error": row["error"]}

    def ratios(key):
        parts = row.get(key) or [float("nan")] * len(unseen)
        return [float(c / a) for c, a in zip(parts, affine[key], strict=True)]

    return {
        "model": name,
        "forward_ratios": ratios("val_rmse_parts"),
        "inverse_ratios": ratios("inv_rmse_parts"),
        "forward_rmse": row["val_rmse_parts"],
        "affine_forward_rmse": affine["val_rmse_parts"],
    }


def old_pick(table: list[dict], objective: str) -> str:
    """The candidate the pooled held-out error alone would pick (no eligibility check)."""
    metric = "inv_nrmse" if objective == "compensation" else "val_nrmse"
    ok = [r for r in table if not r.get("error") and np.isfinite(r.get(metric, np.nan))]
    return min(ok, key=lambda r: r[metric])["model"]


def one_split(label: str, train, unseen, maxiter: int) -> dict:
    start = time.perf_counter()
    cmp = ts.compare_models(train, maxiter=maxiter)  # cross-validated on the training runs
    result = {"split": label, "train": [log.path for log in train]}
    result["unseen"] = [Path(log.path).name for log in unseen]
    scored: dict[str, dict] = {}
    for objective in eligibility.OBJECTIVES:
        rows = [dict(r) for r in cmp.table]
        eligibility.judge(rows, cmp.validation, objective, eligibility.RANGE_MARGIN)
        rows.sort(key=eligibility.sort_key(objective))
        winner, before = rows[0]["model"], old_pick(rows, objective)
        for name in {winner, before}:
            if name not in scored:
                scored[name] = unseen_score(train, unseen, name, maxiter)
        key = "inverse_ratios" if objective == "compensation" else "forward_ratios"
        w, b = scored[winner], scored[before]
        result[objective] = {
            "winner": winner,
            "winner_unseen_ratios": w.get(key),
            "winner_worse_than_affine_on_an_unseen_run": bool(
                w.get(key) is None or max(w[key]) > 1.0
            ),
            "pooled_error_pick": before,
            "pooled_error_pick_unseen_ratios": b.get(key),
            "pooled_error_pick_worse_than_affine_on_an_unseen_run": bool(
                b.get(key) is None or max(b[key]) > 1.0
            ),
            "excluded": {r["model"]: r["excluded"] for r in rows if r.get("excluded")},
        }
    result["cv_table"] = [
        {k: r.get(k) for k in ("model", "val_nrmse", "inv_nrmse", "val_rmse_parts")}
        for r in cmp.table
    ]
    result["seconds"] = time.perf_counter() - start
    return result


def _fmt(ratios) -> str:
    return "-" if ratios is None else ", ".join(f"{q:.2f}" for q in ratios)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nhoyh", type=Path, default=HERE / "nhoyh_vio_com")
    ap.add_argument("--tool5", type=Path, default=HERE / "davinci_tool5")
    ap.add_argument("--maxiter", type=int, default=100, help="generations of each search")
    args = ap.parse_args()
    warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
    todo = splits(args.nhoyh, args.tool5)
    if not todo:
        print("no data found: benchmarks/results/model_choice.json kept")
        return 0
    start = time.perf_counter()
    results = []
    for label, train, unseen in todo:
        r = one_split(label, train, unseen, args.maxiter)
        results.append(r)
        for objective in eligibility.OBJECTIVES:
            o = r[objective]
            print(
                f"{label} [{objective}]: winner {o['winner']} (unseen / affine: "
                f"{_fmt(o['winner_unseen_ratios'])}); the pooled error alone: "
                f"{o['pooled_error_pick']} ({_fmt(o['pooled_error_pick_unseen_ratios'])})",
                flush=True,
            )
    misleading = [
        (r["split"], o)
        for r in results
        for o in eligibility.OBJECTIVES
        if r[o]["winner_worse_than_affine_on_an_unseen_run"]
    ]
    before = [
        (r["split"], o)
        for r in results
        for o in eligibility.OBJECTIVES
        if r[o]["pooled_error_pick_worse_than_affine_on_an_unseen_run"]
    ]
    payload = {
        "rule": "a candidate whose held-out error exceeds the affine map's on any held-out run, "
        "or whose prediction leaves the outputs' range by more than 10 % of its span, cannot win",
        "splits": results,
        "winners_worse_than_affine_on_an_unseen_run": misleading,
        "pooled_error_picks_worse_than_affine_on_an_unseen_run": before,
        "seconds": time.perf_counter() - start,
    }
    path = write_results("model_choice", json.loads(json.dumps(payload, default=float)))
    print(f"winners worse than the affine map on an unseen run: {len(misleading)} "
          f"of {2 * len(results)} ({misleading}); with the pooled error alone: {len(before)} "
          f"({before})")  # fmt: skip
    print(f"wrote {path} ({payload['seconds']:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
