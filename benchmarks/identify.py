"""Speed and accuracy of ts.identify against SciPy's differential evolution on a pure-Python
simulation of the same model.

Task: identify BoucWenBacklash from 20 s of data at 1 kHz (noisy), validate on a different
reference (other amplitude and frequency). Both sides use the same differential-evolution
settings (popsize, tol, maxiter, seed, Latin-hypercube start, bounds derived the same way).

- tendonsheath: every generation is one batched C++ call over all cores; the linear
  parameters (c_r, c_l, c_r B_r, c_l B_l) are solved by least squares, so the search covers
  (rho, sigma, n) only; least_squares refines the result.
- baseline: DE over all 7 parameters, one pure-Python simulation per evaluation, no
  refinement. Running it to the end would take tens of minutes, so its time is
  EXTRAPOLATED: the per-evaluation time of the pure-Python objective is measured on
  BASELINE_TIMED_EVALS evaluations, and multiplied by the number of evaluations the same DE
  run needs, obtained (with its validation error) by running that exact run with the
  compiled simulator as the objective. The pure-Python and compiled simulations agree to
  rounding (printed), so the run, the evaluation count and the error are the same.

Prints a table and writes benchmarks/results/identify.json.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import numpy as np
from rich.console import Console
from rich.table import Table
from scipy.optimize import differential_evolution

import tendonsheath as ts
from tendonsheath.identify import metrics
from tendonsheath.identify.data import make_recordings
from tendonsheath.identify.specs import BoucWenBacklashSpec, Scale

TRUTH = dict(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.10, rho=15.0, sigma=1.5, n=6.0)
NOISE = 0.003
SETTINGS = dict(popsize=15, tol=0.01, maxiter=100, seed=0)
BASELINE_TIMED_EVALS = int(os.environ.get("BASELINE_TIMED_EVALS", "6"))
NAMES = ("c_r", "c_l", "B_r", "B_l", "rho", "sigma", "n")


def reference(duration=20.0, rate=1000.0, amplitude=1.0, freq=0.25):
    t = np.arange(0.0, duration, 1.0 / rate)
    x = amplitude * np.sin(2 * np.pi * freq * t) * (1.0 - 0.5 * t / duration)
    x += 0.15 * amplitude * np.sin(2 * np.pi * 2.7 * freq * t)
    return t, x


def simulate_python(p, x, max_step=0.05, max_substeps=256):
    """Pure-Python BoucWenBacklash, the same numerics as the C++ core (RK4 in x)."""
    c_r, c_l, b_r, b_l, rho, sigma, n = p
    y = np.empty(len(x))
    w = 0.0
    x_prev = float(x[0])

    def f(w, s):
        a = abs(w)
        q = a ** (n - 1.0) if a > 0.0 else (1.0 if n == 1.0 else 0.0)
        return rho * (s - sigma * q * w + (sigma - 1.0) * s * q * a)

    def clamp(v):
        return 1.0 if v > 1.0 else (-1.0 if v < -1.0 else v)

    for k in range(len(x)):
        xk = float(x[k])
        if k > 0:
            dx = xk - x_prev
            if dx != 0.0:
                travel = abs(dx)
                m = math.ceil(rho * travel / max_step)
                m = 1 if not m >= 1 else min(m, max_substeps)
                h = travel / m
                s = 1.0 if dx > 0 else -1.0
                for _ in range(m):
                    k1 = f(w, s)
                    k2 = f(clamp(w + 0.5 * h * k1), s)
                    k3 = f(clamp(w + 0.5 * h * k2), s)
                    k4 = f(clamp(w + h * k3), s)
                    w = clamp(w + h * (k1 + 2 * k2 + 2 * k3 + k4) / 6.0)
            x_prev = xk
        phi = 0.5 * (1.0 + w)
        y[k] = phi * c_r * (xk - b_r) + (1.0 - phi) * c_l * (xk + b_l)
    return y


def main() -> None:
    console = Console()
    truth = ts.models.BoucWenBacklash(**TRUTH)
    rng = np.random.default_rng(2024)
    t, x = reference()
    y = truth.simulate(t, x) + NOISE * rng.standard_normal(t.size)
    tv, xv = reference(amplitude=0.7, freq=0.4)
    yv = truth.simulate(tv, xv) + NOISE * rng.standard_normal(tv.size)

    # -- tendonsheath -----------------------------------------------------------------
    start = time.perf_counter()
    fit = ts.identify(ts.models.BoucWenBacklash, t, x, y, progress=False, **SETTINGS)
    ours_seconds = time.perf_counter() - start
    ours_val = fit.validate(tv, xv, yv)

    # -- baseline: same DE settings, all 7 parameters, one simulation per evaluation --------
    spec = BoucWenBacklashSpec()
    b = spec.bounds(Scale.of(make_recordings(t, x, y)), {})
    bounds = [b[k] for k in NAMES]
    base = truth._engine.params

    def compiled_objective(p):
        try:
            m = ts.models.BoucWenBacklash(**dict(zip(NAMES, p, strict=True)))
        except ValueError:
            return 1e100
        return float(np.sum((y - m.simulate(t, x)) ** 2))

    def python_objective(p):
        return float(np.sum((y - simulate_python(p, x)) ** 2))

    probe = [np.array([TRUTH[k] for k in NAMES])]
    prng = np.random.default_rng(0)
    while len(probe) < BASELINE_TIMED_EVALS:
        probe.append(np.array([prng.uniform(lo, hi) for lo, hi in bounds]))
    agree = float(np.max(np.abs(simulate_python(probe[0], x) - truth.simulate(t, x))))
    start = time.perf_counter()
    for p in probe:
        python_objective(p)
    per_eval_python = (time.perf_counter() - start) / len(probe)

    start = time.perf_counter()
    base_res = differential_evolution(
        compiled_objective, bounds, polish=False, init="latinhypercube", **SETTINGS
    )
    compiled_run_seconds = time.perf_counter() - start
    base_model = ts.models.BoucWenBacklash(**dict(zip(NAMES, base_res.x, strict=True)))
    base_val = metrics(yv, base_model.simulate(tv, xv))
    base_seconds = per_eval_python * base_res.nfev
    del base

    speedup = base_seconds / ours_seconds
    results = {
        "task": "BoucWenBacklash from 20 s at 1 kHz, noise std 0.003; validation on another "
        "reference (amplitude 0.7, 0.4 Hz)",
        "settings": SETTINGS,
        "cores": os.cpu_count(),
        "tendonsheath": {
            "seconds": ours_seconds,
            "evaluations": fit.evaluations,
            "generations": fit.generations,
            "train_rmse": fit.rmse,
            "validation_rmse": ours_val["rmse"],
            "validation_nrmse": ours_val["nrmse"],
            "params": fit.model.params,
        },
        "baseline": {
            "seconds_extrapolated": base_seconds,
            "seconds_per_evaluation_python": per_eval_python,
            "evaluations": int(base_res.nfev),
            "timed_python_evaluations": len(probe),
            "compiled_replay_seconds": compiled_run_seconds,
            "validation_rmse": base_val["rmse"],
            "validation_nrmse": base_val["nrmse"],
            "python_vs_compiled_max_abs_difference": agree,
            "params": base_model.params,
        },
        "speedup": speedup,
        "targets": {
            "under_5_s": ours_seconds < 5.0,
            "validation_error_equal_or_better": ours_val["rmse"] <= base_val["rmse"] * 1.0001,
            "at_least_50x": speedup >= 50.0,
        },
    }
    table = Table(title="identify BoucWenBacklash: 20 s at 1 kHz")
    table.add_column("")
    table.add_column("tendonsheath", justify="right")
    table.add_column("SciPy DE + pure Python", justify="right")
    table.add_row("time (s)", f"{ours_seconds:.2f}", f"{base_seconds:.0f} (extrapolated)")
    table.add_row("evaluations", str(fit.evaluations), str(base_res.nfev))
    table.add_row("validation rmse", f"{ours_val['rmse']:.5f}", f"{base_val['rmse']:.5f}")
    table.add_row(
        "validation nrmse", f"{100 * ours_val['nrmse']:.3f} %", f"{100 * base_val['nrmse']:.3f} %"
    )
    console.print(table)
    console.print(
        f"speed-up {speedup:.0f}x. Baseline time = {per_eval_python * 1e3:.1f} ms per pure-Python "
        f"evaluation (timed on {len(probe)}) x {base_res.nfev} evaluations of the same DE run, "
        f"replayed with the compiled simulator in {compiled_run_seconds:.1f} s "
        f"(pure Python vs compiled max |difference| {agree:.1e})."
    )
    out = Path(__file__).resolve().parent / "results" / "identify.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(results, indent=2) + "\n")
    console.print(f"wrote {out}")


if __name__ == "__main__":
    main()
