"""Cost per cycle of bench.run's one loop on each kind of plant: a shipped plant (its C++ engine
through the plant function table), a compiled user plant (examples/cpp/user_plant, through the
same table), and the same plants written in Python (one step call per cycle, stepped from C++).

    python benchmarks/plant_loop.py [--seconds 20] [--shipped-only]

``--shipped-only`` times the shipped plants alone (with the uncompensated and the shipped
InverseFeedforward loops): run it against an older build (PYTHONPATH) to compare the typed loop
it had with the table. Needs the example module that `make install` builds into
build/<wheel tag>/. Times are process CPU time (best of 3 runs). Writes
benchmarks/results/plant_loop.json (not with --shipped-only).
"""

from __future__ import annotations

import argparse
import importlib
import importlib.machinery
import os
import sys
import time
from pathlib import Path

import numpy as np

import tendonsheath as ts
from _common import best_time, write_results

ROOT = Path(__file__).resolve().parent.parent


class PythonPlay:
    """A play of half-width h written in Python (the twin of the compiled PlayPlant)."""

    kinematic_gain = 1.0

    def __init__(self, h=0.05):
        self.h = h
        self.reset()

    params = property(lambda self: {"half_width": self.h})

    def reset(self):
        self.y = 0.0

    def step(self, command, dt=0.0):
        self.y = min(max(self.y, command - self.h), command + self.h)
        return self.y

    def simulate(self, t, command):
        twin = PythonPlay(self.h)
        return ts.SimulationResult(np.array([twin.step(c) for c in command]), t=t)


class Wrapped:
    """A shipped plant built without a motor, stepped from Python, its motor beside it."""

    def __init__(self, inner, motor):
        self.inner, self.motor = inner, motor
        self.kinematic_gain = inner.kinematic_gain

    params = property(lambda self: self.inner.params)

    def reset(self):
        self.inner.reset()

    def step(self, command, dt=0.0):
        return self.inner.step(command, dt)

    def simulate(self, t, command):
        return self.inner.simulate(t, command)

    def output(self):
        return self.inner.output()


def _pair(elements, motor):
    return ts.PullPullPlant(
        ts.Route.uniform(1.2, 3.0),
        friction=0.1,
        stiffness=5e3,
        pretension=20.0,
        proximal_radius=0.015,
        distal_radius=0.015,
        elements=elements,
        motor=motor,
    )


def _plants(shipped_only: bool) -> dict:
    servo = ts.Motor.position(60.0, 0.8)
    plants = {f"PullPullPlant N={n} (C++ engine)": _pair(n, servo) for n in (10, 100)}
    if shipped_only:
        return plants
    plants["PullPullPlant N=10 wrapped in Python"] = Wrapped(_pair(10, None), servo)
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    found = sorted(ROOT.glob(f"build/*/examples/cpp/user_plant/user_plants{suffix}"))
    if not found:
        sys.exit("the example module is missing: run `make install` first")
    sys.path.insert(0, str(found[-1].parent))
    plants["PlayPlant compiled (function table)"] = importlib.import_module(
        "user_plants"
    ).PlayPlant()
    plants["PlayPlant in Python (step per cycle)"] = PythonPlay()
    return plants


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--shipped-only", action="store_true")
    args = parser.parse_args()
    t = np.arange(0.0, args.seconds, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.5 * t)
    ff = ts.compensate.InverseFeedforward(ts.models.BoucWenBacklash(B_r=0.05, B_l=0.05))
    rows = {}
    for name, plant in _plants(args.shipped_only).items():
        for label, controller in (("none", None), ("InverseFeedforward", ff)):
            run = lambda p=plant, c=controller: ts.bench.run(p, c, t, y_d)  # noqa: E731
            rows[f"{name}, {label}"] = 1e6 * best_time(run, clock=time.process_time) / t.size
    load = os.getloadavg()
    print(f"{t.size} cycles; load average {load[0]:.2f} (CPU time, best of 3)")
    for k, us in rows.items():
        print(f"  {k:60s} {us:8.3f} us/cycle")
    if not args.shipped_only:
        write_results(
            "plant_loop", {"cycles": int(t.size), "load_average": load[0], "us_per_cycle": rows}
        )


if __name__ == "__main__":
    main()
