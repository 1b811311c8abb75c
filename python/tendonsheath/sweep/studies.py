"""Built-in studies for the demo's report: robustness of each compensator, not one lucky run.

:func:`robustness_study` runs each compensator over 200 draws of friction (+/-30 %),
pretension (+/-30 %) and route (random arcs: 1 to 4 pieces, a random split of a total
curve angle drawn within +/-50 % of nominal); :func:`robustness_section` turns the result
into the report's figure and numbers. The run is any sweep run that takes these parameter
names (``friction``, ``pretension``, ``route_angle``, ``route_pieces``, ``route_seed``): the
demo passes the do2015 scenario's
:func:`~tendonsheath.bench.scenarios.do.robustness_run`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.atomic import save_figure
from ..report.units import check_angle_unit, convert, header, unit_after, unit_of_key
from .distributions import Integers, MonteCarlo, Relative, Seed
from .driver import sweep

if TYPE_CHECKING:
    from dask.distributed import Client

    from .result import SweepResult

ROBUSTNESS_RUNS = 200
ROBUSTNESS_SEED = 2015


def robustness_design(
    friction: float = 0.1,
    pretension: float = 10.0,
    route_angle: float = math.pi,
    spread: float = 0.3,
    **fixed,
) -> MonteCarlo:
    """Friction and pretension within +/- ``spread`` of nominal; a random-arc route whose
    total angle is within +/-50 % of nominal; ``fixed`` are constants passed to every run."""
    return MonteCarlo(
        {
            "friction": Relative(friction, spread),
            "pretension": Relative(pretension, spread),
            "route_angle": Relative(route_angle, 0.5),
            "route_pieces": Integers(1, 4),
            "route_seed": Seed(),
            **fixed,
        }
    )


def robustness_study(
    run: Callable[[dict], Mapping],
    n: int = ROBUSTNESS_RUNS,
    seed: int = ROBUSTNESS_SEED,
    engine: str | Client = "local",
    design: MonteCarlo | None = None,
    **sweep_options: Any,
) -> SweepResult:
    """Each compensator's metrics over ``n`` perturbed plants (a :class:`SweepResult`).

    Parameters
    ----------
    run : callable
        The run: perturbed parameters in, each compensator's metrics out (for example
        :func:`tendonsheath.bench.scenarios.do.robustness_run`).
    n : int, default 200
        Number of perturbed plants.
    seed : int, default 2015
        The sweep's seed.
    engine : str or dask.distributed.Client, default "local"
        As for :func:`tendonsheath.sweep`.
    design : MonteCarlo, optional
        The perturbations (default :func:`robustness_design`).
    **sweep_options
        Other keywords of :func:`tendonsheath.sweep`.

    Returns
    -------
    SweepResult
        The runs' metrics.
    """
    return sweep(run, design or robustness_design(), n=n, seed=seed, engine=engine,
                 **sweep_options)  # fmt: skip


def robustness_section(
    result: SweepResult,
    out_dir: str | Path,
    metric: str = "mse",
    bound: float | None = None,
    design: MonteCarlo | None = None,
    angle_unit: str = "rad",
) -> dict:
    """The report's robustness figure (robustness_<metric>.png: the spread of ``metric`` per
    compensator, log scale) and numbers: quantiles per compensator and, with ``bound``, the
    fraction of runs within it. ``design``: the design that ran (written to the numbers;
    without it only the result's design name is known).

    Parameters
    ----------
    result : SweepResult
        A robustness study's result.
    out_dir : str or Path
        Where the figure goes.
    metric : str, default "mse"
        The metric shown.
    bound : float, optional
        A bound on the metric, drawn and counted.
    design : MonteCarlo, optional
        The design that ran.
    angle_unit : {"rad", "deg"}, default "rad"
        The figure's unit for an angle metric (the numbers returned stay in radians).

    Returns
    -------
    dict
        runs, seed, design, metric, bound, per-compensator quantiles and the figure's path.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    check_angle_unit(angle_unit)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary = result.summary({metric: bound} if bound is not None else None)
    summary = summary[summary["metric"] == metric]
    groups = list(result._groups())
    fig, ax = plt.subplots(figsize=(6.5, 3.8))
    unit = unit_of_key(metric)
    factor = convert(1.0, unit, angle_unit)  # radians to the report's unit (1 for others)
    data = [factor * g[metric].dropna().to_numpy() for _, g in groups]
    ax.boxplot(data, whis=(5, 95), showfliers=True, flierprops={"markersize": 2})
    ax.set_xticks(range(1, len(groups) + 1), [c for c, _ in groups])
    positive = all(d.size and np.all(d > 0) for d in data)
    if positive:
        ax.set_yscale("log")
    if bound is not None:
        shown = factor * bound
        ax.axhline(shown, color="r", ls="--", lw=1, label=f"bound {shown:.3g}")
        ax.legend(fontsize="small")
    ax.set_ylabel(header(metric, unit_after(unit, angle_unit)))
    ax.set_title(
        f"{metric} over {result.n_runs} perturbed plants (box: quartiles, whiskers: 5-95 %)",
        fontsize="medium",
    )
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    path = out / f"robustness_{metric}.png"
    save_figure(fig, path, dpi=120)
    plt.close(fig)

    def clean(v):
        return None if isinstance(v, float) and not math.isfinite(v) else v

    return {
        "runs": result.n_runs,
        "seed": result.seed,
        "design": (
            {name: repr(d) for name, d in design.distributions.items()}
            if design is not None
            else {"name": str(result.design)}
        ),
        "metric": metric,
        "bound": bound,
        "compensators": {
            row["compensator"]: {
                **{
                    k: clean(float(row[k]))
                    for k in ("median", "q05", "q95", "max", "within_bound")
                    if k in row
                },
                **_limit_cycle_share(groups, row["compensator"]),
            }
            for _, row in summary.iterrows()
        },
        "figure": str(path),
    }


def _limit_cycle_share(groups: list, compensator: str) -> dict[str, float]:
    """The share of a compensator's runs with a limit cycle, where the run reports one (the
    ``limit_cycle`` metric, 1 or 0)."""
    for name, g in groups:
        if name == compensator and "limit_cycle" in g:
            return {"limit_cycle_share": float(g["limit_cycle"].mean())}
    return {}


__all__ = [
    "ROBUSTNESS_RUNS",
    "ROBUSTNESS_SEED",
    "robustness_design",
    "robustness_section",
    "robustness_study",
]
