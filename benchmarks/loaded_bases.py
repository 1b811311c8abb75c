"""Loaded(base) for every hysteresis base, on a physics plant with a measured load.

    python benchmarks/loaded_bases.py [--seeds 5] [--bases Backlash BoucWen ...]

Data (outside every model class; tests/_loaded_plant.py): a pull-pull pair (capstan friction
along a bent sheath, compliant tendons, sheath viscosity, tendon creep, an unequal pair, a
dynamic distal joint) under eight distal loads, constant torques and torsional springs (the
load then varies with the output), the joint torque measured with noise, the output read by a
noisy encoder. Each seed draws another drive (friction, stiffness, pretension, bend) and other
inputs (two tones).

Training: four loads (constant -0.03, +0.02 and +0.05 N m and the spring 0.01 + 0.03 q); the
other four (constant 0 and +0.04 N m, two other springs) are predicted from their start.

Per base and seed: the held-out rmse (all held-out samples) of ``Loaded(base)`` identified
with the load, of the base identified without it, and of the affine map y = a x + b (least
squares on the training runs); the ratios loaded / base and loaded / affine, their median and
worst over the seeds; whether a (generalized) Prandtl-Ishlinskii base's weights are all >= 0.

Writes benchmarks/results/loaded_bases.json.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings

import numpy as np

import _common  # noqa: F401 (puts tests/ on sys.path for the loaded plant)
import tendonsheath as ts
from _common import write_results

#: the bases (each made by a function) and their identification options: the hysteretic
#: oscillator is a force-driven model whose staged path refuses a position input (its best
#: linear approximation is no mass-spring-damper), so its plain search is used
OPTIONS = {"HystereticOscillator": {"strategy": "search"}}
BASES = {
    "Backlash": lambda: ts.models.Backlash,
    "BoucWen": lambda: ts.models.BoucWen,
    "BoucWenBacklash": lambda: ts.models.BoucWenBacklash,
    "PrandtlIshlinskii": lambda: ts.models.PrandtlIshlinskii,
    "GeneralizedPrandtlIshlinskii": lambda: ts.models.GeneralizedPrandtlIshlinskii,
    "HystereticOscillator": lambda: ts.models.HystereticOscillator,
    "Chain(BoucWenBacklash, Polynomial(3))": lambda: ts.models.Chain(
        ts.models.BoucWenBacklash(), ts.models.Polynomial(3)
    ),
}


def weights_of(model) -> list[float] | None:
    """A (generalized) Prandtl-Ishlinskii base's weights, else None."""
    base = model.base if isinstance(model, ts.models.Loaded) else model
    base = base.inner if isinstance(base, ts.models.Scaled) else base
    w = base.params.get("weights")
    return None if w is None else [float(v) for v in w]


def held_out_rmse(runs, predict) -> float:
    from _loaded_plant import TRAIN  # tests/ (on sys.path through _common)

    err = [predict(g) - g.y for k, g in runs.items() if k not in TRAIN]
    return float(np.sqrt(np.mean(np.concatenate(err) ** 2)))


def one_seed(seed: int, bases: list[str]) -> dict:
    """Every base's figures for one drawn drive."""
    from _loaded_plant import TRAIN, loaded_runs  # tests/ (on sys.path through _common)

    runs = loaded_runs(seed)
    train = [runs[k] for k in TRAIN]
    plain = [(g.t, g.x, g.y) for g in train]
    a = np.column_stack(
        [np.concatenate([g.x for g in train]), np.ones(sum(g.x.size for g in train))]
    )
    coef = np.linalg.lstsq(a, np.concatenate([g.y for g in train]), rcond=None)[0]
    affine = held_out_rmse(runs, lambda g: coef[0] * g.x + coef[1])
    out = {"affine": affine, "bases": {}}
    for name in bases:
        cls = BASES[name]()
        start = time.perf_counter()
        kw = {"seed": 0, "progress": False, **OPTIONS.get(name, {})}
        fit = ts.identify(ts.models.Loaded(cls), recordings=train, **kw)
        seconds = time.perf_counter() - start
        alone = ts.identify(cls, recordings=plain, **kw).model
        loaded = held_out_rmse(runs, lambda g, m=fit.model: m.simulate(g.t, g.x, load=g.load))
        unloaded = held_out_rmse(runs, lambda g, m=alone: m.simulate(g.t, g.x))
        w = weights_of(fit.model)
        out["bases"][name] = {
            "loaded": loaded,
            "base": unloaded,
            "ratio_to_base": loaded / unloaded,
            "ratio_to_affine": loaded / affine,
            "weights_non_negative": None if w is None else bool(min(w) >= 0),
            "fit_seconds": seconds,
            "model": repr(fit.model),
        }
        print(
            f"  seed {seed} {name:38s} loaded {1e3 * loaded:6.2f} mrad, base {1e3 * unloaded:6.2f},"
            f" affine {1e3 * affine:6.2f}: /base {loaded / unloaded:5.2f}, /affine "
            f"{loaded / affine:5.2f} ({seconds:.1f} s)",
            flush=True,
        )
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--bases", nargs="+", choices=list(BASES), default=list(BASES))
    args = ap.parse_args()
    warnings.simplefilter("ignore")
    per_seed = [one_seed(s, args.bases) for s in range(args.seeds)]
    summary = {}
    print("\nheld-out rmse ratios over the seeds: median (worst)")
    for name in args.bases:
        rows = [p["bases"][name] for p in per_seed]
        entry = {}
        for fig in ("ratio_to_base", "ratio_to_affine"):
            vals = np.array([r[fig] for r in rows])
            entry[fig] = {"median": float(np.median(vals)), "worst": float(np.max(vals))}
        nonneg = [r["weights_non_negative"] for r in rows]
        entry["weights_non_negative"] = None if nonneg[0] is None else all(nonneg)
        entry["fit_seconds_median"] = float(np.median([r["fit_seconds"] for r in rows]))
        summary[name] = entry
        print(
            f"  {name:38s} loaded/base {entry['ratio_to_base']['median']:5.2f} "
            f"({entry['ratio_to_base']['worst']:5.2f})  loaded/affine "
            f"{entry['ratio_to_affine']['median']:5.2f} ({entry['ratio_to_affine']['worst']:5.2f})"
            f"  weights >= 0: {entry['weights_non_negative']}"
        )
    from _loaded_plant import TRAIN

    path = write_results(
        "loaded_bases",
        {
            "data": "tests/_loaded_plant.py: pull-pull pair with effects, 8 loads; train "
            + ", ".join(TRAIN),
            "seeds": args.seeds,
            "summary": summary,
            "per_seed": per_seed,
        },
    )
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
