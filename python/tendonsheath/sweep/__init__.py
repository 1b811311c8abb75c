"""Robustness sweeps: Monte Carlo, Latin hypercube, grids and Sobol studies of any run.

    import tendonsheath as ts
    from tendonsheath.sweep import Relative, Integers, LatinHypercube

    res = ts.sweep(run, {"friction": Relative(0.1, 0.3), "pretension": Relative(10, 0.3)},
                   n=200, seed=1)                      # engine="local": all cores
    res = ts.sweep(run, LatinHypercube({...}), n=200, seed=1, engine="tcp://host:8786")
    res.table; res.summary(bound=1e-4); res.sensitivity(); res.save("out/")

``run(params: dict) -> dict[metric, float]`` or ``-> dict[compensator, dict[metric, float]]``
(the table then has a ``compensator`` column); it must be picklable (a top-level function) to
run on a process pool or a Dask cluster, and deterministic given its parameters, so that
the table is reproducible from the seed on any engine and any number of workers.
"""

from .distributions import (
    Choice,
    Design,
    Distribution,
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
from .driver import sweep
from .engines import SweepError
from .plan import Plan, make_plan
from .result import SweepResult
from .studies import robustness_section, robustness_study

# ``tendonsheath.sweep`` (the attribute) is this function, which shadows the subpackage:
# give it the design classes so ``ts.sweep.Relative(0.1, 0.3)`` works as well.
for _name in (
    "Choice",
    "Grid",
    "Integers",
    "LatinHypercube",
    "LogNormal",
    "MonteCarlo",
    "Normal",
    "Relative",
    "Saltelli",
    "Seed",
    "Uniform",
    "SweepResult",
    "SweepError",
):
    setattr(sweep, _name, globals()[_name])
del _name

__all__ = [
    "Choice",
    "Design",
    "Distribution",
    "Grid",
    "Integers",
    "LatinHypercube",
    "LogNormal",
    "MonteCarlo",
    "Normal",
    "Plan",
    "Relative",
    "Saltelli",
    "Seed",
    "SweepError",
    "SweepResult",
    "Uniform",
    "make_plan",
    "robustness_section",
    "robustness_study",
    "sweep",
]
