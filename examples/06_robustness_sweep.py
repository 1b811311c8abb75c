"""How robust is a compensator? A Monte Carlo sweep over friction, pretension and route.

.venv/bin/python examples/06_robustness_sweep.py --out example-out [--scheduler tcp://HOST:8786]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import tendonsheath as ts
from tendonsheath.sweep import LatinHypercube, Relative, Seed, Uniform
from tendonsheath.sweep.example_runs import compensator_study


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("example-out"))
    ap.add_argument("--n", type=int, default=100)
    ap.add_argument("--scheduler", default=None, help="a Dask scheduler (default: local cores)")
    args = ap.parse_args(argv)

    design = LatinHypercube(
        {
            "friction": Relative(0.1, 0.3),  # +/- 30 % around what the compensators assume
            "pretension": Relative(10.0, 0.3),
            "route_angle": Uniform(1.57, 4.71),
            "route_pieces": 3,  # random arcs, split differently in every run
            "route_seed": Seed(),
            "elements": 40,
        }
    )
    res = ts.sweep(compensator_study, design, n=args.n, seed=1, engine=args.scheduler or "local")
    print(res.table.head())
    summary = res.summary(bound={"mse": 1e-4})
    print(summary[summary["metric"] == "mse"].to_string(index=False))
    print(res.sensitivity(metrics="mse").to_string(index=False))
    for path in res.save(args.out / "sweep", bound={"mse": 1e-4}):
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
