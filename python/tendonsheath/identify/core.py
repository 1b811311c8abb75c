"""identify(): one identification from data, and :func:`run`, the dispatch on the kind of model
(normalised data, a Loaded model, a chain, the grey-box plant, one model class) that
:func:`identify` and :class:`~tendonsheath.identify.estimator.Identifier` share
(:func:`fit_recordings`). The global search every path runs is in
:mod:`tendonsheath.identify.search`; the fitters that call back into the whole identification
(per-recording starts of angle laws, a Loaded model's base) are handed :func:`run` or
:func:`identify`, so that the modules form a layered graph with core.py on top."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._typing import ArrayLike
from ..models import Chain, HysteresisModel, Loaded, PlantModel
from ..models.base import _REGISTRY
from . import normalize as _norm
from .chain import identify_chain
from .data import Recording, make_recordings
from .extrapolation import with_training_range
from .fit import Fit
from .generic import identify_class
from .loaded import identify_loaded
from .plant_model import identify_plant
from .refine import TimeBudget
from .search import SEARCH_DEADLINE
from .settings import (
    OPTION_NAMES,
    Options,
    Search,
    check_search_options,
)

__all__ = ["SEARCH_DEADLINE", "check_search_options", "fit_recordings", "identify", "run"]


def identify(
    model_class: type[HysteresisModel] | HysteresisModel | str,
    t: ArrayLike | None = None,
    x: ArrayLike | None = None,
    y: ArrayLike | None = None,
    *,
    recordings: Sequence | None = None,
    curve_angle: ArrayLike | None = None,
    load: Any = None,
    warmup: int = 0,
    bounds: dict | None = None,
    fixed: dict | None = None,
    free: Any = None,
    initial: Any = None,
    depends_on_angle: dict | None = None,
    seed: int | None = 0,
    maxiter: int = 100,
    popsize: int = 15,
    tol: float = 0.01,
    workers: int | None = None,
    polish: bool = True,
    separable: bool = True,
    progress: bool = True,
    search_samples: int | None = 200_000,
    time_budget: Any = None,
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
    recordings share the parameters. ``t`` may be None for rate-independent models. A
    recording's curve angle may also be a :class:`~tendonsheath.Route` (e.g. the sensed
    shape, held over that recording): CurveAngleModel and ``depends_on_angle`` models then use
    its distribution of curvature (the shape integrals g, G, recomputed for every candidate
    friction), not its curve angle alone.

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
    CurveAngleModel: pretension, length, radii and load_stiffness); ``free`` releases those.
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
    "bandlimited"; default: detected from the input when no ``initial`` is given, see
    :mod:`tendonsheath.identify.interpolation`, else ``initial``'s) is the input
    reconstruction between samples,
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

    A measured load (``load=``: per-sample array of t, x, y, or one array per recording;
    recordings that are :class:`~tendonsheath.io.Log` objects bring their own ``Log.load``)
    is taken by a :class:`~tendonsheath.models.Loaded` model, e.g.
    ``identify(Loaded(BoucWenBacklash), recordings=logs)``, staged: the tendon's stretch by a
    linear regression, the base alone on the data without it, the load's play terms with the
    base held, then everything jointly; a (generalized) Prandtl-Ishlinskii base's weights are
    kept >= 0 (see :mod:`tendonsheath.identify.loaded`; ``fixed`` may hold load terms; the
    other settings go to the base's identification).

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
    curve_angle : float, array_like of float, or Route, optional
        The curve angle (rad) of t, x, y, or its route, for models that take one.
    load : array_like of float, or sequence of them, optional
        The measured load of t, x, y (or one per recording), for a Loaded model.
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
        The input reconstruction between samples (None: detected from the input, or
        ``initial``'s when given).
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
    # the settings, by the names of Options (a test holds these keywords and defaults equal
    # to its fields)
    given = locals()
    options = {name: given[name] for name in OPTION_NAMES}
    if isinstance(model_class, Loaded):
        return _identify_loaded(model_class, t, x, y, recordings, load, options)
    if load is not None:
        raise ValueError(
            "a measured load is taken by a Loaded model: identify(Loaded(BaseClass), ..., load=...)"
        )
    if curve_angle is not None and not takes_curve_angle(model_class, depends_on_angle):
        raise ValueError(
            f"curve_angle= is taken by a model that uses the curve angle (CurveAngleModel, "
            f"AngleDependent) or with depends_on_angle=; {_name_of(model_class)} does not: "
            "leave curve_angle out, or say which parameters depend on it"
        )
    return fit_recordings(
        model_class, Options(**options), t, x, y, recordings=recordings, curve_angle=curve_angle
    )


def takes_curve_angle(model: Any, depends_on_angle: dict | None = None) -> bool:
    """Whether identifying ``model`` (a class, an instance, a registered name or a Chain) uses
    a curve angle: a model that uses it (or a Chain with such a part), or parameters that
    depend on it. An unknown name counts as taking it (its own check names it later).

    Parameters
    ----------
    model : type, HysteresisModel or str
        What identify is given.
    depends_on_angle : dict, optional
        identify's ``depends_on_angle``.

    Returns
    -------
    bool
        True when a curve angle given with it is used.
    """
    if depends_on_angle:
        return True
    if isinstance(model, str):
        model = _REGISTRY.get(model)
        if model is None:
            return True
    candidates = [model, getattr(model, "first", None), getattr(model, "second", None)]
    return any(getattr(m, "uses_curve_angle", False) for m in candidates)


def _name_of(model: Any) -> str:
    if isinstance(model, str):
        return model
    return model.__name__ if isinstance(model, type) else type(model).__name__


def fit_recordings(
    model: Any,
    options: Options,
    t: ArrayLike | None = None,
    x: ArrayLike | None = None,
    y: ArrayLike | None = None,
    *,
    recordings: Sequence | None = None,
    curve_angle: ArrayLike | None = None,
) -> Fit:
    """The identification behind :func:`identify` and ``Identifier.fit``: the settings checked
    (before the data), the recordings made, :func:`run`, and the training inputs' range
    recorded on the Fit and its model."""
    search = Search.of(options)  # checked before the data, as identify() always did
    recs = make_recordings(t, x, y, recordings=recordings, curve_angle=curve_angle)
    fit = run(model, recs, options, search)
    _record_input_range(fit, recs)
    return fit


def _record_input_range(fit: Fit, recs: list[Recording]) -> None:
    """The training inputs' range (all recordings, data units) on the Fit and its model."""
    lo = min(float(np.min(r.x)) for r in recs)
    hi = max(float(np.max(r.x)) for r in recs)
    fit.input_range = (lo, hi)
    fit.model.input_range = (lo, hi)


