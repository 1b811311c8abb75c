"""identify_coupled(): a :class:`~tendonsheath.models.Coupled` model from logs of all joints,
by joint least squares, with Newey-West standard errors of the coupling.

Joint i's equation, y_i = H_i(x_i; theta_i) + sum_j C[i, j] y_j, holds its own parameters only,
so the joint least squares splits into one problem per joint: (1) a linear regression of y_i on
x_i and the other joints' angles gives a first coupling; (2) :func:`identify` fits H_i to
y_i minus that coupling; (3) ``scipy.optimize.least_squares`` refines theta_i and row i of C
together. The residuals of a hysteresis model fitted to a real drive are autocorrelated (the
misfit repeats over each cycle), so the standard errors are heteroscedasticity and
autocorrelation consistent: the Newey-West sandwich with a Bartlett kernel, its bandwidth by
Andrews' AR(1) plug-in rule on the coupling's scores (or ``nw_lag_s``, or ``lags``). Several
recordings (sessions) share the parameters; each is simulated from rest and is an independent
block of the covariance: its autocovariances never pair samples of two recordings. With times,
the bandwidth is a time (the residuals are correlated over a time of the drive), converted to
lags in each recording at its own rate (identify/newey_west.py).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._util.typing import ArrayLike, FloatArray
from ..models import Coupled, HysteresisModel
from .coupled_data import CoupledRecording, coupled_recordings
from .estimator import identify
from .fit import Fit
from .newey_west import newey_west as _newey_west


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
        Newey-West standard error of each identified C[i, j] (NaN where not identified, inf
        where the data do not determine it).
    lags : list of list of int
        The Bartlett bandwidth of each joint's covariance, in lags (samples) of each recording.
    rmse : numpy.ndarray, shape (J,)
        Each joint's RMS prediction error (its own input, the others' measured angles).
    fits : list of Fit
        Each joint's own model fitted at stage (2), before the joint refinement.
    seconds : float
        Wall-clock time.
    lag_s : list of float
        The same bandwidth of each joint in seconds (NaN without times, or with ``lags``).
    """

    model: Coupled
    coupling: FloatArray
    coupling_se: FloatArray
    lags: list[list[int]]
    rmse: FloatArray
    fits: list[Fit] = field(repr=False)
    seconds: float = 0.0
    lag_s: list[float] = field(default_factory=list)

    def report(self) -> str:
        """A short text summary: each coupling coefficient with its standard error.

        Returns
        -------
        str
            One line per joint and per identified coefficient.
        """
        lines = [f"Coupled model of {self.model.joints} joints ({self.seconds:.1f} s)"]
        for i, m in enumerate(self.model.models):
            lags = "/".join(str(v) for v in self.lags[i])
            if self.lag_s and math.isfinite(self.lag_s[i]):
                lags += f" ({self.lag_s[i]:.3g} s)"
            lines.append(f"  joint {i}: {m!r}  rmse {self.rmse[i]:.3e}  lags {lags}")
        for i, j in zip(*np.nonzero(np.isfinite(self.coupling_se)), strict=True):
            lines.append(
                f"  C[{i},{j}] = {self.coupling[i, j]:+.5f} +/- {self.coupling_se[i, j]:.5f}"
            )
        return "\n".join(lines)


