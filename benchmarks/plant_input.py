"""Input reconstruction between samples for the realistic pull-pull plant: simulation error
of "hold", "linear" and "bandlimited" against a reference, and their cost.

The plant: ``ts.presets.realistic_plant()`` (distal inertia and damping, sheath viscosity,
creep, unequal tendons) on a 1 m semicircle, 20 elements, pretension 30 N (no slack at these
rates). The input: a sum of 12 sines of random frequency in [0.5, 20] Hz and phase, 0.1 rad
rms-ish, sampled at 100 Hz (band 0.2 fs), 400 samples. The reference: the same plant stepped
256 times finer with the exact continuous input. The error is the rmse over samples 20..380
(away from the windowed sinc's held ends) over the reference's range.

    .venv/bin/python benchmarks/plant_input.py [--seeds 5]

Prints a table and writes benchmarks/results/plant_input.json.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from rich.console import Console
from rich.table import Table

import tendonsheath as ts
from _common import write_results
from tendonsheath.plant.presets import realistic_plant

FS, N, REF = 100.0, 400, 256
MODES = ("hold", "linear", "bandlimited")
SUBSTEPS = (8, 32)


def make_plant():
    kw = realistic_plant()
    kw.pop("route", None)
    kw.update(elements=20, pretension=30.0)
    return ts.PullPullPlant(route=ts.Route.uniform(1.0, np.pi), **kw)


def signal(seed: int, count: int = 12):
    rng = np.random.default_rng(seed)
    f = rng.uniform(0.5, 0.2 * FS, count)
    ph = rng.uniform(0, 2 * np.pi, count)
    return lambda s: 0.1 * np.sin(2 * np.pi * np.outer(s, f) + ph).sum(axis=1) / np.sqrt(count)


def run(seeds: int) -> dict:
    plant = make_plant()
    t = np.arange(N) / FS
    tf = np.arange(N * REF) / (FS * REF)
    errors = {f"{m}/{s}": [] for m in MODES for s in SUBSTEPS}
    cpu = {k: 0.0 for k in errors}
    for seed in range(seeds):
        u = signal(seed)
        ref = plant.simulate(tf, u(tf))[::REF]
        x = u(t)
        for mode in MODES:
            for sub in SUBSTEPS:
                plant.set_input_interpolation(mode, substeps=sub)
                start = time.process_time()
                y = plant.simulate(t, x, periodic=False)
                cpu[f"{mode}/{sub}"] += time.process_time() - start
                e = (y - ref)[20:-20]
                errors[f"{mode}/{sub}"].append(float(np.sqrt(np.mean(e**2)) / np.ptp(ref)))
    return {
        k: {
            "median_rel_rmse": float(np.median(v)),
            "max_rel_rmse": float(np.max(v)),
            "cpu_s_per_simulate": cpu[k] / seeds,
        }
        for k, v in errors.items()
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=5)
    args = ap.parse_args()
    rows = run(args.seeds)
    table = Table(title=f"plant input reconstruction, {args.seeds} random inputs (rmse / range)")
    for col in ("reconstruction/sub-steps", "median", "max", "CPU s / simulate"):
        table.add_column(col, justify="right")
    for k, r in rows.items():
        table.add_row(
            k,
            f"{r['median_rel_rmse']:.2e}",
            f"{r['max_rel_rmse']:.2e}",
            f"{r['cpu_s_per_simulate']:.4f}",
        )
    Console().print(table)
    note = "'hold' ignores the sub-step count (the plant steps once per sample)"
    path = write_results(
        "plant_input",
        {
            "fs": FS,
            "samples": N,
            "reference_factor": REF,
            "seeds": args.seeds,
            "note": note,
            "results": rows,
        },
    )
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
