"""The compensator node's achieved rate and cycle times at 100, 250 and 500 Hz (issue 20).

One process: the compensator node (an InverseFeedforward, the library's lightest saved
compensator) fed by a reference node at the same rate over DDS (Fast DDS, localhost), each
rate for DURATION seconds. Period = time between two cycles (the timer's jitter); compute =
one cycle's work (inputs, the compensator's step, the command and diagnostics published).
The machine is shared: its load average is recorded with the figures.
Writes benchmarks/results/ros2_rate.json. Needs the ros2 extra.
"""

from __future__ import annotations

import os
import platform
import time

import numpy as np
from rclpy.executors import SingleThreadedExecutor

import tendonsheath as ts
from _common import write_results
from tendonsheath.ros2 import _env, compensator_node, reference_node, sine

RATES = (100.0, 250.0, 500.0)
DURATION = 4.0  # s per rate


def percentiles(x: np.ndarray) -> dict[str, float]:
    return {
        "p50_ms": float(np.percentile(x, 50) * 1e3),
        "p95_ms": float(np.percentile(x, 95) * 1e3),
        "p99_ms": float(np.percentile(x, 99) * 1e3),
        "max_ms": float(np.max(x) * 1e3),
    }


def one_rate(rate: float, domain: int) -> dict:
    context = _env.init(domain_id=domain)
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash())
    node = compensator_node(ff, context=context, parameters={"rate": rate})
    ref = reference_node(sine(0.3, 0.5), rate=rate, context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    executor.add_node(ref)
    node.trigger_configure()
    node.trigger_activate()
    load = os.getloadavg()
    end = time.monotonic() + DURATION
    while time.monotonic() < end:
        executor.spin_once(timeout_sec=0.01)
    timing = node.timing()
    context.shutdown()
    period = timing["period"][5:]  # past the start
    return {
        "rate_hz": rate,
        "achieved_hz": float(1.0 / np.mean(period)),
        "cycles": int(period.size),
        "period": percentiles(period),
        "compute": percentiles(timing["compute"][5:]),
        "load_average_1min": load[0],
    }


def main() -> None:
    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    rows = [one_rate(rate, 90 + i) for i, rate in enumerate(RATES)]
    for r in rows:
        print(
            f"{r['rate_hz']:5.0f} Hz: achieved {r['achieved_hz']:6.1f} Hz, period p50 "
            f"{r['period']['p50_ms']:.2f} p95 {r['period']['p95_ms']:.2f} p99 "
            f"{r['period']['p99_ms']:.2f} max {r['period']['max_ms']:.2f} ms; compute p50 "
            f"{r['compute']['p50_ms']:.3f} p99 {r['compute']['p99_ms']:.3f} ms "
            f"(load {r['load_average_1min']:.1f})"
        )
    write_results(
        "ros2_rate",
        {
            "what": "compensator node (InverseFeedforward) and a reference node in one "
            "process over Fast DDS on localhost, one single-threaded executor",
            "duration_s": DURATION,
            "cpus": os.cpu_count(),
            "machine": platform.machine(),
            "rates": rows,
        },
    )


if __name__ == "__main__":
    main()
