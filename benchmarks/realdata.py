"""Model choice checked on a real robot's recordings (nhoyh / ViO-Com tendon-sheath bending joint).

    python benchmarks/realdata.py --data ../shared/data/nhoyh_vio_com [--out DIR] [--files NAME ...]

The data (not part of this repository; licence unknown: read from its folder at run time
only) holds the commanded (input) and measured (output) bending angle, in degrees, of a
tendon-sheath-driven joint at ten sheath "configurations" 0..270 deg (config_XXXdeg.csv,
40 Hz, two periods of a 60 deg sine) and at configurations 0 and 90 with sine amplitudes
50/60/70 deg (confX_ampY.csv, irregular ~1 ms logging of a ~37 Hz sensor). See the data's
README for how the columns were decoded.

1. Per file: ``ts.compare_models`` with its default candidates (Backlash, BoucWenBacklash,
   PrandtlIshlinskii, GeneralizedPrandtlIshlinskii, BoucWenBacklash+poly3, and the
   rate-dependent BoucWenBacklash+lag2 (Hammerstein) and lag1+BoucWenBacklash (Wiener))
   against the affine baseline y = a x + b, selected by cross-validation: each file is cut
   into 3 contiguous blocks, each block is held out in turn (the models are fitted on the
   other two, run over the whole input, and only the block's samples count), and the
   held-out errors are pooled. Each run's start until the input's first reversal (the
   model's initial state is unknown there) is neither fitted nor scored. confX_ampY files
   are resampled to 50 Hz (above the sensor's ~37 Hz update rate). Fitting settings are
   the library defaults (seed 0); nothing is tuned on the held-out parts. ``seconds`` is
   the whole compare_models call on the file (all candidates, all folds, the winner's
   final fit), on this machine; ``cpu_seconds`` its CPU time (all threads) and
   ``load_average`` the machine's load when it ended. A candidate worse than the affine map on
   any held-out block (or leaving the outputs' range) cannot win: each row records the
   winner's error over the affine map's on every held-out block (``winner_part_ratios``),
   whether it is worse on any, and the candidates excluded with the reason.
2. Across configurations: the configuration label (deg) is used as the curve angle, in rad
   (it is an inferred label, not a measured bend). Input and output are converted to rad.
   Models with configuration-dependent parameters are fitted on some configurations (whole
   files) and predict the others (whole files): BoucWenBacklash with c_r, c_l, B_r, B_l
   linear in the angle (``ts.identify(..., depends_on_angle=...)``), CurveAngleModel
   (load_stiffness free), and an affine baseline with a and b linear in the angle.
   Split A (interpolation): train 0/90/180/270, predict 30/60/120/150/210/240.
   Split B (extrapolation): train 0/30/60/90, predict 120..270 (error vs distance).
3. Amplitude: train on conf0_amp60 (whole file), predict conf0_amp50, conf0_amp70 and the
   repeat conf0_amp60_run2 (``compare_models(..., validate=[...])``); whether the winner is
   worse than the affine map on the held-out file (it cannot be: such a candidate cannot win;
   see benchmarks/model_choice.py for runs that the choice never saw).
4. Plant data with a negative gain and a rate-dependent drive (``--plant``, on by default):
   a ``PullPullPlant`` with ``presets.realistic_plant()`` and ``presets.realistic_motor()``
   (its loops widen with the rate) driven by a random-phase sum of sines from 0.1 to 2 Hz,
   logged as a user's rig would: the input in motor steps 1017-2202, the output in degrees,
   negated and offset. ``compare_models`` as in 1, no sign flip by hand. The grey-box
   ``PlantModel`` (the pull-pull plant reduced to friction angle, backlash, viscous time and
   an output map, identified from the log; opt-in, not a default candidate) is
   cross-validated alone on each plant file as well (``greybox`` in the JSON).

Writes benchmarks/results/realdata.json (git-ignored) and a report folder (default
benchmarks/results/realdata/) with a Markdown summary and per-file loop/residual figures.
"""

from __future__ import annotations

import argparse
import json
import os
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


