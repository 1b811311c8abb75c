"""The sweep file of ``tendonsheath sweep sweep.toml``: the scenario plus the distributions.

[run]
function = "tendonsheath.bench.scenarios.do:robustness_run"   # module:function
# or: scenario = "do2015"                                    # a name in SCENARIOS

[sweep]
design = "random"        # random | lhs | grid | saltelli
n = 200                  # draws (saltelli: base samples, n * (d + 2) runs; grid: omit)
seed = 1
# workers = 2            # local engine processes (default: all cores)
# batch_size = 16
# scheduler = "tcp://scheduler:8786"    # Dask; --scheduler overrides
# on_error = "raise"     # or "record"

[parameters]
friction = { relative = [0.1, 0.3] }     # nominal +/- 30 %
pretension = { uniform = [7.0, 13.0] }
stiffness = { normal = [2.4e4, 2e3] }    # or { mean = .., std = .., lo = .., hi = .. }
load = { lognormal = [1.0, 0.3] }        # median, sigma of ln
route_pieces = { integers = [1, 4] }
route_seed = { seed = true }             # a seed per run, not ranked
shape = { choice = ["a", "b"] }
elements = 40                            # a constant
# grid only: x = { values = [1, 2, 3] }, y = { linspace = [0, 1, 5] },
#            z = { geomspace = [1e-3, 1, 4] }

[report]
bound = { mse = 1e-4 }   # or a number for the primary metric (mse)
"""

from __future__ import annotations

import importlib
import tomllib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..io._textread import read_config_text
from .distributions import (
    Choice,
    Design,
    Grid,
    Integers,
    LatinHypercube,
    LogNormal,
    MonteCarlo,
    Normal,
    Relative,
    Saltelli,
    Seed,
    Uniform,
)
from .result import check_bound

#: Named runs for ``[run] scenario = NAME``; the bench scenarios (do2015, ...) belong here.
SCENARIOS: dict[str, str] = {
    "do2015": "tendonsheath.bench.scenarios.do:robustness_run",
}

DESIGNS = {"random": MonteCarlo, "lhs": LatinHypercube, "grid": Grid, "saltelli": Saltelli}
SECTIONS = {"run", "sweep", "parameters", "report"}
SWEEP_KEYS = {"design", "n", "seed", "workers", "batch_size", "scheduler", "on_error", "retries"}


@dataclass
class SweepFile:
    """A parsed sweep file: call ``ts.sweep(run, design, **options)``."""

    path: Path
    run: Callable
    run_name: str
    design: Design
    n: int | None = None
    seed: int | None = None
    workers: int | None = None
    batch_size: int | None = None
    scheduler: str | None = None
    on_error: str = "raise"
    retries: int = 3
    bound: Any = None
    extra: dict = field(default_factory=dict)


def load_run(spec: str) -> Callable:
    """``"package.module:function"`` -> the function (importable, so it pickles to workers)."""
    module, _, attr = spec.partition(":")
    if not module or not attr:
        raise ValueError(f"run function must be 'module:function' (got {spec!r})")
    try:
        mod = importlib.import_module(module)
    except ImportError as exc:
        raise ValueError(f"cannot import the run's module {module!r}: {exc}") from None
    obj = mod
    for part in attr.split("."):
        if not hasattr(obj, part):
            raise ValueError(f"{module!r} has no {attr!r}")
        obj = getattr(obj, part)
    if not callable(obj):
        raise ValueError(f"{spec!r} is not callable")
    return obj


def _pair(name, key, value, size=2):
    if not isinstance(value, list) or len(value) != size:
        raise ValueError(f"[parameters] {name}: {key} needs a list of {size} numbers")
    return value


