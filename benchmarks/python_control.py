"""Cost of the python-control systems: CPU time per sample and memory per engine snapshot.

    python benchmarks/python_control.py [--samples 2000]

For each system: CPU seconds per sample of ``control.input_output_response`` on
``to_control(dt)`` next to ``simulate`` (the C++ loop), and the memory the system keeps per
sample (one snapshot each: Python-tracked bytes from tracemalloc in a second run, which miss
the engines' own heap vectors, e.g. a Prandtl-Ishlinskii's play states). Writes
benchmarks/results/python_control.json.
"""

from __future__ import annotations

import argparse
import os
import time
import tracemalloc

import control as ct
import numpy as np

import tendonsheath as ts
from _common import write_results

DT = 1e-3


def systems():
    m = ts.models
    ff = ts.compensate.InverseFeedforward(m.BoucWenBacklash(), smoothing=0.05)
    plant = m.Chain(m.Backlash(), m.FirstOrderLag(0.02))
    series = lambda: ct.interconnect(  # noqa: E731
        [ff.to_control(DT, name="ff"), plant.to_control(DT, name="plant")],
        inplist=["y_d"],
        outlist=["y"],
    )
    return {
        "Backlash": (m.Backlash().to_control, lambda t, x: m.Backlash().simulate(t, x)),
        "PrandtlIshlinskii (20 plays)": (
            m.PrandtlIshlinskii.uniform(0.3, 20).to_control,
            lambda t, x: m.PrandtlIshlinskii.uniform(0.3, 20).simulate(t, x),
        ),
        "Chain(BoucWenBacklash, FirstOrderLag)": (
            m.Chain(m.BoucWenBacklash(), m.FirstOrderLag(0.02)).to_control,
            lambda t, x: m.Chain(m.BoucWenBacklash(), m.FirstOrderLag(0.02)).simulate(t, x),
        ),
        "interconnect(InverseFeedforward, Chain)": (
            lambda dt: series(),
            lambda t, x: plant.simulate(t, ff.command(t, x)),
        ),
    }


def cpu(fn) -> float:
    start = time.process_time()
    fn()
    return time.process_time() - start


def measure(make, reference, t, x) -> dict:
    seconds = cpu(lambda: ct.input_output_response(make(DT), t, x))
    fast = cpu(lambda: reference(t, x))
    tracemalloc.start()
    kept = make(DT)
    ct.input_output_response(kept, t, x)
    python_bytes = tracemalloc.get_traced_memory()[0]
    tracemalloc.stop()
    return {
        "cpu_us_per_sample": 1e6 * seconds / t.size,
        "simulate_cpu_us_per_sample": 1e6 * fast / t.size,
        "python_bytes_per_sample": python_bytes / t.size,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=2000)
    args = parser.parse_args()
    t = np.arange(args.samples) * DT
    x = 0.5 * np.sin(2 * np.pi * 2.0 * t) + 0.1 * np.sin(2 * np.pi * 7.0 * t)
    rows = {name: measure(make, ref, t, x) for name, (make, ref) in systems().items()}
    for name, r in rows.items():
        print(
            f"{name:42s} {r['cpu_us_per_sample']:8.1f} us/sample CPU "
            f"(simulate {r['simulate_cpu_us_per_sample']:.3f}), "
            f"{r['python_bytes_per_sample']:6.0f} B/sample kept"
        )
    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    path = write_results(
        "python_control", {"samples": args.samples, "load_average": load, "systems": rows}
    )
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
