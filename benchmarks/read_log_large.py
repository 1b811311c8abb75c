"""read_log on a large CSV: peak memory and time. The file (time, motor, tip; about 45 bytes
a row) is written to a temporary folder, then read in a fresh process that reports its peak
resident memory (ru_maxrss) after the imports and after read_log, with wall and CPU time.
The columns alone are 3 x 8 bytes a row (plus 8 for the file row of every sample).

    .venv/bin/python benchmarks/read_log_large.py [--rows 10000000] [--python OTHER/python]

``--python`` reads with another installation's interpreter (e.g. an older tendonsheath) to
compare; the result is printed and written to benchmarks/results/read_log_large.json.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from _common import write_results

CHILD = """
import json, resource, sys, time
import tendonsheath as ts
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
w, c = time.perf_counter(), time.process_time()
log = ts.io.read_log(sys.argv[1], time="time", input="motor", output="tip")
wall, cpu = time.perf_counter() - w, time.process_time() - c
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"rows": len(log), "wall_s": wall, "cpu_s": cpu,
                  "rss_after_imports_mib": base / 1024, "peak_rss_mib": peak / 1024}))
"""


def write_file(path: Path, rows: int, chunk: int = 1_000_000) -> int:
    rng = np.random.default_rng(0)
    with open(path, "w") as f:
        f.write("time,motor,tip\n")
        for start in range(0, rows, chunk):
            k = np.arange(start, min(rows, start + chunk))
            t = k * 1e-3
            x = np.sin(2 * np.pi * 0.2 * t)
            y = 0.9 * x + 1e-3 * rng.standard_normal(k.size)
            np.savetxt(f, np.column_stack([t, x, y]), delimiter=",", fmt="%.10g")
    return path.stat().st_size


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=10_000_000)
    ap.add_argument("--python", default=sys.executable, help="The interpreter that reads.")
    ap.add_argument("--no-save", action="store_true", help="Print only; keep the JSON file.")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "large.csv"
        size = write_file(path, args.rows)
        out = subprocess.run(
            [args.python, "-c", CHILD, str(path)], capture_output=True, text=True, check=True
        )
    result = json.loads(out.stdout)
    result["file_mib"] = size / 2**20
    result["columns_mib"] = 3 * 8 * result["rows"] / 2**20
    result["read_peak_over_imports_mib"] = result["peak_rss_mib"] - result["rss_after_imports_mib"]
    result["load_average"] = os.getloadavg()
    for k, v in result.items():
        print(f"{k:>28}: {v:.1f}" if isinstance(v, float) else f"{k:>28}: {v}")
    if not args.no_save:
        print(f"wrote {write_results('read_log_large', result)}")


if __name__ == "__main__":
    main()
