"""Identifying a :class:`~tendonsheath.models.Loaded` model: the base and the load terms, staged.

1. The tendon's stretch: the gain g of the load in a linear regression of the output on the
   load, an offset and a few plays of the input (:func:`load_stretch`).
2. The base alone (``identify`` of the base class, with the caller's search settings) on the
   recordings with the stretch taken off (y - g load).
3. The play's terms (slack, slack_load on a log scale, friction) with the base held: least
   squares from the best two of a small grid of starts.
4. Everything jointly from there (kept where it lowers the cost).

In every stage the parts linear in the output are solved by least squares for each candidate
(separable): the stretch ``gain``, a Scaled base's output offset and a (generalized)
Prandtl-Ishlinskii base's weights, those kept >= 0 so that the fitted operator stays
invertible (see :mod:`tendonsheath.identify.loaded_problem`). ``fixed`` holds load terms (e.g.
``{"slack": 0, "friction": 0}``: the additive offset alone).

The cost counts every sample after ``warmup`` of every recording; the play starts in the
middle of its band at each recording's first sample.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..models import BoucWen, Chain, HystereticOscillator, Scaled
from ..models.loaded import Loaded, play
from .data import make_recordings
from .diagnostics import Diagnostics, linearised_se, undetermined_notes
from .fit import Fit, fit_quality
from .loaded_problem import SEARCHED, Problem

#: base classes with no output offset that identify does not normalise: fitted on centred data
_NO_OFFSET = (BoucWen, HystereticOscillator)

#: the play half-widths of the first regression's hysteresis regressors (share of the span)
_STRETCH_PLAYS = (0.0, 0.02, 0.05, 0.1, 0.2)


def load_stretch(recs, loads, warmup: int) -> float:
    """Stage 1: the stretch gain g of y ~ sum_j c_j play_{r_j}(x) + b + g load, by linear least
    squares over every recording (a few plays of fixed half-widths stand in for any base's
    loop, so that the loop's width is not read as a load effect)."""
    span = float(np.ptp(np.concatenate([r.x for r in recs]))) or 1.0
    rows, target = [], []
    for r, lo in zip(recs, loads, strict=True):
        k = int(warmup) + r.skip
        cols = [play(r.x, f * span)[k:] for f in _STRETCH_PLAYS]
        rows.append(np.column_stack([*cols, np.ones(r.x.size - k), lo[k:]]))
        target.append(r.y[k:])
    coef = np.linalg.lstsq(np.vstack(rows), np.concatenate(target), rcond=None)[0]
    return float(coef[-1])


def _base_alone(spec, unloaded: list, options: dict, identify_base: Callable[..., Fit]):
    """Stage 2: the base identified on the data without the stretch. A class that ``identify``
    does not normalise and that has no output offset of its own (BoucWen, the hysteretic
    oscillator) is fitted on centred data and put in a Scaled map holding the means (its
    output offset then solved with the rest); given bounds or an initial model, raw units.
    ``identify_base`` is :func:`~tendonsheath.identify.identify`."""
    raw = any(options.get(k) is not None for k in ("bounds", "initial", "depends_on_angle"))
    centre = spec in _NO_OFFSET and not raw and options.get("normalize") is not False
    xc = float(np.mean(np.concatenate([x for _, x, _ in unloaded]))) if centre else 0.0
    yc = float(np.mean(np.concatenate([y for _, _, y in unloaded]))) if centre else 0.0
    recs = [(t, x - xc, y - yc) for t, x, y in unloaded]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        base = identify_base(spec, recordings=recs, **options).model
    return Scaled(base, input_offset=xc, output_offset=yc) if centre else base


def _starts(problem: Problem, x_span: float, scale: float, keep: int) -> list[np.ndarray]:
    """The ``keep`` best of a grid of play terms: slack 0, 1 % or 4 % of the input span,
    slack_load 0.3, 1 or 3 times the median |load|, friction 0 or 2 % of the span per median
    |load| (the base as it is)."""
    grid = {
        "slack": (0.0, 0.01 * x_span, 0.04 * x_span),
        "slack_load": tuple(f * scale for f in (0.3, 1.0, 3.0)),
        "friction": (0.0, 0.02 * x_span / scale),
    }
    combos: list[dict] = [{}]
    for k in problem.free:
        combos = [{**c, k: v} for c in combos for v in grid[k]]
    starts = [
        problem.start({"slack": 0.0, "slack_load": scale, "friction": 0.0, **c}) for c in combos
    ]
    costs = [float(np.sum(problem.residual(p) ** 2)) for p in starts]
    return [starts[i] for i in np.argsort(costs)[:keep]]


def _refine(problem: Problem, starts, box, max_nfev: int):
    """The best least-squares result over the starts (inside the box)."""
    from scipy.optimize import least_squares

    best = None
    lo, hi = box
    for p0 in starts:
        p0 = np.clip(p0, lo, hi)
        res = least_squares(
            problem.residual, p0, bounds=box, max_nfev=max_nfev, x_scale="jac", method="trf"
        )
        if best is None or res.cost < best.cost:
            best = res
    assert best is not None
    return best


def _linearised_errors(problem: Problem, best, model: Loaded) -> dict[str, float]:
    """Standard errors from the refinement's Jacobian (the gain's from its regression with an
    offset, given the others; the parameters solved linearly, a weighted base's weights and
    offset, have none). A direction the data do not determine gets a huge error, never 0
    (the singular values floored, not dropped as a pseudo-inverse does; a parameter the
    output does not depend on gets inf)."""
    jac = np.asarray(best.jac, dtype=float)
    dof = max(problem.y.size - jac.shape[1] - 1, 1)
    sigma2 = 2.0 * float(best.cost) / dof
    if jac.shape[1]:
        se = linearised_se(jac, 2.0 * float(best.cost), problem.y.size - 1)
    else:
        se = np.zeros(0)
    out: dict = {}
    for k, v in zip(problem.base_names, se, strict=False):
        if k.endswith("]"):  # a list parameter's item: the errors as a list, NaN where held
            key, index = k[:-1].split("[")
            size = len(problem.base.params[key])
            out.setdefault(f"base.{key}", [float("nan")] * size)[int(index)] = float(v)
        elif not k.endswith("*"):
            out[f"base.{k}"] = float(v)
    for k, v in zip(problem.free, se[len(problem.base_names) :], strict=True):
        out[k] = float(v * model.terms[k]) if k == "slack_load" else float(v)
    if "gain" not in problem.fixed:
        a = np.column_stack([problem.load_all, np.ones_like(problem.load_all)])
        out["gain"] = float(linearised_se(a, sigma2 * dof, dof + 2)[0])
    return out


def check_load_varies(loads: list[np.ndarray], fixed: dict[str, float]) -> None:
    """Refuse recordings whose load is one constant over all of them while load terms are to
    be identified: ``gain * load`` is then a constant, the output offset's twin, and the
    play's half-width r(load) one number shared by slack, slack_load and friction, which a
    base's own dead band takes as well (Step 22: such a fit returned a gain of -6.8e-8 for
    -1.5 with a standard error of 0)."""
    free = [k for k in ("gain", *SEARCHED) if k not in fixed]
    every = np.concatenate(loads)
    level = float(np.max(np.abs(every)))
    if not free or float(np.ptp(every)) > 1e-9 * level:
        return
    raise ValueError(
        f"identify(Loaded): the load is constant ({every[0]:.6g}) over every recording, so "
        f"the load terms {', '.join(free)} cannot be told from the base's output offset and "
        "dead band; record at two or more loads, hold the terms (fixed={...}), or identify "
        "the base alone"
    )


def _staged(base0, recs, loads, warmup, fixed, max_nfev):
    """Stages 3 and 4: the play terms with the base held, then everything jointly from there
    (kept only where it lowers the cost). Returns (model, problem, least-squares result)."""
    x_span = float(np.ptp(np.concatenate([r.x for r in recs]))) or 1.0
    scale = float(np.median(np.abs(np.concatenate(loads)))) or 1.0
    held = Problem(base0, recs, loads, warmup, fixed, joint=False)
    box = held.bounds(x_span, scale)
    best = _refine(held, _starts(held, x_span, scale, keep=2), box, max_nfev)
    model = held.model(best.x)
    joint = Problem(model.base, recs, loads, warmup, fixed, joint=True)
    box = joint.bounds(x_span, scale)
    polished = _refine(joint, [joint.start(model.terms)], box, max_nfev)
    if polished.cost < best.cost:
        return joint.model(polished.x), joint, polished
    return model, held, best


def identify_loaded(
    template: Loaded,
    recordings: Sequence,
    loads: Sequence,
    *,
    warmup: int = 0,
    fixed: dict[str, float] | None = None,
    base_options: dict[str, Any] | None = None,
    max_nfev: int = 40,
    identify_base: Callable[..., Fit],
) -> Fit:
    """Identify ``template``'s base and load terms from recordings with a measured load.

    Parameters
    ----------
    template : Loaded
        ``Loaded(BaseClass)`` (its base's class is identified) or a Loaded model.
    recordings : sequence
        (t, x, y) per recording, or objects with t, x, y (e.g. :class:`~tendonsheath.io.Log`).
    loads : sequence of array_like
        The measured load of every recording (one per sample).
    warmup : int, default 0
        Samples at the start of every recording left out of the cost.
    fixed : dict of str to float, optional
        Load terms held at given values (gain, slack, slack_load, friction).
    base_options : dict, optional
        Options of the base's own identification (seed, maxiter, ...).
    max_nfev : int, default 40
        Least-squares iterations of every start (each also estimates the Jacobian).
    identify_base : callable
        The base's own identification (stage 2), called as
        ``identify_base(base_class, recordings=..., **base_options)`` and returning a
        :class:`Fit`: :func:`~tendonsheath.identify.identify`, which hands itself here.

    Returns
    -------
    Fit
        The identified Loaded model, its errors over the recordings and a message.

    Raises
    ------
    ValueError
        A load of another length than its recording, not finite, or an unknown fixed term.
    """
    start = time.perf_counter()
    fixed = dict(fixed or {})
    unknown = set(fixed) - {"gain", *SEARCHED}
    if unknown:
        raise ValueError(f"Loaded: unknown fixed term(s) {sorted(unknown)}")
    recs = make_recordings(recordings=list(recordings))
    if len(loads) != len(recs):
        raise ValueError(f"{len(loads)} loads for {len(recs)} recordings: give one per recording")
    arrays = []
    for i, (r, lo) in enumerate(zip(recs, loads, strict=True)):
        arr = np.broadcast_to(np.asarray(lo, dtype=float), r.x.shape).copy()
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"recording {i}: the load is not finite")
        arrays.append(arr)
    check_load_varies(arrays, fixed)
    options = {"progress": False, **(base_options or {})}
    base_cls = type(template.base)
    spec = template.base if isinstance(template.base, Chain) else base_cls  # a Chain: itself
    stretch = float(fixed["gain"]) if "gain" in fixed else load_stretch(recs, arrays, warmup)
    unloaded = [(r.t, r.x, r.y - stretch * a) for r, a in zip(recs, arrays, strict=True)]
    base0 = _base_alone(spec, unloaded, options, identify_base)
    model, problem, best = _staged(base0, recs, arrays, warmup, fixed, max_nfev)
    lo = min(float(r.x.min()) for r in recs)
    hi = max(float(r.x.max()) for r in recs)
    model.input_range = (lo, hi)
    predictions = [
        np.asarray(model.simulate(r.t, r.x, load=a), dtype=float)
        for r, a in zip(recs, arrays, strict=True)
    ]
    names = problem.identified()
    if "gain" not in fixed:
        names.append("gain")
    ses = _linearised_errors(problem, best, model)
    fit = Fit.from_quality(
        model,
        fit_quality(recs, predictions, warmup),
        identified=names,
        fixed=fixed,
        standard_errors=ses,
        evaluations=int(best.nfev),
        seconds=time.perf_counter() - start,
        generations=0,
        method=(
            f"Loaded({base_cls.__name__}): stretch by regression, base on the data without it, "
            "play terms with the base held, then joint least squares"
        ),
        message=str(best.message),
        warmup=int(warmup),
        recordings=recs,
        predictions=predictions,
        input_range=(lo, hi),
        diagnostics=Diagnostics(names=list(ses), notes=undetermined_notes(ses)),
    )
    fit.diagnostics.warn()
    return fit


__all__ = ["check_load_varies", "identify_loaded", "load_stretch"]
