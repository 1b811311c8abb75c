"""One identification from data (:func:`identify_with`, behind
:func:`~tendonsheath.identify.identify`), and :func:`run`, the dispatch on the kind of model
(normalised data, a Loaded model, a chain, the grey-box plant, one model class) that
:func:`~tendonsheath.identify.identify` and
:class:`~tendonsheath.identify.estimator.Identifier` share (:func:`fit_recordings`). The
global search every path runs is in :mod:`tendonsheath.identify.search`; the fitters that
call back into the whole identification (per-recording starts of angle laws, a Loaded
model's base) are handed :func:`run` or :func:`identify_with`, so that the modules form a
layered graph with core.py on top."""

from __future__ import annotations

import functools
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.typing import ArrayLike
from ..models import Chain, Loaded, PlantModel
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
    Search,
    check_search_options,
)

if TYPE_CHECKING:
    from .estimator import Options

__all__ = ["SEARCH_DEADLINE", "check_search_options", "fit_recordings", "identify_with", "run"]


def identify_with(
    model_class: Any,
    options: Options,
    t: ArrayLike | None = None,
    x: ArrayLike | None = None,
    y: ArrayLike | None = None,
    *,
    recordings: Sequence | None = None,
    curve_angle: ArrayLike | None = None,
    load: Any = None,
) -> Fit:
    """:func:`~tendonsheath.identify.identify` with its settings as one
    :class:`~tendonsheath.identify.estimator.Options`: a Loaded model's staged identification,
    or :func:`fit_recordings`."""
    depends_on_angle = options.depends_on_angle
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
        model_class, options, t, x, y, recordings=recordings, curve_angle=curve_angle
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


def _identify_loaded(template, t, x, y, recordings, load, opt: Options) -> Fit:
    """identify() of a Loaded model: the recordings and their loads, then identify_loaded."""
    options = opt.as_dict()
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
        identify_base=functools.partial(_identify_base, type(opt)),
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
        identify_base=functools.partial(_identify_base, type(opt)),
    )


def _identify_base(options_type: type[Options], model_class: Any, **arguments: Any) -> Fit:
    """identify() of a Loaded model's base: its data and settings by keyword (``options_type``
    is :class:`~tendonsheath.identify.estimator.Options`, which reads the defaults)."""
    data = {k: arguments.pop(k) for k in ("t", "x", "y", "recordings", "curve_angle", "load")
            if k in arguments}  # fmt: skip
    return identify_with(model_class, options_type(**arguments), **data)


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
        inner = opt.replace(normalize=False)

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
