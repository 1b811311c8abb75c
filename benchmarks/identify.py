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

``--oscillator`` runs the Step 9 done-when test instead (key "oscillator" of the same JSON,
the other keys kept): a Bouc-Wen hysteretic oscillator simulated by SciPy's DOP853 (at most
dt/20 per step) on the continuous input, driven by a 5-150 Hz random-phase multisine sampled
at 750 Hz (40 periods of 1024 samples: 40 960, the record length of issue 12 and of the
Bouc-Wen benchmark data), noise at 1e-3 of the output range; identified with band-limited
input reconstruction, validated (noise-free reference) on another multisine realisation and
on a 5-150 Hz sine sweep, for random parameter draws around the Bouc-Wen benchmark system
(softening draws, gamma + delta < 0, alternate with hardening ones) and random seeds.
Target: validation rmse within 2x of the generating parameters' rmse through the same
reconstruction, under 120 s of CPU per identification.

The generating rmse g is the discretisation error of the model's own integrator (~1e-7 m)
while the noise is ~4e-6 m, so the ratio is set by the parameter variance that the noise
leaves: "predicted" is the ratio expected at the Cramer-Rao bound of the record,
sqrt(1 + s^2 tr(Jv (J'J)^-1 Jv') / (Nv g^2)), with J, Jv the output Jacobians at the
generating parameters on the training and validation inputs. With 3 periods (3 072 samples)
it is 3.93 for draw 1 (measured 3.71; oscillator_case(..., periods=3)): no estimator gets
within 2x on such a short record. The search is not what fails there: for draw 0 (measured
2.01, expected 1.50) least squares started from the generating parameters ends at the same
estimate.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from pathlib import Path

import numpy as np
from _python_models import bouc_wen_backlash
from rich.console import Console
from rich.table import Table
from scipy.optimize import differential_evolution

import _common  # noqa: F401 (puts tests/ on sys.path for the reference oscillator)
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
    base = truth.params_struct()

    def compiled_objective(p):
        try:
            m = ts.models.BoucWenBacklash(**dict(zip(NAMES, p, strict=True)))
        except ValueError:
            return 1e100
        return float(np.sum((y - m.simulate(t, x)) ** 2))

    def python_objective(p):
        return float(np.sum((y - bouc_wen_backlash(x, *p)) ** 2))

    probe = [np.array([TRUTH[k] for k in NAMES])]
    prng = np.random.default_rng(0)
    while len(probe) < BASELINE_TIMED_EVALS:
        probe.append(np.array([prng.uniform(lo, hi) for lo, hi in bounds]))
    agree = float(np.max(np.abs(bouc_wen_backlash(x, *probe[0]) - truth.simulate(t, x))))
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
    if out.exists() and "oscillator" in (previous := json.loads(out.read_text())):
        results["oscillator"] = previous["oscillator"]  # written by --oscillator
    out.write_text(json.dumps(results, indent=2) + "\n")
    console.print(f"wrote {out}")


def oscillator_draw(i: int, seed: int = 100) -> dict:
    """Parameters of draw i: around the Bouc-Wen benchmark system; even draws softening
    (beta (gamma + delta) < 0), odd draws hardening."""
    from reference.oscillator import BENCHMARK

    rng = np.random.default_rng(seed + i)
    p = dict(BENCHMARK)
    p["m"] *= rng.uniform(0.7, 1.4)
    p["c"] *= rng.uniform(0.5, 2.0)
    p["k"] *= rng.uniform(0.5, 1.5)
    p["alpha"] *= rng.uniform(0.5, 1.5)
    p["gamma"] = rng.uniform(0.4, 1.2)
    total = -rng.uniform(0.1, 0.5) if i % 2 == 0 else rng.uniform(0.1, 0.8)
    p["delta"] = total - p["gamma"]
    return p


def oscillator_case(params: dict, seed: int, period: int = 1024, periods: int = 40) -> dict:
    """One draw: data from the DOP853 reference, identification, validation."""
    from reference.oscillator import Multisine, Sweep, simulate_reference

    fs, rms = 750.0, 50.0
    ms = Multisine(fs, period, 5.0, 150.0, rms, seed)
    t, x = ms.samples(periods)
    y = simulate_reference(params, ms, t)
    rng = np.random.default_rng(seed + 7)
    noise = 1e-3 * float(np.ptp(y))
    y_noisy = y + noise * rng.standard_normal(y.size)
    ms_v = Multisine(fs, period, 5.0, 150.0, rms, seed + 1000)
    tv, xv = ms_v.samples(2)
    yv = simulate_reference(params, ms_v, tv)
    sw = Sweep(fs, 2 * period, 5.0, 150.0, rms * math.sqrt(2.0) * 0.8)
    ts_, xs = sw.samples()
    ys = simulate_reference(params, sw, ts_)

    cpu0, wall0 = time.process_time(), time.perf_counter()
    fit = ts.identify(
        ts.models.HystereticOscillator,
        t,
        x,
        y_noisy,
        input_interpolation="bandlimited",
        seed=seed,
        progress=False,
    )
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    gen = ts.models.HystereticOscillator(**params, input_interpolation="bandlimited")

    def rmse(a, b):
        return float(np.sqrt(np.mean((a - b) ** 2)))

    out = {"params": params, "cpu_seconds": cpu, "wall_seconds": wall, "noise_std": noise}
    out["samples"] = int(t.size)
    for name, (tt, xx, yy) in {
        "multisine": (tv, xv, yv),
        "sweep": (ts_, xs, ys),
    }.items():
        g = rmse(gen.simulate(tt, xx), yy)
        f = rmse(fit.model.simulate(tt, xx), yy)
        out[name] = {"generating_rmse": g, "identified_rmse": f, "ratio": f / g}
        out[name]["predicted_ratio"] = predicted_ratio(gen, (t, x), (tt, xx), noise, g)
        noisy = yy + noise * rng.standard_normal(yy.size)
        out[name]["noisy_ratio"] = rmse(fit.model.simulate(tt, xx), noisy) / rmse(
            gen.simulate(tt, xx), noisy
        )
    p = fit.model.params
    out["identified"] = {
        "m": p["m"],
        "c": p["c"],
        "k": p["k"],
        "alpha": p["alpha"],
        "beta_gamma": p["beta"] * p["gamma"],
        "beta_delta": p["beta"] * p["delta"],
        "nu": p["nu"],
    }
    out["true_beta_gamma"] = params["beta"] * params["gamma"]
    out["true_beta_delta"] = params["beta"] * params["delta"]
    out["train_rmse"] = fit.rmse
    out["method"] = fit.method
    return out


def _output_jacobian(model, t, x) -> np.ndarray:
    """d y / d (m, c, k, alpha, gamma, delta, nu) by forward differences (beta held)."""
    base = model.simulate(t, x)
    p = model.params
    cols = []
    for name in ("m", "c", "k", "alpha", "gamma", "delta", "nu"):
        h = 1e-6 * (abs(p[name]) if name != "nu" else 1.0)
        cols.append((model.with_params(**{name: p[name] + h}).simulate(t, x) - base) / h)
    return np.column_stack(cols)


def predicted_ratio(model, train, valid, noise: float, g: float) -> float:
    """The validation ratio expected at the Cramer-Rao bound of the training record."""
    J = _output_jacobian(model, *train)
    Jv = _output_jacobian(model, *valid)
    cov = noise**2 * np.linalg.inv(J.T @ J)
    var = float(np.einsum("ij,jk,ik->", Jv, cov, Jv)) / Jv.shape[0]
    return math.sqrt(1.0 + var / g**2)


def oscillator_main(draws: int) -> None:
    console = Console()
    rows = []
    for i in range(draws):
        params = oscillator_draw(i)
        seed = int(np.random.default_rng(500 + i).integers(0, 2**31 - 1))  # random start
        console.print(f"draw {i}: {params}")
        rows.append(oscillator_case(params, seed))
    table = Table(title="identify HystereticOscillator: DOP853 reference, bandlimited input")
    for col in (
        "draw",
        "gamma+delta",
        "validation",
        "generating rmse",
        "identified rmse",
        "ratio",
        "predicted",
        "CPU s",
    ):
        table.add_column(col, justify="right")
    for i, r in enumerate(rows):
        gd = r["params"]["gamma"] + r["params"]["delta"]
        for name in ("multisine", "sweep"):
            v = r[name]
            table.add_row(
                str(i),
                f"{gd:+.2f}",
                name,
                f"{v['generating_rmse']:.3g}",
                f"{v['identified_rmse']:.3g}",
                f"{v['ratio']:.2f}",
                f"{v['predicted_ratio']:.2f}",
                f"{r['cpu_seconds']:.1f}",
            )
    console.print(table)
    worst = max(max(r["multisine"]["ratio"], r["sweep"]["ratio"]) for r in rows)
    cpu = max(r["cpu_seconds"] for r in rows)
    out = Path(__file__).resolve().parent / "results" / "identify.json"
    data = json.loads(out.read_text()) if out.exists() else {}
    data["oscillator"] = {
        "task": "HystereticOscillator from 40 periods x 1024 samples at 750 Hz of a DOP853 "
        "reference (5-150 Hz random-phase multisine, noise 1e-3 of the output range), "
        "bandlimited input reconstruction; validation on a new multisine and a 5-150 Hz "
        "sweep against the noise-free reference; predicted_ratio: expected at the Cramer-Rao "
        "bound of the training record",
        "cores": os.cpu_count(),
        "draws": rows,
        "worst_ratio": worst,  # against the noise-free reference
        "worst_noisy_ratio": max(
            max(r["multisine"]["noisy_ratio"], r["sweep"]["noisy_ratio"]) for r in rows
        ),
        "max_cpu_seconds": cpu,
        "targets": {"within_2x": worst <= 2.0, "under_120_s_cpu": cpu < 120.0},
    }
    out.write_text(json.dumps(data, indent=2) + "\n")
    console.print(f"worst ratio {worst:.2f}, max CPU {cpu:.1f} s; wrote {out}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--oscillator", action="store_true", help="the oscillator test")
    parser.add_argument("--draws", type=int, default=10, help="parameter draws (oscillator)")
    args = parser.parse_args()
    if args.oscillator:
        oscillator_main(args.draws)
    else:
        main()
