"""Objective functions: batched simulation error of a population of parameter vectors.

A *direct* problem searches (a subset of) the model's parameters, or the coefficients of
their curve-angle laws; every candidate is simulated on every recording in one C++ call.
A *separable* problem searches only the nonlinear parameters; the linear ones are solved by
least squares for each candidate inside the C++ call (variable projection).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any

import numpy as np

from ..models import CurveAngleModel, HysteresisModel
from ..models.angle_dependent import AngleDependent, angle_factor, law_value
from ._bound import (
    POPULATION,
    features_BoucWen,
    features_BoucWenBacklash,
    features_GeneralizedPrandtlIshlinskii,
    features_PrandtlIshlinskii,
    separable_cost_BoucWen,
    separable_cost_BoucWenBacklash,
    separable_cost_GeneralizedPrandtlIshlinskii,
    separable_cost_PrandtlIshlinskii,
)
from .data import Recording, fitted_mask, recording_set

#: the batched C++ kernels of a separable problem by its kind: the costs with the linear part
#: solved, and the regressors (features) of the linear part
SEPARABLE_COST: dict[str, Callable[..., Any]] = {
    "BoucWen": separable_cost_BoucWen,
    "BoucWenBacklash": separable_cost_BoucWenBacklash,
    "GeneralizedPrandtlIshlinskii": separable_cost_GeneralizedPrandtlIshlinskii,
    "PrandtlIshlinskii": separable_cost_PrandtlIshlinskii,
}
FEATURES: dict[str, Callable[..., Any]] = {
    "BoucWen": features_BoucWen,
    "BoucWenBacklash": features_BoucWenBacklash,
    "GeneralizedPrandtlIshlinskii": features_GeneralizedPrandtlIshlinskii,
    "PrandtlIshlinskii": features_PrandtlIshlinskii,
}


class Space:
    """Search coordinates u (log for log-scaled names) <-> natural values v."""

    def __init__(self, names, bounds: dict, log_names):
        self.names = tuple(names)
        self.log = np.array([n in log_names for n in self.names])
        lo = np.array([bounds[n][0] for n in self.names], dtype=float)
        hi = np.array([bounds[n][1] for n in self.names], dtype=float)
        for n, a, b in zip(self.names, lo, hi, strict=True):
            if not (np.isfinite(a) and np.isfinite(b) and b > a):
                raise ValueError(f"bounds of {n} must be finite with lower < upper (got {a}, {b})")
        bad = self.log & ~(lo > 0)
        if bad.any():
            lo[bad] = hi[bad] * 1e-6
        self.lower = np.where(self.log, np.log(np.maximum(lo, 1e-300)), lo)
        self.upper = np.where(self.log, np.log(hi), hi)

    def natural(self, u: np.ndarray) -> np.ndarray:
        v = np.array(u, dtype=float)
        v[..., self.log] = np.exp(v[..., self.log])
        return v

    def search(self, v: np.ndarray) -> np.ndarray:
        u = np.array(v, dtype=float)
        u[..., self.log] = np.log(np.maximum(u[..., self.log], 1e-300))
        return u


def _base_struct(model_class, options: dict, values: dict | None = None):
    """The C++ parameter struct holding the model's numerical options."""
    return model_class(**(values or {}), **options).params_struct()


#: options that the global search may only coarsen (it needs the basin, not the last digit)
_COARSER = ("max_step",)


def _search_base(model_class, options: dict, search_options: dict | None, values=None):
    """The parameter struct used during the global search only: the spec's
    ``search_options`` cap the work (``max_substeps``: the smaller one; ``max_step``: the
    larger one); the refinement and the fitted model use ``options`` as given."""
    if not search_options:
        return _base_struct(model_class, options, values)
    merged = dict(options)
    for k, v in search_options.items():
        pick = max if k in _COARSER else min
        merged[k] = pick(merged.get(k, v), v)
    if "substeps" in merged and "max_substeps" in merged:
        merged["max_substeps"] = max(merged["max_substeps"], merged["substeps"])
    return _base_struct(model_class, merged, values)


