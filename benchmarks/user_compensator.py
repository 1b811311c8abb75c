"""Cost per cycle of a user's own compensator on the bench: compiled (examples/cpp/
user_compensator, run in bench.run's C++ loop through a function table) against the same
compensator in Python (examples/09, one Python step call per cycle), the shipped
InverseFeedforward and the uncompensated loop, on the same plant and reference.

    python benchmarks/user_compensator.py [--seconds 20]

Needs the example module that `make install` builds into build/<wheel tag>/. Times are process
CPU time (best of 3 runs, so a busy machine inflates them less than wall time). The C++ and
Python PIFeedforward give the same outputs, so the plant does the same work in both runs and
their difference is the cost of stepping the compensator from Python. Writes
benchmarks/results/user_compensator.json.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.machinery
import importlib.util
import os
import sys
import time
from pathlib import Path

import numpy as np

import tendonsheath as ts
from _common import best_time, write_results

ROOT = Path(__file__).resolve().parent.parent


def _modules():
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    found = sorted(ROOT.glob(f"build/*/examples/cpp/user_compensator/user_compensators{suffix}"))
    if not found:
        sys.exit("the example module is missing: run `make install` first")
    sys.path.insert(0, str(found[-1].parent))
    cpp = importlib.import_module("user_compensators")
    spec = importlib.util.spec_from_file_location("ex09", ROOT / "examples/09_user_compensator.py")
    ex09 = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex09)
    return cpp, ex09


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=200.0)
    args = parser.parse_args()
    cpp, ex09 = _modules()
    plant = ts.PullPullPlant(
        ts.Route.uniform(1.2, 3.0),
        friction=0.1,
        stiffness=5e3,
        pretension=20.0,
        proximal_radius=0.015,
        distal_radius=0.015,
        elements=10,
        motor=ts.Motor.position(60.0, 0.8),
    )
    t = np.arange(0.0, args.seconds, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.5 * t)
    model = ts.models.BoucWenBacklash(B_r=0.05, B_l=0.05)
    controllers = {
        "none": None,
        "InverseFeedforward (shipped, C++ loop)": ts.compensate.InverseFeedforward(model),
        "PIFeedforward in C++ (function table)": cpp.PIFeedforward(kp=0.8, ki=6.0),
        "PIFeedforward in Python (step per cycle)": ex09.PIFeedforward(kp=0.8, ki=6.0),
    }
    cpu = {
        k: best_time(lambda c=c: ts.bench.run(plant, c, t, y_d), clock=time.process_time)
        for k, c in controllers.items()
    }
    n = t.size
    rows = {k: 1e6 * v / n for k, v in cpu.items()}
    keys = list(controllers)
    python_cost = rows[keys[3]] - rows[keys[2]]
    load = os.getloadavg()
    print(f"{n} cycles, plant N = 10 per sheath; load average {load[0]:.2f} (CPU time, best of 3)")
    for k, us in rows.items():
        print(f"  {k:44s} {us:8.3f} us/cycle")
    print(f"  stepping PIFeedforward from Python costs {python_cost:.3f} us/cycle more than in C++")
    write_results(
        "user_compensator",
        {"cycles": n, "load_average": load[0], "us_per_cycle": rows, "python_cost_us": python_cost},
    )


if __name__ == "__main__":
    main()
