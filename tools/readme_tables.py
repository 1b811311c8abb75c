"""README.md's result tables, generated from the committed result files in benchmarks/results/.

    python tools/readme_tables.py           # rewrite README.md in place
    python tools/readme_tables.py --check   # exit 1 with a unified diff if README.md drifts

Each generated table sits between two marker comments in README.md:

    <!-- table:NAME:begin -->
    ... (generated: do not edit by hand)
    <!-- table:NAME:end -->

A figure the prose quotes from a result file carries a marker right after it (or in a group
of markers, one a line, after its paragraph or table), which ``--check`` checks too:

    ... is 1.62x a model fitted on that session's own three runs ...
    <!-- result: tool5_sessions.json summary.recalibrated_over_own.median ~ 1.62 -->

the key (dots between its parts, a list index as a number) holds a number that rounds to the
figure at the digits it shows, and the figure stands in the text since the marker group before.

The tables are defined in TABLES at the end of this file (a name, the result files it reads
and a function that renders it). The result files are refreshed by `make results` (the demo's
metrics.json copied to benchmarks/results/demo-metrics.json, the benchmark scripts' JSON),
which then runs this script. A missing file or key is a one-line error naming the file and key
(exit 2). Standard library only: no build needed.
"""

from __future__ import annotations

import argparse
import difflib
import json
import math
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
README = ROOT / "README.md"
SCRIPT = "python tools/readme_tables.py"


class ResultError(Exception):
    """A result file or a key in it is missing or unusable (one line: file and key)."""


# -- reading result files -----------------------------------------------------------------


def _display(path: Path) -> str:
    try:
        return str(path.resolve().relative_to(ROOT))
    except ValueError:
        return str(path)


class Source:
    """One JSON result file; ``get``/``num`` read a key path and fail naming file and key."""

    def __init__(self, path: Path):
        self.path = path
        self.name = _display(path)
        if not path.is_file():
            raise ResultError(f"{self.name}: file not found (refresh with `make results`)")
        try:
            self.data = json.loads(path.read_text())
        except (OSError, ValueError) as exc:
            raise ResultError(f"{self.name}: not readable JSON ({exc})") from None

    def get(self, *parts: str | int):
        node = self.data
        for depth, part in enumerate(parts):
            here = ".".join(str(p) for p in parts[: depth + 1])
            if isinstance(node, dict) and part in node:
                node = node[part]
            elif (
                isinstance(node, list) and isinstance(part, int) and -len(node) <= part < len(node)
            ):
                node = node[part]
            else:
                if isinstance(node, dict):
                    has = ", ".join(map(str, node)) or "nothing"
                elif isinstance(node, list):
                    has = f"a list of {len(node)}"
                else:
                    has = f"a {type(node).__name__}"
                raise ResultError(f"{self.name}: missing key '{here}' (the parent holds {has})")
        return node

    def num(self, *parts: str | int) -> float:
        value = self.get(*parts)
        if isinstance(value, bool) or not isinstance(value, int | float):
            key = ".".join(str(p) for p in parts)
            raise ResultError(f"{self.name}: key '{key}' is {value!r}, not a number")
        return float(value)

    def keys(self, *parts: str | int) -> list[str]:
        node = self.get(*parts)
        if not isinstance(node, dict) or not node:
            key = ".".join(str(p) for p in parts)
            raise ResultError(f"{self.name}: key '{key}' is not a non-empty mapping")
        return list(node)

    def items(self, *parts: str | int) -> list:
        node = self.get(*parts)
        if not isinstance(node, list) or not node:
            key = ".".join(str(p) for p in parts)
            raise ResultError(f"{self.name}: key '{key}' is not a non-empty list")
        return node


# -- formatting ---------------------------------------------------------------------------


def fmt(x: float, sig: int = 3, trim: bool = False) -> str:
    """``sig`` significant digits: fixed point for 1e-3 <= |x| < 1e5, else 8.28e-5.
    ``trim`` drops trailing zeros (for published figures and settings: 0.0012, not 0.00120)."""
    if x is None or not math.isfinite(x):
        return "n/a"
    if x == 0:
        return "0"
    r = float(f"{x:.{sig - 1}e}")  # rounded first, so 9.996 -> 10.0, not 10.00
    e = math.floor(math.log10(abs(r)))
    if -3 <= e < 5:
        text = f"{r:.{max(sig - 1 - e, 0)}f}"
        return text.rstrip("0").rstrip(".") if trim and "." in text else text
    mantissa, exponent = f"{r:.{sig - 1}e}".split("e")
    if trim and "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    return f"{mantissa}e{int(exponent)}"


def times(x: float) -> str:
    return f"{fmt(x)}x"


