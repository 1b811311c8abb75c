"""Samples per second of `simulate` for each hysteresis model, C++ core vs a plain Python loop.

    python benchmarks/models.py [--samples 1000000] [--python-samples 100000]

The Python loop implements the same algorithm (same RK4 sub-stepping); it runs a
shorter input and its rate is compared per sample. Writes benchmarks/results/models.json.
"""

from __future__ import annotations

import argparse

import numpy as np
from _python_models import bouc_wen_backlash

from _common import best_time, write_results
from tendonsheath import models


def py_backlash(x, c_r, c_l, B_r, B_l):
    y = np.empty_like(x)
    yk = 0.5 * (c_r * (x[0] - B_r) + c_l * (x[0] + B_l))
    xp = x[0]
    y[0] = yk
    for k in range(1, len(x)):
        xk = x[k]
        right, left = c_r * (xk - B_r), c_l * (xk + B_l)
        if xk > xp and right > yk:
            yk = right
        elif xk < xp and left < yk:
            yk = left
        xp = xk
        y[k] = yk
    return y


def py_prandtl_ishlinskii(x, thresholds, weights):
    z = [min(max(0.0, x[0] - r), x[0] + r) for r in thresholds]
    y = np.empty_like(x)
    for k in range(len(x)):
        acc = 0.0
        for i, r in enumerate(thresholds):
            z[i] = min(max(z[i], x[k] - r), x[k] + r)
            acc += weights[i] * z[i]
        y[k] = acc
    return y


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1_000_000)
    parser.add_argument("--python-samples", type=int, default=100_000)
    args = parser.parse_args()

    t = np.arange(args.samples) * 1e-3
    x = np.sin(2 * np.pi * 0.5 * t) * (1 + 0.3 * np.sin(2 * np.pi * 0.05 * t))
    xp = x[: args.python_samples]
    bwb_args = dict(c_r=1.0, c_l=0.95, B_r=0.12, B_l=0.10, rho=2 / 0.22, sigma=1.0, n=8.0)
    pi_r, pi_w = list(np.linspace(0, 0.35, 8)), [1.0] + [0.08] * 7
    cases = [
        (
            "Backlash",
            models.Backlash(1.0, 0.95, 0.12, 0.10),
            lambda: py_backlash(xp, 1.0, 0.95, 0.12, 0.10),
        ),
        (
            "BoucWenBacklash",
            models.BoucWenBacklash(**bwb_args),
            lambda: bouc_wen_backlash(xp, **bwb_args),
        ),
        (
            "PrandtlIshlinskii (8 plays)",
            models.PrandtlIshlinskii(pi_r, pi_w),
            lambda: py_prandtl_ishlinskii(xp, pi_r, pi_w),
        ),
        ("BoucWen", models.BoucWen(A=1, beta=2, gamma=1, n=1.5, alpha=0.3, k=1), None),
        (
            "HystereticOscillator",
            models.HystereticOscillator(m=1, c=0.5, k=2, alpha=3, beta=2, gamma=0.6, delta=0.4),
            None,
        ),
    ]
    rows = []
    print(f"{'model':30s} {'C++ samples/s':>15s} {'Python samples/s':>17s} {'speed-up':>9s}")
    for name, model, py in cases:
        sec = best_time(lambda m=model: m.simulate(t, x))
        rate = args.samples / sec
        py_rate = args.python_samples / best_time(py, repeat=1) if py else float("nan")
        speedup = rate / py_rate if py else float("nan")
        rows.append(
            {
                "model": name,
                "samples": args.samples,
                "cpp_samples_per_s": rate,
                "python_samples": args.python_samples,
                "python_samples_per_s": py_rate,
                "speedup": speedup,
            }
        )
        py_text = f"{py_rate:17.3e}" if py else f"{'-':>17s}"
        sp_text = f"{speedup:8.0f}x" if py else f"{'-':>9s}"
        print(f"{name:30s} {rate:15.3e} {py_text} {sp_text}")
    path = write_results(
        "models",
        {"rows": rows, "targets": {"speedup": 100, "Backlash": 2e7, "BoucWenBacklash": 2e7}},
    )
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
