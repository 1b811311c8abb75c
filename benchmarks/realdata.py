"""Model choice checked on a real robot's recordings (nhoyh / ViO-Com tendon-sheath bending joint).

    python benchmarks/realdata.py --data ../shared/data/nhoyh_vio_com [--out DIR] [--quick]

The data (not part of this repository; licence unknown: read from its folder at run time
only) holds the commanded (input) and measured (output) bending angle, in degrees, of a
tendon-sheath-driven joint at ten sheath "configurations" 0..270 deg (config_XXXdeg.csv,
40 Hz, two periods of a 60 deg sine) and at configurations 0 and 90 with sine amplitudes
50/60/70 deg (confX_ampY.csv, irregular ~1 ms logging of a ~37 Hz sensor). See the data's
README for how the columns were decoded.

1. Per file: ``ts.compare_models`` (Backlash, BoucWenBacklash, PrandtlIshlinskii,
   GeneralizedPrandtlIshlinskii, Chain(BoucWenBacklash, Polynomial(3))) against the affine
   baseline y = a x + b. Held-out data: config_* files are fitted on the first period
   (first half of the time span) and scored on the second; confX_ampY files (resampled to
   50 Hz, above the sensor's ~37 Hz update rate) are fitted on the first two thirds and
   scored on the last third. The models run over the whole input; only held-out samples
   count. Fitting settings are the library defaults (seed 0); nothing is tuned on the
   held-out part.
2. Across configurations: the configuration label (deg) is used as the curve angle, in rad
   (it is an inferred label, not a measured bend). Input and output are converted to rad.
   Models with configuration-dependent parameters are fitted on some configurations (whole
   files) and predict the others (whole files): BoucWenBacklash with c_r, c_l, B_r, B_l
   linear in the angle (``ts.identify(..., depends_on_angle=...)``), CurveAngleModel (spring
   free), and an affine baseline with a and b linear in the angle.
   Split A (interpolation): train 0/90/180/270, predict 30/60/120/150/210/240.
   Split B (extrapolation): train 0/30/60/90, predict 120..270 (error vs distance).
3. Amplitude: train on conf0_amp60 (whole file), predict conf0_amp50, conf0_amp70 and the
   repeat conf0_amp60_run2 (``compare_models(..., validate=[...])``).

Writes benchmarks/results/realdata.json (git-ignored) and a report folder (default
benchmarks/results/realdata/) with a Markdown summary and per-file loop/residual figures.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import tendonsheath as ts  # noqa: E402
from _common import RESULTS, write_results  # noqa: E402
from tendonsheath.identify.fit import metrics  # noqa: E402

CONFIGS = [0, 30, 60, 90, 120, 150, 180, 210, 240, 270]
AMP_FILES = [
    "conf0_amp50",
    "conf0_amp60",
    "conf0_amp60_run2",
    "conf0_amp70",
    "conf90_amp50",
    "conf90_amp60",
    "conf90_amp70",
]
CONF_RATE = 50.0  # Hz, resampling of the confX_ampY files


def read(data: Path, name: str, rate: float | None = None) -> ts.io.Log:
    return ts.io.read_log(
        data / f"{name}.csv", time="t", input="input", output="output", resample=rate
    )


def per_file(data: Path, out: Path, maxiter: int) -> list[dict]:
    rows = []
    jobs = [(f"config_{c:03d}deg", None, 0.5) for c in CONFIGS]
    jobs += [(n, CONF_RATE, 1.0 / 3.0) for n in AMP_FILES]
    for name, rate, frac in jobs:
        log = read(data, name, rate)
        start = time.perf_counter()
        cmp = ts.compare_models([log], validate=frac, maxiter=maxiter, refit=False)
        seconds = time.perf_counter() - start
        cmp.report(out / name)
        affine = cmp.row("affine")
        best = next(r for r in cmp.table if r["model"] != "affine" and not r.get("error"))
        rows.append(
            {
                "file": name,
                "samples": len(log),
                "held_out_fraction": frac,
                "resampled_hz": rate,
                "table": cmp.table,
                "best": best["model"],
                "best_val_rmse": best["val_rmse"],
                "affine_val_rmse": affine["val_rmse"],
                "ratio": best["val_rmse"] / affine["val_rmse"],
                "target_met": best["val_rmse"] <= affine["val_rmse"] / 3.0,
                "seconds": seconds,
            }
        )
        print(f"\n== {name} ({len(log)} samples, {seconds:.1f} s)")
        print(cmp.text())
    return rows


def _config_recs(data: Path, angles) -> dict[int, tuple]:
    recs = {}
    for c in angles:
        log = read(data, f"config_{c:03d}deg").to_radians()
        recs[c] = (log.t, log.x, log.y, np.full(len(log), np.deg2rad(c)))
    return recs


def _affine_in_angle(recs):
    """y = (a0 + a1 theta) x + (b0 + b1 theta), least squares over the training recordings."""
    A = np.concatenate([np.column_stack([x, th * x, np.ones_like(x), th]) for _, x, _, th in recs])
    y = np.concatenate([r[2] for r in recs])
    c = np.linalg.lstsq(A, y, rcond=None)[0]

    def predict(x, th):
        return (c[0] + c[1] * th) * x + c[2] + c[3] * th

    return predict


def cross_config(data: Path, train: list[int], test: list[int], maxiter: int) -> dict:
    recs = _config_recs(data, CONFIGS)
    tr = [recs[c] for c in train]
    laws = {"c_r": "linear", "c_l": "linear", "B_r": "linear", "B_l": "linear"}
    start = time.perf_counter()
    models = {
        "BoucWenBacklash(angle-linear)": ts.identify(
            ts.models.BoucWenBacklash,
            recordings=tr,
            depends_on_angle=laws,
            maxiter=maxiter,
            progress=False,
        ).model,
        "CurveAngleModel": ts.identify(
            ts.models.CurveAngleModel,
            recordings=tr,
            free=["spring"],
            maxiter=maxiter,
            progress=False,
        ).model,
    }
    seconds = time.perf_counter() - start
    affine = _affine_in_angle(tr)
    rows = []
    for c in test:
        t, x, y, th = recs[c]
        dist = min(abs(c - a) for a in train)
        row = {"config": c, "distance_deg": dist}
        yd = np.rad2deg(y)
        row["affine_rmse_deg"] = metrics(yd, np.rad2deg(affine(x, th)))["rmse"]
        for name, m in models.items():
            pred = m.simulate(t, x, curve_angle=th)
            row[f"{name}_rmse_deg"] = metrics(yd, np.rad2deg(pred))["rmse"]
        rows.append(row)
    return {"train": train, "test": test, "rows": rows, "fit_seconds": seconds}


def amplitude(data: Path, out: Path, maxiter: int) -> dict:
    train = read(data, "conf0_amp60", CONF_RATE)
    result = {}
    for name in ("conf0_amp50", "conf0_amp70", "conf0_amp60_run2"):
        val = read(data, name, CONF_RATE)
        cmp = ts.compare_models([train], validate=[val], maxiter=maxiter, refit=False)
        cmp.report(out / f"amplitude_{name}")
        result[name] = cmp.table
        print(f"\n== amplitude: train conf0_amp60, predict {name}")
        print(cmp.text())
    return result


def markdown(per: list[dict], cross: dict, amp: dict) -> str:
    names = [
        "Backlash",
        "BoucWenBacklash",
        "PrandtlIshlinskii",
        "GeneralizedPrandtlIshlinskii",
        "BoucWenBacklash+poly3",
    ]
    short = {
        "Backlash": "BL",
        "BoucWenBacklash": "BWB",
        "PrandtlIshlinskii": "PI",
        "GeneralizedPrandtlIshlinskii": "GPI",
        "BoucWenBacklash+poly3": "BWB+poly3",
    }
    lines = [
        "Held-out rmse in degrees (in-sample rmse in brackets); best/affine is the ratio of the "
        "best model's held-out rmse to the affine baseline's (target <= 0.333).",
        "",
        "| file | affine | " + " | ".join(short[n] for n in names) + " | best | best/affine |",
        "|---|---:|" + "---:|" * len(names) + "---|---:|",
    ]
    for p in per:
        by = {r["model"]: r for r in p["table"]}
        cells = []
        for n in ["affine", *names]:
            r = by.get(n)
            if r is None or r.get("error"):
                cells.append("failed")
            else:
                cells.append(f"{r['val_rmse']:.2f} ({r['train_rmse']:.2f})")
        lines.append(
            f"| {p['file']} | "
            + " | ".join(cells)
            + f" | {short.get(p['best'], p['best'])} | {p['ratio']:.3f} |"
        )
    for key, title in (("interpolation", "A"), ("extrapolation", "B")):
        c = cross[key]
        lines += [
            "",
            f"Cross-configuration {title} ({key}): train on {c['train']} deg, predict the "
            "others (whole files), rmse in degrees:",
            "",
            "| config | distance | affine(angle) | BWB(angle-linear) | CurveAngleModel |",
            "|---:|---:|---:|---:|---:|",
        ]
        for r in c["rows"]:
            lines.append(
                f"| {r['config']} | {r['distance_deg']} | {r['affine_rmse_deg']:.2f} | "
                f"{r['BoucWenBacklash(angle-linear)_rmse_deg']:.2f} | "
                f"{r['CurveAngleModel_rmse_deg']:.2f} |"
            )
    lines += [
        "",
        "Amplitude: train on conf0_amp60, predict other amplitudes (whole files), rmse in degrees:",
        "",
        "| predicted file | affine | " + " | ".join(short[n] for n in names) + " |",
        "|---|---:|" + "---:|" * len(names),
    ]
    for name, table in amp.items():
        by = {r["model"]: r for r in table}
        cells = [
            "failed" if by.get(n, {}).get("error") or n not in by else f"{by[n]['val_rmse']:.2f}"
            for n in ["affine", *names]
        ]
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", type=Path, default=Path("../shared/data/nhoyh_vio_com"))
    ap.add_argument("--out", type=Path, default=RESULTS / "realdata")
    ap.add_argument("--maxiter", type=int, default=100, help="generations of each search")
    args = ap.parse_args()
    if not (args.data / "config_000deg.csv").is_file():
        print(f"error: no config_000deg.csv in {args.data}", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    per = per_file(args.data, args.out, args.maxiter)
    cross = {
        "interpolation": cross_config(
            args.data, [0, 90, 180, 270], [30, 60, 120, 150, 210, 240], args.maxiter
        ),
        "extrapolation": cross_config(
            args.data, [0, 30, 60, 90], [120, 150, 180, 210, 240, 270], args.maxiter
        ),
    }
    amp = amplitude(args.data, args.out, args.maxiter)
    md = markdown(per, cross, amp)
    print()
    print(md)
    (args.out / "summary.md").write_text(md)
    met = all(p["target_met"] for p in per)
    payload = {
        "data": str(args.data),
        "seconds": time.perf_counter() - start,
        "target": "best held-out rmse <= affine held-out rmse / 3 on every file",
        "target_met_on_every_file": met,
        "per_file": per,
        "cross_configuration": cross,
        "amplitude": amp,
    }
    path = write_results("realdata", json.loads(json.dumps(payload, default=float)))
    print(f"target met on every file: {met}")
    print(f"wrote {path} and {args.out / 'summary.md'} ({payload['seconds']:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
