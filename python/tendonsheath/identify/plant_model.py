"""Identification of the grey-box :class:`~tendonsheath.models.PlantModel`.

The output map (gain, offset) is linear given the plant's output, so it is solved by least
squares for every candidate (variable projection, as for the chains); the search covers the
three physical groups (friction angle, backlash, viscous time). Each candidate is one C++
plant simulation per recording; a population is spread over threads (the simulation releases
the GIL). The search is a short differential evolution (at most ``SEARCH_MAXITER``
generations of ``SEARCH_POPSIZE`` per parameter: three smooth parameters, each evaluation a
full plant simulation), then the shared least-squares refinement.
"""

from __future__ import annotations

import dataclasses
import os
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..models import PlantModel
from .data import check_for_fit, fitted_mask
from .fit import Fit, fit_quality, simulate_model
from .problem import Space
from .search import search_and_refine
from .specs import Scale
from .uncertainty import assess

SEARCH_NAMES = ("friction_angle", "backlash", "viscous_time")
SEARCH_MAXITER = 25
SEARCH_POPSIZE = 6
_PENALTY = 1e100


class PlantProblem:
    """Search the physical groups; solve the output gain and offset for every candidate."""

    def __init__(self, recs, warmup: int, workers: int, elements: int):
        for i, r in enumerate(recs):
            if r.t is None:
                raise ValueError(f"recording {i}: PlantModel is rate-dependent: t is required")
        self.recs = recs
        self.warmup = warmup
        self.elements = elements
        s = Scale.of(recs)
        dt = s.sample_time or 1e-3
        self.bounds = {
            "friction_angle": (0.02, 15.0),
            "backlash": (1e-3 * s.x_range, 0.5 * s.x_range),
            "viscous_time": (0.1 * dt, max(s.duration or 1.0, 10 * dt)),
        }
        self.space = Space(SEARCH_NAMES, self.bounds, set(SEARCH_NAMES))
        self.y_all = np.concatenate([r.y for r in recs])
        self.mask = fitted_mask(recs, warmup)
        self.y = self.y_all[self.mask]
        n = workers if workers > 0 else (os.cpu_count() or 1)
        self.pool = ThreadPoolExecutor(n) if n > 1 else None

    def _plant(self, c: np.ndarray) -> PlantModel:
        values = dict(zip(SEARCH_NAMES, (float(v) for v in c), strict=True))
        return PlantModel(**values, elements=self.elements)

    def linear(self, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(gain, offset) by least squares and the residual at the physical groups c."""
        try:
            m = self._plant(c)
            q = np.concatenate([m.simulate(r.t, r.x) for r in self.recs])[self.mask]
        except ValueError:
            q = np.full(self.y.size, np.nan)
        A = np.column_stack([q, np.ones_like(q)])
        if not np.all(np.isfinite(A)) or not np.ptp(q) > 0:
            return np.full(2, np.nan), np.full(self.y.size, 1e6 * (np.ptp(self.y) + 1.0))
        theta = np.linalg.lstsq(A, self.y, rcond=None)[0]
        return theta, self.y - A @ theta

    def _one_cost(self, c: np.ndarray) -> float:
        theta, r = self.linear(c)
        return float(r @ r) if np.all(np.isfinite(theta)) else _PENALTY

    def cost(self, C: np.ndarray) -> np.ndarray:
        if self.pool is None:
            return np.array([self._one_cost(c) for c in C])
        return np.array(list(self.pool.map(self._one_cost, C)))

    def residual(self, c: np.ndarray) -> np.ndarray:
        return self.linear(c)[1]

    def model(self, c: np.ndarray) -> PlantModel:
        theta, _ = self.linear(c)
        if not np.all(np.isfinite(theta)) or theta[0] == 0:
            raise ValueError("identification failed: the plant's output does not move")
        return self._plant(c).with_params(gain=float(theta[0]), offset=float(theta[1]))

    def close(self) -> None:
        if self.pool is not None:
            self.pool.shutdown()
            self.pool = None


def identify_plant(recs, *, warmup=0, initial=None, search) -> Fit:
    """Identify a :class:`PlantModel` (see the module docstring) with the
    :class:`~tendonsheath.identify.settings.Search` settings ``search`` (its generations and
    population capped); returns a :class:`Fit`."""

    elements = (initial or PlantModel()).options["elements"]
    problem = PlantProblem(recs, warmup, search.n_workers, elements)
    check_for_fit(recs, warmup, len(PlantModel.param_names), True, False)
    counter = {"evaluations": 0}
    capped = dataclasses.replace(
        search,
        maxiter=min(search.maxiter, SEARCH_MAXITER),
        popsize=min(search.popsize, SEARCH_POPSIZE),
    )
    start = time.perf_counter()
    try:
        u_best, res, message = search_and_refine(
            problem, problem.space, counter, "identify PlantModel", capped
        )
        model = problem.model(problem.space.natural(u_best))
    finally:
        problem.close()
    seconds = time.perf_counter() - start
    predictions = [simulate_model(model, r.t, r.x) for r in recs]
    quality = fit_quality(recs, predictions, warmup)
    fit = Fit.from_quality(
        model,
        quality,
        _assess(problem, recs, warmup, model, quality, u_best, search),
        identified=list(PlantModel.param_names),
        fixed={},
        evaluations=counter["evaluations"],
        seconds=seconds,
        generations=int(res.nit),
        method="differential evolution + least squares (grey-box plant: output map solved)",
        message=message,
        warmup=warmup,
        bounds=dict(problem.bounds),
        recordings=recs,
        predictions=predictions,
    )
    fit.diagnostics.warn()
    return fit


def _assess(problem, recs, warmup, model, quality, u_best, search) -> dict:
    """Standard errors and diagnostics w.r.t. the plant model's parameters."""

    return assess(
        cls=PlantModel,
        model=model,
        problem=problem,
        recs=recs,
        warmup=warmup,
        values={},
        free_names=[],
        all_bounds={},
        spec=None,
        options={},
        depends={},
        workers=search.n_workers,
        sse=quality.sse,
        n_fit=quality.n,
        u_best=u_best,
        use_separable=False,
        method=search.standard_errors,
        count=search.bootstrap,
        block=search.bootstrap_block,
        seed=search.seed,
        generic=(list(PlantModel.param_names), []),
    )


__all__ = ["PlantProblem", "SEARCH_MAXITER", "SEARCH_NAMES", "SEARCH_POPSIZE", "identify_plant"]
