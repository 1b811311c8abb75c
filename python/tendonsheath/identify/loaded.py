"""Identifying a :class:`~tendonsheath.models.Loaded` model: the base and the load terms jointly.

1. The base is identified alone (``identify`` of the base class on the same recordings, with
   the caller's search settings) to give a starting point.
2. Simulation-error least squares over the base's parameters and the play's three terms
   (slack, slack_load on a log scale, friction), from a few starts of slack_load spread over
   the measured loads; the compliance ``gain`` is linear in the output and solved by least
   squares for every candidate (separable). ``fixed`` holds load terms (e.g.
   ``{"slack": 0, "friction": 0}``: the additive offset alone).

The cost counts every sample after ``warmup`` of every recording; the play starts in the
middle of its band at each recording's first sample.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np
from scipy.optimize import least_squares

from ..models import Chain, HysteresisModel
from ..models.loaded import Loaded, play, play_radius
from .fit import Fit, fit_quality

#: the play's terms searched by least squares (gain is solved in closed form)
_SEARCHED = ("slack", "slack_load", "friction")


def _base_vector(base: HysteresisModel) -> tuple[list[str], np.ndarray]:
    """The base's float parameters that it accepts changed (names, values; a list parameter
    item by item as ``name[i]``): what the refinement moves (an integer exponent or a
    discrete setting stays as identified)."""
    names, values = [], []
    for k, v in base.params.items():
        items = list(enumerate(v)) if isinstance(v, list) else [(None, v)]
        for i, vi in items:
            if not isinstance(vi, float) or not np.isfinite(vi):
                continue
            name = k if i is None else f"{k}[{i}]"
            try:
                _with_values(base, [name], [vi * (1.0 + 1e-6) + 1e-9])
            except (ValueError, TypeError):
                continue
            names.append(name)
            values.append(vi)
    return names, np.asarray(values, dtype=float)


def _with_values(base: HysteresisModel, names: list[str], values) -> HysteresisModel:
    """``base`` with the named parameters (``name`` or ``name[i]``) set to ``values``."""
    if not names:
        return base
    params = base.params
    changes: dict = {}
    for name, value in zip(names, values, strict=True):
        if name.endswith("]"):
            key, index = name[:-1].split("[")
            changes.setdefault(key, list(params[key]))[int(index)] = float(value)
        else:
            changes[name] = float(value)
    return base.with_params(**changes)


class _Problem:
    """The joint residual: base parameters and play terms in, simulation errors out."""

    def __init__(self, base, recs, loads, warmup: int, fixed: dict[str, float]):
        self.base = base
        self.recs = recs
        self.loads = loads
        self.warmup = int(warmup)
        self.fixed = fixed
        self.base_names, self.base_values = _base_vector(base)
        self.free = [k for k in _SEARCHED if k not in fixed]
        self.firsts = [self.warmup + r.skip for r in recs]  # the first sample counted
        self.y = np.concatenate([r.y[k:] for r, k in zip(recs, self.firsts, strict=True)])
        self.load_all = np.concatenate([lo[k:] for lo, k in zip(loads, self.firsts, strict=True)])

    def terms(self, p: np.ndarray) -> dict[str, float]:
        out = dict(self.fixed)
        for k, v in zip(self.free, p[len(self.base_names) :], strict=True):
            out[k] = float(np.exp(v)) if k == "slack_load" else float(abs(v))
        out.setdefault("slack", 0.0)
        out.setdefault("slack_load", 1.0)
        out.setdefault("friction", 0.0)
        return out

    def base_output(self, p: np.ndarray):
        """(the base's output over the plays, the play terms), or None for an invalid base."""
        terms = self.terms(p)
        try:
            base = _with_values(self.base, self.base_names, p[: len(self.base_names)])
        except (ValueError, TypeError):
            return None, terms
        parts = []
        for r, lo, k in zip(self.recs, self.loads, self.firsts, strict=True):
            radius = play_radius(lo, terms["slack"], terms["slack_load"], terms["friction"])
            try:
                out = np.asarray(base.simulate(r.t, play(r.x, radius)), dtype=float)
            except ValueError:
                return None, terms
            parts.append(out[k:])
        u = np.concatenate(parts)
        return (u if np.all(np.isfinite(u)) else None), terms

    def gain(self, u: np.ndarray) -> float:
        if "gain" in self.fixed:
            return float(self.fixed["gain"])
        d = self.load_all
        den = float(d @ d)
        return float(d @ (self.y - u) / den) if den > 0 else 0.0

    def residual(self, p: np.ndarray) -> np.ndarray:
        u, _ = self.base_output(p)
        if u is None:
            return np.full(self.y.size, 1e3 * (np.ptp(self.y) + 1.0))
        return u + self.gain(u) * self.load_all - self.y

    def model(self, p: np.ndarray) -> Loaded:
        u, terms = self.base_output(p)
        if u is None:
            raise ValueError("identification failed: the base model rejects the best point")
        base = _with_values(self.base, self.base_names, p[: len(self.base_names)])
        return Loaded(base, gain=self.gain(u), **terms)


def _starts(problem: _Problem, keep: int = 3) -> list[np.ndarray]:
    """The ``keep`` best of a grid of starting points: the base as identified alone, the
    play's slack at 1 % and 4 % of the input span, slack_load at 0.3, 1 and 3 times the median
    |load| and friction 0 or 2 % of the span per median |load|."""
    scale = float(np.median(np.abs(problem.load_all))) or 1.0
    x_span = float(np.ptp(np.concatenate([r.x for r in problem.recs]))) or 1.0
    grid = {
        "slack": (0.01 * x_span, 0.04 * x_span),
        "slack_load": tuple(np.log(f * scale) for f in (0.3, 1.0, 3.0)),
        "friction": (0.0, 0.02 * x_span / scale),
    }
    combos: list[list[float]] = [[]]
    for k in problem.free:
        combos = [c + [v] for c in combos for v in grid[k]]
    starts = [np.asarray([*problem.base_values, *c], dtype=float) for c in combos]
    costs = [float(np.sum(problem.residual(p) ** 2)) for p in starts]
    order = np.argsort(costs)[:keep]
    return [starts[i] for i in order]


def _linearised_errors(problem: _Problem, best, model: Loaded) -> dict[str, float]:
    """Standard errors from the refinement's Jacobian (the gain's given the others)."""
    jac = np.asarray(best.jac, dtype=float)
    dof = max(problem.y.size - jac.shape[1] - 1, 1)
    sigma2 = 2.0 * float(best.cost) / dof
    cov = sigma2 * np.linalg.pinv(jac.T @ jac)
    se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    out: dict = {}
    for k, v in zip(problem.base_names, se, strict=False):
        if k.endswith("]"):  # a list parameter's item: the errors as a list, NaN where held
            key, index = k[:-1].split("[")
            size = len(problem.base.params[key])
            out.setdefault(f"base.{key}", [float("nan")] * size)[int(index)] = float(v)
        else:
            out[f"base.{k}"] = float(v)
    for k, v in zip(problem.free, se[len(problem.base_names) :], strict=True):
        out[k] = float(v * model.terms[k]) if k == "slack_load" else float(v)
    if "gain" not in problem.fixed:
        den = float(problem.load_all @ problem.load_all)
        out["gain"] = float(np.sqrt(sigma2 / den)) if den > 0 else float("nan")
    return out


def identify_loaded(
    template: Loaded,
    recordings: Sequence,
    loads: Sequence,
    *,
    warmup: int = 0,
    fixed: dict[str, float] | None = None,
    base_options: dict[str, Any] | None = None,
    max_nfev: int = 40,
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

    Returns
    -------
    Fit
        The identified Loaded model, its errors over the recordings and a message.

    Raises
    ------
    ValueError
        A load of another length than its recording, not finite, or an unknown fixed term.
    """
    from .core import identify
    from .data import make_recordings

    start = time.perf_counter()
    fixed = dict(fixed or {})
    unknown = set(fixed) - {"gain", *_SEARCHED}
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
    options = {"progress": False, **(base_options or {})}
    base_cls = type(template.base)
    spec = template.base if isinstance(template.base, Chain) else base_cls  # a Chain: itself
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        base0 = identify(spec, recordings=[(r.t, r.x, r.y) for r in recs], **options).model
    problem = _Problem(base0, recs, arrays, warmup, fixed)
    best = None
    for p0 in _starts(problem, keep=2):
        res = least_squares(problem.residual, p0, max_nfev=max_nfev, x_scale="jac")
        if best is None or res.cost < best.cost:
            best = res
    assert best is not None
    model = problem.model(best.x)
    lo = min(float(r.x.min()) for r in recs)
    hi = max(float(r.x.max()) for r in recs)
    model.input_range = (lo, hi)
    predictions = [
        np.asarray(model.simulate(r.t, r.x, load=a), dtype=float)
        for r, a in zip(recs, arrays, strict=True)
    ]
    names = sorted({f"base.{k.split('[')[0]}" for k in problem.base_names}) + problem.free
    if "gain" not in fixed:
        names.append("gain")
    ses = _linearised_errors(problem, best, model)
    return Fit.from_quality(
        model,
        fit_quality(recs, predictions, warmup),
        identified=names,
        fixed=fixed,
        standard_errors=ses,
        evaluations=int(best.nfev),
        seconds=time.perf_counter() - start,
        generations=0,
        method=f"Loaded({base_cls.__name__}): base alone, then joint least squares",
        message=str(best.message),
        warmup=int(warmup),
        recordings=recs,
        predictions=predictions,
        input_range=(lo, hi),
    )
