"""identify(): global search (differential evolution, batched in C++) then local refinement."""

from __future__ import annotations

import time
from collections.abc import Iterable, Sequence
from contextvars import ContextVar

import numpy as np
from scipy.optimize import differential_evolution

from .._progress import StepProgress
from ..models import (
    Chain,
    GeneralizedPrandtlIshlinskii,
    HysteresisModel,
    HystereticOscillator,
    PlantModel,
    PrandtlIshlinskii,
)
from ..models.base import _REGISTRY
from .data import check_for_fit, make_recordings, search_windows, thin_for_search
from .fit import Fit, fit_quality, simulate_model
from .problem import DirectProblem, SeparableProblem, law_check
from .refine import TimeBudget, refine
from .specs import SPECS, GeneralizedPrandtlIshlinskiiSpec, PrandtlIshlinskiiSpec, Scale

GPI_PLAYS = 10  # default number of plays of an identified GeneralizedPrandtlIshlinskii


def check_search_options(*, maxiter, popsize, tol, workers, warmup) -> None:
    """The global search's settings, checked once with a message naming the option."""
    counts = (("maxiter", maxiter, 0), ("popsize", popsize, 1), ("warmup", warmup, 0))
    for name, value, low in counts:
        if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low:
            raise ValueError(f"{name} must be an integer >= {low} (got {value!r})")
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int | np.integer) or workers < 1
    ):
        raise ValueError(f"workers must be an integer >= 1 or None (got {workers!r})")
    if isinstance(tol, bool) or not isinstance(tol, int | float) or not tol >= 0:
        raise ValueError(f"tol must be a number >= 0 (got {tol!r})")


def _model_class(model_class) -> type[HysteresisModel]:
    if isinstance(model_class, HysteresisModel):
        raise ValueError(
            f"identify takes a model class, e.g. {type(model_class).__name__}, not an instance "
            f"({model_class!r}); give starting values with initial="
        )
    if isinstance(model_class, str):
        if model_class not in _REGISTRY:
            raise ValueError(f"unknown model {model_class!r}; known: {sorted(SPECS_BY_NAME)}")
        model_class = _REGISTRY[model_class]
    if model_class not in SPECS:
        raise ValueError(
            f"cannot identify {getattr(model_class, '__name__', model_class)}; "
            f"identifiable models: {sorted(SPECS_BY_NAME)}"
        )
    return model_class


SPECS_BY_NAME = {cls.__name__: cls for cls in SPECS}
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


def global_search(
    problem, space, counter, label, progress, *, maxiter, popsize, tol, seed, x0=None, budget=None
):
    """SciPy's differential evolution over ``space`` (search coordinates), each generation
    evaluated in one batched call of ``problem.cost``; invalid candidates cost _PENALTY. Stops
    after the generation in which ``budget`` (a TimeBudget) runs out."""

    def population(U: np.ndarray) -> np.ndarray:  # U: (D, S) in search coordinates
        C = space.natural(np.asarray(U).T)
        counter["evaluations"] += C.shape[0]
        costs = problem.cost(C)
        return np.where(np.isfinite(costs), costs, _PENALTY)

    bar = _Progress(progress, label, maxiter)
    generation = {"n": 0}

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
            popsize=popsize,
            maxiter=maxiter,
            tol=tol,
            seed=seed,
            polish=False,
            init="latinhypercube",
            x0=x0,
            callback=callback,
        )
    finally:
        bar.close()