def identify_coupled(
    model_class: type[HysteresisModel] | Sequence[type[HysteresisModel]],
    t: ArrayLike | None = None,
    x: ArrayLike | None = None,
    y: ArrayLike | None = None,
    *,
    recordings: Sequence | None = None,
    warmup: int = 0,
    couple: ArrayLike | None = None,
    lags: int | None = None,
    nw_lag_s: float | None = None,
    **options: Any,
) -> CoupledFit:
    """Identify coupled joints from logs of all of them (see the module's description).

    Call it as ``identify_coupled(cls, t, x, y)`` (one log) or ``identify_coupled(cls,
    recordings=[(t1, x1, y1), (t2, x2, y2), ...])`` (several sessions, each at its own rate).
    The recordings share the parameters and the coupling; each starts from the models' rest
    state (no state carries over a gap), loses its own ``warmup`` samples, and is an
    independent block of the Newey-West covariance (no lag pairs samples of two recordings).
    The joints should be excited independently (different signals): a coupling is told apart
    from a joint's own hysteresis only by what the other joints do.

    Parameters
    ----------
    model_class : type or sequence of type
        Each joint's own model class (one for all, or one per joint).
    t : array_like of float, shape (n,), or None
        Sample times (s), strictly increasing; None for rate-independent models.
    x : array_like of float, shape (n, J)
        The joints' inputs (motor angles), one column per joint (or give ``recordings``).
    y : array_like of float, shape (n, J)
        The joints' measured angles.
    recordings : sequence of tuple, optional
        (t, x, y) per recording (or objects with ``t``, ``x``, ``y``), x and y of shape
        (n_r, J) with the same J in all; t None in all of them or in none. Not with t, x, y.
    warmup : int, default 0
        Samples at the start of each recording left out of every fit.
    couple : array_like of bool, shape (J, J), optional
        True where C[i, j] is identified (default every pair i != j); the others are 0.
    lags : int, optional
        Bartlett bandwidth of the Newey-West covariance in samples, the same number in every
        recording (default: ``nw_lag_s``'s rule). Not with ``nw_lag_s``.
    nw_lag_s : float, optional
        Bartlett bandwidth in seconds (finite, > 0; needs times t), converted to lags in each
        recording at its own sample period (the median of its time steps): ceil(nw_lag_s /
        period), at most its samples less one. Default (None): Andrews' AR(1) rule, pooled
        over the recordings in seconds (in samples without times).
    **options
        Passed to :func:`identify` for each joint's own model (``seed``, ``maxiter``, ...);
        ``normalize`` is off (the joint refinement moves the class's own parameters).

    Returns
    -------
    CoupledFit
        The model, the coupling and its standard errors.

    Raises
    ------
    TypeError
        Both t, x, y and ``recordings`` given, or neither.
    ValueError
        Signals of the wrong shape, not finite, times not increasing, recordings with
        different numbers of joints, a bad ``couple``, ``lags`` or ``nw_lag_s`` (or both of
        them), too few samples after the warm-up, or two coupled joints driven by the same
        signal (their inputs correlated beyond ``SAME_SIGNAL``, 0.999).
    """
    start = time.perf_counter()
    recs = coupled_recordings(t, x, y, recordings)
    joints = recs[0].x.shape[1]
    classes = _classes(model_class, joints)
    mask = _mask(couple, joints)
    blocks = _blocks(recs, warmup, joints)
    _check_independent_inputs(recs, mask, int(warmup))
    n = sum(blocks)
    if lags is not None and not (isinstance(lags, int | np.integer) and 0 <= lags < n):
        raise ValueError(f"identify_coupled: lags must be an integer in [0, n) (got {lags!r})")
    periods = _periods(recs, nw_lag_s, lags)
    options = {"progress": False, "standard_errors": "none", **options, "normalize": False}
    models, fits, coupling = [], [], np.zeros((joints, joints))
    se = np.full((joints, joints), np.nan)
    used_lags, lag_s, rmse = [], [], np.zeros(joints)
    for i in range(joints):
        others = np.flatnonzero(mask[i])
        joint = _fit_joint(classes[i], _JointData(recs, i, others), int(warmup), options)
        c_se, lag, seconds = _newey_west(
            joint.jac, joint.residual, len(others), lags, blocks, periods, nw_lag_s
        )
        models.append(joint.model)
        fits.append(joint.fit)
        coupling[i, others] = joint.coefficients
        se[i, others] = c_se
        used_lags.append(lag)
        lag_s.append(seconds)
        rmse[i] = math.sqrt(float(np.mean(joint.residual**2)))
    model = Coupled(models, coupling)
    seconds = time.perf_counter() - start
    return CoupledFit(model, coupling, se, used_lags, rmse, fits, seconds, lag_s)


def _periods(recs: list[CoupledRecording], nw_lag_s, lags) -> list[float] | None:
    """Each recording's sample period (the median time step; None without times), with
    ``nw_lag_s`` checked."""
    if nw_lag_s is not None:
        bad = isinstance(nw_lag_s, bool) or not isinstance(nw_lag_s, int | float | np.number)
        if bad or not (math.isfinite(nw_lag_s) and nw_lag_s > 0):
            raise ValueError(
                f"identify_coupled: nw_lag_s must be a finite number of seconds > 0 "
                f"(got {nw_lag_s!r})"
            )
        if lags is not None:
            raise ValueError(
                "identify_coupled: give the Newey-West bandwidth as lags (samples) or as "
                "nw_lag_s (seconds), not both"
            )
        if recs[0].t is None:
            raise ValueError(
                "identify_coupled: nw_lag_s (seconds) needs the sample times t of the "
                "recordings (or give lags in samples)"
            )
    if recs[0].t is None:
        return None
    return [float(np.median(np.diff(r.t))) for r in recs if r.t is not None]