class DirectProblem:
    """Search the free parameters (or angle-law coefficients) of a model directly."""

    def __init__(
        self,
        model_class,
        recs: list[Recording],
        warmup: int,
        values: dict[str, float],
        free: list[str],
        bounds: dict[str, tuple[float, float]],
        log_names,
        options: dict,
        depends: dict[str, str] | None = None,
        workers: int = 0,
        search_options: dict | None = None,
    ):
        self.model_class = model_class
        self.recs = recs
        self.warmup = warmup
        self.values = dict(values)
        self.free = list(free)
        self.options = dict(options)
        self.depends = dict(depends or {})
        self.workers = workers
        self.names = list(model_class.param_names)
        self.with_angle = model_class is CurveAngleModel
        self.rs = recording_set(recs, warmup, self.with_angle)
        self.base = _base_struct(model_class, options)
        self.search_base = _search_base(model_class, options, search_options)
        self.population_cost, self.population_simulate = POPULATION[model_class.__name__]
        self.y = np.concatenate([r.y for r in recs])
        self.mask = fitted_mask(recs, warmup)
        self.angles: list[float] | None = None
        # coefficient layout
        coef_names: list[str] = []
        coef_bounds = {}
        self.layout = []  # (param, law, index of first coefficient)
        for p in self.free:
            law = self.depends.get(p, "constant")
            lo, hi = bounds[p]
            self.layout.append((p, law, len(coef_names)))
            if law == "constant":
                coef_names.append(p)
                coef_bounds[p] = (lo, hi)
            else:
                span = hi - lo
                coef_names += [f"{p}[0]", f"{p}[1]"]
                if law == "linear":
                    tmax = max(abs(a) for a in self._angles()) or 1.0
                    coef_bounds[f"{p}[0]"] = (lo - span, hi + span)
                    coef_bounds[f"{p}[1]"] = (-span / tmax, span / tmax)
                else:
                    coef_bounds[f"{p}[0]"] = (lo - 0.5 * span, hi)
                    coef_bounds[f"{p}[1]"] = (-span, span)
        self.tanh = any(law == "tanh" for _, law, _ in self.layout)
        if self.tanh:
            coef_names.append("angle_friction")
            coef_bounds["angle_friction"] = bounds.get("angle_friction", (0.01, 1.0))
        log = {n for n in coef_names if n in log_names and n in self.free}
        self.space = Space(coef_names, coef_bounds, log)

    def _angles(self) -> list[float]:
        if self.angles is None:
            angles = []
            for i, r in enumerate(self.recs):
                a = r.angle()
                if a is None:
                    raise ValueError(
                        f"recording {i}: parameters that depend on the curve angle need one "
                        "constant curve angle per recording"
                    )
                angles.append(a)
            self.angles = angles
        return self.angles

    def tanh_basis(self, mu: np.ndarray) -> np.ndarray:
        """(len(mu), R) basis of the "tanh" laws: tanh(mu |Theta_r|/2) of recording r's curve
        angle, or the dead-zone factor F(g, G, mu Theta) of its route (g, G recomputed for
        every candidate friction)."""
        mu = np.atleast_1d(np.asarray(mu, dtype=float))
        theta = np.asarray(self._angles())
        out = np.tanh(0.5 * mu[:, None] * np.abs(theta)[None, :])
        for j, r in enumerate(self.recs):
            if r.route is not None:
                out[:, j] = angle_factor(r.route, mu)
        return out

    # -- coefficients -> per-recording parameter rows ------------------------------------
    def rows(self, C: np.ndarray) -> np.ndarray:
        C = np.atleast_2d(C)
        P, R = C.shape[0], len(self.recs)
        full = np.empty((P, R, len(self.names)))
        for j, name in enumerate(self.names):
            if name in self.values and name not in self.free:
                full[:, :, j] = self.values[name]
        mu = C[:, -1] if self.tanh else None
        basis = None  # the tanh laws' basis, computed once for all of them
        for p, law, i in self.layout:
            j = self.names.index(p)
            if law == "constant":
                full[:, :, j] = C[:, i : i + 1]
            else:
                theta = np.asarray(self._angles())[None, :]
                if law == "linear":
                    full[:, :, j] = C[:, i : i + 1] + C[:, i + 1 : i + 2] * theta
                else:
                    assert mu is not None  # a tanh law: mu is the last coefficient
                    if basis is None:
                        basis = self.tanh_basis(mu)
                    full[:, :, j] = C[:, i : i + 1] + C[:, i + 1 : i + 2] * basis
        return np.ascontiguousarray(full.reshape(P, R * len(self.names)))

    def cost(self, C: np.ndarray) -> np.ndarray:
        return self.population_cost(self.search_base, self.rows(C), self.rs, self.workers)

    def simulate(self, C: np.ndarray, search: bool = False) -> np.ndarray:
        """Outputs of a population (``search``: with the global search's options)."""
        base = self.search_base if search else self.base
        return self.population_simulate(base, self.rows(C), self.rs, self.workers)

    def residuals(self, C: np.ndarray) -> np.ndarray:
        """(P, n_fitted) residuals y - y_hat after warm-up."""
        return self.y[self.mask][None, :] - self.simulate(C)[:, self.mask]

    def coefficients_of(self, model: HysteresisModel) -> np.ndarray:
        """The coefficient vector of a fitted model (inverse of model())."""
        if isinstance(model, AngleDependent):
            p = model.params
            c = []
            for name, _law, _ in self.layout:
                c += p["coefficients"][name]
            if self.tanh:
                c.append(p["angle_friction"])
            return np.array(c, dtype=float)
        params = model.params
        return np.array([params[n] for n in self.free], dtype=float)

    def model(self, c: np.ndarray) -> HysteresisModel:
        c = np.asarray(c, dtype=float)
        if not self.depends:
            values = {**self.values, **{n: float(v) for n, v in zip(self.free, c, strict=True)}}
            return self.model_class(**values, **self.options)
        coefficients = {n: [float(self.values[n])] for n in self.names if n not in self.free}
        laws = {}
        for p, law, i in self.layout:
            laws[p] = law
            k = 1 if law == "constant" else 2
            coefficients[p] = [float(v) for v in c[i : i + k]]
        return AngleDependent(
            self.model_class.__name__,
            coefficients,
            laws,
            angle_friction=float(c[-1]) if self.tanh else None,
            base_options=self.options,
        )

    def standard_errors(self, c: np.ndarray, sse: float, n_fit: int):
        """Standard errors of the coefficients from the Jacobian of the simulation output
        (central differences, one batched call): s^2 (J'J)^-1 with s^2 = SSE / (N - p)."""
        return _covariance_se(self.jacobian(c), sse, n_fit)

    def jacobian(self, c: np.ndarray) -> np.ndarray:
        """(n_fitted, k) Jacobian of the simulation output with respect to the coefficients
        (central differences, one batched call; one-sided at a validity limit)."""
        c = np.asarray(c, dtype=float)
        k = c.size
        h = 1e-4 * np.maximum(np.abs(c), 1e-3 * (self.space.upper - self.space.lower + 1e-300))
        h = np.where(self.space.log, 1e-4 * np.maximum(np.abs(c), 1e-300), h)
        plus = c[None, :] + np.diag(h)
        minus = c[None, :] - np.diag(h)
        out = self.simulate(np.vstack([plus, minus, c[None, :]]))[:, self.mask]
        up, down, mid = out[:k], out[k : 2 * k], out[2 * k]
        J = np.empty((k, mid.size))
        for i in range(k):  # one-sided at a validity limit (e.g. n = 1)
            ok_up, ok_down = np.all(np.isfinite(up[i])), np.all(np.isfinite(down[i]))
            if ok_up and ok_down:
                J[i] = (up[i] - down[i]) / (2 * h[i])
            elif ok_up:
                J[i] = (up[i] - mid) / h[i]
            else:
                J[i] = (mid - down[i]) / h[i]
        return J.T


