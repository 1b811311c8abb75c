"""Hammerstein and Wiener chains: a hysteresis operator and a linear dynamic block.

``Chain(H, L)`` (Hammerstein: y = L[H[x]]) and ``Chain(L, H)`` (Wiener: y = H[L[x]]), with H a
BoucWenBacklash or a PrandtlIshlinskii and L a :class:`~tendonsheath.models.FirstOrderLag` or
:class:`~tendonsheath.models.SecondOrderLag` (unit static gain, at rest at the first input).

Both stay separable: H's output is linear in its linear parameters (BoucWenBacklash: c_r,
c_r B_r, c_l, c_l B_l; PrandtlIshlinskii: the weights' partial sums) given its nonlinear ones,
and L is linear, so for each candidate (H's nonlinear parameters, L's time constants) the
regressors are H's features (one C++ call) filtered by L (Hammerstein) or computed on the
filtered input (Wiener), and the linear parameters follow from bounded least squares. The
global search and the refinement are the same as for the other models. The cost per
candidate is linear in the number of samples.
"""

from __future__ import annotations

import copy
import os
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..models import BoucWenBacklash, Chain, LinearBlock, PrandtlIshlinskii, SecondOrderLag
from ..models.linear_block import apply_filter, sample_time
from .data import Recording, check_for_fit, decimate_for_search, fitted_mask, recording_set
from .fit import Fit, fit_quality, simulate_model
from .problem import FEATURES, Space, _base_struct, _search_base, bounded_lsq
from .search import search_and_refine
from .specs import BoucWenBacklashSpec, PrandtlIshlinskiiSpec, Scale
from .uncertainty import assess

STATIC = (BoucWenBacklash, PrandtlIshlinskii)
_PENALTY = 1e100


def is_dynamic_chain(chain) -> bool:
    if not isinstance(chain, Chain):
        return False
    a, b = chain.first, chain.second
    return (isinstance(a, STATIC) and isinstance(b, LinearBlock)) or (
        isinstance(a, LinearBlock) and isinstance(b, STATIC)
    )


def _times(recs: list[Recording]) -> list[np.ndarray]:
    """The recordings' times (a dynamic model needs them: DynamicProblem checks first)."""
    times = [r.t for r in recs if r.t is not None]
    assert len(times) == len(recs)
    return times


def _block_bounds(block: LinearBlock, recs: list[Recording]) -> dict:
    times = _times(recs)
    dt = float(np.median(np.concatenate([np.diff(t) for t in times])))
    duration = float(max(t[-1] - t[0] for t in times))
    if isinstance(block, SecondOrderLag):
        return {"frequency": (2.0 / duration, 0.45 / dt), "damping": (0.05, 3.0)}
    return {"time_constant": (0.2 * dt, 0.5 * duration)}