def slash(values, trim: bool = False) -> str:
    return " / ".join(fmt(v, trim=trim) for v in values)


def md_table(header: list[str], rows: list[list[str]], align: str | None = None) -> str:
    """Markdown table; ``align`` is one letter per column, l or r (default: all l)."""
    align = align or "l" * len(header)
    rule = ["---:" if a == "r" else "---" for a in align]
    lines = [header, rule, *rows]
    return "\n".join("| " + " | ".join(cells) + " |" for cells in lines)


def generated_from(*sources: Source) -> str:
    files = ", ".join(f"`{s.name}`" for s in sources)
    return f"_Generated by `{SCRIPT}` from {files} (refresh: `make results`)._"


# -- the tables ---------------------------------------------------------------------------


def scenarios(m: Source) -> str:
    """The demo's three seed experiments and the robustness study beside the papers."""
    rows = []

    # do2015: the headline compensator's MSE reduction on each servo (the do2015 table: all)
    servos = m.keys("details", "do2015", "servo_summary")
    head = "shape-aware InverseFeedforward + EncoderLoop"
    cells = []
    for servo in servos:
        s = ("details", "do2015", "servo_summary", servo, head)
        cells.append(
            f"{servo.upper()} servo: {times(m.num(*s, 'factor_fixed'))} fixed route, "
            f"{times(m.num(*s, 'factor_random', 'median'))} random routes (median; worst "
            f"{times(m.num(*s, 'factor_random', 'min'))})"
        )
    paper_comps = m.keys("paper", "do2015", "mse_rad2")
    paper = [m.num("paper", "do2015", "mse_rad2", c) for c in paper_comps]
    tip = ("details", "do2015", "tip_sensor", "1 ms", "TipLoop", "factor_random")
    cells.append(
        f"with a tip sensor (1 ms), TipLoop: {times(m.num(*tip, 'median'))} random routes "
        f"(median; worst {times(m.num(*tip, 'min'))})"
    )
    rows.append(
        [
            "`do2015`",
            "pull-pull pair driving a distal joint; a fixed route and random route changes "
            "(5 seeds), behind a PID and a PD servo",
            f"{head} (no tip sensor); TipLoop (tip sensor); the others in the do2015 tables",
            "MSE reduction: " + "; ".join(cells),
            f"{times(paper[0] / paper[1])} (InverseFeedforward), "
            f"{times(paper[0] / paper[2])} (AdaptiveController)",
        ]
    )

    # sun2015: RMSE with a mid-run route change (headline) and the mean over the conditions
    comps = m.keys("scenarios", "sun2015")
    change = [math.degrees(m.num("scenarios", "sun2015", c, "rmse")) for c in comps]
    mean = [
        math.degrees(m.num("details", "sun2015", "mean_rmse_over_conditions", c)) for c in comps
    ]
    conditions = len(m.keys("details", "sun2015", "per_condition"))
    rows.append(
        [
            "`sun2015`",
            "curve angles 0-2 pi x no, constant and spring loads, and a mid-run route change",
            " / ".join(comps),
            f"route change: RMSE {slash(change)} deg; "
            f"mean over {conditions} conditions {slash(mean)} deg",
            "published values not recoverable; ranking",
        ]
    )

    # lau2015: the headline's percent error on each servo, and the -3 dB bandwidths
    servos = m.keys("details", "lau2015", "servo_runs")
    head = "ContinuumFeedforward (exact) + EncoderLoop"
    cells = []
    for servo in servos:
        r = ("details", "lau2015", "servo_runs", servo)
        cells.append(
            f"{servo.upper()} servo: mean error {fmt(m.num(*r, head, 'percent_error'))} % "
            f"(max {fmt(m.num(*r, head, 'max_percent_error'))} %), uncompensated "
            f"{fmt(m.num(*r, 'none', 'percent_error'))} %"
        )
    responses = m.keys("details", "lau2015", "frequency")
    bandwidth = [m.num("details", "lau2015", "frequency", c, "bandwidth_3db_hz") for c in responses]

    def short(name: str) -> str:  # "ContinuumFeedforward (exact)" -> "exact"
        found = re.fullmatch(r".*\((.+)\)", name)
        return found.group(1) if found else name

    rows.append(
        [
            "`lau2015`",
            "continuum segment, +/-90 deg at 0.4 Hz, 1 m sheath on a 0.6 m semicircle, behind "
            "a PID and a PD servo",
            f"{head}; the others in the lau2015 table",
            "; ".join(cells) + f"; -3 dB bandwidth {slash(bandwidth)} Hz "
            f"({' / '.join(short(c) for c in responses)}) behind a 1.2 Hz motor lag",
            f"< {fmt(m.num('paper', 'lau2015', 'percent_error'), trim=True)} % "
            f"({fmt(m.num('paper', 'lau2015', 'max_percent_error'), trim=True)} % at the "
            f"extremes); {fmt(m.num('paper', 'lau2015', 'bandwidth_hz'), trim=True)} Hz",
        ]
    )

    # robustness: do2015's compensators over perturbed plants
    comps = m.keys("robustness", "compensators")
    median = [m.num("robustness", "compensators", c, "median") for c in comps]
    share = [100 * m.num("robustness", "compensators", c, "within_bound") for c in comps]
    runs = m.num("robustness", "runs")
    rows.append(
        [
            "robustness",
            f"do2015 over {runs:.0f} draws of friction and pretension (+/-30 %) "
            "and random-arc routes",
            " / ".join(comps),
            f"median MSE {slash(median)} rad^2; "
            f"share <= {fmt(m.num('robustness', 'bound'), trim=True)}: {slash(share)} %",
            "",
        ]
    )
    header = ["scenario", "conditions", "compensators", "this simulation", "paper"]
    return md_table(header, rows) + "\n\n" + generated_from(m)


