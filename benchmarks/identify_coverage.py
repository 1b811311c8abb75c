"""Coverage of the standard errors of ts.identify: linearised vs moving-block bootstrap.

Self-class study: every record is simulated by the very class that is fitted (known truth),
so this checks the uncertainty machinery, not how well a model describes a tendon-sheath
mechanism. For each case and each of DRAWS seeded draws: the true parameters are jittered
(uniform, +-10 %, seeded), 1500 samples of a decaying two-tone input are simulated, noise
is added (``white``: Gaussian, sd 0.005; ``ar1``: AR(1) with coefficient 0.9 and the same
marginal sd, i.e. coloured noise that a white-noise linearisation ignores), and the model is
identified twice from the same data: ``standard_errors="linearised"`` and
``standard_errors="bootstrap"`` (RESAMPLES moving-block resamples, seeded). For each
identified scalar z = (estimate - truth) / se; the coverage is the fraction with |z| < 1
(nominal 68.3 %) and |z| < 1.96 (nominal 95 %), pooled over the scalars of all draws
(scalars with no standard error, e.g. a weight at an active constraint in the linearised
case, are counted apart in ``missing``; a threshold grid counts once, by its scale). Draws
whose fit rmse exceeds 1.05 times the noise's rms (the global search stopped in another
basin) are listed in ``not_converged`` and kept in the figures.

    .venv/bin/python benchmarks/identify_coverage.py [--draws 50] [--resamples 100]
        [--cases BoucWenBacklash/white,BoucWenBacklash/ar1,Chain/white,GPI/white]

Prints a table and writes benchmarks/results/identify_coverage.json. The committed results:
``--draws 50 --resamples 100 --cases BoucWenBacklash/white,BoucWenBacklash/ar1,Chain/white``
(identify_coverage.json, about 10 min on 2 shared cores) and ``--draws 10 --resamples 25
--cases GPI/white --out identify_coverage_gpi`` (a GPI bootstrap re-fit costs about 1 s: its
bounded linear solve runs in every residual evaluation).
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np
from rich.console import Console
from rich.table import Table

import tendonsheath as ts
from _common import write_results
from tendonsheath.models import (
    BoucWenBacklash,
    Chain,
    GeneralizedPrandtlIshlinskii,
    Polynomial,
)

NOISE_SD = 0.005
AR1 = 0.9
T = np.arange(0.0, 6.0, 4e-3)
X = np.sin(2 * np.pi * 0.5 * T) * (1 - 0.4 * T / T[-1]) + 0.25 * np.sin(2 * np.pi * 1.3 * T)


def _jitter(rng, value, rel=0.1):
    return float(value) * (1.0 + rel * rng.uniform(-1.0, 1.0))


def bouc_wen_backlash(rng):
    base = dict(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.08, rho=12.0, sigma=1.2, n=4.0)
    truth = BoucWenBacklash(**{k: _jitter(rng, v) for k, v in base.items()})
    return truth, BoucWenBacklash, {}


def chain(rng):
    first = BoucWenBacklash(
        c_r=1.0,
        c_l=_jitter(rng, 0.9),
        B_r=_jitter(rng, 0.12),
        B_l=_jitter(rng, 0.08),
        rho=_jitter(rng, 12.0),
        sigma=_jitter(rng, 1.2),
        n=_jitter(rng, 3.0),
    )
    poly = Polynomial(coefficients=[_jitter(rng, 0.9), _jitter(rng, -0.4)], odd=True)
    return Chain(first, poly), Chain(BoucWenBacklash(), Polynomial(3, odd=True)), {"maxiter": 40}


GPI_PLAYS = 6


def gpi(rng):
    """A GPI inside the identified class: thresholds = r_frac * (half the envelopes' span
    over the input range) * k/(K-1), as the identification parameterises them."""
    rising = (1.0, _jitter(rng, 1.3), _jitter(rng, 0.05), 0.0)
    falling = (_jitter(rng, 1.2), _jitter(rng, 1.0), _jitter(rng, -0.1), _jitter(rng, 0.05))
    lo, hi = X.min(), X.max()
    up = np.tanh(rising[1] * (hi - rising[2]))
    down = falling[0] * np.tanh(falling[1] * (lo - falling[2])) + falling[3]
    r_max = _jitter(rng, 0.6) * 0.5 * (up - down)
    pattern = np.arange(GPI_PLAYS) / (GPI_PLAYS - 1)
    weights = [_jitter(rng, w) for w in (0.5, 0.3, 0.25, 0.2, 0.15, 0.1)]
    truth = GeneralizedPrandtlIshlinskii(rising, falling, r_max * pattern, weights)
    initial = GeneralizedPrandtlIshlinskii(thresholds=pattern, weights=np.ones(GPI_PLAYS))
    return truth, GeneralizedPrandtlIshlinskii, {"initial": initial}


MODELS = {"BoucWenBacklash": bouc_wen_backlash, "Chain": chain, "GPI": gpi}


def noise(kind: str, rng, n: int) -> np.ndarray:
    e = rng.standard_normal(n)
    if kind == "white":
        return NOISE_SD * e
    if kind == "ar1":
        out = np.empty(n)
        out[0] = e[0]
        scale = np.sqrt(1.0 - AR1**2)
        for k in range(1, n):
            out[k] = AR1 * out[k - 1] + scale * e[k]
        return NOISE_SD * out
    raise ValueError(f"unknown noise {kind!r}")


def z_scores(fit, truth) -> tuple[list[float], int]:
    z, missing = [], 0
    params, true = fit.model.params, truth.params
    for name, se in fit.standard_errors.items():
        got = np.atleast_1d(params[name]).astype(float)
        want = np.atleast_1d(true[name]).astype(float)
        se = np.atleast_1d(se).astype(float)
        if name == "thresholds":  # one identified scale: counted once
            got, want, se = got[-1:], want[-1:], se[-1:]
        for g, w, s in zip(got, want, se, strict=True):
            if g == w == 0.0:  # a structural zero (the first threshold)
                continue
            if not (np.isfinite(s) and s > 0):
                missing += 1
                continue
            z.append(abs(g - w) / s)
    return z, missing


def run_case(model: str, kind: str, draws: int, resamples: int) -> dict:
    z_lin, z_boot, miss_lin, miss_boot, secs_lin, secs_boot = [], [], 0, 0, 0.0, 0.0
    not_converged = []
    for d in range(draws):
        rng = np.random.default_rng(1000 + d)
        truth, cls, kwargs = MODELS[model](rng)
        y = truth.simulate(T, X) + noise(kind, rng, T.size)
        common = dict(seed=d, progress=False, **kwargs)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
            start = time.perf_counter()
            lin = ts.identify(cls, T, X, y, **common)
            secs_lin += time.perf_counter() - start
            start = time.perf_counter()
            boot = ts.identify(
                cls, T, X, y, standard_errors="bootstrap", bootstrap=resamples, **common
            )
            secs_boot += time.perf_counter() - start
        if lin.rmse > 1.05 * np.std(y - truth.simulate(T, X)):  # stopped in another basin
            not_converged.append({"draw": d, "rmse": lin.rmse})
        z, m = z_scores(lin, truth)
        z_lin += z
        miss_lin += m
        z, m = z_scores(boot, truth)
        z_boot += z
        miss_boot += m

    def cov(z):
        z = np.asarray(z)
        return {
            "within_1se": float(np.mean(z < 1.0)),
            "within_1.96se": float(np.mean(z < 1.96)),
            "median_abs_z": float(np.median(z)),
            "scalars": int(z.size),
        }

    return {
        "model": model,
        "noise": kind,
        "draws": draws,
        "resamples": resamples,
        "not_converged": not_converged,
        "linearised": {**cov(z_lin), "missing": miss_lin, "seconds_per_fit": secs_lin / draws},
        "bootstrap": {**cov(z_boot), "missing": miss_boot, "seconds_per_fit": secs_boot / draws},
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--draws", type=int, default=50)
    ap.add_argument("--resamples", type=int, default=100)
    ap.add_argument(
        "--cases", default="BoucWenBacklash/white,BoucWenBacklash/ar1,Chain/white,GPI/white"
    )
    ap.add_argument("--out", default="identify_coverage")
    args = ap.parse_args()
    console = Console()
    rows = []
    for case in args.cases.split(","):
        model, kind = case.split("/")
        start = time.perf_counter()
        rows.append(run_case(model, kind, args.draws, args.resamples))
        console.print(f"{case}: {time.perf_counter() - start:.0f} s")
    table = Table(title=f"standard-error coverage over {args.draws} draws (nominal 68.3 % / 95 %)")
    table.add_column("case", no_wrap=True)
    for col in ("method", "|z|<1", "|z|<1.96", "median |z|", "scalars", "missing", "s/fit"):
        table.add_column(col, justify="right")
    for r in rows:
        for method in ("linearised", "bootstrap"):
            c = r[method]
            table.add_row(
                f"{r['model']}/{r['noise']}",
                method,
                f"{100 * c['within_1se']:.1f} %",
                f"{100 * c['within_1.96se']:.1f} %",
                f"{c['median_abs_z']:.2f}",
                str(c["scalars"]),
                str(c["missing"]),
                f"{c['seconds_per_fit']:.2f}",
            )
    console.print(table)
    path = write_results(
        args.out,
        {
            "study": "self-class coverage of linearised and bootstrap standard errors",
            "noise_sd": NOISE_SD,
            "ar1": AR1,
            "samples": int(T.size),
            "cases": rows,
        },
    )
    console.print(f"wrote {path}")


if __name__ == "__main__":
    main()
