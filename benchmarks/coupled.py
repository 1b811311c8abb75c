"""Coupled joints: the coupling identified with its standard error, and tracking with the
coupled compensator, two independent single-joint ones, and none, on routes not used for
identification.

The plant: two realistic pull-pull drives (distal dynamics, sheath viscosity, creep, an unequal
pair: outside every model class), joint 1's cables over an idler on joint 0's axis (coupling
C[1,0] = 0.25), encoders with 2e-4 rad noise and 1e-4 rad steps on both joints.

* Identification: for each calibration seed, both joints excited at once by independent
  amplitude-modulated sines (frequencies drawn per seed, 20 s at 1 kHz), a Coupled model of two
  BoucWenBacklash joints by identify_coupled; reported: C[1,0] +/- its Newey-West SE, and how
  many SEs each coefficient lies from the truth.
* Compensation (calibration seed 0's models): coupled = CoupledFeedforward of that model;
  independent = an InverseFeedforward per joint, each joint's BoucWenBacklash identified from
  its own calibration run with the other joint at rest (the best case for single-joint
  models); none = the desired angles as commands. Each test route is three random sines per
  joint (0.1 to 0.6 Hz, peak 0.4 to 0.9 rad), 15 s; figures: RMS tracking error of each joint
  after the first second, median and max (the worst) over the route seeds, and the factor
  (other RMS / coupled RMS) per route seed, median and min.

    .venv/bin/python benchmarks/coupled.py [--seeds 5]
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

import numpy as np

import tendonsheath as ts
from _common import write_results
from tendonsheath.identify import identify_coupled

C10 = 0.25
RIG = dict(pretension=20.0, proximal_radius=15e-3, distal_radius=15e-3, elements=40)
ROUTES = (
    ts.Route.arcs([(0.5, 0.0), (0.5, math.pi / 2)]),
    ts.Route.arcs([(0.4, 0.0), (0.6, 3 * math.pi / 4)]),
)
DT, WARMUP = 1e-3, 2000


def wrist(seed: int) -> ts.CoupledPlant:
    plants = [
        ts.PullPullPlant(r, **RIG, **ts.presets.realistic_plant(friction=0.1, stiffness=5e3))
        for r in ROUTES
    ]
    sensors = [ts.Sensor(resolution=1e-4, noise_std=2e-4, seed=seed + k) for k in range(2)]
    return ts.CoupledPlant(plants, [[0.0, 0.0], [C10, 0.0]], sensors=sensors)


def calibration(seed: int, duration: float = 20.0):
    """Independent amplitude-modulated sines on the two joints, frequencies drawn by seed."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration, DT)
    f0, f1 = rng.uniform(0.15, 0.35), rng.uniform(0.35, 0.65)
    env = np.pi * t / duration
    x = np.column_stack(
        [
            1.1 * np.sin(2 * np.pi * f0 * t) * (1 - 0.5 * np.sin(env)),
            1.0 * np.sin(2 * np.pi * f1 * t + 1.0) * (1 - 0.4 * np.cos(env)),
        ]
    )
    return t, x


def test_route(seed: int, duration: float = 15.0):
    rng = np.random.default_rng(1000 + seed)
    t = np.arange(0.0, duration, DT)
    cols = []
    for _ in range(2):
        f, a, ph = rng.uniform(0.1, 0.6, 3), rng.uniform(0.2, 0.45, 3), rng.uniform(0, 2 * np.pi, 3)
        c = sum(a[k] * np.sin(2 * np.pi * f[k] * t + ph[k]) for k in range(3))
        c = c - c[0]
        cols.append(c * rng.uniform(0.4, 0.9) / np.max(np.abs(c)))
    return t, np.column_stack(cols)