def do2015(m: Source) -> str:
    """Every do2015 compensator on both servos: MSE reduction on the fixed route and under
    random route changes (median and worst of the route seeds)."""
    servos = m.keys("details", "do2015", "servo_summary")
    comps = m.keys("details", "do2015", "servo_summary", servos[0])
    rows = []
    for comp in comps:
        if comp == "none":
            continue
        cells = [comp]
        for servo in servos:
            s = ("details", "do2015", "servo_summary", servo, comp)
            if comp not in m.keys(*s[:-1]):  # TipLoop: designed on the PID servo only
                cells += ["-", "-"]
                continue
            cells += [
                times(m.num(*s, "factor_fixed")),
                f"{times(m.num(*s, 'factor_random', 'median'))} "
                f"({times(m.num(*s, 'factor_random', 'min'))})",
            ]
        rows.append(cells)
    header = ["compensator"]
    for servo in servos:
        header += [f"{servo.upper()}: fixed route", f"{servo.upper()}: random, median (worst)"]
    note = (
        "MSE reduction over each servo's uncompensated run (the AdaptiveController drives a "
        "torque motor: the same run in both columns, divided into each servo's; it and the "
        "TipLoop read a tip sensor with 1 ms of latency); random routes: the median and the "
        f"worst of {len(m.items('details', 'do2015', 'route_seeds'))} route-schedule seeds."
    )
    return md_table(header, rows) + "\n\n" + note + "\n\n" + generated_from(m)


def do2015_tip(m: Source) -> str:
    """The tip-feedback controllers at each latency of the tip sensor, with what each was
    designed from."""
    rows = []
    for latency in m.keys("details", "do2015", "tip_sensor"):
        for comp in m.keys("details", "do2015", "tip_sensor", latency):
            s = ("details", "do2015", "tip_sensor", latency, comp)
            design = ("details", "do2015", "tip_sensor", latency, comp, "design")
            resonances = [m.num(*design, "resonances_hz", i) for i in range(3)]
            delays = [1e3 * m.num(*design, "delays_s", i) for i in range(3)]
            rows.append(
                [
                    latency,
                    comp,
                    times(m.num(*s, "factor_fixed")),
                    f"{times(m.num(*s, 'factor_random', 'median'))} "
                    f"({times(m.num(*s, 'factor_random', 'min'))})",
                    f"{m.num(*s, 'saturated_cycles'):.0f}",
                    f"{slash(resonances)} Hz; {slash(delays, trim=True)} ms",
                ]
            )
    header = [
        "latency",
        "controller",
        "fixed route",
        "random, median (worst)",
        "saturated cycles",
        "designed from: resonance; delay (3 calibration shapes)",
    ]
    note = (
        "MSE reduction over the PID servo's uncompensated run; the tip sensor has 2e-4 rad "
        "noise and 1e-4 rad resolution. Each controller was designed at each latency from "
        "calibration runs only: a chirp on a fast ramp per calibration shape (the loop's "
        "dynamics) and trial runs on those shapes."
    )
    return md_table(header, rows) + "\n\n" + note + "\n\n" + generated_from(m)


def lau2015(m: Source) -> str:
    """Every lau2015 compensator on both servos: mean (max) error over the range."""
    servos = m.keys("details", "lau2015", "servo_runs")
    comps = m.keys("details", "lau2015", "servo_runs", servos[0])
    rows = []
    for comp in comps:
        cells = [comp]
        for servo in servos:
            r = ("details", "lau2015", "servo_runs", servo, comp)
            cells.append(
                f"{fmt(m.num(*r, 'percent_error'))} % ({fmt(m.num(*r, 'max_percent_error'))} %)"
            )
        rows.append(cells)
    header = ["compensator", *(f"{s.upper()} servo: mean (max) error" for s in servos)]
    return md_table(header, rows) + "\n\n" + generated_from(m)