def _compare_row(name: str, log, out: Path, maxiter: int, rate) -> dict:
    start, cpu = time.perf_counter(), time.process_time()
    cmp = ts.compare_models([log], maxiter=maxiter)
    seconds = time.perf_counter() - start
    cpu_seconds = time.process_time() - cpu  # all threads of this process
    cmp.report(out / name)
    affine = cmp.row("affine")
    best = cmp.table[0]  # the selected model (cross-validated), possibly the affine map
    print(f"\n== {name} ({len(log)} samples, {seconds:.1f} s wall, {cpu_seconds:.1f} s CPU)")
    print(cmp.text())
    return {
        **held_out_check(cmp),
        "file": name,
        "samples": len(log),
        "validation": cmp.mode,
        "resampled_hz": rate,
        "table": cmp.table,
        "best": best["model"],
        "best_val_rmse": best["val_rmse"],
        "affine_val_rmse": affine["val_rmse"],
        "ratio": best["val_rmse"] / affine["val_rmse"],
        "target_met": best["val_rmse"] <= affine["val_rmse"] / 3.0,
        "seconds": seconds,
        "cpu_seconds": cpu_seconds,
        "load_average": list(os.getloadavg()),
        "seconds_per_candidate": {r["model"]: r.get("seconds") for r in cmp.table},
        "winner_final_fit_seconds": best.get("final_fit_seconds"),
    }


def held_out_check(cmp) -> dict:
    """Whether the winner is worse than the affine map on any held-out part (a held-out block
    or file), its largest ratio there, and the candidates that could not win (why)."""
    best, affine = cmp.row(cmp.winner_name), cmp.row("affine")
    ratios = [c / a for c, a in zip(best["val_rmse_parts"], affine["val_rmse_parts"], strict=True)]
    return {
        "winner": cmp.winner_name,
        "winner_part_ratios": ratios,
        "winner_worse_than_affine_on_any_part": bool(max(ratios) > 1.0),
        "excluded": cmp.excluded(),
    }


def per_file(data: Path, out: Path, maxiter: int) -> list[dict]:
    jobs = [(f"config_{c:03d}deg", None) for c in CONFIGS]
    jobs += [(n, CONF_RATE) for n in AMP_FILES]
    return [_compare_row(name, read(data, name, rate), out, maxiter, rate) for name, rate in jobs]


STEPS = (1017.0, 2202.0)  # motor steps over the drive's range


def plant_log(seed: int, duration: float = 30.0, rate: float = 100.0) -> ts.io.Log:
    """Realistic pull-pull plant (rate-dependent: viscous sheath, creep, distal inertia,
    motor friction and backlash), logged in motor steps and negated, offset degrees."""
    rng = np.random.default_rng(seed)
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(length=1.2, curve_angle=2 * np.pi),
        pretension=20.0,
        **ts.presets.realistic_plant(),
        motor=ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8),
    )
    t = np.arange(0.0, duration, 1e-3)  # simulated at 1 kHz, logged at ``rate``
    freqs = np.array([0.1, 0.3, 0.8, 2.0])
    phases = rng.uniform(0.0, 2 * np.pi, freqs.size)
    q = np.sum(np.sin(2 * np.pi * freqs[:, None] * t + phases[:, None]), axis=0)
    q /= np.max(np.abs(q))  # +-1 rad at the motor
    out = plant.simulate(t, q)
    keep = slice(None, None, int(round(1e-3**-1 / rate)))
    x = STEPS[0] + (q[keep] + 1.0) * 0.5 * (STEPS[1] - STEPS[0])
    y = 35.0 - np.degrees(out[keep])  # the tip angle falls as the motor steps rise
    return ts.io.Log(t[keep], x, y, path=f"plant seed {seed}")


def greybox_row(log, maxiter: int) -> dict:
    """The grey-box PlantModel (opt-in: not a default candidate) cross-validated alone on a
    plant file, as in 1: its held-out rmse, its ratio to the affine map's, wall and CPU s."""
    start, cpu = time.perf_counter(), time.process_time()
    cmp = ts.compare_models([log], models=["plant"], maxiter=maxiter)
    seconds, cpu_seconds = time.perf_counter() - start, time.process_time() - cpu
    row, affine = cmp.row("PlantModel"), cmp.row("affine")
    print(f"  grey-box PlantModel alone: {seconds:.1f} s wall, {cpu_seconds:.1f} s CPU")
    print("  " + cmp.text().replace("\n", "\n  "))
    return {
        "model": cmp.winner.to_dict() if cmp.winner_name == "PlantModel" else None,
        "val_rmse": row.get("val_rmse"),
        "train_rmse": row.get("train_rmse"),
        "ratio": row["val_rmse"] / affine["val_rmse"] if not row.get("error") else None,
        "error": row.get("error"),
        "seconds": seconds,
        "cpu_seconds": cpu_seconds,
        "load_average": list(os.getloadavg()),
    }


