"""Speed of the physics plant: 60 s at 1 kHz through a PullPullPlant for N = 25 ... 400 elements
per sheath, against a plain NumPy/SciPy implementation of the same algorithm (spec A.5) that
runs a shorter horizon and is scaled to 60 s; then the same with every realistic effect on
(``presets.realistic_plant`` and ``realistic_motor``: distal joint dynamics, viscous sheath
friction, tendon creep, an unequal pair, motor friction and gear backlash). Prints tables and
writes JSON.

    .venv/bin/python benchmarks/plant.py [--elements 25 50 100 200 400] [--numpy-seconds 2]
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np

import tendonsheath as ts
from tendonsheath._reference_plant import ReferencePullPull


def scenario(seconds: float, rate: float = 1000.0):
    t = np.arange(int(round(seconds * rate))) / rate
    # a 0.5 Hz sine of 0.5 rad plus a slower one: reversals of several sizes
    q = 0.5 * np.sin(2 * np.pi * 0.5 * t) + 0.1 * np.sin(2 * np.pi * 0.13 * t)
    return t, q


def best_of(fn, repeats):
    best = float("inf")
    out = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def slope(ns, times):
    """Exponent p of time ~ N^p (least squares in log-log)."""
    return float(np.polyfit(np.log(ns), np.log(times), 1)[0])


def realistic_rows(route, t, q, elements, repeats):
    """60 s through the plant with every realistic effect on (no NumPy reference exists)."""
    rows = []
    print(f"\nthe same with every realistic effect on ({t.size} steps)")
    print(f"{'N':>5} {'C++ (s)':>9} {'us/step':>8} {'unconverged':>12}")
    for n in elements:
        plant = ts.PullPullPlant(
            route=route,
            elements=n,
            motor=ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8),
            **ts.presets.realistic_plant(),
        )
        cpp, sim = best_of(lambda p=plant: p.simulate(t, q, full=True), repeats)
        rows.append(
            {
                "elements": n,
                "steps": int(t.size),
                "cpp_seconds": cpp,
                "cpp_us_per_step": cpp / t.size * 1e6,
                "nonconverged": sim.nonconverged,
            }
        )
        print(f"{n:>5} {cpp:>9.4f} {cpp / t.size * 1e6:>8.2f} {sim.nonconverged:>12d}")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, nargs="+", default=[25, 50, 100, 200, 400])
    ap.add_argument("--seconds", type=float, default=60.0, help="simulated horizon (s)")
    ap.add_argument("--numpy-seconds", type=float, default=2.0, help="NumPy horizon (s)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", type=Path, default=Path(__file__).parent / "results" / "plant.json")
    args = ap.parse_args(argv)

    route = ts.Route.uniform(1.2, 2 * np.pi)
    t, q = scenario(args.seconds)
    tn, qn = scenario(args.numpy_seconds)
    rows = []
    print(f"PullPullPlant, {args.seconds:g} s at 1 kHz ({t.size} steps), uniform route 2 pi")
    print(
        f"{'N':>5} {'C++ (s)':>9} {'us/step':>8} {'NumPy (s, scaled)':>18} {'speed-up':>9} "
        f"{'max |C++ - NumPy| (rad)':>24}"
    )
    for n in args.elements:
        plant = ts.PullPullPlant(route=route, elements=n)
        cpp, y = best_of(lambda p=plant: p.simulate(t, q), args.repeats)
        ref = ReferencePullPull(route, elements=n)
        t0 = time.perf_counter()
        y_ref = ref.simulate(qn)
        np_time = (time.perf_counter() - t0) * (t.size / tn.size)
        diff = float(np.abs(plant.simulate(tn, qn) - y_ref).max())
        rows.append(
            {
                "elements": n,
                "steps": int(t.size),
                "cpp_seconds": cpp,
                "cpp_us_per_step": cpp / t.size * 1e6,
                "numpy_seconds_scaled": np_time,
                "numpy_horizon_seconds": args.numpy_seconds,
                "speedup": np_time / cpp,
                "max_abs_difference_rad": diff,
            }
        )
        r = rows[-1]
        print(
            f"{n:>5} {cpp:>9.4f} {r['cpp_us_per_step']:>8.2f} {np_time:>18.1f} "
            f"{r['speedup']:>9.0f} {diff:>24.2e}"
        )
    ns = [r["elements"] for r in rows]
    p_cpp = slope(ns, [r["cpp_seconds"] for r in rows]) if len(ns) > 1 else float("nan")
    p_np = slope(ns, [r["numpy_seconds_scaled"] for r in rows]) if len(ns) > 1 else float("nan")
    print(f"growth with N: C++ ~ N^{p_cpp:.2f}, NumPy ~ N^{p_np:.2f}")
    target = next((r for r in rows if r["elements"] == 100), None)
    if target is not None:
        ok = target["cpp_seconds"] < 0.2
        print(
            f"target N=100, 60 s at 1 kHz < 0.2 s: {target['cpp_seconds']:.3f} s "
            f"({'met' if ok else 'NOT met'})"
        )
    realistic = realistic_rows(route, t, q, args.elements, args.repeats)
    target = next((r for r in realistic if r["elements"] == 100), None)
    if target is not None:
        ok = target["cpp_seconds"] < 0.2
        print(
            f"target N=100, 60 s at 1 kHz with all effects < 0.2 s: {target['cpp_seconds']:.3f} s "
            f"({'met' if ok else 'NOT met'})"
        )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(
        json.dumps(
            {
                "benchmark": "plant",
                "scenario": "PullPullPlant, 0.5 rad 0.5 Hz + 0.1 rad 0.13 Hz sine, 1 kHz",
                "route": "uniform, L = 1.2 m, Theta = 2 pi",
                "machine": platform.platform(),
                "python": platform.python_version(),
                "rows": rows,
                "growth_exponent_cpp": p_cpp,
                "growth_exponent_numpy": p_np,
                "realistic_rows": realistic,
                "realistic_preset": {
                    "plant": ts.presets.realistic_plant(),
                    "motor": ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8).params,
                },
            },
            indent=2,
        )
        + "\n"
    )
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