def targets(m: Source) -> str:
    """Each paper's headline claim, measured on the realistic plant (metrics.json targets)."""
    rows = []
    for scenario in m.keys("targets"):
        for i in range(len(m.items("targets", scenario))):
            unit = m.get("targets", scenario, i, "unit")
            rows.append(
                [
                    f"`{scenario}`",
                    str(m.get("targets", scenario, i, "claim")),
                    str(m.get("targets", scenario, i, "target")),
                    f"{fmt(m.num('targets', scenario, i, 'measured'))} {unit}".strip(),
                    "met" if m.get("targets", scenario, i, "met") else "**not met**",
                    str(m.get("targets", scenario, i, "seen")) or "-",
                ]
            )
    header = ["scenario", "paper's claim", "target", "measured", "verdict", "also seen"]
    return md_table(header, rows) + "\n\n" + generated_from(m)


def performance(
    models: Source,
    plant: Source,
    identify: Source,
    compensators: Source,
    sweep: Source,
    identify_long: Source,
) -> str:
    """Speed figures of the benchmark scripts, one row each."""
    rows = []

    # models.py: C++ samples/s and the speed-up over a Python loop where one exists
    rates, speedups = [], []
    for i, _ in enumerate(models.items("rows")):
        name = models.get("rows", i, "model")
        name = name.replace("PrandtlIshlinskii", "PI")
        rates.append(f"{name} {fmt(models.num('rows', i, 'cpp_samples_per_s'))}")
        speedup = models.get("rows", i, "speedup")
        if isinstance(speedup, int | float) and math.isfinite(speedup):
            speedups.append((name, speedup))
    rows.append(
        [
            "`simulate`, samples/s",
            ", ".join(rates)
            + "; "
            + " / ".join(times(s) for _, s in speedups)
            + " a Python loop of the same algorithm ("
            + " / ".join(n for n, _ in speedups)
            + ")",
            "`benchmarks/models.py`",
        ]
    )

    # plant.py: 60 s at 1 kHz for N elements per sheath
    prow = plant.items("rows")
    by_n = {int(plant.num("rows", i, "elements")): i for i in range(len(prow))}
    if 100 not in by_n:
        raise ResultError(f"{plant.name}: no row with elements = 100 in 'rows'")
    i100, first, last = by_n[100], min(by_n), max(by_n)
    rows.append(
        [
            f"physics plant, {plant.num('rows', i100, 'steps') / 1000:g} s at 1 kHz",
            f"N = 100: {fmt(plant.num('rows', i100, 'cpp_seconds'))} s "
            f"({fmt(plant.num('rows', i100, 'cpp_us_per_step'))} us/step); "
            f"N = {first} ... {last}: {fmt(plant.num('rows', by_n[first], 'cpp_seconds'))} ... "
            f"{fmt(plant.num('rows', by_n[last], 'cpp_seconds'))} s "
            f"(about N^{fmt(plant.num('growth_exponent_cpp'), 2)}: slip fronts are marched "
            "node by node, but each event still costs O(N) solves)",
            "`benchmarks/plant.py`",
        ]
    )
    real = {
        int(plant.num("realistic_rows", i, "elements")): i
        for i in range(len(plant.items("realistic_rows")))
    }
    if 100 not in real:
        raise ResultError(f"{plant.name}: no row with elements = 100 in 'realistic_rows'")
    rows.append(
        [
            "physics plant with every realistic effect on (presets), 60 s at 1 kHz",
            f"N = 100: {fmt(plant.num('realistic_rows', real[100], 'cpp_seconds'))} s "
            f"({fmt(plant.num('realistic_rows', real[100], 'cpp_us_per_step'))} us/step; "
            "target 0.2 s)",
            "`benchmarks/plant.py`",
        ]
    )

    rows.append(
        [
            f"identify BoucWenBacklash, {identify_long.num('samples'):.0f} samples",
            f"{fmt(identify_long.num('wall_seconds'))} s wall, "
            f"{fmt(identify_long.num('cpu_seconds'))} s CPU (target 60 s), peak memory "
            f"{fmt(identify_long.num('peak_memory_mib'))} MiB, "
            f"{fmt(identify_long.num('evaluations_per_second'))} evaluations/s; rmse "
            f"{fmt(identify_long.num('rmse'))} at noise {fmt(identify_long.num('noise_std'))}",
            "`benchmarks/identify_long.py`",
        ]
    )

    # identify.py: tendonsheath vs SciPy DE over a pure-Python simulation
    rows.append(
        [
            "identify BoucWenBacklash, 20 s at 1 kHz",
            f"{fmt(identify.num('tendonsheath', 'seconds'))} s, validation rmse "
            f"{fmt(identify.num('tendonsheath', 'validation_rmse'))} (SciPy DE on pure Python: "
            f"{fmt(identify.num('baseline', 'validation_rmse'))}), "
            f"{times(identify.num('speedup'))} faster",
            "`benchmarks/identify.py`",
        ]
    )

    # compensators.py: per-step latency, feedforwards (ranges), the root-searching inverses and
    # the adaptive controller
    groups: dict[str, tuple[list, list]] = {"ff": ([], []), "root": ([], []), "ad": ([], [])}
    for i, _ in enumerate(compensators.items("rows")):
        name = str(compensators.get("rows", i, "name"))
        key = "ad" if name.startswith("Adaptive") else "root" if "root search" in name else "ff"
        groups[key][0].append(compensators.num("rows", i, "median_ns"))
        groups[key][1].append(compensators.num("rows", i, "p999_ns"))
    (ff_median, ff_p999), (root_median, root_p999), (ad_median, ad_p999) = groups.values()
    if not ff_median or not ad_median or not root_median:
        raise ResultError(
            f"{compensators.name}: 'rows' lacks a feedforward, a root-search or an Adaptive row"
        )

    def span(values):
        lo, hi = min(values), max(values)
        return fmt(lo) if fmt(lo) == fmt(hi) else f"{fmt(lo)}-{fmt(hi)}"

    rows.append(
        [
            "compensator step (C++, median / p99.9)",
            f"feedforwards and the encoder loop {span(ff_median)} ns / {span(ff_p999)} ns, "
            f"root-searching inverses (GPI, a chain with a polynomial) {span(root_median)} ns / "
            f"{span(root_p999)} ns, adaptive controller {span(ad_median)} ns / "
            f"{span(ad_p999)} ns",
            "`benchmarks/compensators.py`",
        ]
    )

    # sweep.py: runs/s of the local pool on 1 and 2 workers, Dask overhead
    local, dask = {}, None
    for i, _ in enumerate(sweep.items("rows")):
        engine = str(sweep.get("rows", i, "engine"))
        if engine.startswith("local"):
            local[int(sweep.num("rows", i, "workers"))] = sweep.num("rows", i, "runs_per_second")
        elif engine.startswith("dask"):
            dask = sweep.num("rows", i, "overhead_per_run")
    if 1 not in local or 2 not in local or dask is None:
        raise ResultError(
            f"{sweep.name}: 'rows' needs local pool rows for 1 and 2 workers and a dask row"
        )
    rows.append(
        [
            "sweep, do2015 at reduced length",
            f"{fmt(local[1])} runs/s on 1 worker, {fmt(local[2])} on 2 "
            f"({times(local[2] / local[1])}); Dask LocalCluster overhead "
            f"{fmt(100 * dask)} % of a run",
            "`benchmarks/sweep.py`",
        ]
    )
    return (
        md_table(["what", "figure", "script"], rows)
        + "\n\n"
        + generated_from(models, plant, identify, compensators, sweep, identify_long)
    )