class DynamicProblem:
    """Search H's nonlinear parameters and L's; solve H's linear ones for every candidate."""

    def __init__(self, chain: Chain, recs: list[Recording], warmup: int, workers: int):
        self.hammerstein = isinstance(chain.first, STATIC)
        static, block = (
            (chain.first, chain.second) if self.hammerstein else (chain.second, chain.first)
        )
        assert isinstance(block, LinearBlock)  # a dynamic chain (is_dynamic_chain)
        self.static_cls = type(static)
        self.block_cls = type(block)
        self.recs = recs
        self.warmup = warmup
        self.workers = workers
        for r in recs:
            sample_time(r.t)  # uniform sampling, or a clear error
        self.spec: PrandtlIshlinskiiSpec | BoucWenBacklashSpec
        if self.static_cls is PrandtlIshlinskii:
            thr = np.asarray(static.params["thresholds"], dtype=float)
            self.spec = PrandtlIshlinskiiSpec(
                thr / thr[-1] if thr[-1] > 0 else np.linspace(0, 1, thr.size)
            )
        else:
            self.spec = BoucWenBacklashSpec()
        self.options = static.options
        scale = Scale.of(recs)
        sb = self.spec.search_bounds(scale, {})
        self.n_static = len(self.spec.search_names)
        bb = _block_bounds(block, recs)
        names = [*self.spec.search_names, *block.param_names]
        log = set(self.spec.log_names) | set(block.param_names) - {"damping"}
        self.space = Space(names, {**sb, **bb}, log)
        self.block_names = block.param_names
        self.base = _base_struct(self.static_cls, self.options, static.params)
        self.search_base = _search_base(
            self.static_cls, self.options, self.spec.search_options, static.params
        )
        self.features = FEATURES[self.spec.kind]
        self.rs = recording_set(recs, warmup, False)
        self.y = np.concatenate([r.y for r in recs])
        self.mask = fitted_mask(recs, warmup)
        self.lo, self.hi = self.spec.linear_bounds(scale)
        self.lin_lo, self.lin_hi = self.lo, self.hi  # as SeparableProblem names them
        self.bounds = {n: (float(v[0]), float(v[1])) for n, v in {**sb, **bb}.items()}
        self.n_params = len(names) + self.lo.size
        self.edges = np.cumsum([0] + [r.n for r in recs])
        self.dts = [float(np.median(np.diff(t))) for t in _times(recs)]
        n_threads = workers if workers > 0 else (os.cpu_count() or 1)
        self.pool = ThreadPoolExecutor(n_threads) if n_threads > 1 else None

    def over_recordings(self, recs: list[Recording], warmup: int) -> DynamicProblem:
        """A shallow copy over other recordings (same parameters and bounds)."""
        p = copy.copy(self)
        p.recs = recs
        p.rs = recording_set(recs, warmup, False)
        p.y = np.concatenate([r.y for r in recs])
        p.mask = fitted_mask(recs, warmup)
        p.edges = np.cumsum([0] + [r.n for r in recs])
        p.dts = [float(np.median(np.diff(t))) for t in _times(recs)]
        return p

    def _split(self, c: np.ndarray):
        c = np.asarray(c, dtype=float)
        values = {
            n: np.atleast_1d(v)
            for n, v in zip(self.spec.search_names, c[: self.n_static], strict=True)
        }
        block = self.block_cls(
            **{n: float(v) for n, v in zip(self.block_names, c[self.n_static :], strict=True)}
        )
        return values, block

    def _filter(self, block: LinearBlock, X: np.ndarray) -> np.ndarray:
        out = np.empty_like(X)
        cache = {}
        for i, dt in enumerate(self.dts):
            if dt not in cache:
                cache[dt] = block.filter_coefficients(dt)
            b, a = cache[dt]
            s = slice(self.edges[i], self.edges[i + 1])
            out[s] = apply_filter(b, a, X[s], axis=0)
        return out

    def regressors(self, c: np.ndarray, search: bool = False) -> np.ndarray:
        values, block = self._split(c)
        nl = np.ascontiguousarray(self.spec.nonlinear(values)[0], dtype=float)
        base = self.search_base if search else self.base
        if self.hammerstein:
            F = self._filter(block, self.features(base, nl, self.rs))
        else:
            xf = self._filter(block, np.concatenate([r.x for r in self.recs]))
            recs = [
                Recording(r.t, xf[self.edges[i] : self.edges[i + 1]], r.y, None, r.skip)
                for i, r in enumerate(self.recs)
            ]
            F = self.features(base, nl, recording_set(recs, self.warmup, False))
        F = F[self.mask]
        if hasattr(self.spec, "to_partial_sums"):
            F = self.spec.to_partial_sums(F)
        return F

    def linear(self, c: np.ndarray, search: bool = False):
        """(linear parameters, residual) at c (``search``: the global search's options)."""
        y = self.y[self.mask]
        try:
            F = self.regressors(c, search)
        except ValueError:
            F = np.full((y.size, self.lo.size), np.nan)
        if not np.all(np.isfinite(F)):
            return np.full(self.lo.size, np.nan), np.full(y.size, 1e6 * (np.ptp(y) + 1.0))
        theta = bounded_lsq(F, y, self.lo, self.hi)
        return theta, y - F @ theta

    def _one_cost(self, c: np.ndarray) -> float:
        theta, r = self.linear(c, search=True)
        return float(r @ r) if np.all(np.isfinite(theta)) else _PENALTY

    def cost(self, C: np.ndarray) -> np.ndarray:
        """Costs of a population; candidates spread over ``workers`` threads (the C++
        feature computation releases the GIL)."""
        if self.pool is None:
            return np.array([self._one_cost(c) for c in C])
        return np.array(list(self.pool.map(self._one_cost, C)))

    def residual(self, c: np.ndarray) -> np.ndarray:
        return self.linear(c)[1]

    def model(self, c: np.ndarray) -> Chain:
        theta, _ = self.linear(c)
        values, block = self._split(c)
        public = self.spec.public({k: float(v[0]) for k, v in values.items()}, theta)
        static = self.static_cls(**public, **self.options)
        return Chain(static, block) if self.hammerstein else Chain(block, static)


