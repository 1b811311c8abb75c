"""How robust is a compensator? A Monte Carlo sweep over friction, pretension and route.

.venv/bin/python examples/06_robustness_sweep.py --out example-out [--scheduler tcp://HOST:8786]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import tendonsheath as ts
from tendonsheath.bench.scenarios.do import robustness_run
from tendonsheath.sweep import LatinHypercube, Relative, Seed, Uniform


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("example-out"))
    ap.add_argument("--n", type=int, default=100)
    ap.add_argument("--scheduler", default=None, help="a Dask scheduler (default: local cores)")
    args = ap.parse_args(argv)

    design = LatinHypercube(
        {
            # +/- 30 % around the nominal plant the compensators were calibrated on
            "friction": Relative(0.1, 0.3),
            "pretension": Relative(20.0, 0.3),
            "route_angle": Uniform(1.57, 4.71),
            "route_pieces": 3,  # random arcs, split differently in every run
            "route_seed": Seed(),
        }
    )
    # the do2015 bench scenario: no compensation, InverseFeedforward and AdaptiveController,
    # calibrated once on the nominal plant, judged on each drawn plant
    res = ts.sweep(robustness_run, design, n=args.n, seed=1, engine=args.scheduler or "local")
    print(res.table.head())
    summary = res.summary(bound={"mse": 1e-4})
    print(summary[summary["metric"] == "mse"].to_string(index=False))
    print(res.sensitivity(metrics="mse").to_string(index=False))
    for path in res.save(args.out / "sweep", bound={"mse": 1e-4}):
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