# models compared on the real data, in column order, with their short names
REAL_MODELS = {
    "affine": "affine",
    "Backlash": "BL",
    "BoucWenBacklash": "BWB",
    "PrandtlIshlinskii": "PI",
    "GeneralizedPrandtlIshlinskii": "GPI",
    "BoucWenBacklash+poly3": "BWB+poly3",
    "BoucWenBacklash+lag2": "BWB+lag2",
}


def _by_model(src: Source, *parts) -> dict:
    table = src.items(*parts)
    by = {}
    for i, _ in enumerate(table):
        by[src.get(*parts, i, "model")] = i
    missing = [m for m in REAL_MODELS if m not in by]
    if missing:
        key = ".".join(str(p) for p in parts)
        raise ResultError(f"{src.name}: '{key}' has no row for model(s) {', '.join(missing)}")
    return by


def _failed(src: Source, *parts) -> bool:
    """A model row that records a failed fit (shown as 'failed', as realdata.py does)."""
    row = src.get(*parts)
    return isinstance(row, dict) and bool(row.get("error"))


def realdata_files(r: Source) -> str:
    """Cross-validated (in-sample) rmse per file and model, the selected model, best/affine
    and the CPU seconds per file (the wall time depends on what else the machine runs; both
    are in the JSON); the plant-data rows (negative gain, rate-dependent) last."""
    rows, met, worse, worst, slowest = [], 0, 0, None, None
    sections = [("per_file", i) for i, _ in enumerate(r.items("per_file"))]
    sections += [("plant", i) for i, _ in enumerate(r.items("plant"))]
    for key, i in sections:
        by = _by_model(r, key, i, "table")
        cells = [str(r.get(key, i, "file"))]
        for model in REAL_MODELS:
            j = by[model]
            if _failed(r, key, i, "table", j):
                cells.append("failed")
                continue
            val = r.num(key, i, "table", j, "val_rmse")
            train = r.num(key, i, "table", j, "train_rmse")
            mark = " x" if model in r.get(key, i, "excluded") else ""
            cells.append(f"{fmt(val)} ({fmt(train)}){mark}")
        best = str(r.get(key, i, "best"))
        ratio = r.num(key, i, "ratio")
        part = max(r.num(key, i, "winner_part_ratios", k) for k in range(3))
        seconds = r.num(key, i, "cpu_seconds")
        met += ratio <= 1 / 3
        worse += part > 1
        if worst is None or ratio > worst[1]:
            worst = (cells[0], ratio)
        if slowest is None or seconds > slowest[1]:
            slowest = (cells[0], seconds)
        cells += [REAL_MODELS.get(best, best), fmt(ratio), fmt(part), f"{seconds:.0f}"]
        rows.append(cells)
    header = ["file", *REAL_MODELS.values(), "best", "best/affine", "worst block", "CPU s"]
    target = (
        f"The target (the selected model's held-out rmse at most a third of the affine "
        f"baseline's) is met on {met} of {len(rows)} files; the largest best/affine is "
        f"{fmt(worst[1])} ({worst[0]}); the winner is worse than the affine map on a held-out "
        f"block in {worse} files (worst block: its largest ratio over the three); x: cannot win "
        f"(worse than the affine map on a block, or leaving the outputs' range); the slowest "
        f"file took {slowest[1]:.0f} s of CPU ({slowest[0]})."
    )
    align = "l" + "r" * len(REAL_MODELS) + "lrrr"
    return md_table(header, rows, align) + "\n\n" + target + "\n\n" + generated_from(r)


