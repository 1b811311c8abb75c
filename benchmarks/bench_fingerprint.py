"""A fingerprint of every bench run of the three built-in scenarios, and of one short run per
controller path (each shipped compensator, each loop around one, a learned table, a Python
compensator, with and without a route schedule): per run, the sha256 of its output, measured,
command, motor and status arrays, and its mse. Two builds whose fingerprints match ran every
closed loop bit for bit the same (how the one erased plant loop, then the one controller
entry point, were checked against the typed loops they replaced).

    python benchmarks/bench_fingerprint.py OUT.json [--scale 0.25]

Compare two files with ``diff``; run an older build with PYTHONPATH pointing at its package.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import time

import numpy as np

import tendonsheath as ts
from tendonsheath.bench.scenarios import SCENARIOS

# the motor encoder is `q_motor` (`motor` in builds before the results took one name)
FIELDS = ("output", "measured", "command", ("q_motor", "motor"), "status")


def _has(res, name) -> bool:
    """Whether the result has the field (a dataclass's, or a SimulationResult's)."""
    fields = getattr(type(res), "__dataclass_fields__", None)
    return name in fields if fields is not None else name in res._info


def _field(res, name):
    if isinstance(name, tuple):  # the first name this build has
        return getattr(res, next(n for n in name if _has(res, n)))
    return getattr(res, name)


class _PythonFeedforward:
    """A compensator written in Python: the kinematic gain and a fixed offset."""

    def __init__(self, gain: float):
        self.gain = gain

    def reset(self) -> None:
        pass

    def step(self, y_d: float, dt: float) -> float:
        return self.gain * y_d + 0.01


def _path_runs() -> dict:
    """One short run per controller path of bench.run."""
    t = np.arange(0.0, 2.0, 1e-3)
    y_d = 0.4 * np.sin(2 * np.pi * 0.8 * t)
    route = ts.Route.uniform(1.0, np.pi)

    def bent(time: float):
        return ts.Route.uniform(1.0, np.pi if time < 1.0 else 1.5 * np.pi)

    def pair(**kw):
        return ts.PullPullPlant(route, elements=20, friction=0.1, **kw)

    servo = dict(motor=ts.Motor.position(bandwidth_hz=20.0), sensor=ts.Sensor(noise_std=1e-3))
    backlash = ts.models.Backlash(B_r=0.05, B_l=0.05)
    curve = ts.models.CurveAngleModel(friction=0.1, stiffness=2.4e4, length=1.0, pretension=10.0)
    cases = {
        "open": (pair(), None, {}),
        "inverse": (pair(**servo), ts.compensate.InverseFeedforward(backlash), {}),
        "inverse-routes": (pair(), ts.compensate.InverseFeedforward(curve), {"routes": bent}),
        "curve-angle": (
            pair(),
            ts.compensate.CurveAngleFeedforward(0.1, 2.4e4, 1.0, 10.0, curve_angle=np.pi),
            {"routes": bent},
        ),
        "encoder": (
            pair(**servo),
            ts.compensate.EncoderLoop(ts.compensate.InverseFeedforward(backlash), ki=20.0),
            {},
        ),
        "tip-scheduled": (
            pair(**servo),
            ts.compensate.TipLoop(
                ts.compensate.InverseFeedforward(backlash),
                ki=5.0,
                schedule=[(np.pi, 1.0), (1.5 * np.pi, 0.5)],
            ),
            {"routes": bent},
        ),
        "learned": (
            pair(),
            ts.compensate.LearnedFeedforward(
                ts.compensate.InverseFeedforward(backlash), 0.01 * np.sin(t[::10]), 1e-2
            ),
            {},
        ),
        "python": (pair(**servo), _PythonFeedforward(1.0), {"routes": bent}),
        "python-tip-scheduled": (
            pair(**servo),
            ts.compensate.TipLoop(
                _PythonFeedforward(1.0), ki=5.0, schedule=[(np.pi, 1.0), (1.5 * np.pi, 0.5)]
            ),
            {"routes": bent},
        ),
        "adaptive": (
            pair(motor=ts.Motor.torque(inertia=1e-3, viscous=0.01), sensor=ts.Sensor()),
            ts.compensate.AdaptiveController.from_model(backlash, inertia=1e-3, viscous=0.01),
            {},
        ),
        "continuum": (ts.ContinuumPlant(elements=20), ts.compensate.ContinuumFeedforward(), {}),
    }
    return {f"paths/{k}": ts.bench.run(p, c, t, y_d, **kw) for k, (p, c, kw) in cases.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--scale", type=float, default=0.25)
    args = parser.parse_args()
    start, prints = time.perf_counter(), {}
    runs = {
        f"{name}/{key}": res
        for name, run in SCENARIOS.items()
        for key, res in run(scale=args.scale, seed=0).runs.items()
    }
    for key, res in {**runs, **_path_runs()}.items():
        arrays = [np.ascontiguousarray(_field(res, f)) for f in FIELDS]
        digest = hashlib.sha256(b"".join(a.tobytes() for a in arrays)).hexdigest()
        prints[key] = [digest, float(res.metrics["mse"])]
    with open(args.out, "w") as f:
        json.dump(prints, f, indent=1)
    print(f"{len(prints)} runs in {time.perf_counter() - start:.0f} s -> {args.out}")


if __name__ == "__main__":
    main()
