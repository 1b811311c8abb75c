"""Choosing a model from few runs: which rule picks a winner that holds on runs it never saw.

    python benchmarks/choice_few_runs.py [--scenarios 8]

Real data, read as a user would (every column the log has for the drive): the shared da Vinci
tool 5 (its first session, 25 runs at 0.1-0.3 Hz and ten loads, jaw torque as the load; see
``_tool5``) and the nhoyh bending joint's ten configurations (tension_1 as the load). For each
of ``--scenarios`` random pairs of training runs per source (seeded):

- ``ts.compare_models(train)`` with every default: leave-one-run-out cross-validation, two
  folds; its rows hold each candidate's held-out error on each fold;
- ``ts.compare_models(train, validate=unseen)``: every candidate fitted on both runs and
  scored on every other run of the source (the runs no rule saw).

Each rule picks a winner from the first call's rows alone (among the eligible candidates:
never worse than the affine map on a held-out fold); its error on the unseen runs over the
affine map's, per run, is then read from the second call. The rules:

- ``pooled``: the lowest pooled held-out error (compare_models' rule before issue 35);
- ``worst_fold``: the lowest worst-fold ratio to the affine map;
- ``one_se``: Breiman's one-standard-error rule on the folds' ratios to the affine map (the
  fewest parameters within one standard error of the lowest mean ratio);
- ``mean_ratio``: the lowest mean ratio to the affine map over the folds.

Figures per rule: over the scenarios, the median of the scenario medians (unseen runs), the
worst scenario median, the worst run, and the scenarios whose winner is worse than the affine
map on its median unseen run. Writes benchmarks/results/choice_few_runs.json.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

import numpy as np
from _tool5 import DEFAULT as TOOL5
from _tool5 import read_all, sessions

import tendonsheath as ts
from _common import write_results
from tendonsheath.apps.compare import AFFINE

NHOYH = TOOL5.parent / "nhoyh_vio_com"
CONFIGS = tuple(range(0, 271, 30))


def nhoyh_logs(data: Path) -> dict[str, ts.io.Log]:
    return {
        f"config_{c:03d}deg": ts.io.read_log(
            data / f"config_{c:03d}deg.csv",
            time="t",
            input="input",
            output="output",
            degrees=True,
            load="tension_1",
        )  # fmt: skip
        for c in CONFIGS
    }


def _eligible(rows):
    return [r for r in rows if not r.get("error") and r.get("eligible")]


def _fold_ratios(r, base):
    return np.asarray(r["val_rmse_parts"], float) / np.asarray(base["val_rmse_parts"], float)


def pick(rows: list[dict], rule: str) -> str:
    """The winner's name under ``rule`` (see the module's doc)."""
    base = next(r for r in rows if r["model"] == AFFINE)
    ok = _eligible(rows)
    q = {r["model"]: _fold_ratios(r, base) for r in ok}
    if rule == "pooled":
        return min(ok, key=lambda r: r["val_nrmse"])["model"]
    if rule == "worst_fold":
        return min(ok, key=lambda r: (float(np.max(q[r["model"]])), r["val_nrmse"]))["model"]
    if rule == "mean_ratio":
        return min(ok, key=lambda r: float(np.mean(q[r["model"]])))["model"]
    best = min(ok, key=lambda r: float(np.mean(q[r["model"]])))
    qb = q[best["model"]]
    limit = float(np.mean(qb) + np.std(qb, ddof=1) / np.sqrt(qb.size))
    within = [r for r in ok if float(np.mean(q[r["model"]])) <= limit]
    return min(within, key=lambda r: (r["n_params"], float(np.mean(q[r["model"]]))))["model"]


RULES = ("pooled", "worst_fold", "one_se", "mean_ratio")


def scenario(logs: dict, names: list[str], rng) -> dict:
    train_names = sorted(rng.choice(names, size=2, replace=False).tolist())
    unseen = [n for n in names if n not in train_names]
    train = [logs[n] for n in train_names]
    cv = ts.compare_models(train)
    held = ts.compare_models(train, validate=[logs[n] for n in unseen])
    hrows = {r["model"]: r for r in held.table}
    base = np.asarray(hrows[AFFINE]["val_rmse_parts"], float)
    out = {"train": train_names, "picks": {}}
    for rule in RULES:
        name = pick(cv.table, rule)
        ratios = np.asarray(hrows[name]["val_rmse_parts"], float) / base
        out["picks"][rule] = {
            "model": name,
            "unseen_median": float(np.median(ratios)),
            "unseen_worst": float(np.max(ratios)),
        }
    return out


def summarise(found: list[dict]) -> dict:
    out = {}
    for rule in RULES:
        med = [s["picks"][rule]["unseen_median"] for s in found]
        worst = [s["picks"][rule]["unseen_worst"] for s in found]
        out[rule] = {
            "median": float(np.median(med)),
            "worst_scenario_median": float(np.max(med)),
            "worst_run": float(np.max(worst)),
            "scenarios_worse_than_affine": int(np.sum(np.asarray(med) > 1.0)),
        }
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenarios", type=int, default=8)
    args = ap.parse_args()
    if not (TOOL5 / "f0.10Hz_load010.csv").exists():
        print(f"no data at {TOOL5}: results/choice_few_runs.json kept as it is")
        return 0
    warnings.simplefilter("ignore")
    tool5 = read_all(TOOL5)
    sources = {"tool5_session1": (tool5, sessions(tool5)[0]),
               "nhoyh_configurations": (nhoyh_logs(NHOYH), None)}  # fmt: skip
    results = {}
    for source, (logs, names) in sources.items():
        names = list(logs) if names is None else names
        rng = np.random.default_rng(0)
        found = []
        for i in range(args.scenarios):
            found.append(scenario(logs, names, rng))
            print(source, i, {k: (v["model"], round(v["unseen_median"], 3))
                              for k, v in found[-1]["picks"].items()})  # fmt: skip
        results[source] = {"summary": summarise(found), "scenarios": found}
        print(source, results[source]["summary"])
    path = write_results("choice_few_runs", {"rules": list(RULES), "sources": results})
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