def _cross(r: Source, split: str, title: str) -> str:
    train = r.items("cross_configuration", split, "train")
    caption = (
        f"Cross-configuration {title} ({split}): train on "
        f"{', '.join(str(a) for a in train)} deg, predict the others (whole files), "
        "rmse in degrees:"
    )
    columns = {
        "affine_rmse_deg": "affine(angle)",
        "BoucWenBacklash(angle-linear)_rmse_deg": "BWB(angle-linear)",
        "CurveAngleModel_rmse_deg": "CurveAngleModel",
    }
    rows = []
    for i, _ in enumerate(r.items("cross_configuration", split, "rows")):
        row = ("cross_configuration", split, "rows", i)
        rows.append(
            [
                f"{r.num(*row, 'config'):g}",  # labels (deg), not measurements
                f"{r.num(*row, 'distance_deg'):g}",
                *(fmt(r.num(*row, key)) for key in columns),
            ]
        )
    header = ["config", "distance", *columns.values()]
    return caption + "\n\n" + md_table(header, rows, "rrrrr")


def realdata_interpolation(r: Source) -> str:
    return _cross(r, "interpolation", "A")


def realdata_extrapolation(r: Source) -> str:
    return _cross(r, "extrapolation", "B")


def realdata_amplitude(r: Source) -> str:
    rows = []
    for name in r.keys("amplitude"):
        by = _by_model(r, "amplitude", name, "table")
        cells = [name]
        for model in REAL_MODELS:
            if _failed(r, "amplitude", name, "table", by[model]):
                cells.append("failed")
            else:
                cells.append(fmt(r.num("amplitude", name, "table", by[model], "val_rmse")))
        rows.append(cells)
    return md_table(["predicted file", *REAL_MODELS.values()], rows, "l" + "r" * len(REAL_MODELS))


# the population's pipelines, in the table's order, with the targets (median, worst)
POPULATION_ROWS = (
    ("sensorless (encoder loop where it helps)", "sensed shape, no tip sensor", 60.0, 13.0),
    ("shape-aware InverseFeedforward", "sensed shape, no tip sensor", None, None),
    ("shape-aware InverseFeedforward + EncoderLoop", "sensed shape, no tip sensor", None, None),
    ("TipLoop, 1 ms", "tip sensor, 1 ms latency", 500.0, 190.0),
    ("TipLoop, 5 ms", "tip sensor, 5 ms latency", 100.0, None),
    ("AdaptiveController, 1 ms", "tip sensor, 1 ms; torque motor identified", 190.0, None),
)


