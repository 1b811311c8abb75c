"""Per-step latency of each compensator in C++ (median and 99.9th percentile over 1e6 steps).

    python benchmarks/compensators.py [--steps 1000000]

Builds benchmarks/cpp with CMake (Release) into build/bench, runs it, prints a table and
writes benchmarks/results/compensators.json. Targets: feedforwards and the encoder loop < 100 ns
per step, adaptive controller < 500 ns (a 10 kHz loop spends under 1 % of its budget); the
inverses that search a root each cycle (GPI, a chain with a polynomial) < 10 us (1 % of a 1 kHz
loop).
"""

from __future__ import annotations

import argparse
import json
import subprocess
from pathlib import Path

from _common import write_results

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build" / "bench"


def build() -> Path:
    subprocess.run(
        [
            "cmake",
            "-S",
            str(ROOT),
            "-B",
            str(BUILD),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DTENDONSHEATH_BUILD_BENCHMARKS=ON",
        ],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    subprocess.run(
        ["cmake", "--build", str(BUILD), "--target", "bench_compensators"],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    return BUILD / "benchmarks" / "cpp" / "bench_compensators"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1_000_000)
    args = parser.parse_args()
    exe = build()
    out = subprocess.run([str(exe), str(args.steps)], check=True, capture_output=True, text=True)
    result = json.loads(out.stdout)
    print(f"{'compensator':58s} {'median':>9s} {'p99.9':>9s} {'target':>9s}")
    for row in result["rows"]:
        target = 500.0 if row["name"].startswith("Adaptive") else 100.0
        target = 10_000.0 if "root search" in row["name"] else target
        row["target_ns"] = target
        flag = "" if row["median_ns"] < target else "  (above target)"
        print(
            f"{row['name']:58s} {row['median_ns']:7.1f}ns {row['p999_ns']:7.1f}ns "
            f"{target:7.0f}ns{flag}"
        )
    path = write_results("compensators", result)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