def plant_files(out: Path, maxiter: int, seeds=(0, 1)) -> list[dict]:
    rows = []
    for s in seeds:
        log = plant_log(s)
        row = _compare_row(f"plant_seed{s}", log, out, maxiter, None)
        row["greybox"] = greybox_row(log, maxiter)
        rows.append(row)
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
            free=["load_stiffness"],
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
        result[name] = {"table": cmp.table, **held_out_check(cmp)}
        print(f"\n== amplitude: train conf0_amp60, predict {name}")
        print(cmp.text())
    return result


SHORT = {
    "Backlash": "BL",
    "BoucWenBacklash": "BWB",
    "PrandtlIshlinskii": "PI",
    "GeneralizedPrandtlIshlinskii": "GPI",
    "BoucWenBacklash+poly3": "BWB+poly3",
    "BoucWenBacklash+lag2": "BWB+lag2",
    "lag1+BoucWenBacklash": "lag1+BWB",
}


def markdown(per: list[dict], cross: dict, amp: dict) -> str:
    names = list(SHORT)
    short = SHORT
    lines = [
        "Cross-validated rmse in degrees (in-sample rmse in brackets); best/affine is the ratio "
        "of the selected model's held-out rmse to the affine baseline's (target <= 0.333); "
        "s: wall seconds for the file (CPU seconds in the JSON).",
        "",
        "| file | affine | "
        + " | ".join(short[n] for n in names)
        + " | best | best/affine | worst block/affine | s |",
        "|---|---:|" + "---:|" * len(names) + "---|---:|---:|---:|",
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
            + f" | {short.get(p['best'], p['best'])} | {p['ratio']:.3f} | "
            f"{max(p['winner_part_ratios']):.3f} | {p['seconds']:.0f} |"
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
    for name, split in amp.items():
        by = {r["model"]: r for r in split["table"]}
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
    ap.add_argument(
        "--files", nargs="*", default=None, help="only these files (part 1 only; no JSON)"
    )
    args = ap.parse_args()
    if not (args.data / "config_000deg.csv").is_file():
        print(f"error: no config_000deg.csv in {args.data}", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    if args.files is not None:  # a quick look at some files: printed, nothing written
        for name in args.files:
            if name.startswith("plant_seed"):
                log = plant_log(int(name.removeprefix("plant_seed")))
                _compare_row(name, log, args.out, args.maxiter, None)
                continue
            rate = None if name.startswith("config_") else CONF_RATE
            _compare_row(name, read(args.data, name, rate), args.out, args.maxiter, rate)
        return 0
    per = per_file(args.data, args.out, args.maxiter)
    plant = plant_files(args.out, args.maxiter)
    cross = {
        "interpolation": cross_config(
            args.data, [0, 90, 180, 270], [30, 60, 120, 150, 210, 240], args.maxiter
        ),
        "extrapolation": cross_config(
            args.data, [0, 30, 60, 90], [120, 150, 180, 210, 240, 270], args.maxiter
        ),
    }
    amp = amplitude(args.data, args.out, args.maxiter)
    md = markdown(per + plant, cross, amp)
    print()
    print(md)
    (args.out / "summary.md").write_text(md)
    met = all(p["target_met"] for p in per)
    worse = [p["file"] for p in per + plant if p["winner_worse_than_affine_on_any_part"]]
    worse += [f"amplitude {n}" for n, a in amp.items() if a["winner_worse_than_affine_on_any_part"]]
    payload = {
        "winners_worse_than_affine_on_a_held_out_part": worse,
        "data": str(args.data),
        "seconds": time.perf_counter() - start,
        "target": "best held-out rmse <= affine held-out rmse / 3 on every file, in under 60 s",
        "target_met_on_every_file": met,
        "slowest_file_seconds": max(p["seconds"] for p in per + plant),
        "slowest_file_cpu_seconds": max(p["cpu_seconds"] for p in per + plant),
        "per_file": per,
        "plant": plant,
        "plant_target_met": all(p["target_met"] for p in plant),
        "cross_configuration": cross,
        "amplitude": amp,
    }
    path = write_results("realdata", json.loads(json.dumps(payload, default=float)))
    print(f"target met on every file: {met}; on the plant data: {payload['plant_target_met']}")
    print(f"winners worse than the affine map on a held-out block or file: {worse or 'none'}")
    print(
        f"slowest file: {payload['slowest_file_seconds']:.1f} s wall, "
        f"{payload['slowest_file_cpu_seconds']:.1f} s CPU"
    )
    print(f"wrote {path} and {args.out / 'summary.md'} ({payload['seconds']:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