def identify_dynamic(chain: Chain, recs, *, warmup=0, search) -> Fit:
    """Identify a Hammerstein or Wiener chain (see the module docstring) with the
    :class:`~tendonsheath.identify.settings.Search` settings ``search``. Standard errors
    and diagnostics: the Jacobian with respect to the chain's parameters (the operator's and
    the block's), or the bootstrap re-fits of :mod:`tendonsheath.identify.uncertainty`."""

    for i, r in enumerate(recs):
        if r.t is None:
            raise ValueError(f"recording {i}: a linear dynamic block needs the time t")
    problem = DynamicProblem(chain, recs, warmup, search.n_workers)
    check_for_fit(recs, warmup, problem.n_params, True, False)
    search_problem = None  # the search needs the basin: every m-th sample suffices
    coarse, coarse_warmup = decimate_for_search(recs, warmup)
    if coarse is not recs:
        search_problem = DynamicProblem(chain, coarse, coarse_warmup, search.n_workers)
    counter = {"evaluations": 0}
    kind = "Hammerstein" if problem.hammerstein else "Wiener"
    label = f"identify {kind} ({problem.static_cls.__name__}, {problem.block_cls.__name__})"
    start = time.perf_counter()
    u_best, res, message = search_and_refine(
        problem, problem.space, counter, label, search, search_problem=search_problem
    )
    if search_problem is not None and search_problem.pool is not None:
        search_problem.pool.shutdown()
    model = problem.model(problem.space.natural(u_best))
    if problem.pool is not None:
        problem.pool.shutdown()
        problem.pool = None
    seconds = time.perf_counter() - start
    predictions = [simulate_model(model, r.t, r.x) for r in recs]
    quality = fit_quality(recs, predictions, warmup)
    part = "first" if problem.hammerstein else "second"
    other = "second" if problem.hammerstein else "first"
    assessed = _assess(
        problem,
        model,
        quality,
        u_best,
        search.n_workers,
        method=search.standard_errors,
        count=search.bootstrap,
        block=search.bootstrap_block,
        seed=search.seed,
    )
    fit = Fit.from_quality(
        model,
        quality,
        assessed,
        identified=[f"{part}.{n}" for n in problem.static_cls.param_names]
        + [f"{other}.{n}" for n in problem.block_names],
        fixed={},
        evaluations=counter["evaluations"],
        seconds=seconds,
        generations=int(res.nit),
        method=f"differential evolution + least squares ({kind}: the operator's linear "
        "parameters solved)",
        message=message,
        warmup=warmup,
        bounds={
            f"{part if n in problem.spec.search_names else other}.{n}": b
            for n, b in problem.bounds.items()
        },
        recordings=recs,
        predictions=predictions,
    )
    fit.diagnostics.warn()
    return fit


def _assess(problem: DynamicProblem, model: Chain, quality, u_best, workers: int, **se) -> dict:
    """Standard errors and diagnostics w.r.t. the chain's parameters (the operator's, named
    first./second. as in the Chain, and the block's)."""

    part = "first" if problem.hammerstein else "second"
    other = "second" if problem.hammerstein else "first"

    def label_of(name: str) -> str:
        return f"{other if name in problem.block_names else part}.{name}"

    if problem.static_cls is PrandtlIshlinskii:
        names, scales = [f"{part}.weights"], [f"{part}.thresholds"]
    else:
        names, scales = [f"{part}.{n}" for n in problem.static_cls.param_names], []
    return assess(
        cls=problem.static_cls,
        model=model,
        problem=problem,
        recs=problem.recs,
        warmup=problem.warmup,
        values={},
        free_names=[],
        all_bounds={},
        spec=problem.spec,
        options={},
        depends={},
        workers=workers,
        sse=quality.sse,
        n_fit=quality.n,
        u_best=u_best,
        use_separable=True,
        generic=(names + [f"{other}.{n}" for n in problem.block_names], scales),
        label_of=label_of,
        **se,
    )


__all__ = ["DynamicProblem", "STATIC", "identify_dynamic", "is_dynamic_chain"]