def population(p: Source) -> str:
    """Every pipeline over the population of drives: the median over members of each member's
    median over its route seeds, the worst member, and the demo's plant as one member."""
    pull = ("pull_pull",)
    members = int(p.num("members"))
    rows = []
    for name, told, need_median, need_worst in POPULATION_ROWS:
        median = p.num(*pull, name, "median", "median")
        worst = p.num(*pull, name, "median", "worst")
        if need_median is None:
            verdict = "-"
        else:
            met = median >= need_median and (need_worst is None or worst >= need_worst)
            target = f">= {fmt(need_median, trim=True)}x" + (
                f", worst >= {fmt(need_worst, trim=True)}x" if need_worst else ""
            )
            verdict = f"{target}: {'met' if met else '**not met**'}"
        demo = p.num("demo_member", name, "median")
        rows.append(
            [
                name,
                told,
                times(median),
                times(worst),
                times(p.num(*pull, name, "min", "worst")),
                times(p.num(*pull, name, "fixed", "median")),
                times(demo),
                verdict,
            ]
        )
    ilc = p.get(*pull, "ILC, 10 trials")
    rows.append(
        [
            "ILC, 10 trials (run without the sensor)",
            "tip sensor while learning, 1 ms",
            times(ilc["median"]["median"]),
            times(ilc["min"]["worst"]) + " (min over noise seeds)",
            "-",
            "-",
            times(p.num("demo_member", "ILC, 10 trials", "min")),
            f">= 1000x on every member: {'met' if ilc['min']['worst'] >= 1000 else '**not met**'}"
            f"; shifted route no worse than the feedforward on "
            f"{int(sum(ilc['shifted_ok']['values']))} of {members}",
        ]
    )
    kept = p.get(*pull, "sensorless (encoder loop where it helps)", "loop_kept", "values")
    chosen = p.get(*pull, "sensorless (encoder loop where it helps)", "median", "values")
    alone = p.get(*pull, "shape-aware InverseFeedforward", "median", "values")
    worse = sum(c < 0.999 * a for c, a in zip(chosen, alone, strict=True))
    cont = p.get("continuum", "ContinuumFeedforward (exact) + EncoderLoop")
    met = cont["median"]["median"] < 2.0 and max(cont["median"]["values"]) < 5.0
    cont_verdict = "met" if met else "**not met**"
    header = [
        "pipeline",
        "told",
        "median over members",
        "worst member",
        "worst member's worst seed",
        "fixed route (median)",
        "demo's plant",
        "target",
    ]
    note = (
        f"MSE reduction over each drive's uncompensated run, simulated on {members} pull-pull "
        "drives drawn by `ts.presets.random_realistic_plant(0..."
        f"{members - 1})`: a member's figure is its median over "
        f"{int(p.num('route_seeds'))} route seeds. Every member is "
        "calibrated from its own logs (quantised, noisy motor encoder; tip sensor with drawn "
        "noise and resolution; noisy, delayed shape sensing) and tested on the same drive "
        "drifted a little since, on references off the calibration's frequency that start "
        f"away from rest. The encoder loop was kept on {int(sum(kept))} of {members} members "
        "(left out unless calibration trials at two speeds showed it helping); the chosen "
        f"pipeline "
        f"is worse than the feedforward alone on {worse} of {members}. Continuum drives "
        f"(`random_continuum_plant`, lau2015's pipeline): mean error "
        f"{fmt(cont['median']['median'])} % median over members (each member's median over "
        f"its test routes), worst member {fmt(max(cont['median']['values']))} % (target < 2 %, "
        f"worst < 5 %: {cont_verdict}); worst single route {fmt(cont['max']['worst'])} %; "
        "uncompensated "
        f"{fmt(cont['none_median']['median'])} %. The run took {fmt(p.num('wall_s'))} s on "
        f"{int(p.num('workers'))} workers ({int(p.num('cores'))} cores). A simulation, not a "
        "rig: the papers' figures were measured on hardware."
    )
    return md_table(header, rows, "llrrrrrl") + "\n\n" + note + "\n\n" + generated_from(p)


# -- the table specs: marker name, result files (in benchmarks/results/), renderer ----------


@dataclass(frozen=True)
class Table:
    name: str  # README markers: <!-- table:NAME:begin --> ... <!-- table:NAME:end -->
    files: tuple[str, ...]  # in benchmarks/results/, passed to render in this order
    render: Callable[..., str]


