"""Python against the C++ loader (tendonsheath/io/json_multi_input.hpp) on LoadCompensated and
CoupledFeedforward files: the largest |C++ command - Python command| over random cases.

The cases are tests/test_cpp_multi_input_json.py's (random Loaded models over four bases,
settings and loads with dropouts; 2 or 3 coupled joints over the same bases, their own ranges or
the file's, desired angles with dropouts), over more seeds: each file saved by Python, run by
C++ example 12 over a 2 s, 1 kHz trajectory, and compared with Python's streamed commands. The
test asserts 1e-12; this reports the figure.

With --export the same cases go through `tendonsheath export --cpp` instead of the JSON loader:
each file's header, all of them built into one program with g++ -fno-exceptions
(tests/test_export_cpp_multi.py's run_exported, whose test asserts bit for bit).

    .venv/bin/python benchmarks/cpp_multi_input_json.py [--seeds 24] [--export]

(it builds example 12 into build/cpp with CMake first when it is not there).
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from _common import write_results

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
import test_cpp_multi_input_json as cases  # noqa: E402  (the test's random cases)
import test_export_cpp_multi as exported  # noqa: E402  (the exported headers' program)

EXAMPLE = ROOT / "build" / "cpp" / "examples" / "cpp" / "example_12_load_and_run"


def load_compensated_gap(k: int, tmp: Path) -> float:
    """max |C++ - Python| of LoadCompensated case k."""
    ff = cases._load_compensated(k)
    ff.to_json(tmp / "lc.json")
    rng = np.random.default_rng(80 + k)
    y_d = cases._desired(rng)
    t = cases.T
    load = 0.3 * np.sin(2 * np.pi * rng.uniform(0.2, 1.0) * t + 1.0) + rng.normal(0, 0.01, t.size)
    load[rng.integers(0, t.size, 5)] = np.nan
    cpp = cases._run(EXAMPLE, tmp / "lc.json", zip(t, y_d, load, strict=True), tmp)
    ff.reset()
    python = [ff.step(a, dt, b) for a, dt, b in zip(y_d, cases.DTS, load, strict=True)]
    return float(np.max(np.abs(cpp - np.array(python))))


def coupled_gap(k: int, tmp: Path) -> float:
    """max |C++ - Python| of CoupledFeedforward case k."""
    ff = cases._coupled(k)
    ff.to_json(tmp / "cf.json")
    rng = np.random.default_rng(90 + k)
    y_d = cases._desired(rng, ff.model.joints)
    y_d[rng.integers(0, cases.T.size, 4), rng.integers(0, ff.model.joints, 4)] = np.nan
    rows = (np.r_[t, y] for t, y in zip(cases.T, y_d, strict=True))
    cpp = cases._run(EXAMPLE, tmp / "cf.json", rows, tmp)
    ff.reset()
    python = np.array([ff.step(y, dt) for y, dt in zip(y_d, cases.DTS, strict=True)])
    return float(np.max(np.abs(cpp - python)))


def build_example() -> None:
    """Example 12 into build/cpp (Release, nlohmann/json needed), as `make test-cpp` builds it."""
    build = ROOT / "build" / "cpp"
    configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"]
    subprocess.run([*configure, "-DTENDONSHEATH_BUILD_EXAMPLES=ON"], check=True)
    target = ["--target", "example_12_load_and_run", "-j2"]
    subprocess.run(["cmake", "--build", str(build), *target], check=True)


def export_gaps(seeds: int) -> tuple[float, float]:
    """max |C++ - Python| of the exported headers of the seeds' cases (one program)."""
    items = {f"lc{k}": cases._load_compensated(k) for k in range(seeds)}
    items.update({f"cf{k}": cases._coupled(k) for k in range(seeds)})
    cxx = shutil.which("c++") or shutil.which("g++")
    if cxx is None:
        raise SystemExit("--export needs a C++ compiler")
    with tempfile.TemporaryDirectory() as d:
        python, cpp, _ = exported.run_exported(items, Path(d), cxx)
    gaps = {ns: float(np.max(np.abs(cpp[ns] - python[ns]))) for ns in python}
    lc = max(v for ns, v in gaps.items() if ns.startswith("lc"))
    return lc, max(v for ns, v in gaps.items() if ns.startswith("cf"))


def main() -> None:
    """Run the cases and write benchmarks/results/cpp_multi_input_json.json (with --export:
    cpp_multi_input_export.json)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=24)
    parser.add_argument("--export", action="store_true", help="the exported headers instead")
    args = parser.parse_args()
    seeds = args.seeds
    if args.export:
        lc, cf = export_gaps(seeds)
        print(f"exported headers, {seeds} cases each, 2000 cycles: max |C++ - Python| "
              f"LoadCompensated {lc:.3g}, CoupledFeedforward {cf:.3g}")  # fmt: skip
        result = {"seeds": seeds, "cycles": int(cases.T.size), "load_compensated": lc}
        write_results("cpp_multi_input_export", {**result, "coupled": cf})
        return
    if not EXAMPLE.is_file():
        build_example()
    with tempfile.TemporaryDirectory() as d:
        lc = max(load_compensated_gap(k, Path(d)) for k in range(seeds))
        cf = max(coupled_gap(k, Path(d)) for k in range(seeds))
    print(f"{seeds} cases each, 2000 cycles: max |C++ - Python| LoadCompensated {lc:.3g}, "
          f"CoupledFeedforward {cf:.3g}")  # fmt: skip
    write_results(
        "cpp_multi_input_json",
        {"seeds": seeds, "cycles": int(cases.T.size), "load_compensated": lc, "coupled": cf},
    )


if __name__ == "__main__":
    main()
