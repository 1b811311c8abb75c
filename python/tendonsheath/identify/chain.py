"""Joint identification of ``Chain(first, Polynomial(...))``: a hysteresis model followed by a
static polynomial output map.

Given the first model's output u, the output y = sum_k a_k u^k is linear in the polynomial
coefficients, so they are solved by least squares for every candidate (variable projection):
the global search covers only the first model's parameters. The polynomial carries the output
scale (and, at full degree, the offset), so the first model's scale is held (``c_r = 1`` for
Backlash and BoucWenBacklash, ``k = 1`` for BoucWen); its other parameters are searched. The
first model's population is simulated in one batched C++ call per generation; the
least-squares stage is vectorised NumPy.
"""

from __future__ import annotations

import copy
import time

import numpy as np

from ..models import Backlash, BoucWen, BoucWenBacklash, Chain, HystereticOscillator, Polynomial
from . import gauge
from .data import check_for_fit, thin_for_search
from .dynamic import identify_dynamic, is_dynamic_chain
from .fit import Fit, fit_quality, simulate_model
from .problem import DirectProblem, over_recordings
from .search import search_and_refine
from .specs import Scale, spec_for
from .uncertainty import assess

# parameters of the first model that the polynomial makes redundant, and their held values
CHAIN_HELD = {
    Backlash: {"c_r": 1.0},
    BoucWenBacklash: {"c_r": 1.0},
    BoucWen: {"k": 1.0},
    HystereticOscillator: {},
}
# bounds of the first model's relative slopes (the scale is in the polynomial)
_RELATIVE = {"c_l": (0.2, 5.0)}


