"""The identification of one model class, in named steps: the spec (held and free parameters,
bounds), the problem (separable or direct, on windows of long records for the search), the
global search (started from per-recording fits when parameters depend on the curve angle), the
refinement, and the diagnostics that make the Fit."""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..models import (
    GeneralizedPrandtlIshlinskii,
    HysteresisModel,
    HystereticOscillator,
    PrandtlIshlinskii,
)
from ..models.base import _REGISTRY
from ._bound import POPULATION
from .data import check_for_fit, make_recordings, search_windows, thin_for_search
from .fit import Fit, fit_quality, simulate_model
from .oscillator import identify_oscillator
from .problem import DirectProblem, SeparableProblem, law_check
from .refine import refine
from .search import PENALTY, global_search
from .settings import Search
from .specs import (
    SPECS,
    GeneralizedPrandtlIshlinskiiSpec,
    PrandtlIshlinskiiSpec,
    Scale,
    spec_for,
)
from .uncertainty import assess, setup_single_angle

if TYPE_CHECKING:
    from .estimator import Options

#: the whole identification of one model class on checked recordings (core.run), handed down
#: for the per-recording fits that start a search of angle laws
FitOne = Callable[[Any, list, "Options", Search], Fit]

GPI_PLAYS = 10  # default number of plays of an identified GeneralizedPrandtlIshlinskii
SPECS_BY_NAME = {cls.__name__: cls for cls in SPECS}
_PLAYS = (PrandtlIshlinskii, GeneralizedPrandtlIshlinskii)