def _identify_loaded(template, t, x, y, recordings, load, options: dict) -> Fit:
    """identify() of a Loaded model: the recordings and their loads, then identify_loaded."""
    if recordings is None:
        if x is None or y is None or load is None:
            raise ValueError("a Loaded model needs t, x, y and load=, or recordings with loads")
        recordings, loads = [(t, x, y)], [load]
    else:
        recordings = list(recordings)
        if load is None:
            loads = [getattr(r, "load", None) for r in recordings]
            missing = [i for i, lo in enumerate(loads) if lo is None]
            if missing:
                raise ValueError(
                    f"recording(s) {missing} have no load: read them with read_log(..., load=) "
                    "or give load=[...] (one per recording)"
                )
        else:
            one = len(recordings) == 1 and not (isinstance(load, list | tuple) and len(load) == 1)
            loads = [load] if one else list(load)
    fixed = options.pop("fixed", None)
    warmup = int(options.pop("warmup", 0))
    return identify_loaded(
        template,
        recordings,
        loads,
        warmup=warmup,
        fixed=fixed,
        base_options=options,
        identify_base=identify,
    )


def _run_loaded(template, recs: list[Recording], opt: Options, search: Search) -> Fit:
    missing = [i for i, r in enumerate(recs) if r.load is None]
    if missing:
        raise ValueError(
            f"recording(s) {missing} have no load: read them with read_log(..., load=)"
        )
    base = {"seed": search.seed, "maxiter": search.maxiter, "popsize": search.popsize}
    return identify_loaded(
        template,
        recs,
        [r.load for r in recs],
        warmup=int(opt.warmup),
        fixed=opt.fixed,
        base_options={**base, "workers": search.workers},
        identify_base=identify,
    )


def run(model_class, recs: list[Recording], options: Options, search: Search) -> Fit:
    """One identification on checked recordings: normalised data, a chain, the grey-box
    plant or one model class (see :mod:`tendonsheath.identify.generic`)."""
    if isinstance(model_class, str) and model_class in _REGISTRY:
        model_class = _REGISTRY[model_class]
    if isinstance(model_class, Loaded):  # recordings that carry their load (Logs read with it)
        return _stamp(search.budget, _run_loaded(model_class, recs, options, search))
    fit = _dispatch(model_class, recs, options, search)
    return _stamp(search.budget, with_training_range(fit, recs))


def _dispatch(model_class, recs, opt: Options, search: Search) -> Fit:
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
    return identify_class(model_class, recs, opt, search, fit_one=run)


def _identify_chain(chain: Chain, recs, opt: Options, search: Search) -> Fit:
    if opt.depends_on_angle:
        raise ValueError("a Chain's parameters cannot depend on the curve angle")
    return identify_chain(
        chain, recs, warmup=int(opt.warmup), bounds=opt.bounds, fixed=opt.fixed, search=search
    )


def _identify_plant(recs, opt: Options, search: Search) -> Fit:
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