class ChainProblem:
    """Search the first model's free parameters; solve the polynomial for each candidate."""

    def __init__(self, chain: Chain, recs, warmup, bounds, fixed, workers):
        first, second = chain.first, chain.second
        cls = type(first)
        if cls not in CHAIN_HELD:
            raise ValueError(
                f"Chain: cannot identify a chain whose first model is {cls.__name__}; "
                f"supported: {sorted(c.__name__ for c in CHAIN_HELD)}"
            )
        if not isinstance(second, Polynomial):
            raise ValueError(
                f"Chain: the second model must be a Polynomial to identify the chain "
                f"(got {type(second).__name__})"
            )
        self.first_cls = cls
        self.second = second
        spec = spec_for(cls)
        values = first.params
        options = first.options
        held = {n: values[n] for n in spec.default_fixed}
        held.update(CHAIN_HELD[cls])
        for k, v in (fixed or {}).items():
            name = k.removeprefix("first.")
            if name not in cls.param_names:
                raise ValueError(f"Chain: unknown parameter {k!r} of {cls.__name__}")
            held[name] = float(v)
        self.free = [n for n in cls.param_names if n not in held]
        scale = Scale.of(recs)
        b = spec.bounds(scale, held)
        b.update({k: v for k, v in _RELATIVE.items() if k in b})
        for k, v in (bounds or {}).items():
            b[k.removeprefix("first.")] = (float(v[0]), float(v[1]))
        values.update(held)
        self.held = held
        self.inner = DirectProblem(
            cls,
            recs,
            warmup,
            values,
            self.free,
            b,
            spec.log_names,
            options,
            None,
            workers,
            spec.search_options,
        )
        self.space = self.inner.space
        self.bounds = {n: b[n] for n in self.free}
        self.options = options
        self.values = values
        self.y = self.inner.y[self.inner.mask]
        self.odd = bool(second.options["odd"])
        self.degree = second.degree
        self.powers = np.arange(1, self.degree + 1, 2) if self.odd else np.arange(self.degree + 1)
        self.n_params = len(self.free) + self.powers.size

    def with_fitted_output(self, y_star: np.ndarray) -> ChainProblem:
        """A shallow copy whose measured output is ``y_star`` (``y`` holds the fitted samples
        only)."""
        p = copy.copy(self)
        p.y = np.asarray(y_star, dtype=float)
        return p

    def over_recordings(self, recs, warmup: int) -> ChainProblem:
        """A shallow copy over other recordings (same parameters and bounds)."""
        p = copy.copy(self)
        p.inner = over_recordings(self.inner, recs, warmup)
        p.y = p.inner.y[p.inner.mask]
        return p

    def _solve(self, U: np.ndarray):
        """Polynomial coefficients (P, K) and sums of squared residuals (P,) for outputs U."""
        U = U[:, self.inner.mask]
        ok = np.all(np.isfinite(U), axis=1)
        U = np.where(ok[:, None], U, 0.0)
        m = np.max(np.abs(U), axis=1)
        m = np.where(m > 0, m, 1.0)
        Us = U / m[:, None]
        B = _powers(Us, self.powers)  # (P, M, K), entries in [-1, 1]
        Bt = B.transpose(0, 2, 1)
        G = Bt @ B
        rhs = Bt @ self.y
        ridge = 1e-12 * np.trace(G, axis1=1, axis2=2)[:, None, None] + 1e-300
        G = G + ridge * np.eye(self.powers.size)[None]
        try:
            coef = np.linalg.solve(G, rhs[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            coef = np.stack(
                [np.linalg.lstsq(g, r, rcond=None)[0] for g, r in zip(G, rhs, strict=True)]
            )
        resid = self.y[None, :] - (B @ coef[:, :, None])[:, :, 0]
        sse = np.sum(resid**2, axis=1)
        sse = np.where(ok & np.isfinite(sse), sse, np.inf)
        a = coef / m[:, None] ** self.powers[None, :]
        return a, sse, resid

    def cost(self, C: np.ndarray) -> np.ndarray:
        return self._solve(self.inner.simulate(C, search=True))[1]

    def residual(self, c: np.ndarray) -> np.ndarray:
        _, sse, resid = self._solve(self.inner.simulate(np.atleast_2d(c)))
        if not np.isfinite(sse[0]):
            return np.full(self.y.size, 1e6 * (np.ptp(self.y) + 1.0))
        return resid[0]

    def model(self, c: np.ndarray) -> Chain:
        a, _, _ = self._solve(self.inner.simulate(np.atleast_2d(c)))
        first = self.inner.model(c)
        return Chain(first, Polynomial(coefficients=a[0], odd=self.odd))


def _powers(U: np.ndarray, powers: np.ndarray) -> np.ndarray:
    """U**k for the (evenly spaced) powers k, by repeated products (pow() is ~10x slower)."""
    B = np.empty((*U.shape, powers.size))
    step = U * U if powers.size > 1 and powers[1] - powers[0] == 2 else U
    cur = U.copy() if powers[0] == 1 else np.ones_like(U)
    for j in range(powers.size):
        B[..., j] = cur
        if j + 1 < powers.size:
            cur = cur * step
    return B


def identify_chain(chain: Chain, recs, *, warmup: int = 0, bounds=None, fixed=None, search) -> Fit:
    """Identify a Chain (see the module docstring) with the :class:`Search` settings
    ``search``; returns a :class:`Fit`."""
    if is_dynamic_chain(chain):
        if bounds or fixed:
            raise ValueError("Chain with a linear block: bounds and fixed are not supported")
        return identify_dynamic(chain, recs, warmup=warmup, search=search)
    n_workers = search.n_workers
    problem = ChainProblem(chain, recs, warmup, bounds, fixed, n_workers)
    check_for_fit(recs, warmup, problem.n_params, not problem.first_cls.rate_independent, False)
    space = problem.space
    counter = {"evaluations": 0}
    search_problem = None
    if chain.rate_independent:  # the search needs the basin: thinned records suffice
        thin, thin_warmup = thin_for_search(recs, warmup)
        if thin is not recs:
            search_problem = ChainProblem(chain, thin, thin_warmup, bounds, fixed, n_workers)

    start = time.perf_counter()
    label = f"identify Chain({problem.first_cls.__name__}, Polynomial)"
    u_best, res, message = search_and_refine(
        problem, space, counter, label, search, search_problem=search_problem
    )
    model = problem.model(space.natural(u_best))
    gauged = gauge.applies(model) and {"B_r", "B_l"} <= set(problem.free)
    if gauged:  # the same map in its identifiable parameterisation
        model = gauge.canonical(model)
    seconds = time.perf_counter() - start
    predictions = [simulate_model(model, r.t, r.x) for r in recs]
    quality = fit_quality(recs, predictions, warmup)
    assessed = _assess(problem, recs, warmup, model, quality, u_best, search, gauged)
    fit = Fit.from_quality(
        model,
        quality,
        assessed,
        identified=[f"first.{n}" for n in problem.free] + ["second.coefficients"],
        fixed={f"first.{k}": v for k, v in problem.held.items()},
        evaluations=counter["evaluations"],
        seconds=seconds,
        generations=int(res.nit),
        method="differential evolution + least squares (chain: polynomial solved)",
        message=message,
        warmup=warmup,
        bounds={f"first.{k}": v for k, v in problem.bounds.items()},
        recordings=recs,
        predictions=predictions,
    )
    fit.diagnostics.warn()
    return fit


def _assess(problem: ChainProblem, recs, warmup, model, quality, u_best, search, gauged) -> dict:
    """Standard errors and diagnostics of the first model's free parameters and the
    polynomial's coefficients (the gauge's identifiable groups when it applies)."""
    assessed = assess(
        cls=Chain,
        model=model,
        problem=problem,
        recs=recs,
        warmup=warmup,
        values=problem.values,
        free_names=problem.free,
        all_bounds=problem.bounds,
        spec=None,
        options={},
        depends={},
        workers=search.n_workers,
        sse=quality.sse,
        n_fit=quality.n,
        u_best=u_best,
        use_separable=True,
        method=search.standard_errors,
        count=search.bootstrap,
        block=search.bootstrap_block,
        seed=search.seed,
        chain_free=problem.free,
        generic=(gauge.entry_names(problem.free), []) if gauged else None,
        canon=gauge.canonical if gauged else None,
    )
    if gauged:
        assessed["diagnostics"].notes.append(
            "the first model's output shift is undone exactly by re-expanding the polynomial: "
            "fitted in the gauge B_r = B_l (the polynomial carries the offset); the identified "
            "quantities are in fit.groups"
        )
        assessed["groups"] = gauge.groups(model, assessed["standard_errors"])
    return assessed


__all__ = ["CHAIN_HELD", "ChainProblem", "identify_chain"]
