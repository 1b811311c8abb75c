"""A fingerprint of every bench run of the three built-in scenarios: per run, the sha256 of its
output, measured, command, motor and status arrays, and its mse. Two builds whose fingerprints
match ran every closed loop bit for bit the same (how the one erased plant loop was checked
against the typed loop it replaced).

    python benchmarks/bench_fingerprint.py OUT.json [--scale 0.25]

Compare two files with ``diff``; run an older build with PYTHONPATH pointing at its package.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import time

import numpy as np

from tendonsheath.bench.scenarios import SCENARIOS

# the motor encoder is `q_motor` (`motor` in builds before the results took one name)
FIELDS = ("output", "measured", "command", ("q_motor", "motor"), "status")


def _field(res, name):
    if isinstance(name, tuple):  # the first name this build has
        return getattr(res, next(n for n in name if n in type(res).__dataclass_fields__))
    return getattr(res, name)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--scale", type=float, default=0.25)
    args = parser.parse_args()
    start, prints = time.perf_counter(), {}
    for name, run in SCENARIOS.items():
        for key, res in run(scale=args.scale, seed=0).runs.items():
            arrays = [np.ascontiguousarray(_field(res, f)) for f in FIELDS]
            digest = hashlib.sha256(b"".join(a.tobytes() for a in arrays)).hexdigest()
            prints[f"{name}/{key}"] = [digest, float(res.metrics["mse"])]
    with open(args.out, "w") as f:
        json.dump(prints, f, indent=1)
    print(f"{len(prints)} runs in {time.perf_counter() - start:.0f} s -> {args.out}")


if __name__ == "__main__":
    main()
