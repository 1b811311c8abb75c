"""Identification on a long record: 10^6 samples (about 17 minutes at 1 kHz) of a
BoucWenBacklash with noise, identified with the defaults (global search on windows of the
record, refinement on all of it). Prints wall and CPU time, peak memory, evaluations per second
and the fit, and writes JSON.

    .venv/bin/python benchmarks/identify_long.py [--samples 1000000]
"""

from __future__ import annotations

import argparse
import json
import platform
import resource
import time
from pathlib import Path

import numpy as np

import tendonsheath as ts


def record(n: int, seed: int = 0):
    """A slowly amplitude-modulated 0.2 Hz sine with a 0.73 Hz ripple: many nested loops."""
    t = np.arange(n) / 1000.0
    x = np.sin(2 * np.pi * 0.2 * t) * (0.6 + 0.4 * np.sin(2 * np.pi * 0.003 * t))
    x += 0.2 * np.sin(2 * np.pi * 0.73 * t)
    truth = ts.models.BoucWenBacklash(c_r=1.0, c_l=0.95, B_r=0.1, B_l=0.08, n=6)
    noise = 1e-3
    y = truth.simulate(t, x) + np.random.default_rng(seed).normal(0.0, noise, n)
    return t, x, y, truth, noise


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=1_000_000)
    ap.add_argument(
        "--out", type=Path, default=Path(__file__).parent / "results" / "identify_long.json"
    )
    args = ap.parse_args(argv)
    t, x, y, truth, noise = record(args.samples)
    rss_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    wall, cpu = time.perf_counter(), time.process_time()
    fit = ts.identify(ts.models.BoucWenBacklash, t, x, y, progress=False)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    errors = {k: fit.model.params[k] - v for k, v in truth.params.items()}
    out = {
        "benchmark": "identify_long",
        "samples": args.samples,
        "wall_seconds": wall,
        "cpu_seconds": cpu,
        "peak_memory_mib": peak,
        "memory_before_fit_mib": rss_before,
        "evaluations": fit.evaluations,
        "evaluations_per_second": fit.evaluations / wall,
        "rmse": fit.rmse,
        "noise_std": noise,
        "parameter_errors": errors,
        "method": fit.method,
        "machine": platform.platform(),
    }
    print(f"BoucWenBacklash, {args.samples} samples (noise std {noise:g})")
    print(f"  wall {wall:.1f} s, CPU {cpu:.1f} s (target: under 60 s on 2 cores)")
    print(f"  peak memory {peak:.0f} MiB ({rss_before:.0f} MiB before the fit: data and imports)")
    print(f"  {fit.evaluations} evaluations, {fit.evaluations / wall:.0f} per second")
    print(f"  rmse {fit.rmse:.4g} (noise {noise:g}); {fit.method}")
    print("  parameter errors: " + ", ".join(f"{k} {v:+.2e}" for k, v in errors.items()))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(out, indent=2) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
