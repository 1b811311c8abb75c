"""Helpers shared by the benchmark scripts: timing and the JSON results folder."""

from __future__ import annotations

import platform
import sys
import time
from pathlib import Path

from tendonsheath._util.atomic import write_json

RESULTS = Path(__file__).resolve().parent / "results"
# the independent references (tests/reference/) that some benchmarks time or fit against
TESTS = Path(__file__).resolve().parents[1] / "tests"
if str(TESTS) not in sys.path:
    sys.path.append(str(TESTS))


def best_time(fn, repeat: int = 3, clock=time.perf_counter) -> float:
    """Best time of `repeat` calls (seconds) on `clock`: wall clock by default,
    ``time.process_time`` for CPU time."""
    best = float("inf")
    for _ in range(repeat):
        start = clock()
        fn()
        best = min(best, clock() - start)
    return best


def write_results(name: str, payload: dict) -> Path:
    RESULTS.mkdir(exist_ok=True)
    payload = {"machine": platform.machine(), "python": platform.python_version(), **payload}
    path = RESULTS / f"{name}.json"
    return write_json(path, payload)  # atomic: an interrupted benchmark leaves the old file