TABLES = [
    Table("population", ("population.json",), population),
    Table("scenarios", ("demo-metrics.json",), scenarios),
    Table("targets", ("demo-metrics.json",), targets),
    Table("do2015", ("demo-metrics.json",), do2015),
    Table("do2015-tip", ("demo-metrics.json",), do2015_tip),
    Table("lau2015", ("demo-metrics.json",), lau2015),
    Table(
        "performance",
        (
            "models.json",
            "plant.json",
            "identify.json",
            "compensators.json",
            "sweep.json",
            "identify_long.json",
        ),
        performance,
    ),
    Table("realdata-files", ("realdata.json",), realdata_files),
    Table("realdata-interpolation", ("realdata.json",), realdata_interpolation),
    Table("realdata-extrapolation", ("realdata.json",), realdata_extrapolation),
    Table("realdata-amplitude", ("realdata.json",), realdata_amplitude),
]


# -- rewriting README.md ------------------------------------------------------------------


def _markers(name: str) -> tuple[str, str]:
    return f"<!-- table:{name}:begin -->", f"<!-- table:{name}:end -->"


def render(text: str, results: Path = RESULTS, tables: list[Table] = TABLES) -> str:
    """``text`` (README.md's) with every table's marker block regenerated."""
    cache: dict[str, Source] = {}
    for table in tables:
        begin, end = _markers(table.name)
        if text.count(begin) != 1 or text.count(end) != 1:
            raise ResultError(
                f"README.md: expected one '{begin}' and one '{end}' "
                f"(found {text.count(begin)} and {text.count(end)})"
            )
        head, rest = text.split(begin)
        _, tail = rest.split(end)
        for f in table.files:
            if f not in cache:
                cache[f] = Source(results / f)
        sources = [cache[f] for f in table.files]
        body = table.render(*sources).strip("\n")
        text = f"{head}{begin}\n{body}\n{end}{tail}"
    return text


# a quoted figure: <!-- result: FILE KEY.PATH ~ FIGURE -->
RESULT = re.compile(r"<!-- result: (\S+) (\S+) ~ (\S+) -->")
FIGURE = re.compile(r"-?\d+(?:\.\d+)?(?:e[+-]?\d+)?")


def rounds_to(value: float, figure: str) -> bool:
    """Whether ``value`` rounded to the digits ``figure`` shows is ``figure``."""
    mantissa, _, exponent = figure.lower().partition("e")
    digits = len(mantissa.partition(".")[2])
    shown = f"{value:.{digits}e}" if exponent else f"{value:.{digits}f}"
    return float(shown) == float(figure)


def figures_wrong(text: str, results: Path = RESULTS, page: str = "README.md") -> list[str]:
    """Every ``result:`` marker of ``text`` (README.md's, or ``page``'s) whose figure is not its
    result file's, one line each (a missing file or key raises ResultError)."""
    cache: dict[str, Source] = {}
    wrong, since, end = [], 0, 0
    for m in RESULT.finditer(text):
        if text[end : m.start()].strip():  # not the next of a group of markers: a new text
            since = end
        end = m.end()
        name, key, figure = m.groups()
        if name not in cache:
            cache[name] = Source(results / name)
        parts = [int(k) if re.fullmatch(r"-?\d+", k) else k for k in key.split(".")]
        value = cache[name].num(*parts)
        where = f"{page}: {name} {key}"
        if not FIGURE.fullmatch(figure):
            wrong.append(f"{where}: {figure!r} is not a figure")
        elif not re.search(rf"(?<![\d.]){re.escape(figure)}(?![\d])", text[since : m.start()]):
            wrong.append(f"{where}: the text before the marker no longer quotes {figure}")
        elif not rounds_to(value, figure):
            wrong.append(f"{where} is {value:.6g}; the text quotes {figure}")
    return wrong


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="do not write; exit 1 on a diff")
    ap.add_argument("--readme", type=Path, default=README)
    ap.add_argument("--results", type=Path, default=RESULTS)
    args = ap.parse_args(argv)
    try:
        current = args.readme.read_text()
        new = render(current, args.results)
        wrong = figures_wrong(current, args.results)
    except (ResultError, OSError) as exc:
        print(f"readme_tables: error: {exc}", file=sys.stderr)
        return 2
    if wrong:  # a figure in the prose is the writer's to fix: never rewritten
        print("\n".join(wrong))
        print(f"{_display(args.readme)}: {len(wrong)} quoted figure(s) differ from their results")
        return 1
    if args.check:
        if new == current:
            print(f"{_display(args.readme)}: tables up to date")
            return 0
        diff = difflib.unified_diff(
            current.splitlines(keepends=True),
            new.splitlines(keepends=True),
            f"{_display(args.readme)} (committed)",
            f"{_display(args.readme)} (generated)",
        )
        sys.stdout.writelines(diff)
        print(f"\n{_display(args.readme)} differs from its result files: run `{SCRIPT}`")
        return 1
    if new != current:
        args.readme.write_text(new)
        print(f"rewrote {_display(args.readme)}")
    else:
        print(f"{_display(args.readme)}: tables up to date")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
