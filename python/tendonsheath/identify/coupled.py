"""identify_coupled(): a :class:`~tendonsheath.models.Coupled` model from logs of all joints,
by joint least squares, with Newey-West standard errors of the coupling.

Joint i's equation, y_i = H_i(x_i; theta_i) + sum_j C[i, j] y_j, holds its own parameters only,
so the joint least squares splits into one problem per joint: (1) a linear regression of y_i on
x_i and the other joints' angles gives a first coupling; (2) :func:`identify` fits H_i to
y_i minus that coupling; (3) ``scipy.optimize.least_squares`` refines theta_i and row i of C
together. The residuals of a hysteresis model fitted to a real drive are autocorrelated (the
misfit repeats over each cycle), so the standard errors are heteroscedasticity and
autocorrelation consistent: the Newey-West sandwich with a Bartlett kernel, its bandwidth by
Andrews' AR(1) plug-in rule on the coupling's scores (or ``lags``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import least_squares

from .._typing import ArrayLike, FloatArray
from ..coupled_plant import _joint_matrix
from ..models import Coupled, HysteresisModel
from .core import identify
from .fit import Fit


@dataclass
class CoupledFit:
    """The result of :func:`identify_coupled`.

    Parameters
    ----------
    model : Coupled
        The identified model.
    coupling : numpy.ndarray, shape (J, J)
        Its coupling matrix C (0 where not identified).
    coupling_se : numpy.ndarray, shape (J, J)
        Newey-West standard error of each identified C[i, j] (NaN where not identified).
    lags : list of int
        The Bartlett bandwidth (lags) of each joint's covariance.
    rmse : numpy.ndarray, shape (J,)
        Each joint's RMS prediction error (its own input, the others' measured angles).
    fits : list of Fit
        Each joint's own model fitted at stage (2), before the joint refinement.
    seconds : float
        Wall-clock time.
    """

    model: Coupled
    coupling: FloatArray
    coupling_se: FloatArray
    lags: list[int]
    rmse: FloatArray
    fits: list[Fit] = field(repr=False)
    seconds: float = 0.0

    def report(self) -> str:
        """A short text summary: each coupling coefficient with its standard error.

        Returns
        -------
        str
            One line per joint and per identified coefficient.
        """
        lines = [f"Coupled model of {self.model.joints} joints ({self.seconds:.1f} s)"]
        for i, m in enumerate(self.model.models):
            lines.append(f"  joint {i}: {m!r}  rmse {self.rmse[i]:.3e}  lags {self.lags[i]}")
        for i, j in zip(*np.nonzero(np.isfinite(self.coupling_se)), strict=True):
            lines.append(
                f"  C[{i},{j}] = {self.coupling[i, j]:+.5f} +/- {self.coupling_se[i, j]:.5f}"
            )
        return "\n".join(lines)


def identify_coupled(
    model_class: type[HysteresisModel] | Sequence[type[HysteresisModel]],
    t: ArrayLike | None,
    x: ArrayLike,
    y: ArrayLike,
    *,
    warmup: int = 0,
    couple: ArrayLike | None = None,
    lags: int | None = None,
    **options: Any,
) -> CoupledFit:
    """Identify coupled joints from logs of all of them (see the module's description).

    The joints should be excited independently (different signals): a coupling is told apart
    from a joint's own hysteresis only by what the other joints do.

    Parameters
    ----------
    model_class : type or sequence of type
        Each joint's own model class (one for all, or one per joint).
    t : array_like of float, shape (n,), or None
        Sample times (s); None for rate-independent models.
    x : array_like of float, shape (n, J)
        The joints' inputs (motor angles), one column per joint.
    y : array_like of float, shape (n, J)
        The joints' measured angles.
    warmup : int, default 0
        Samples at the start left out of every fit.
    couple : array_like of bool, shape (J, J), optional
        True where C[i, j] is identified (default every pair i != j); the others are 0.
    lags : int, optional
        Bartlett bandwidth of the Newey-West covariance (default: Andrews' rule).
    **options
        Passed to :func:`identify` for each joint's own model (``seed``, ``maxiter``, ...);
        ``normalize`` is off (the joint refinement moves the class's own parameters).

    Returns
    -------
    CoupledFit
        The model, the coupling and its standard errors.

    Raises
    ------
    ValueError
        Signals of different shapes, not finite, a bad ``couple`` or ``lags``, or too few
        samples after the warm-up.
    """
    start = time.perf_counter()
    xs = _joint_matrix(x, _joints(x), "x", "identify_coupled")
    n, joints = xs.shape
    ys = _joint_matrix(y, joints, "y", "identify_coupled")
    if ys.shape[0] != n:
        raise ValueError(f"identify_coupled: x has {n} samples, y {ys.shape[0]}")
    classes = _classes(model_class, joints)
    mask = _mask(couple, joints)
    warmup = int(warmup)
    if not 0 <= warmup < n - 10 * joints:
        raise ValueError(f"identify_coupled: warmup {warmup} leaves too few of the {n} samples")
    if lags is not None and not (isinstance(lags, int | np.integer) and 0 <= lags < n):
        raise ValueError(f"identify_coupled: lags must be an integer in [0, n) (got {lags!r})")
    options = {"progress": False, "standard_errors": "none", **options, "normalize": False}
    models, fits, coupling = [], [], np.zeros((joints, joints))
    se = np.full((joints, joints), np.nan)
    used_lags, rmse = [], np.zeros(joints)
    for i in range(joints):
        others = np.flatnonzero(mask[i])
        joint = _fit_joint(classes[i], t, xs[:, i], ys[:, i], ys[:, others], warmup, options)
        c_se, lag = _newey_west(joint.jac, joint.residual, len(others), lags)
        models.append(joint.model)
        fits.append(joint.fit)
        coupling[i, others] = joint.coefficients
        se[i, others] = c_se
        used_lags.append(lag)
        rmse[i] = math.sqrt(float(np.mean(joint.residual**2)))
    model = Coupled(models, coupling)
    return CoupledFit(model, coupling, se, used_lags, rmse, fits, time.perf_counter() - start)


def _joints(x: ArrayLike) -> int:
    a = np.asarray(x)
    if a.ndim != 2:
        raise ValueError(f"identify_coupled: x must have shape (n, J) (got {a.shape})")
    return int(a.shape[1])


def _classes(model_class, joints: int) -> list:
    if isinstance(model_class, type):
        return [model_class] * joints
    classes = list(model_class)
    if len(classes) != joints:
        raise ValueError(
            f"identify_coupled: {joints} joints but {len(classes)} model classes were given"
        )
    return classes


def _mask(couple, joints: int) -> np.ndarray:
    if couple is None:
        return ~np.eye(joints, dtype=bool)
    m = np.asarray(couple)
    if m.shape != (joints, joints) or m.dtype != bool:
        raise ValueError(f"identify_coupled: couple must be a {joints} x {joints} bool array")
    if np.any(np.diag(m)):
        raise ValueError("identify_coupled: couple's diagonal must be False (no self-coupling)")
    return m


@dataclass
class _Joint:
    model: HysteresisModel
    fit: Fit
    coefficients: FloatArray
    jac: FloatArray  # d residual / d (own parameters, coefficients), fitted samples
    residual: FloatArray


def _fit_joint(cls, t, x, y, others, warmup: int, options: dict) -> _Joint:
    """Stages (1) to (3) for one joint: linear start, its own model, joint refinement."""
    keep = slice(warmup, None)
    k = others.shape[1]
    a = np.column_stack([x, np.ones_like(x), others])[keep]
    c0 = np.linalg.lstsq(a, y[keep], rcond=None)[0][2:] if k else np.zeros(0)
    fit = identify(cls, t, x, y - others @ c0, warmup=warmup, **options)
    names = list(fit.identified)
    theta0 = np.array([fit.model.params[name] for name in names], dtype=float)
    lo, hi = _bounds(fit, names, theta0)

    def residual(p):
        try:
            model = fit.model.with_params(**dict(zip(names, p[: len(names)], strict=True)))
        except ValueError:  # an invalid step: a large residual makes the solver step back
            return np.full(y.size - warmup, 1e3)
        pred = np.asarray(model.simulate(t, x)) + others @ p[len(names) :]
        return (pred - y)[keep]

    p0 = np.r_[theta0, c0]
    res = least_squares(
        residual,
        p0,
        bounds=(np.r_[lo, np.full(k, -np.inf)], np.r_[hi, np.full(k, np.inf)]),
        x_scale="jac",
    )
    model = fit.model.with_params(**dict(zip(names, res.x[: len(names)], strict=True)))
    return _Joint(model, fit, res.x[len(names) :], np.asarray(res.jac), residual(res.x))


def _bounds(fit: Fit, names: list[str], theta0: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The search bounds of the identified parameters, widened to hold the start."""
    bounds = fit.bounds or {}
    lo = np.array([bounds.get(k, (-np.inf, np.inf))[0] for k in names], dtype=float)
    hi = np.array([bounds.get(k, (-np.inf, np.inf))[1] for k in names], dtype=float)
    return np.minimum(lo, theta0), np.maximum(hi, theta0)


def _newey_west(jac: FloatArray, r: FloatArray, k: int, lags: int | None) -> tuple[FloatArray, int]:
    """Standard errors of the last k parameters: (J'J)^-1 S (J'J)^-1, S the Bartlett-weighted
    sum of the scores' autocovariances up to ``lags`` (None: Andrews' AR(1) rule)."""
    if k == 0:
        return np.zeros(0), 0
    scores = jac * r[:, None]
    lag = _andrews_lags(scores[:, -k:]) if lags is None else int(lags)
    s = scores.T @ scores
    for ell in range(1, lag + 1):
        gamma = scores[ell:].T @ scores[:-ell]
        s += (1.0 - ell / (lag + 1.0)) * (gamma + gamma.T)
    bread = np.linalg.pinv(jac.T @ jac)
    cov = bread @ s @ bread
    return np.sqrt(np.clip(np.diag(cov)[-k:], 0.0, None)), lag


def _andrews_lags(scores: FloatArray) -> int:
    """Andrews (1991) Bartlett bandwidth 1.1447 (alpha n)^(1/3), alpha from an AR(1) fit to
    each score column (weighted equally), at most n - 1."""
    n = scores.shape[0]
    num = den = 0.0
    for g in scores.T:
        g = g - g.mean()
        denom = float(g[:-1] @ g[:-1])
        if denom <= 0.0:
            continue
        rho = float(np.clip(g[1:] @ g[:-1] / denom, -0.999, 0.999))
        var = float(np.mean((g[1:] - rho * g[:-1]) ** 2))
        num += 4 * rho**2 * var**2 / ((1 - rho) ** 6 * (1 + rho) ** 2)
        den += var**2 / (1 - rho) ** 4
    alpha = num / den if den > 0 else 0.0
    return int(min(n - 1, math.ceil(1.1447 * (alpha * n) ** (1.0 / 3.0))))