def identified(seeds: int):
    rows, fits = [], []
    for seed in range(seeds):
        t, x = calibration(seed)
        log = wrist(10 * seed + 1).simulate(t, x)
        fit = identify_coupled(ts.models.BoucWenBacklash, t, x, log.measured, warmup=WARMUP)
        c, se = fit.coupling, fit.coupling_se
        rows.append(
            {
                "seed": seed,
                "c10": c[1, 0],
                "c10_se": se[1, 0],
                "c10_off_in_se": (c[1, 0] - C10) / se[1, 0],
                "c01": c[0, 1],
                "c01_se": se[0, 1],
                "c01_off_in_se": c[0, 1] / se[0, 1],
                "lags": fit.lags,
                "seconds": fit.seconds,
            }
        )
        fits.append(fit)
        print(
            f"calibration seed {seed}: C[1,0] = {c[1, 0]:.5f} +/- {se[1, 0]:.5f} "
            f"({rows[-1]['c10_off_in_se']:+.2f} SE from 0.25), C[0,1] = {c[0, 1]:+.5f} +/- "
            f"{se[0, 1]:.5f} ({rows[-1]['c01_off_in_se']:+.2f} SE), {fit.seconds:.1f} s"
        )
    return rows, fits


def single_joint_models():
    """Each joint identified alone from its own run (the other joint held at 0)."""
    t, x = calibration(0)
    models = []
    for i in range(2):
        xi = np.zeros_like(x)
        xi[:, i] = x[:, i]
        log = wrist(100 + i).simulate(t, xi)
        fit = ts.identify(
            ts.models.BoucWenBacklash,
            t,
            xi[:, i],
            log.measured[:, i],
            warmup=WARMUP,
            progress=False,
            standard_errors="none",
        )
        models.append(fit.model)
    return models


def tracking(model, singles, seeds: int):
    errors = {"none": [], "independent": [], "coupled": []}
    for seed in range(seeds):
        t, y_d = test_route(seed)
        commands = {
            "none": y_d,
            "independent": np.column_stack(
                [
                    ts.compensate.InverseFeedforward(m, smoothing=0.03).command(t, y_d[:, i])
                    for i, m in enumerate(singles)
                ]
            ),
            "coupled": ts.compensate.CoupledFeedforward(model, smoothing=0.03).command(t, y_d),
        }
        plant = wrist(500 + seed)
        for name, u in commands.items():
            e = plant.simulate(t, u).q_out[1000:] - y_d[1000:]
            errors[name].append(np.sqrt(np.mean(e**2, axis=0)))
    out = {}
    for name, rms in errors.items():
        rms = np.array(rms)
        out[name] = {
            "rms_median": np.median(rms, axis=0).tolist(),
            "rms_max": rms.max(axis=0).tolist(),
            "rms_min": rms.min(axis=0).tolist(),
        }
        print(
            f"{name:>12}: RMS error joint 0 median {out[name]['rms_median'][0]:.2e} "
            f"(worst {out[name]['rms_max'][0]:.2e}), joint 1 median "
            f"{out[name]['rms_median'][1]:.2e} (worst {out[name]['rms_max'][1]:.2e}) rad"
        )
    for base in ("none", "independent"):  # per route seed: base's RMS / the coupled one's
        factor = np.array(errors[base]) / np.array(errors["coupled"])
        out[f"coupled_factor_vs_{base}"] = {
            "median": np.median(factor, axis=0).tolist(),
            "min": factor.min(axis=0).tolist(),
        }
        print(
            f"coupled vs {base}: joint 1 RMS {np.median(factor[:, 1]):.1f}x smaller (median), "
            f"{factor[:, 1].min():.1f}x (min); joint 0 {np.median(factor[:, 0]):.2f}x (median)"
        )
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=5)
    args = ap.parse_args(argv)
    start = time.perf_counter()
    with warnings.catch_warnings():  # bounds reached by the realistic drives: reported below
        warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
        rows, fits = identified(args.seeds)
        singles = single_joint_models()
    print(fits[0].report())
    track = tracking(fits[0].model, singles, args.seeds)
    off10 = np.abs([r["c10_off_in_se"] for r in rows])
    off01 = np.abs([r["c01_off_in_se"] for r in rows])
    print(
        f"|C[1,0] - 0.25| in SE: median {np.median(off10):.2f}, max {off10.max():.2f}; "
        f"|C[0,1]| in SE: median {np.median(off01):.2f}, max {off01.max():.2f}"
    )
    path = write_results(
        "coupled",
        {
            "true_c10": C10,
            "identification": rows,
            "model": fits[0].model.to_dict(),
            "tracking_rms_rad": track,
            "seconds": time.perf_counter() - start,
        },
    )
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