def _covariance_se(J: np.ndarray, sse: float, n_fit: int) -> np.ndarray:
    k = J.shape[1]
    if not np.all(np.isfinite(J)):
        return np.full(k, np.nan)
    dof = max(n_fit - k, 1)
    s2 = sse / dof
    cov = s2 * np.linalg.pinv(J.T @ J)
    return np.sqrt(np.clip(np.diag(cov), 0.0, None))


class SeparableProblem:
    """Search the nonlinear parameters; the linear ones are solved for every candidate."""

    def __init__(
        self, spec, recs, warmup, values, search_bounds, scale, options, workers=0, initial=None
    ):
        self.spec = spec
        self.model_class = spec.model_class
        self.recs = recs
        self.warmup = warmup
        self.values = dict(values)  # fixed nonlinear values (by public or search name)
        self.options = dict(options)
        self.workers = workers
        self.scale = scale
        names = [n for n in spec.search_names if n not in self.values]
        self.space = Space(names, search_bounds, spec.log_names)
        self.rs = recording_set(recs, warmup, False)
        self.base = _base_struct(self.model_class, options, initial)
        self.search_base = _search_base(self.model_class, options, spec.search_options, initial)
        kind = spec.kind
        self.separable_cost = SEPARABLE_COST[kind]
        self.features = FEATURES[kind]
        self.y = np.concatenate([r.y for r in recs])
        self.mask = fitted_mask(recs, warmup)
        self.lin_lo, self.lin_hi = spec.linear_bounds(scale)

    def _values(self, S: np.ndarray) -> dict[str, np.ndarray]:
        S = np.atleast_2d(S)
        v = {n: S[:, i] for i, n in enumerate(self.space.names)}
        for n, val in self.values.items():
            v[n] = np.full(S.shape[0], float(val))
        return v

    def cost(self, S: np.ndarray) -> np.ndarray:
        nl = np.ascontiguousarray(self.spec.nonlinear(self._values(S)), dtype=float)
        return self.separable_cost(self.search_base, nl, self.rs, self.workers)

    def _regressors(self, s: np.ndarray) -> np.ndarray:
        nl = np.ascontiguousarray(self.spec.nonlinear(self._values(s))[0], dtype=float)
        F = self.features(self.base, nl, self.rs)[self.mask]
        if hasattr(self.spec, "to_partial_sums"):
            F = self.spec.to_partial_sums(F)
        return F

    def linear(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Bounded least-squares linear coefficients and the residual at nonlinear s."""
        F = self._regressors(s)
        y = self.y[self.mask]
        if not np.all(np.isfinite(F)):
            return np.full(F.shape[1], np.nan), np.full(y.size, 1e6 * (np.ptp(y) + 1.0))
        theta = bounded_lsq(F, y, self.lin_lo, self.lin_hi)
        return theta, y - F @ theta

    def residual(self, s: np.ndarray) -> np.ndarray:
        return self.linear(s)[1]

    def model(self, s: np.ndarray) -> HysteresisModel:
        theta, _ = self.linear(s)
        values = {k: float(v[0]) for k, v in self._values(s).items()}
        public = self.spec.public(values, theta)
        return self.model_class(**public, **self.options)


def _triangular_factor(M: np.ndarray) -> np.ndarray:
    """R with R^T R = M^T M (as from M = Q R): the Cholesky factor of the column-scaled Gram
    matrix, one BLAS product, ~30x cheaper than a Householder QR of a tall matrix. Squaring
    the condition number costs accuracy only along directions M hardly excites, which move
    the residual as little; a singular Gram matrix (a play that never moves: a constant
    column) gets a 1e-10 relative ridge, a QR is the last resort."""
    norms = np.linalg.norm(M, axis=0)
    norms[norms == 0] = 1.0
    Ms = M / norms
    G = Ms.T @ Ms
    for ridge in (0.0, 1e-10):
        try:
            return np.linalg.cholesky(G + ridge * np.eye(G.shape[0])).T * norms
        except np.linalg.LinAlgError:
            continue
    return np.linalg.qr(Ms, mode="r") * norms  # pragma: no cover - defensive


def bounded_lsq(F: np.ndarray, y: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """min ||y - F theta|| with lo <= theta <= hi, for bounds of the kinds the specs use.

    Coefficients bounded below only (theta >= lo) are shifted to v = theta - lo >= 0 and the
    unbounded ones (an offset) projected out, so the problem is an exact active-set NNLS
    (Lawson-Hanson, as in the C++ batch), solved on the triangular factor of [F y]. SciPy's
    ``lsq_linear`` (trust-region reflective) is kept for other bounds only: with an
    unbounded column and every other bound active, as on a negative-gain record, its
    reflected step multiplies an infinite stride by zero ("invalid value encountered in
    multiply") and it is also ~50x slower.
    """
    from scipy.optimize import lsq_linear, nnls

    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    if F.shape[0] > F.shape[1] + 1:
        # ||F theta - y|| = ||R[:, :n] theta - R[:, n]|| up to a constant, for R the
        # triangular factor of [F y]: the same minimiser from n+1 rows instead of every sample
        R = _triangular_factor(np.column_stack([F, y]))
        F, y = R[:, :-1], R[:, -1]
    col = np.linalg.norm(F, axis=0)
    col[col == 0] = 1.0
    Fs = F / col
    if np.any(np.isfinite(hi)):
        res = lsq_linear(Fs, y, bounds=(lo * col, hi * col), lsmr_tol="auto")
        return res.x / col
    free = ~np.isfinite(lo)
    shift = np.where(free, 0.0, lo * col)
    r = y - Fs[:, ~free] @ shift[~free]
    A = Fs[:, ~free]
    if free.any():
        Q, _ = np.linalg.qr(Fs[:, free])
        A = A - Q @ (Q.T @ A)
        b = r - Q @ (Q.T @ r)
    else:
        b = r
    theta = np.empty(F.shape[1])
    v = nnls(A, b, maxiter=50 * max(A.shape[1], 1))[0] if A.shape[1] else np.empty(0)
    theta[~free] = shift[~free] + v
    if free.any():
        rest = r - Fs[:, ~free] @ v
        theta[free] = np.linalg.lstsq(Fs[:, free], rest, rcond=None)[0]
    return theta / col


def law_check(depends: dict[str, str], names) -> dict[str, str]:
    """Validate a depends_on_angle mapping."""
    out = {}
    for name, law in (depends or {}).items():
        if name not in names:
            raise ValueError(
                f"depends_on_angle: unknown parameter {name!r}; expected {list(names)}"
            )
        if law not in ("constant", "linear", "tanh"):
            raise ValueError(
                f"depends_on_angle[{name!r}] must be 'constant', 'linear' or 'tanh' (got {law!r})"
            )
        out[name] = law
    return out


def with_fitted_output(problem, y_star: np.ndarray):
    """A shallow copy of ``problem`` whose measured output (fitted samples) is ``y_star``: the
    problem's own ``with_fitted_output`` when it has one (a chain's), else its ``y`` at
    ``mask`` replaced."""
    own = getattr(problem, "with_fitted_output", None)
    if own is not None:
        return own(y_star)
    p = copy.copy(problem)
    y = np.array(problem.y, dtype=float)
    y[problem.mask] = y_star
    p.y = y
    return p


def over_recordings(problem, recs: list[Recording], warmup: int):
    """A shallow copy of ``problem`` over other recordings (same parameters and bounds): the
    problem's own ``over_recordings`` when it has one (a chain's), else its recordings, their
    set, output and mask replaced."""
    own = getattr(problem, "over_recordings", None)
    if own is not None:
        return own(recs, warmup)
    p = copy.copy(problem)
    p.recs = recs
    p.rs = recording_set(recs, warmup, getattr(problem, "with_angle", False))
    p.y = np.concatenate([r.y for r in recs])
    p.mask = fitted_mask(recs, warmup)
    if hasattr(p, "angles"):
        p.angles = None
    return p


__all__ = [
    "FEATURES",
    "SEPARABLE_COST",
    "DirectProblem",
    "SeparableProblem",
    "Space",
    "law_check",
    "law_value",
    "over_recordings",
    "with_fitted_output",
]
