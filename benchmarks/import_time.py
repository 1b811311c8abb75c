"""How long ``import tendonsheath`` takes in a fresh interpreter (issue 37, item 5).

    python benchmarks/import_time.py [--runs 5] [--top 12]

Each run starts a new interpreter (the one running this script, with its environment) that
times ``import tendonsheath`` alone (``time.perf_counter`` around the import: the interpreter's
own start is not counted). The bytecode cache is allowed (an installed package has its ``.pyc``
files): one unmeasured import first writes it where it can. The figure is the median of
--runs (wall clock; the CPU time and the machine's load average beside it, since other work
on a shared machine slows the wall clock); the target is < 0.3 s on a 2-core CI machine.
Scipy's submodules (signal, stats, optimize, ...), matplotlib and pandas are imported where a
feature uses them, never by the import itself (tests/test_import_weight.py checks which
modules it loads).

One more run under ``python -X importtime`` lists the slowest imports (cumulative time, the
top-level packages, and the package's own modules by their own time) to show where the rest
goes.

Writes benchmarks/results/import_time.json.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys

from _common import write_results

TARGET_S = 0.3  # issue 37: `import tendonsheath` < 0.3 s on the CI machine (median of 5)
_TIMED = (
    "import time\n"
    "start, cpu = time.perf_counter(), time.process_time()\n"
    "import tendonsheath\n"
    "print(time.perf_counter() - start, time.process_time() - cpu)\n"
)


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # time the import as installed: with its .pyc
    return env


def _python(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, *args], env=_env(), capture_output=True, text=True, check=True
    )


def import_seconds(runs: int) -> list[tuple[float, float]]:
    """``import tendonsheath``'s (wall, CPU) time (s) in each of ``runs`` fresh interpreters."""
    _python("-c", "import tendonsheath")  # writes the bytecode cache, unmeasured
    timed = [_python("-c", _TIMED).stdout.split()[-2:] for _ in range(runs)]
    return [(float(wall), float(cpu)) for wall, cpu in timed]


def import_profile() -> list[tuple[str, float, float]]:
    """(module, own time s, cumulative time s) of every import, from ``-X importtime``."""
    rows = []
    for line in _python("-X", "importtime", "-c", "import tendonsheath").stderr.splitlines():
        fields = line.removeprefix("import time:").split("|")
        if len(fields) != 3 or not fields[0].strip().isdigit():
            continue  # the header line
        rows.append((fields[2].strip(), int(fields[0]) * 1e-6, int(fields[1]) * 1e-6))
    return rows


def _by_package(rows: list[tuple[str, float, float]]) -> dict[str, float]:
    """Own import time (s) summed per top-level package, largest first."""
    total: dict[str, float] = {}
    for name, own, _ in rows:
        top = name.split(".")[0]
        total[top] = total.get(top, 0.0) + own
    return dict(sorted(total.items(), key=lambda kv: -kv[1]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--top", type=int, default=12)
    args = parser.parse_args()
    load = os.getloadavg()[0]  # a shared machine's other work slows the wall clock
    timed = import_seconds(args.runs)
    seconds, cpu = [w for w, _ in timed], [c for _, c in timed]
    median = statistics.median(seconds)
    rows = import_profile()
    packages = _by_package(rows)
    own = sorted((r for r in rows if r[0].startswith("tendonsheath")), key=lambda r: -r[1])
    print(f"import tendonsheath: median {median:.3f} s of {args.runs} fresh interpreters")
    print("  runs: " + ", ".join(f"{s:.3f}" for s in seconds) + f"  (target < {TARGET_S} s)")
    print(f"  CPU time median {statistics.median(cpu):.3f} s; load average {load:.2f}")
    print("own import time by top-level package (-X importtime, one run):")
    for name, s in list(packages.items())[: args.top]:
        print(f"  {name:32s} {1e3 * s:8.1f} ms")
    print("the package's slowest modules (own time):")
    for name, s, _ in own[: args.top]:
        print(f"  {name:48s} {1e3 * s:8.1f} ms")
    heavy = sorted(n for n, _, _ in rows if n.split(".")[0] in ("scipy", "matplotlib", "pandas"))
    write_results(
        "import_time",
        {
            "cpus": os.cpu_count(),
            "runs": args.runs,
            "median_s": median,
            "seconds": seconds,
            "cpu_median_s": statistics.median(cpu),
            "cpu_seconds": cpu,
            "load_average_1min": load,
            "target_s": TARGET_S,
            "packages_ms": {k: round(1e3 * v, 2) for k, v in list(packages.items())[: args.top]},
            "slowest_own_ms": {n: round(1e3 * s, 2) for n, s, _ in own[: args.top]},
            "heavy_modules_loaded": heavy,
        },
    )


if __name__ == "__main__":
    main()
