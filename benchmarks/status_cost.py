"""What always reporting each sample's Status flags costs a batch run (issue 26 item 7).

    python benchmarks/status_cost.py [--samples 200000] [--repeat 5]

Since every ``model.simulate`` and ``ff.command`` returns a SimulationResult whose ``status``
holds each sample's flags, the C++ batch loops are always asked for them (one uint8 buffer of n
bytes, written once per sample). This times, per sample (best of --repeat, wall clock, CPU
time), the C++ engine call without flags and with them, and the public call (flags, the result
object and its success check), for a few models and one inverse feedforward.

Writes benchmarks/results/status_cost.json.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import tendonsheath as ts
from _common import best_time, write_results


def _cases():
    """(name, engine call without flags, engine call with them, the public call)."""
    bl = ts.models.BoucWenBacklash(B_r=0.05, B_l=0.04)
    pi = ts.models.PrandtlIshlinskii(thresholds=[0.0, 0.1, 0.2, 0.3], weights=[1, 0.5, 0.3, 0.2])
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash(B_r=0.05, B_l=0.05), smoothing=0.01)
    cases = []
    for name, model in (("Backlash", ts.models.Backlash()), ("BoucWenBacklash", bl),
                        ("PrandtlIshlinskii", pi)):  # fmt: skip
        eng = getattr(ts._core, name)(model)  # the bare C++ class: a copy of the model
        cases.append((f"{name}.simulate", lambda t, x, e=eng: e.simulate(t, x, False),
                      lambda t, x, e=eng: e.simulate(t, x, True),
                      lambda t, x, m=model: m.simulate(t, x)))  # fmt: skip
    eng = ts._core.ModelInverse(ff)  # the bare C++ class: a copy of the compensator
    cases.append(("InverseFeedforward(Backlash).command",
                  lambda t, y, e=eng: e.command(t, y, None, None, None, False),
                  lambda t, y, e=eng: e.command(t, y, None, None, None, True),
                  lambda t, y: ff.command(t, y)))  # fmt: skip
    return cases


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--samples", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    t = np.arange(args.samples) * 1e-3
    x = 0.8 * np.sin(2 * np.pi * 0.5 * t)
    rows = []
    print(f"{'call':40s} {'no flags':>10s} {'flags':>10s} {'public':>10s}  ns/sample (wall)")
    for name, plain, flagged, public in _cases():
        row = {"call": name}
        for key, fn in (("no_flags", plain), ("flags", flagged), ("public", public)):
            wall = best_time(lambda fn=fn: fn(t, x), args.repeat)
            cpu = best_time(lambda fn=fn: fn(t, x), args.repeat, time.process_time)
            row[f"{key}_ns_per_sample"] = 1e9 * wall / args.samples
            row[f"{key}_cpu_ns_per_sample"] = 1e9 * cpu / args.samples
        row["flags_overhead"] = row["flags_cpu_ns_per_sample"] / row["no_flags_cpu_ns_per_sample"]
        rows.append(row)
        ns = [row[f"{key}_ns_per_sample"] for key in ("no_flags", "flags", "public")]
        print(f"{name:40s} " + " ".join(f"{v:10.2f}" for v in ns))
    write_results("status_cost", {"samples": args.samples, "repeat": args.repeat, "rows": rows})


if __name__ == "__main__":
    main()