def parse_parameter(name: str, value, design_kind: str):
    """One [parameters] entry -> a Distribution, a grid axis (list) or a constant."""
    if not isinstance(value, dict):
        if isinstance(value, list):
            if design_kind == "grid":
                return value
            raise ValueError(
                f"[parameters] {name}: a plain list is ambiguous; write "
                f"{{ choice = [...] }} (a random pick) or use design = 'grid'"
            )
        return value  # a constant
    if design_kind == "grid":
        if set(value) == {"values"}:
            return list(value["values"])
        if set(value) == {"linspace"}:
            lo, hi, k = _pair(name, "linspace", value["linspace"], 3)
            return np.linspace(lo, hi, int(k)).tolist()
        if set(value) == {"geomspace"}:
            lo, hi, k = _pair(name, "geomspace", value["geomspace"], 3)
            return np.geomspace(lo, hi, int(k)).tolist()
        raise ValueError(
            f"[parameters] {name}: a grid takes {{ values = [...] }}, {{ linspace = [lo, hi, k] "
            f"}} or {{ geomspace = [lo, hi, k] }} (got {sorted(value)})"
        )
    if set(value) <= {"mean", "std", "lo", "hi"} and {"mean", "std"} <= set(value):
        return Normal(value["mean"], value["std"], value.get("lo"), value.get("hi"))
    if len(value) != 1:
        raise ValueError(f"[parameters] {name}: one distribution per parameter (got {value})")
    ((kind, args),) = value.items()
    makers = {
        "uniform": lambda a: Uniform(*_pair(name, kind, a)),
        "relative": lambda a: Relative(*_pair(name, kind, a)),
        "normal": lambda a: Normal(*_pair(name, kind, a)),
        "lognormal": lambda a: LogNormal(*_pair(name, kind, a)),
        "integers": lambda a: Integers(*_pair(name, kind, a)),
        "choice": lambda a: Choice(a),
        "seed": lambda a: Seed(),
    }
    if kind not in makers:
        raise ValueError(
            f"[parameters] {name}: unknown distribution {kind!r}; use one of {sorted(makers)}"
        )
    try:
        return makers[kind](args)
    except ValueError as exc:
        raise ValueError(f"[parameters] {name}: {exc}") from None


def read_sweep_file(path) -> SweepFile:
    """Parse and check a sweep file; every mistake is a ValueError naming the entry."""
    path = Path(path)
    try:
        data = tomllib.loads(read_config_text(path, "a sweep file (TOML)"))
    except FileNotFoundError:
        raise ValueError(f"{path}: no such file") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML ({exc})") from None
    unknown = set(data) - SECTIONS
    if unknown:
        raise ValueError(f"{path}: unknown section(s) {sorted(unknown)}; known: {sorted(SECTIONS)}")
    run_sec = data.get("run", {})
    if set(run_sec) - {"function", "scenario"} or len(run_sec) != 1:
        raise ValueError(f"{path}: [run] needs exactly one of function = 'module:function' or "
                         f"scenario = one of {sorted(SCENARIOS)}")  # fmt: skip
    if "scenario" in run_sec:
        name = run_sec["scenario"]
        if name not in SCENARIOS:
            raise ValueError(f"{path}: unknown scenario {name!r}; known: {sorted(SCENARIOS)}")
        spec = SCENARIOS[name]
    else:
        spec = name = run_sec["function"]
    run = load_run(spec)

    sw = data.get("sweep", {})
    bad = set(sw) - SWEEP_KEYS
    if bad:
        raise ValueError(
            f"{path}: unknown [sweep] key(s) {sorted(bad)}; known: {sorted(SWEEP_KEYS)}"
        )
    kind = sw.get("design", "random")
    if kind not in DESIGNS:
        raise ValueError(f"{path}: [sweep] design must be one of {sorted(DESIGNS)} (got {kind!r})")
    params = data.get("parameters", {})
    if not params:
        raise ValueError(f"{path}: [parameters] is empty: nothing to sweep")
    try:
        parsed = {k: parse_parameter(k, v, kind) for k, v in params.items()}
        design = DESIGNS[kind](parsed)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
    report = data.get("report", {})
    if set(report) - {"bound"}:
        raise ValueError(f"{path}: unknown [report] key(s) {sorted(set(report) - {'bound'})}")
    try:
        check_bound(report.get("bound"))
    except ValueError as exc:
        raise ValueError(f"{path} [report]: {exc}") from None
    return SweepFile(
        path=path,
        run=run,
        run_name=name,
        design=design,
        n=sw.get("n"),
        seed=sw.get("seed"),
        workers=sw.get("workers"),
        batch_size=sw.get("batch_size"),
        scheduler=sw.get("scheduler"),
        on_error=sw.get("on_error", "raise"),
        retries=sw.get("retries", 3),
        bound=report.get("bound"),
    )


__all__ = [
    "DESIGNS",
    "SCENARIOS",
    "SECTIONS",
    "SWEEP_KEYS",
    "SweepFile",
    "load_run",
    "parse_parameter",
    "read_sweep_file",
]