def identify_class(model_class, recs, opt: Options, search: Search, *, fit_one: FitOne) -> Fit:
    """Identify one model class (or hand a HystereticOscillator to its staged method);
    ``fit_one`` is the whole identification (:func:`tendonsheath.identify.core.run`), which
    fits each recording alone to start a search of angle laws."""
    cls = _model_class(model_class)
    depends = _angle_laws(cls, opt.depends_on_angle)
    if opt.strategy not in ("auto", "search"):
        raise ValueError(f"strategy must be 'auto' or 'search' (got {opt.strategy!r})")
    if cls is HystereticOscillator and opt.strategy == "auto" and not depends:
        return identify_oscillator(
            recs,
            warmup=int(opt.warmup),
            bounds=opt.bounds,
            fixed=opt.fixed,
            free=opt.free,
            initial=opt.initial,
            search=search,
            input_interpolation=opt.input_interpolation,
            periodic=opt.periodic,
        )
    setup = ClassSetup.of(cls, recs, opt, depends)
    posed = Posed.of(setup, recs, opt, search)
    counter = {"evaluations": 0}
    x0, search_here = None, search
    if depends:
        x0 = _start_from_recordings(setup, posed.problem, recs, opt, search, counter, fit_one)
        search_here = dataclasses.replace(search, maxiter=max(5, search.maxiter // 5))
    start = time.perf_counter()
    res, u_best, message = _search_and_refine(setup, posed, search_here, counter, x0)
    model = posed.problem.model(posed.problem.space.natural(u_best))
    seconds = time.perf_counter() - start
    return _diagnose(setup, posed, recs, model, u_best, search, counter, seconds, res, message)


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
    if model_class not in SPECS and not _table_identifiable(model_class):
        raise ValueError(
            f"cannot identify {getattr(model_class, '__name__', model_class)}; "
            f"identifiable models: {sorted(SPECS_BY_NAME)}"
        )
    return model_class


def _angle_laws(cls, depends_on_angle) -> dict:
    depends = law_check(depends_on_angle or {}, cls.param_names)
    if depends and getattr(cls, "uses_curve_angle", False):
        raise ValueError(f"{cls.__name__} already takes the curve angle: depends_on_angle is moot")
    if depends and cls in _PLAYS:
        raise ValueError(f"{cls.__name__} parameters cannot depend on the curve angle")
    return depends


# -- spec: the starting model, the held and free parameters and their bounds ---------------


@dataclasses.dataclass
class ClassSetup:
    """What is identified of ``cls``: the spec, the starting values (held ones included), the
    free parameters, the bounds, the angle laws and the single-curve-angle setup."""

    cls: type[HysteresisModel]
    spec: Any
    initial: HysteresisModel
    values: dict
    options: dict
    held: dict
    free_names: list[str]
    depends: dict
    scale: Scale
    all_bounds: dict
    angle: Any
    warmup: int

    @classmethod
    def of(setup, cls, recs, opt: Options, depends: dict) -> ClassSetup:
        initial = _initial(cls, opt)
        values = initial.params
        spec = _spec_of(cls, values)
        held, free_names = _held_and_free(cls, spec, values, opt, depends)
        _check_fixed_values(cls, opt.fixed or {})
        warmup = int(opt.warmup)
        n_params = len(free_names) + sum(1 for v in depends.values() if v != "constant")
        needs_angle = bool(depends) or getattr(cls, "uses_curve_angle", False)
        check_for_fit(recs, warmup, n_params, not cls.rate_independent, needs_angle)
        scale = Scale.of(recs)
        all_bounds = spec.bounds(scale, held)
        for name, b in (opt.bounds or {}).items():
            if len(tuple(b)) != 2:
                raise ValueError(f"bounds[{name!r}] must be (low, high)")
            all_bounds[name] = (float(b[0]), float(b[1]))
        angle = None
        if not depends:  # CurveAngleModel at a single curve angle: hold friction, report groups
            angle = setup_single_angle(
                cls, recs, held, values, opt.fixed, opt.bounds, all_bounds, free_names
            )
        return setup(
            cls,
            spec,
            initial,
            values,
            initial.options,
            held,
            free_names,
            depends,
            scale,
            all_bounds,
            angle,
            warmup,
        )


def _initial(cls, opt: Options) -> HysteresisModel:
    """The starting model: ``initial``, the input interpolation applied, or the defaults."""
    initial = opt.initial
    if opt.input_interpolation is not None:
        if cls is not HystereticOscillator:
            raise ValueError(f"{cls.__name__} has no input_interpolation option")
        initial = (initial or cls()).with_params(input_interpolation=opt.input_interpolation)
    if initial is None and cls is GeneralizedPrandtlIshlinskii:
        initial = cls(thresholds=np.arange(GPI_PLAYS) / GPI_PLAYS, weights=np.full(GPI_PLAYS, 1.0))
    if initial is None:
        initial = cls()
    elif type(initial) is not cls:
        raise ValueError(f"initial must be a {cls.__name__} (got {type(initial).__name__})")
    if initial.options.get("envelope_range") is not None:
        # fitted on the tanh alone; the training range is set afterwards (identify.extrapolation)
        initial = initial.with_params(envelope_range=None)
    return initial


def _spec_of(cls, values: dict):
    if cls is PrandtlIshlinskii:
        thr = np.asarray(values["thresholds"], dtype=float)
        return PrandtlIshlinskiiSpec(thr / thr[-1] if thr[-1] > 0 else np.linspace(0, 1, thr.size))
    if cls is GeneralizedPrandtlIshlinskii:
        thr = np.asarray(values["thresholds"], dtype=float)
        return GeneralizedPrandtlIshlinskiiSpec(thr / thr[-1] if thr[-1] > 0 else thr)
    return spec_for(cls)


def identifiable(cls) -> bool:
    """Whether ``identify`` takes model class ``cls``: a spec of its own, or a parameter table
    of numbers and the core's batched kernels (TableSpec)."""
    return cls in SPECS or _table_identifiable(cls)


def _table_identifiable(cls) -> bool:
    """A model with no spec of its own that its parameter table and the core's batched kernels
    identify (:class:`~tendonsheath.identify.specs.TableSpec`)."""
    return (
        isinstance(cls, type)
        and issubclass(cls, HysteresisModel)
        and getattr(cls, "_core_params", None) is not None
        and cls.__name__ in POPULATION
    )


def _check_fixed_values(cls, fixed: dict) -> None:
    """Each fixed value inside its parameter's valid range (the C++ parameter table's), else
    a ValueError naming it: a value outside makes every simulation fail, and the search would
    only say that no parameters give a finite one."""
    table = getattr(cls, "_core_params", None)
    rows = {r["name"]: r for r in table.fields()} if table is not None else {}
    for name, value in fixed.items():
        v = float(value)
        row = rows.get(name)
        if not math.isfinite(v):
            raise ValueError(f"fixed {name} = {v:g} is not a finite number")
        if row is None or row["check"] in ("unchecked", "finite", "documented"):
            continue
        lo_ok = v > row["lo"] or (row["lo_closed"] and v == row["lo"])
        hi_ok = v < row["hi"] or (row["hi_closed"] and v == row["hi"])
        if not (lo_ok and hi_ok):
            left, right = "[" if row["lo_closed"] else "(", "]" if row["hi_closed"] else ")"
            raise ValueError(
                f"fixed {name} = {v:g} is outside {cls.__name__}'s valid range of {name}, "
                f"{left}{row['lo']:g}, {row['hi']:g}{right}"
            )


def _held_and_free(cls, spec, values: dict, opt: Options, depends: dict):
    """The held parameters ({name: value}, written into ``values``) and the free names."""
    free_set = set(opt.free or ())
    unknown = (free_set | set(opt.fixed or {}) | set(opt.bounds or {})) - set(cls.param_names)
    if unknown:
        raise ValueError(
            f"unknown parameter(s) {sorted(unknown)} of {cls.__name__}; "
            f"expected {list(cls.param_names)}"
        )
    held = {n: values[n] for n in spec.default_fixed if n not in free_set}
    held.update({k: float(v) for k, v in (opt.fixed or {}).items()})
    if cls in _PLAYS and held:
        raise ValueError(f"{cls.__name__}: fixed parameters are not supported")
    free_names = [n for n in cls.param_names if n not in held]
    if not free_names and not depends:
        raise ValueError(f"every parameter of {cls.__name__} is fixed: nothing to identify")
    values.update(held)
    if set(depends) & set(held):
        raise ValueError(f"fixed parameters cannot depend on the curve angle: {sorted(depends)}")
    return held, free_names


# -- problem: separable or direct; the search's (windowed, thinned) copy --------------------


@dataclasses.dataclass
class Posed:
    """The problem the refinement and diagnostics use, the one the global search uses (on
    windows or thinned records of long ones) and the method's description."""

    problem: Any
    search_problem: Any
    separable: bool
    method: str

    @classmethod
    def of(cls, s: ClassSetup, recs, opt: Options, search: Search) -> Posed:
        separable = _use_separable(s, opt)
        make = _problem_maker(s, opt, search, separable)
        method = "differential evolution + least squares"
        if separable:
            method += " (separable: linear part solved)"
        problem = make(recs, s.warmup)
        search_problem = problem
        if opt.search_samples is not None and not s.depends:
            search_recs, search_warmup = recs, s.warmup
            if s.cls.rate_independent:
                search_recs, search_warmup = thin_for_search(recs, s.warmup)
            windows, win_warmup = search_windows(
                search_recs, search_warmup, int(opt.search_samples)
            )
            if windows is not recs:
                search_problem = make(windows, win_warmup)
                how = "in windows" if windows is not search_recs else "thinned"
                method += f" (global search on {sum(r.n for r in windows)} samples {how})"
        return cls(problem, search_problem, separable, method)


def _use_separable(s: ClassSetup, opt: Options) -> bool:
    user_fixed = set(opt.fixed or {})
    return bool(
        s.spec.separable
        and not s.depends
        and (opt.separable or s.cls in _PLAYS)
        and user_fixed <= set(getattr(s.spec, "search_names", ())) | set(s.spec.default_fixed)
    )


def _problem_maker(s: ClassSetup, opt: Options, search: Search, separable: bool):
    """make(recordings, warmup) -> the problem on those recordings."""
    n_workers = search.n_workers
    if separable:
        sb = s.spec.search_bounds(s.scale, s.held)
        sb.update({k: v for k, v in s.all_bounds.items() if k in sb and k in (opt.bounds or {})})

        def make_separable(recs_, warmup_):
            return SeparableProblem(
                s.spec,
                recs_,
                warmup_,
                dict(s.held),
                sb,
                s.scale,
                s.options,
                n_workers,
                s.initial.params,
            )

        return make_separable

    def make(recs_, warmup_):
        return DirectProblem(
            s.cls,
            recs_,
            warmup_,
            s.values,
            s.free_names,
            s.all_bounds,
            s.spec.log_names,
            s.options,
            s.depends,
            n_workers,
            s.spec.search_options,
        )

    return make


# -- global search and refinement ----------------------------------------------------------


def _start_from_recordings(
    s: ClassSetup, problem, recs, opt: Options, search: Search, counter, fit_one: FitOne
):
    """A starting candidate for angle laws: per-recording fits by ``fit_one`` (fast, separable
    where possible) and the laws fitted to them; the joint search has it in its population."""
    per_options = type(opt)(  # Options, its other settings at their defaults
        warmup=s.warmup,
        fixed=opt.fixed,
        free=opt.free,
        initial=s.initial,
        seed=search.seed,
        maxiter=search.maxiter,
        popsize=search.popsize,
        tol=search.tol,
        workers=search.workers,
        polish=True,
        separable=opt.separable,
        progress=False,
        time_budget=search.budget,
    )
    per_search = Search.of(per_options)
    per_rec = [
        fit_one(s.cls, make_recordings(recordings=[(r.t, r.x, r.y)]), per_options, per_search)
        for r in recs
    ]
    counter["evaluations"] += sum(f.evaluations for f in per_rec)
    space = problem.space
    c0 = laws_from_points(problem, [f.model.params for f in per_rec])
    return np.clip(space.search(c0), space.lower, space.upper)


def _search_and_refine(s: ClassSetup, posed: Posed, search: Search, counter, x0):
    """The global search, then least squares from its best (unless ``polish`` is off or the
    time budget is spent): (the DE result, the best search coordinates, the message)."""
    problem = posed.problem
    space = problem.space
    label = f"identify {s.cls.__name__}"
    res = global_search(posed.search_problem, space, counter, label, search, x0=x0)
    if not np.isfinite(res.fun) or res.fun >= PENALTY:
        raise ValueError(
            f"identification failed: no parameters within the bounds give a finite simulation "
            f"of {s.cls.__name__} (search bounds: "
            f"{dict(zip(space.names, zip(space.lower, space.upper, strict=True), strict=True))})"
        )
    u_best = res.x
    message = f"differential evolution: {res.message}"
    if search.polish and space.lower.size and not search.budget.over():
        u_best, msg = refine(
            problem,
            space,
            u_best,
            counter,
            separable=posed.separable,
            budget=search.budget,
            max_nfev=200 if posed.separable else 100,
        )
        message += f"; least squares: {msg}"
    return res, u_best, message


# -- diagnostics: quality, standard errors, the Fit ----------------------------------------


def _diagnose(
    s: ClassSetup, posed: Posed, recs, model, u_best, search, counter, seconds, res, message
) -> Fit:
    predictions = [simulate_model(model, r.t, r.x, r.angle_input) for r in recs]
    quality = fit_quality(recs, predictions, s.warmup)
    assessed = assess(
        cls=s.cls,
        model=model,
        problem=posed.problem,
        recs=recs,
        warmup=s.warmup,
        values=s.values,
        free_names=s.free_names,
        all_bounds=s.all_bounds,
        spec=s.spec,
        options=s.options,
        depends=s.depends,
        workers=search.n_workers,
        sse=quality.sse,
        n_fit=quality.n,
        u_best=u_best,
        use_separable=posed.separable,
        method=search.standard_errors,
        count=search.bootstrap,
        block=search.bootstrap_block,
        seed=search.seed,
        angle=s.angle,
    )
    fit = Fit.from_quality(
        model,
        quality,
        assessed,
        identified=list(s.free_names),
        fixed=s.held,
        evaluations=counter["evaluations"],
        seconds=seconds,
        generations=int(res.nit),
        method=posed.method,
        message=message,
        warmup=s.warmup,
        bounds={n: (float(a), float(b)) for n, (a, b) in s.all_bounds.items() if n in s.free_names},
        recordings=recs,
        predictions=predictions,
    )
    fit.diagnostics.warn()
    return fit


def laws_from_points(problem: DirectProblem, points: list[dict]) -> np.ndarray:
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
            A = np.column_stack([np.ones_like(theta), problem.tanh_basis(m)[0]])
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
        if law == "linear":
            basis = theta
        else:
            assert mu is not None  # searched above for the tanh laws
            basis = problem.tanh_basis(mu)[0]
        A = np.column_stack([np.ones_like(theta), basis])
        c[i : i + 2] = np.linalg.lstsq(A, v, rcond=None)[0]
    if problem.tanh:
        c[-1] = mu
    return c


__all__ = [
    "ClassSetup",
    "GPI_PLAYS",
    "Posed",
    "SPECS_BY_NAME",
    "identifiable",
    "identify_class",
    "laws_from_points",
]