def identify(
    model_class,
    t=None,
    x=None,
    y=None,
    *,
    recordings: Sequence | None = None,
    curve_angle=None,
    warmup: int = 0,
    bounds: dict[str, tuple[float, float]] | None = None,
    fixed: dict[str, float] | None = None,
    free: Iterable[str] | None = None,
    initial: HysteresisModel | None = None,
    depends_on_angle: dict[str, str] | None = None,
    seed: int | None = 0,
    maxiter: int = 100,
    popsize: int = 15,
    tol: float = 0.01,
    workers: int | None = None,
    polish: bool = True,
    separable: bool = True,
    progress: bool = True,
    search_samples: int | None = 200_000,
    time_budget: float | None = None,
    input_interpolation: str | None = None,
    periodic: bool | None = None,
    strategy: str = "auto",
    normalize: bool = True,
    standard_errors: str = "linearised",
    bootstrap: int | None = None,
    bootstrap_block: int | None = None,
) -> Fit:
    """Identify a model from input/output recordings by simulation-error minimisation.

    Data: ``identify(cls, t, x, y)`` (``curve_angle=`` a number or per-sample array for models
    that use it) or ``identify(cls, recordings=[(t, x, y), (t, x, y, curve_angle), ...])``; the
    recordings share the parameters. ``t`` may be None for rate-independent models.

    The cost is the sum of squared simulation errors (the model runs free from its initial
    state; the first ``warmup`` samples of every recording are not counted). A global search
    by SciPy's differential evolution (``popsize``, ``maxiter``, ``tol``, ``seed``: seeded and
    reproducible) evaluates each generation in one batched C++ call spread over ``workers``
    threads (default: all cores), then ``scipy.optimize.least_squares`` refines the best
    candidate (``polish=False`` skips it). Bounds are derived from the data's scale unless
    given in ``bounds`` ({name: (low, high)}); some are searched on a log scale.

    Long records: the global search only has to find the basin, so when the recordings hold
    more than ``search_samples`` samples (default 200 000; None: no limit) it runs on 8 evenly
    spaced windows per recording counting that many samples (each window starts from the
    model's rest state, with a warm-up of a fifth of its length); the refinement and
    everything after it use every sample. A rate-independent model's search runs on the
    records thinned to about 2 000 samples (every m-th sample, m <= 20, and every turning
    point of the input; see :func:`~tendonsheath.identify.data.thin_for_search`).
    The cost per evaluation is linear in the samples and
    memory grows linearly with them (no candidate's output is kept during the search).

    Linear-in-parameter parts are solved by least squares instead of searched (``separable``):
    BoucWenBacklash (c_r, c_l, c_r B_r, c_l B_l given rho, sigma, n), BoucWen (a, (1-a) k
    given the state z) and PrandtlIshlinskii (the weights, given the threshold scale).

    ``fixed`` holds parameters at given values; some are held by default because they are
    not identifiable from input/output data (BoucWen: A; HystereticOscillator: beta;
    CurveAngleModel: pretension, length, radii and spring); ``free`` releases those.
    ``initial`` supplies the values of held parameters and the numerical options (for
    PrandtlIshlinskii: the threshold pattern, whose scale is identified).

    ``depends_on_angle`` ({name: "constant" | "linear" | "tanh"}) makes parameters functions
    of the curve angle (one constant angle per recording); the result is then an
    :class:`~tendonsheath.models.AngleDependent` model that predicts at any angle.

    ``model_class`` may also be a :class:`~tendonsheath.models.Chain` instance, e.g.
    ``Chain(BoucWenBacklash(), Polynomial(3))``: the first model's nonlinear parameters are
    searched (its output scale held, the polynomial carries it) and the polynomial
    coefficients are solved by least squares for every candidate (see
    :func:`~tendonsheath.identify.chain.identify_chain`).

    HystereticOscillator (``strategy="auto"``): best linear approximation, then an
    equation-error stage, then simulation-error least squares (see
    :mod:`tendonsheath.identify.oscillator`); ``strategy="search"`` runs the plain
    differential evolution instead. ``input_interpolation`` ("hold", "linear",
    "bandlimited"; default: ``initial``'s) is the input reconstruction between samples,
    recorded in the fitted model's options and the Fit's method; ``periodic`` says whether
    the records are whole periods (None: detected) for the band-limited reconstruction;
    ``time_budget`` (seconds of wall clock, every model and chain): the global search stops
    after the generation in which it runs out and the least-squares stage at its next
    evaluation, keeping the best point so far; ``fit.stopped_on_budget`` records it and
    ``fit.message`` says so. Standard errors and diagnostics are computed after it, outside
    the budget.

    PlantModel (the grey-box pull-pull plant): friction angle, backlash and viscous time are
    searched by a short differential evolution (at most 25 generations of 6 per parameter:
    each candidate is a plant simulation) and refined by least squares; the output gain and
    offset are solved by least squares for every candidate (see
    :mod:`tendonsheath.identify.plant_model`). ``bounds``, ``fixed`` and ``depends_on_angle``
    are not supported for it; ``initial`` sets its element count.

    GeneralizedPrandtlIshlinskii: the envelopes and the threshold scale are searched, the
    weights (>= 0) and an output offset are solved by bounded least squares; ``initial``
    gives the number of plays and the threshold pattern (default 10 evenly spaced plays).

    Any sign, offset and units (``normalize``, default on): Backlash, BoucWenBacklash,
    PrandtlIshlinskii, GeneralizedPrandtlIshlinskii and Chains of a (Bouc-Wen)
    backlash and a polynomial are fitted on centred, scaled data with a positive gain and
    mapped back (see :mod:`tendonsheath.identify.normalize`): into the class's own parameters
    where exact, otherwise as a :class:`~tendonsheath.models.Scaled` model (e.g. a negative
    gain). Not applied with ``bounds``, ``fixed`` or ``depends_on_angle`` (raw units).

    Uncertainty and identifiability (:mod:`tendonsheath.identify.diagnostics`): every Fit
    carries ``standard_errors`` (``standard_errors="linearised"``: from the Jacobian at the
    optimum; ``"bootstrap"``: the spread of ``bootstrap`` (default 200) moving-block
    bootstrap resamples of the residuals, each re-fitted by least squares from the estimate,
    seeded by ``seed``, blocks of ``bootstrap_block`` samples (default from the residual's
    autocorrelation); ``"bootstrap-recordings"``: resamples of the recordings, drawn with
    replacement (for many recordings); ``"none"``) and ``diagnostics`` (parameters near
    their bounds, correlations, condition number); an :class:`IdentifiabilityWarning` names
    the parameters involved. CurveAngleModel recordings that cover a single curve angle
    cannot separate friction from EA: the friction is then held (at ``initial``'s value, 0.1
    by default, unless given in ``fixed``), with a warning, and the identifiable groups
    (dead-zone half-width, load offset, gain at that angle) are reported in ``fit.groups``.

    Parameters
    ----------
    model_class : type or Chain
        The model class (e.g. ``BoucWenBacklash``), or a Chain instance.
    t : array_like of float, shape (n,), optional
        Sample times (s); None for a rate-independent model.
    x : array_like of float, shape (n,), optional
        Input samples (or give ``recordings``).
    y : array_like of float, shape (n,), optional
        Output samples.
    recordings : sequence of tuple, optional
        (t, x, y) or (t, x, y, curve_angle) per recording, instead of t, x, y.
    curve_angle : float or array_like of float, optional
        The curve angle (rad) of t, x, y, for models that take one.
    warmup : int, default 0
        Samples at the start of every recording left out of the cost.
    bounds : dict of str to (float, float), optional
        Search bounds by parameter (default from the data's scale).
    fixed : dict of str to float, optional
        Parameters held at given values.
    free : iterable of str, optional
        Parameters held by default that are to be identified.
    initial : HysteresisModel, optional
        Values of held parameters and numerical options.
    depends_on_angle : dict of str to str, optional
        Parameter -> "constant", "linear" or "tanh" law of the curve angle.
    seed : int or None, default 0
        Seed of the search (and of the bootstrap).
    maxiter : int, default 100
        Generations of differential evolution.
    popsize : int, default 15
        Population per parameter.
    tol : float, default 0.01
        Relative tolerance of the search.
    workers : int, optional
        Threads of the batched simulations (default all cores).
    polish : bool, default True
        Refine the search's best candidate by least squares.
    separable : bool, default True
        Solve linear-in-parameter parts by least squares.
    progress : bool, default True
        Show a progress bar.
    search_samples : int or None, default 200000
        Samples the global search runs on at most (None: no limit).
    time_budget : float, optional
        Seconds of wall clock for the search and the refinement.
    input_interpolation : {"hold", "linear", "bandlimited"}, optional
        The input reconstruction between samples.
    periodic : bool, optional
        Whether the records are whole periods (None: detected).
    strategy : {"auto", "search"}, default "auto"
        HystereticOscillator's path.
    normalize : bool, default True
        Fit on centred, scaled data and map back.
    standard_errors : {"linearised", "bootstrap", "bootstrap-recordings", "none"}
        How the standard errors are obtained (default "linearised").
    bootstrap : int, optional
        Bootstrap resamples (default 200).
    bootstrap_block : int, optional
        Block length of the residual bootstrap (default from the autocorrelation).

    Returns
    -------
    Fit
        The identified model, its errors, standard errors and diagnostics.

    Raises
    ------
    ValueError
        Bad data or arguments (the message names them), or an option the model does not
        support.
    """
    from .uncertainty import check_method

    check_search_options(maxiter=maxiter, popsize=popsize, tol=tol, workers=workers, warmup=warmup)
    se_method, n_boot = check_method(standard_errors, bootstrap)
    budget = time_budget if isinstance(time_budget, TimeBudget) else TimeBudget(time_budget)
    # the search and standard-error settings every path below takes as they are
    search = dict(
        seed=seed,
        maxiter=maxiter,
        popsize=popsize,
        tol=tol,
        workers=workers,
        polish=polish,
        progress=progress,
        standard_errors=se_method,
        bootstrap=n_boot,
        bootstrap_block=bootstrap_block,
        budget=budget,
    )
    if normalize:
        from . import normalize as _norm

        if isinstance(model_class, str) and model_class in _REGISTRY:
            model_class = _REGISTRY[model_class]
        if _norm.applies(
            model_class, depends=depends_on_angle, bounds=bounds, fixed=fixed, initial=initial
        ):
            fit = _norm.identify_normalized(
                identify,
                model_class,
                make_recordings(t, x, y, recordings=recordings, curve_angle=curve_angle),
                warmup=warmup,
                free=free,
                initial=initial,
                seed=seed,
                maxiter=maxiter,
                popsize=popsize,
                tol=tol,
                workers=workers,
                polish=polish,
                separable=separable,
                progress=progress,
                search_samples=search_samples,
                standard_errors=standard_errors,
                bootstrap=bootstrap,
                bootstrap_block=bootstrap_block,
                time_budget=budget,
            )
            return _stamp(budget, fit)
    if isinstance(model_class, Chain):
        from .chain import identify_chain

        if depends_on_angle:
            raise ValueError("a Chain's parameters cannot depend on the curve angle")
        recs = make_recordings(t, x, y, recordings=recordings, curve_angle=curve_angle)
        fit = identify_chain(
            model_class,
            recs,
            warmup=int(warmup),
            bounds=bounds,
            fixed=fixed,
            **search,
        )
        return _stamp(budget, fit)
    if model_class in (PlantModel, "PlantModel"):
        from .plant_model import identify_plant

        if depends_on_angle or bounds or fixed:
            raise ValueError("PlantModel: bounds, fixed and depends_on_angle are not supported")
        if initial is not None and not isinstance(initial, PlantModel):
            raise ValueError(f"initial must be a PlantModel (got {type(initial).__name__})")
        fit = identify_plant(
            make_recordings(t, x, y, recordings=recordings, curve_angle=curve_angle),
            warmup=int(warmup),
            initial=initial,
            **search,
        )
        return _stamp(budget, fit)
    cls = _model_class(model_class)
    depends = law_check(depends_on_angle or {}, cls.param_names)
    if depends and getattr(cls, "uses_curve_angle", False):
        raise ValueError(f"{cls.__name__} already takes the curve angle: depends_on_angle is moot")
    if depends and cls in (PrandtlIshlinskii, GeneralizedPrandtlIshlinskii):
        raise ValueError(f"{cls.__name__} parameters cannot depend on the curve angle")
    recs = make_recordings(t, x, y, recordings=recordings, curve_angle=curve_angle)
    warmup = int(warmup)
    if strategy not in ("auto", "search"):
        raise ValueError(f"strategy must be 'auto' or 'search' (got {strategy!r})")
    if cls is HystereticOscillator and strategy == "auto" and not depends:
        from .oscillator import identify_oscillator

        fit = identify_oscillator(
            recs,
            warmup=warmup,
            bounds=bounds,
            fixed=fixed,
            free=free,
            initial=initial,
            seed=seed,
            maxiter=maxiter,
            popsize=popsize,
            tol=tol,
            workers=workers,
            polish=polish,
            progress=progress,
            budget=budget,
            input_interpolation=input_interpolation,
            periodic=periodic,
        )
        return _stamp(budget, fit)
    if input_interpolation is not None:
        if cls is not HystereticOscillator:
            raise ValueError(f"{cls.__name__} has no input_interpolation option")
        initial = (initial or cls()).with_params(input_interpolation=input_interpolation)

    if initial is None and cls is GeneralizedPrandtlIshlinskii:
        initial = cls(thresholds=np.arange(GPI_PLAYS) / GPI_PLAYS, weights=np.full(GPI_PLAYS, 1.0))
    if initial is None:
        initial = cls()
    elif type(initial) is not cls:
        raise ValueError(f"initial must be a {cls.__name__} (got {type(initial).__name__})")
    values = initial.params
    options = initial.options
    if cls is PrandtlIshlinskii:
        thr = np.asarray(values["thresholds"], dtype=float)
        spec = PrandtlIshlinskiiSpec(thr / thr[-1] if thr[-1] > 0 else np.linspace(0, 1, thr.size))
    elif cls is GeneralizedPrandtlIshlinskii:
        thr = np.asarray(values["thresholds"], dtype=float)
        spec = GeneralizedPrandtlIshlinskiiSpec(thr / thr[-1] if thr[-1] > 0 else thr)
    else:
        spec = SPECS[cls]()

    free_set = set(free or ())
    unknown = (free_set | set(fixed or {}) | set(bounds or {})) - set(cls.param_names)
    if unknown:
        raise ValueError(
            f"unknown parameter(s) {sorted(unknown)} of {cls.__name__}; "
            f"expected {list(cls.param_names)}"
        )
    held = {n: values[n] for n in spec.default_fixed if n not in free_set}
    held.update({k: float(v) for k, v in (fixed or {}).items()})
    if cls in (PrandtlIshlinskii, GeneralizedPrandtlIshlinskii) and held:
        raise ValueError(f"{cls.__name__}: fixed parameters are not supported")
    free_names = [n for n in cls.param_names if n not in held]
    if not free_names and not depends:
        raise ValueError(f"every parameter of {cls.__name__} is fixed: nothing to identify")
    values.update(held)
    if set(depends) & set(held):
        raise ValueError(f"fixed parameters cannot depend on the curve angle: {sorted(depends)}")

    n_params = len(free_names) + sum(1 for v in depends.values() if v != "constant")
    needs_angle = bool(depends) or getattr(cls, "uses_curve_angle", False)
    check_for_fit(recs, warmup, n_params, not cls.rate_independent, needs_angle)
    scale = Scale.of(recs)
    all_bounds = spec.bounds(scale, held)
    for name, b in (bounds or {}).items():
        if len(tuple(b)) != 2:
            raise ValueError(f"bounds[{name!r}] must be (low, high)")
        all_bounds[name] = (float(b[0]), float(b[1]))
    from .uncertainty import assess, setup_single_angle

    angle = None
    if not depends:  # CurveAngleModel at a single curve angle: hold friction, report groups
        angle = setup_single_angle(cls, recs, held, values, fixed, bounds, all_bounds, free_names)
    n_workers = 0 if workers is None else int(workers)

    user_fixed = set(fixed or {})
    use_separable = (
        spec.separable
        and not depends
        and (separable or cls in (PrandtlIshlinskii, GeneralizedPrandtlIshlinskii))
        and user_fixed <= set(getattr(spec, "search_names", ())) | set(spec.default_fixed)
    )
    if use_separable:
        sb = spec.search_bounds(scale, held)
        sb.update({k: v for k, v in all_bounds.items() if k in sb and k in (bounds or {})})

        def make_problem(recs_, warmup_):
            return SeparableProblem(
                spec, recs_, warmup_, dict(held), sb, scale, options, n_workers, initial.params
            )

        method = "differential evolution + least squares (separable: linear part solved)"
    else:

        def make_problem(recs_, warmup_):
            return DirectProblem(
                cls,
                recs_,
                warmup_,
                values,
                free_names,
                all_bounds,
                spec.log_names,
                options,
                depends,
                n_workers,
                spec.search_options,
            )

        method = "differential evolution + least squares"
    problem = make_problem(recs, warmup)
    space = problem.space
    search_problem = problem
    if search_samples is not None and not depends:
        search_recs, search_warmup = recs, warmup
        if cls.rate_independent:
            search_recs, search_warmup = thin_for_search(recs, warmup)
        windows, win_warmup = search_windows(search_recs, search_warmup, int(search_samples))
        if windows is not recs:
            search_problem = make_problem(windows, win_warmup)
            how = "in windows" if windows is not search_recs else "thinned"
            method += f" (global search on {sum(r.n for r in windows)} samples {how})"

    counter = {"evaluations": 0}
    x0 = None
    if depends:
        # Start from per-recording fits (fast, separable where possible) and the angle laws
        # fitted to them; the joint search then starts with that candidate in its population.
        per_rec = [
            identify(
                cls,
                recordings=[(r.t, r.x, r.y)],
                warmup=warmup,
                fixed=fixed,
                free=free,
                initial=initial,
                seed=seed,
                maxiter=maxiter,
                popsize=popsize,
                tol=tol,
                workers=workers,
                polish=True,
                separable=separable,
                progress=False,
                time_budget=budget,
            )
            for r in recs
        ]
        counter["evaluations"] += sum(f.evaluations for f in per_rec)
        c0 = _laws_from_points(problem, [f.model.params for f in per_rec])
        x0 = np.clip(space.search(c0), space.lower, space.upper)
        maxiter = max(5, maxiter // 5)  # the search starts from a good candidate

    start = time.perf_counter()
    res = global_search(
        search_problem,
        space,
        counter,
        f"identify {cls.__name__}",
        progress,
        maxiter=maxiter,
        popsize=popsize,
        tol=tol,
        seed=seed,
        x0=x0,
        budget=budget,
    )
    if not np.isfinite(res.fun) or res.fun >= _PENALTY:
        raise ValueError(
            f"identification failed: no parameters within the bounds give a finite simulation "
            f"of {cls.__name__} (search bounds: "
            f"{dict(zip(space.names, zip(space.lower, space.upper, strict=True), strict=True))})"
        )
    u_best = res.x
    message = f"differential evolution: {res.message}"

    if polish and space.lower.size and not budget.over():
        u_best, msg = refine(
            problem,
            space,
            u_best,
            counter,
            separable=use_separable,
            budget=budget,
            max_nfev=200 if use_separable else 100,
        )
        message += f"; least squares: {msg}"
    best = space.natural(u_best)
    model = problem.model(best)
    seconds = time.perf_counter() - start

    predictions = [simulate_model(model, r.t, r.x, r.curve_angle) for r in recs]
    quality = fit_quality(recs, predictions, warmup)

    assessed = assess(
        cls=cls,
        model=model,
        problem=problem,
        recs=recs,
        warmup=warmup,
        values=values,
        free_names=free_names,
        all_bounds=all_bounds,
        spec=spec,
        options=options,
        depends=depends,
        workers=n_workers,
        sse=quality.sse,
        n_fit=quality.n,
        u_best=u_best,
        use_separable=use_separable,
        method=se_method,
        count=n_boot,
        block=bootstrap_block,
        seed=seed,
        angle=angle,
    )
    fit = Fit.from_quality(
        model,
        quality,
        assessed,
        identified=list(free_names),
        fixed=held,
        evaluations=counter["evaluations"],
        seconds=seconds,
        generations=int(res.nit),
        method=method,
        message=message,
        warmup=warmup,
        bounds={n: (float(a), float(b)) for n, (a, b) in all_bounds.items() if n in free_names},
        recordings=recs,
        predictions=predictions,
    )
    fit.diagnostics.warn(stacklevel=3)
    return _stamp(budget, fit)


def _stamp(budget: TimeBudget, fit: Fit) -> Fit:
    """Record on the Fit that the time budget stopped a stage (once, for nested calls)."""
    if budget.hit and not fit.stopped_on_budget:
        fit.stopped_on_budget = True
        fit.message += budget.note()
    return fit


def search_and_refine(
    problem,
    space,
    counter,
    label,
    progress,
    *,
    maxiter,
    popsize,
    tol,
    seed,
    polish,
    search_problem=None,
    budget=None,
):
    """Global search (on ``search_problem``, e.g. thinned records, default ``problem``) then
    least-squares refinement of a separable problem (chains): returns (the best search
    coordinates, the DE result, a message). Raises when no candidate gives a finite
    simulation."""
    res = global_search(
        search_problem or problem,
        space,
        counter,
        label,
        progress,
        maxiter=maxiter,
        popsize=popsize,
        tol=tol,
        seed=seed,
        budget=budget,
    )
    if not np.isfinite(res.fun) or res.fun >= _PENALTY:
        raise ValueError("identification failed: no candidate gives a finite simulation")
    u_best = res.x
    message = f"differential evolution: {res.message}"
    if polish and space.lower.size and not (budget is not None and budget.over()):
        u_best, msg = refine(
            problem, space, u_best, counter, separable=True, budget=budget, max_nfev=200
        )
        message += f"; least squares: {msg}"
    return u_best, res, message


def _laws_from_points(problem: DirectProblem, points: list[dict]) -> np.ndarray:
    """Coefficients of the angle laws fitted (least squares) to per-recording parameters; the
    shared friction of the tanh laws by a 1-D grid search."""
    theta = np.asarray(problem._angles(), dtype=float)
    values = {p: np.array([pt[p] for pt in points], dtype=float) for p, _, _ in problem.layout}
    tanh_params = [p for p, law, _ in problem.layout if law == "tanh"]
    mu = None
    if tanh_params:
        lo = problem.space.natural(problem.space.lower)[-1]
        hi = problem.space.natural(problem.space.upper)[-1]
        best = np.inf
        for m in np.geomspace(max(lo, 1e-3), hi, 60):
            A = np.column_stack([np.ones_like(theta), np.tanh(0.5 * m * np.abs(theta))])
            err = 0.0
            for p in tanh_params:
                v = values[p]
                coef = np.linalg.lstsq(A, v, rcond=None)[0]
                err += float(np.sum((A @ coef - v) ** 2)) / (float(np.var(v)) + 1e-300)
            if err < best:
                best, mu = err, m
    c = np.empty(len(problem.space.names))
    for p, law, i in problem.layout:
        v = values[p]
        if law == "constant":
            c[i] = float(np.mean(v))
            continue
        basis = theta if law == "linear" else np.tanh(0.5 * mu * np.abs(theta))
        A = np.column_stack([np.ones_like(theta), basis])
        c[i : i + 2] = np.linalg.lstsq(A, v, rcond=None)[0]
    if problem.tanh:
        c[-1] = mu
    return c
