"""The local stage of every identification path: least squares on the simulation error, and the
wall-clock budget (``identify(..., time_budget=)``) that the search and this stage respect."""

from __future__ import annotations

import time
from contextvars import ContextVar

import numpy as np


class TimeBudget:
    """A wall-clock budget in seconds (None: unlimited); ``hit`` records that it stopped a stage."""

    def __init__(self, seconds: float | None):
        if seconds is not None and not (np.isfinite(seconds) and seconds > 0):
            raise ValueError(f"time_budget must be a number of seconds > 0 (got {seconds})")
        self.seconds = None if seconds is None else float(seconds)
        self.start = time.perf_counter()
        self.hit = False

    def elapsed(self) -> float:
        return time.perf_counter() - self.start

    def over(self) -> bool:
        if self.seconds is not None and self.elapsed() > self.seconds:
            self.hit = True
        return self.hit

    def note(self) -> str:
        return f"; stopped by the time budget ({self.seconds:g} s)" if self.hit else ""


class _Stop(Exception):
    pass


def forward_jacobian(problem, space, u: np.ndarray, h: np.ndarray) -> np.ndarray:
    """(n_fitted, k) forward-difference Jacobian of the residuals in search coordinates, all
    k + 1 candidates simulated in one batched call (a step past the upper bound is mirrored);
    non-finite entries are zeroed."""
    U = np.vstack([u, u[None, :] + np.diag(h)])
    flip = U[1:] > space.upper
    U[1:][flip] -= 2 * np.diag(h)[flip]
    R = problem.residuals(space.natural(U))
    step = np.diag(U[1:] - u[None, :])
    J = (R[1:] - R[0][None, :]) / step[:, None]
    J[~np.isfinite(J)] = 0.0
    return J.T


#: a cap on each refinement's evaluations while it is set (compare_models sets it for its
#: cross-validation folds, the fits that only rank the candidates; the winner's final fit on
#: all the data is not capped). None: the caller's ``max_nfev``.
REFINE_LIMIT: ContextVar[int | None] = ContextVar("REFINE_LIMIT", default=None)


def refine(
    problem,
    space,
    u0,
    counter: dict,
    *,
    separable: bool = False,
    budget: TimeBudget | None = None,
    jacobian=None,
    max_nfev: int = 100,
    xtol: float = 1e-10,
    gtol: float = 1e-8,
):
    """SciPy's trust-region least squares on the simulation error from ``u0`` (search
    coordinates, clipped inside the bounds); returns (u, message).

    Residuals: ``problem.residual(v)`` when ``separable`` (the linear part solved inside,
    2-point Jacobian), else ``problem.residuals`` of one candidate with ``jacobian(u)`` (default:
    batched forward differences, steps 1e-6 of the bounds' span). A non-finite residual
    becomes a large constant one. Keeps ``u0`` when nothing improved on it; when ``budget``
    runs out it stops and returns the best point evaluated so far. At most REFINE_LIMIT
    evaluations while that is set.
    """
    from scipy.optimize import least_squares

    limit = REFINE_LIMIT.get()
    if limit is not None:
        max_nfev = min(max_nfev, int(limit))
    span = space.upper - space.lower
    u0 = np.clip(u0, space.lower + 1e-9 * span, space.upper - 1e-9 * span)
    best = {"u": np.array(u0, dtype=float), "cost": np.inf}
    big = 1e3 * (float(np.ptp(problem.y)) + 1.0)

    def fun(u):
        if budget is not None and best["cost"] < np.inf and budget.over():
            raise _Stop
        counter["evaluations"] += 1
        v = space.natural(u)
        r = problem.residual(v) if separable else problem.residuals(v[None, :])[0]
        if not np.all(np.isfinite(r)):
            return np.full(r.size, big)
        cost = float(r @ r)
        if cost < best["cost"]:
            best["u"], best["cost"] = np.array(u, dtype=float), cost
        return r

    def jac(u):
        if budget is not None and budget.over():
            raise _Stop
        counter["evaluations"] += u.size + 1
        if jacobian is not None:
            return jacobian(u)
        return forward_jacobian(problem, space, u, 1e-6 * span)

    cost0 = float(np.sum(fun(u0) ** 2))
    try:
        res = least_squares(
            fun,
            u0,
            jac="2-point" if separable else jac,
            bounds=(space.lower, space.upper),
            method="trf",
            x_scale="jac",
            max_nfev=max_nfev,
            ftol=1e-12,
            xtol=xtol,
            gtol=gtol,
        )
    except _Stop:
        return best["u"], "stopped by the time budget at the best point so far"
    except (ValueError, np.linalg.LinAlgError) as exc:  # pragma: no cover - defensive
        return best["u"], f"failed ({exc})"
    if np.isfinite(2.0 * res.cost) and 2.0 * res.cost <= cost0:
        return res.x, res.message
    return u0, "kept the start (no improvement)"


__all__ = ["REFINE_LIMIT", "TimeBudget", "forward_jacobian", "refine"]
