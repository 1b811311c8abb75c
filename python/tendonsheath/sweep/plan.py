"""The full list of runs, built from the seed before any work starts.

Run i's random draws come from its own child seed, ``SeedSequence(seed, spawn_key=(i,))``,
so a run's parameters depend only on (seed, i): not on the engine, the number of workers,
the batching, or ``n`` (the first 100 runs of ``n=200`` are the runs of ``n=100``). Latin
hypercube and Saltelli designs are joint over all runs; they are drawn once from ``seed``.
Parameters are drawn in sorted name order, so the order of a dict does not matter either.
"""

from __future__ import annotations

import secrets
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .distributions import Design, Grid, LatinHypercube, MonteCarlo, Saltelli


def _py(value) -> Any:
    """Plain Python scalars (floats pickle and compare exactly; numpy types are unwrapped)."""
    return value.item() if isinstance(value, np.generic) else value


@dataclass
class Plan:
    """Every run's parameters (``runs[i]`` is run i), and how they were made.

    Parameters
    ----------
    design : Design
        The design the runs were drawn from.
    seed : int
        The seed they were drawn with.
    runs : list of dict
        Each run's parameters, by name.
    drawn : list of str
        The parameters that vary (distributions, or a grid's axes).
    fixed : dict, optional
        The constants passed to every run.
    salib_problem : dict, optional
        SALib's problem definition (Saltelli designs only).
    """

    design: Design
    seed: int
    runs: list[dict[str, Any]]
    drawn: list[str]
    fixed: dict[str, Any] = field(default_factory=dict)
    salib_problem: dict | None = None

    @property
    def unranked(self) -> list[str]:
        """Drawn parameters a sensitivity ranking leaves out (seeds, text choices)."""
        dists = getattr(self.design, "distributions", {})
        return [name for name, d in dists.items() if not d.ranked]

    def __len__(self) -> int:
        return len(self.runs)

    @property
    def kind(self) -> str:
        """The design's kind: "random", "lhs", "saltelli" or "grid"."""
        return self.design.kind


def new_seed() -> int:
    """A fresh seed (63 bits) for a sweep called with seed=None; it is kept in the result."""
    return secrets.randbits(63)


def _check_n(n, kind: str) -> int:
    if n is None:
        raise ValueError(f"sweep: n (the number of {kind} draws) is required for this design")
    if isinstance(n, bool) or int(n) != n or int(n) < 1:
        raise ValueError(f"sweep: n must be a positive integer (got {n!r})")
    return int(n)


def _unit_to_runs(design: Design, names: list[str], u: np.ndarray) -> list[dict[str, Any]]:
    columns = {name: design.distributions[name].ppf(u[:, j]) for j, name in enumerate(names)}
    runs = []
    for i in range(u.shape[0]):
        p = {name: _py(columns[name][i]) for name in design.distributions}
        p.update(design.fixed)
        runs.append(p)
    return runs


def make_plan(design: Design, n: int | None, seed: int | None) -> Plan:
    """All runs of ``design``: ``n`` draws (or the grid), reproducible from ``seed``.

    Parameters
    ----------
    design : Design
        A MonteCarlo, LatinHypercube, Saltelli or Grid design.
    n : int or None
        Number of draws (Saltelli: base samples); None (or the grid's size) for a Grid.
    seed : int or None
        A non-negative seed; None draws a fresh one (kept in the plan).

    Returns
    -------
    Plan
        Every run's parameters.

    Raises
    ------
    ValueError
        A bad seed, n missing or not a positive integer, n not the grid's size, or SALib
        missing for a Saltelli design.
    """
    if seed is None:
        seed = new_seed()
    if isinstance(seed, bool) or int(seed) != seed or int(seed) < 0:
        raise ValueError(f"sweep: seed must be a non-negative integer or None (got {seed!r})")
    seed = int(seed)
    names = sorted(design.distributions)

    if isinstance(design, Grid):
        size = design.size
        if n is not None and n != size:
            raise ValueError(f"sweep: a Grid has {size} runs; n={n} does not match (omit n)")
        axes = list(design.axes)
        runs = []
        for combo in np.ndindex(*[len(design.axes[a]) for a in axes]) if axes else [()]:
            p = {a: _py(design.axes[a][k]) for a, k in zip(axes, combo, strict=True)}
            p.update(design.fixed)
            runs.append(p)
        return Plan(design, seed, runs, drawn=axes, fixed=dict(design.fixed))

    if isinstance(design, LatinHypercube):
        n = _check_n(n, "Latin hypercube")
        from scipy.stats import qmc

        sampler = qmc.LatinHypercube(
            d=len(names), optimization=design.optimization, rng=np.random.default_rng(seed)
        )
        u = sampler.random(n)
        runs = _unit_to_runs(design, names, u)
    elif isinstance(design, Saltelli):
        n = _check_n(n, "Saltelli base")
        try:
            from SALib.sample import sobol as salib_sobol
        except ImportError:  # pragma: no cover - depends on the install
            raise ValueError(
                "sweep: a Saltelli design needs SALib: pip install 'tendonsheath[sweep]'"
            ) from None
        unit_problem = {"num_vars": len(names), "names": names, "bounds": [[0.0, 1.0]] * len(names)}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # SALib warns when n is not a power of 2
            u = salib_sobol.sample(unit_problem, n, calc_second_order=False, seed=seed)
        u = np.clip(u, 1e-12, 1 - 1e-12)
        runs = _unit_to_runs(design, names, u)
        problem = {"num_vars": len(names), "names": names, "bounds": [[0.0, 1.0]] * len(names)}
        return Plan(
            design,
            seed,
            runs,
            drawn=list(design.distributions),
            fixed=dict(design.fixed),
            salib_problem=problem,
        )
    elif isinstance(design, MonteCarlo):
        n = _check_n(n, "random")
        u = np.empty((n, len(names)))
        for i in range(n):
            rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(i,)))
            u[i] = rng.random(len(names))
        runs = _unit_to_runs(design, names, u)
    else:  # pragma: no cover - a new design kind must be added here
        raise ValueError(f"sweep: unknown design {type(design).__name__}")
    return Plan(design, seed, runs, drawn=list(design.distributions), fixed=dict(design.fixed))


__all__ = ["Plan", "make_plan", "new_seed"]
