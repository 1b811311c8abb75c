"""The global search every identification path shares: SciPy's differential evolution with each
generation evaluated in one batched call (:func:`global_search`), its progress bar, the deadline
a comparison of models sets over all its candidates (:data:`SEARCH_DEADLINE`), and the search
followed by least-squares refinement of a separable problem (:func:`search_and_refine`)."""

from __future__ import annotations

import time
from contextvars import ContextVar

import numpy as np

from .._util.progress import StepProgress
from .refine import refine
from .settings import Search

__all__ = ["PENALTY", "SEARCH_DEADLINE", "global_search", "search_and_refine"]


PENALTY = 1e100  # cost of invalid candidates (finite: DE squares energies)


#: a time.perf_counter() instant past which every global search stops after its generation
#: and keeps its best so far (set by compare_models' time budget; None: no deadline)
SEARCH_DEADLINE: ContextVar[float | None] = ContextVar("SEARCH_DEADLINE", default=None)


class _Progress:
    """The shared progress bar (generations, best cost, ETA), shown only when the search lasts
    more than a second and the output is a terminal."""

    def __init__(self, enabled: bool, title: str, total: int):
        self.enabled = enabled
        self.title = title
        self.total = total
        self.start = time.perf_counter()
        self.bar: StepProgress | None = None
        self.shown = 0  # generations counted on the bar

    def update(self, generation: int, best: float) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            if time.perf_counter() - self.start < 1.0:
                return
            self.bar = StepProgress(True, self.total, self.title, "generations")
        self.bar.show(f"{self.title}  best cost {best:.4g}")
        self.bar.advance(generation - self.shown)
        self.shown = generation

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def global_search(problem, space, counter, label, search: Search, *, x0=None):
    """SciPy's differential evolution over ``space`` (search coordinates), each generation
    evaluated in one batched call of ``problem.cost``; invalid candidates cost PENALTY. Stops
    after the generation in which ``search.budget`` runs out."""
    from scipy.optimize import differential_evolution

    def population(U: np.ndarray) -> np.ndarray:  # U: (D, S) in search coordinates
        C = space.natural(np.asarray(U).T)
        counter["evaluations"] += C.shape[0]
        costs = problem.cost(C)
        return np.where(np.isfinite(costs), costs, PENALTY)

    bar = _Progress(search.progress, label, search.maxiter)
    generation = {"n": 0}
    budget = search.budget

    def callback(intermediate_result):
        generation["n"] += 1
        bar.update(generation["n"], float(intermediate_result.fun))
        deadline = SEARCH_DEADLINE.get()  # compare_models' budget over all candidates
        over_deadline = deadline is not None and time.perf_counter() > deadline
        return over_deadline or (budget is not None and budget.over())  # True stops DE

    try:
        return differential_evolution(
            population,
            list(zip(space.lower, space.upper, strict=True)),
            vectorized=True,
            updating="deferred",
            popsize=search.popsize,
            maxiter=search.maxiter,
            tol=search.tol,
            seed=search.seed,
            polish=False,
            init="latinhypercube",
            x0=x0,
            callback=callback,
        )
    finally:
        bar.close()


def search_and_refine(problem, space, counter, label, search: Search, *, search_problem=None):
    """Global search (on ``search_problem``, e.g. thinned records, default ``problem``) then
    least-squares refinement of a separable problem (chains): returns (the best search
    coordinates, the DE result, a message). Raises when no candidate gives a finite
    simulation."""
    res = global_search(search_problem or problem, space, counter, label, search)
    if not np.isfinite(res.fun) or res.fun >= PENALTY:
        raise ValueError("identification failed: no candidate gives a finite simulation")
    u_best = res.x
    message = f"differential evolution: {res.message}"
    budget = search.budget
    if search.polish and space.lower.size and not (budget is not None and budget.over()):
        u_best, msg = refine(
            problem, space, u_best, counter, separable=True, budget=budget, max_nfev=200
        )
        message += f"; least squares: {msg}"
    return u_best, res, message