def _blocks(recs: list[CoupledRecording], warmup, joints: int) -> list[int]:
    """The fitted samples of each recording, checked against the warm-up."""
    if isinstance(warmup, bool) or int(warmup) != warmup or warmup < 0:
        raise ValueError(f"identify_coupled: warmup must be a number of samples >= 0 ({warmup})")
    for i, r in enumerate(recs):
        if r.n <= warmup + 1:
            who = "" if len(recs) == 1 else f"recording {i}: "
            raise ValueError(
                f"identify_coupled: {who}warmup {int(warmup)} leaves too few of its {r.n} samples"
            )
    blocks = [r.n - int(warmup) for r in recs]
    if sum(blocks) <= 10 * joints:
        raise ValueError(
            f"identify_coupled: warmup {int(warmup)} leaves too few of the {sum(r.n for r in recs)}"
            f" samples ({sum(blocks)} fitted, more than {10 * joints} needed)"
        )
    return blocks


#: inputs of two coupled joints correlated beyond this are the same signal: a coupling is told
#: from a joint's own hysteresis only by what the other joint does differently
SAME_SIGNAL = 0.999


def _check_independent_inputs(recs: list[CoupledRecording], mask: np.ndarray, warmup: int):
    """Refuse a coupled pair whose inputs are one signal (up to scale and offset) over the
    fitted samples: the other joint's angle is then a function of this joint's own input, and
    the coupling takes whatever share of the hysteresis the fit gives it (Step 22: 0.54 and
    1.23 for 0.25 and 0, standard errors 0.006)."""
    x = np.vstack([r.x[warmup:] for r in recs])
    x = x - x.mean(axis=0)
    norms = np.linalg.norm(x, axis=0)
    for i, j in zip(*np.nonzero(np.triu(mask | mask.T, 1)), strict=True):
        if not (norms[i] > 0 and norms[j] > 0):
            continue
        r = float(x[:, i] @ x[:, j] / (norms[i] * norms[j]))
        if abs(r) > SAME_SIGNAL:
            raise ValueError(
                f"identify_coupled: joints {i} and {j} are driven by the same signal (input "
                f"correlation {r:+.4f}): the coupling C[{i},{j}], C[{j},{i}] cannot be told from "
                "each joint's own hysteresis; excite the joints independently, or leave the "
                "pair out (couple=)"
            )


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


class _JointData:
    """Joint i's signals in every recording: its times, input and angle, and the angles of
    the joints coupled into it (columns ``others``)."""

    def __init__(self, recs: list[CoupledRecording], i: int, others: np.ndarray):
        self.t = [r.t for r in recs]
        self.x = [r.x[:, i] for r in recs]
        self.y = [r.y[:, i] for r in recs]
        self.others = [r.y[:, others] for r in recs]
        self.k = int(others.size)

    def stacked(self, warmup: int) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(input, angle, others' angles) of the fitted samples of all recordings."""
        keep = slice(warmup, None)
        return (
            np.concatenate([x[keep] for x in self.x]),
            np.concatenate([y[keep] for y in self.y]),
            np.concatenate([o[keep] for o in self.others]),
        )

    def recordings(self, c: np.ndarray) -> list[tuple]:
        """(t, x, y - others @ c) per recording: joint i's own model's data."""
        return [
            (t, x, y - o @ c)
            for t, x, y, o in zip(self.t, self.x, self.y, self.others, strict=True)
        ]

    def residual(self, model: HysteresisModel, c: FloatArray, warmup: int) -> FloatArray:
        """The fitted samples' prediction errors, each recording simulated from rest."""
        parts = [
            (np.asarray(model.simulate(t, x)) + o @ c - y)[warmup:]
            for t, x, y, o in zip(self.t, self.x, self.y, self.others, strict=True)
        ]
        return np.concatenate(parts)


def _fit_joint(cls, data: _JointData, warmup: int, options: dict) -> _Joint:
    """Stages (1) to (3) for one joint: linear start, its own model, joint refinement."""
    from scipy.optimize import least_squares

    k = data.k
    x, y, others = data.stacked(warmup)
    a = np.column_stack([x, np.ones_like(x), others])
    c0 = np.linalg.lstsq(a, y, rcond=None)[0][2:] if k else np.zeros(0)
    fit = identify(cls, recordings=data.recordings(c0), warmup=warmup, **options)
    names = list(fit.identified)
    theta0 = np.array([fit.model.params[name] for name in names], dtype=float)
    lo, hi = _bounds(fit, names, theta0)

    def residual(p):
        try:
            model = fit.model.with_params(**dict(zip(names, p[: len(names)], strict=True)))
        except ValueError:  # an invalid step: a large residual makes the solver step back
            return np.full(y.size, 1e3)
        return data.residual(model, p[len(names) :], warmup)

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


__all__ = ["SAME_SIGNAL", "CoupledFit", "identify_coupled"]
