"""identify(): the thin function over :class:`~tendonsheath.identify.estimator.Identifier`, the
dispatch on the kind of model (normalised, chain, grey-box plant, one model class) and the global
search (differential evolution, batched in C++) every path shares."""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Sequence
from contextvars import ContextVar

import numpy as np
from scipy.optimize import differential_evolution

from .._progress import StepProgress
from ..models import Chain, PlantModel
from ..models.base import _REGISTRY
from .data import Recording, make_recordings
from .fit import Fit
from .refine import TimeBudget, refine
from .settings import Options, Search, check_search_options, with_settings_signature

__all__ = ["check_search_options", "identify", "run"]


_PENALTY = 1e100  # cost of invalid candidates (finite: DE squares energies)


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
        self.bar = None
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
    evaluated in one batched call of ``problem.cost``; invalid candidates cost _PENALTY. Stops
    after the generation in which ``search.budget`` runs out."""

    def population(U: np.ndarray) -> np.ndarray:  # U: (D, S) in search coordinates
        C = space.natural(np.asarray(U).T)
        counter["evaluations"] += C.shape[0]
        costs = problem.cost(C)
        return np.where(np.isfinite(costs), costs, _PENALTY)

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


@with_settings_signature
def identify(
    model_class,
    t=None,
    x=None,
    y=None,
    *,
    recordings: Sequence | None = None,
    curve_angle=None,
    **options,
) -> Fit:
    """Identify a model from input/output recordings by simulation-error minimisation.

    ``identify(cls, t, x, y, **options)`` is ``Identifier(cls, **options).fit(...)``, with the
    Fit returned: see :class:`~tendonsheath.identify.estimator.Identifier` for the options
    (search, refinement, bounds, fixed parameters, standard errors, time budget, ...).

    Data: ``identify(cls, t, x, y)`` (``curve_angle=`` a number or per-sample array for models
    that use it) or ``identify(cls, recordings=[(t, x, y), (t, x, y, curve_angle), ...])``; the
    recordings share the parameters. ``t`` may be None for rate-independent models.
    ``model_class``: a model class, its name, or a Chain instance. An unknown option raises
    TypeError naming it.
    """
    from .estimator import Identifier

    estimator = Identifier(model_class, **options)
    estimator.fit_data(t, x, y, recordings=recordings, curve_angle=curve_angle)
    return estimator.fit_


def run(model_class, recs: list[Recording], options: Options, search: Search) -> Fit:
    """One identification on checked recordings: normalised data, a chain, the grey-box
    plant or one model class (see :mod:`tendonsheath.identify.generic`)."""
    if isinstance(model_class, str) and model_class in _REGISTRY:
        model_class = _REGISTRY[model_class]
    return _stamp(search.budget, _dispatch(model_class, recs, options, search))


def _dispatch(model_class, recs, opt: Options, search: Search) -> Fit:
    from . import normalize as _norm

    if opt.normalize and _norm.applies(
        model_class,
        depends=opt.depends_on_angle,
        bounds=opt.bounds,
        fixed=opt.fixed,
        initial=opt.initial,
    ):
        inner = dataclasses.replace(opt, normalize=False)

        def fit_normalised(cls, normalised_recs):
            return run(cls, make_recordings(recordings=normalised_recs), inner, search)

        return _norm.identify_normalized(fit_normalised, model_class, recs)
    if isinstance(model_class, Chain):
        return _identify_chain(model_class, recs, opt, search)
    if model_class in (PlantModel, "PlantModel"):
        return _identify_plant(recs, opt, search)
    from .generic import identify_class

    return identify_class(model_class, recs, opt, search)


def _identify_chain(chain: Chain, recs, opt: Options, search: Search) -> Fit:
    from .chain import identify_chain

    if opt.depends_on_angle:
        raise ValueError("a Chain's parameters cannot depend on the curve angle")
    return identify_chain(
        chain, recs, warmup=int(opt.warmup), bounds=opt.bounds, fixed=opt.fixed, search=search
    )


def _identify_plant(recs, opt: Options, search: Search) -> Fit:
    from .plant_model import identify_plant

    if opt.depends_on_angle or opt.bounds or opt.fixed:
        raise ValueError("PlantModel: bounds, fixed and depends_on_angle are not supported")
    if opt.initial is not None and not isinstance(opt.initial, PlantModel):
        raise ValueError(f"initial must be a PlantModel (got {type(opt.initial).__name__})")
    return identify_plant(recs, warmup=int(opt.warmup), initial=opt.initial, search=search)


def _stamp(budget: TimeBudget, fit: Fit) -> Fit:
    """Record on the Fit that the time budget stopped a stage (once, for nested calls)."""
    if budget.hit and not fit.stopped_on_budget:
        fit.stopped_on_budget = True
        fit.message += budget.note()
    return fit


def search_and_refine(problem, space, counter, label, search: Search, *, search_problem=None):
    """Global search (on ``search_problem``, e.g. thinned records, default ``problem``) then
    least-squares refinement of a separable problem (chains): returns (the best search
    coordinates, the DE result, a message). Raises when no candidate gives a finite
    simulation."""
    res = global_search(search_problem or problem, space, counter, label, search)
    if not np.isfinite(res.fun) or res.fun >= _PENALTY:
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
