"""Identifiability diagnostics of a fit, generic Jacobians and bootstrap standard errors.

Every :class:`~tendonsheath.identify.Fit` carries a :class:`Diagnostics`: the identified
parameters that sit at or near a search bound (and which bound), the correlation matrix of
the parameter estimates and the condition number of the Jacobian of the simulation output
with respect to the identified parameters at the optimum (the Jacobian the linearised
standard errors come from). A fit whose diagnostics cross one of the limits below raises an
:class:`IdentifiabilityWarning` naming the parameters involved:

- ``BOUND_TOLERANCE``: a parameter within 1 % of its search range from a bound (on a log
  scale for positive ranges spanning more than a decade; a parameter constrained only from
  one side, such as a weight >= 0, when the constraint is active);
- ``CORRELATION_LIMIT``: a pair of estimates with ``|correlation| > 0.95``;
- ``CONDITION_LIMIT``: the condition number of the column-normalised Jacobian (every column
  scaled to unit length, so the figure does not depend on the parameters' units) above
  1e4. Belsley, Kuh and Welsch (Regression Diagnostics, 1980) call condition indices of a
  column-scaled regressor matrix above 30-100 strong near-dependencies; above 1e4 a
  combination of parameters is determined about 1e4 times worse than a single one, i.e.
  the data fix it only through the noise floor (a correlation of 1 - 1e-8 between two
  parameters gives 2e4).

Standard errors: linearised (``s^2 (J'J)^-1``, s^2 = SSE/(N - p)) by default; with
``standard_errors="bootstrap"`` a moving-block bootstrap of the residuals (y* = y_hat + e*,
see :func:`moving_block_resample`), with ``"bootstrap-recordings"`` a bootstrap over the
recordings (drawn with replacement; meaningful with many recordings); each resample is
re-fitted by least squares from the estimate (seeded). The re-fits do not repeat the global
search: they measure the spread of the estimate inside its basin.
"""

from __future__ import annotations

import math
import os
import sys
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from types import FrameType
from typing import Any

import numpy as np

BOUND_TOLERANCE = 0.01
CORRELATION_LIMIT = 0.95
CONDITION_LIMIT = 1e4


class IdentifiabilityWarning(UserWarning):
    """A fit whose parameters are not all determined by the data: parameters at their search
    bounds, strongly correlated pairs, an ill-conditioned Jacobian, or a group (such as the
    CurveAngleModel's friction at a single curve angle) that the data cannot separate."""


# -- bounds --------------------------------------------------------------------------------


def bound_side(
    value: float, lo: float, hi: float, tol: float = BOUND_TOLERANCE, ref: float = 0.0
) -> str | None:
    """ "lower", "upper" or None: whether ``value`` is within ``tol`` of its range from a bound
    (log scale for positive ranges spanning more than a decade). A one-sided range (one bound
    infinite) counts as at the finite bound only when the value sits on it (active
    constraint: within 1e-6 of ``ref``, the magnitude of its kind of values, e.g. the largest
    weight)."""
    v, lo, hi = float(value), float(lo), float(hi)
    if not math.isfinite(v):
        return None
    near = 1e-6 * max(abs(ref), abs(v), 1e-300)
    if math.isfinite(lo) and not math.isfinite(hi):
        return "lower" if v - lo <= near else None
    if math.isfinite(hi) and not math.isfinite(lo):
        return "upper" if hi - v <= near else None
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        return None
    if lo == 0.0 and v >= 0.0 and hi > 0:  # a physical floor: at it only when ~0
        if v <= 1e-6 * hi:
            return "lower"
        if hi - v <= tol * hi:
            return "upper"
        return None
    if lo > 0 and hi / lo > 10 and v > 0:
        lo, hi, v = math.log(lo), math.log(hi), math.log(v)
    span = hi - lo
    if v - lo <= tol * span:
        return "lower"
    if hi - v <= tol * span:
        return "upper"
    return None


# -- the diagnostics -----------------------------------------------------------------------


@dataclass
class Diagnostics:
    """Identifiability figures of one fit (see the module docstring for the limits).

    ``names``: the identified quantities the Jacobian columns stand for (parameters, angle-law
    coefficients or, for separable models, the searched and the solved parameters);
    ``correlation``: their correlation matrix (nested lists, NaN where undefined);
    ``condition_number``: of the column-normalised Jacobian; ``near_bounds``: {name: "lower"
    or "upper"} with the bound values in ``bounds``; ``correlated``: pairs (a, b, r) with
    |r| > CORRELATION_LIMIT; ``notes``: other identifiability findings (e.g. the
    CurveAngleModel's single-angle reparameterisation; those that start with "!" are also
    warnings); ``jacobian``: where J came from; ``weak``: the parameters that dominate the
    least determined direction.

    Parameters
    ----------
    names : list of str, optional
        The identified quantities.
    correlation : list of list of float, optional
        Their correlation matrix.
    condition_number : float, default nan
        Of the column-normalised Jacobian.
    near_bounds : dict of str to str, optional
        Name -> "lower" or "upper".
    bounds : dict of str to (float, float), optional
        The search bounds of those names.
    correlated : list of (str, str, float), optional
        Pairs correlated beyond CORRELATION_LIMIT.
    notes : list of str, optional
        Other findings ("!" first: also a warning).
    jacobian : str, default ""
        Where the Jacobian came from.
    weak : list of str, optional
        The parameters of the least determined direction.
    """

    names: list[str] = field(default_factory=list)
    correlation: list[list[float]] = field(default_factory=list)
    condition_number: float = float("nan")
    near_bounds: dict[str, str] = field(default_factory=dict)
    bounds: dict[str, tuple[float, float]] = field(default_factory=dict)
    correlated: list[tuple[str, str, float]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    jacobian: str = ""
    weak: list[str] = field(default_factory=list)

    @classmethod
    def from_jacobian(
        cls,
        J: np.ndarray | None,
        names: Sequence[str],
        *,
        values: dict[str, float] | None = None,
        bounds: dict[str, tuple[float, float]] | None = None,
        refs: dict[str, float] | None = None,
        source: str = "",
        notes: Sequence[str] = (),
    ) -> Diagnostics:
        """The diagnostics of a Jacobian J of the output (samples x identified quantities).

        Parameters
        ----------
        J : numpy.ndarray of float, shape (n, len(names)), or None
            The Jacobian; None or empty: only the bounds are checked.
        names : sequence of str
            The quantity of each column.
        values : dict of str to float, optional
            The identified values (to check against the bounds).
        bounds : dict of str to (float, float), optional
            The search bounds.
        refs : dict of str to float, optional
            Reference values of the bound test (default 0).
        source : str, default ""
            Where J came from.
        notes : sequence of str, optional
            Findings to keep.

        Returns
        -------
        Diagnostics
            Bounds, correlation, condition number and the weakest direction.
        """
        names = list(names)
        d = cls(names=names, jacobian=source, notes=list(notes))
        for name, (lo, hi) in (bounds or {}).items():
            if values is None or name not in values:
                continue
            side = bound_side(values[name], lo, hi, ref=(refs or {}).get(name, 0.0))
            if side is not None:
                d.near_bounds[name] = side
                d.bounds[name] = (float(lo), float(hi))
        if J is None or J.size == 0 or J.shape[1] != len(names):
            return d
        J = np.asarray(J, dtype=float)
        if not np.all(np.isfinite(J)):
            d.notes.append("the Jacobian is not finite: no correlation or condition number")
            return d
        norms = np.linalg.norm(J, axis=0)
        dead = [n for n, v in zip(names, norms, strict=True) if not v > 0]
        if dead:
            d.notes.append(
                "the output does not depend on " + ", ".join(dead) + " (zero Jacobian column)"
            )
        Js = J / np.where(norms > 0, norms, 1.0)
        _, sv, vt = np.linalg.svd(Js, full_matrices=False)
        d.condition_number = float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")
        weak = np.abs(vt[-1])
        d.weak = [names[i] for i in np.argsort(weak)[::-1] if weak[i] > 0.25][:4]
        cov = inverse_gram(sv, vt)
        sd = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        with np.errstate(invalid="ignore", divide="ignore"):
            corr = cov / np.outer(sd, sd)
        corr[~np.isfinite(corr)] = np.nan
        for i in range(len(names)):
            if norms[i] > 0:
                corr[i, i] = 1.0
        d.correlation = [[float(v) for v in row] for row in corr]
        for i in range(len(names)):
            for j in range(i + 1, len(names)):
                r = corr[i, j]
                if np.isfinite(r) and abs(r) > CORRELATION_LIMIT:
                    d.correlated.append((names[i], names[j], float(r)))
        return d

    # -- reading -----------------------------------------------------------------------
    def warnings(self) -> list[str]:
        """One message per finding that crosses a limit, naming the parameters.

        Returns
        -------
        list of str
            The messages (empty when nothing crosses a limit).
        """
        out = []
        if self.near_bounds:
            items = ", ".join(
                f"{n} at its {s} bound {self.bounds[n][0 if s == 'lower' else 1]:.4g}"
                if n in self.bounds
                else f"{n} at its {s} bound"
                for n, s in self.near_bounds.items()
            )
            out.append(f"parameters at or near their search bounds: {items}")
        if self.correlated:
            top = sorted(self.correlated, key=lambda p: -abs(p[2]))
            pairs = ", ".join(f"{a} ~ {b} (r = {r:+.3f})" for a, b, r in top[:6])
            if len(top) > 6:
                pairs += f" and {len(top) - 6} more pairs"
            out.append(f"strongly correlated estimates (|r| > {CORRELATION_LIMIT}): {pairs}")
        if math.isfinite(self.condition_number) or self.condition_number == float("inf"):
            if self.condition_number > CONDITION_LIMIT:
                out.append(
                    f"ill-conditioned Jacobian: condition number {self.condition_number:.3g} "
                    f"> {CONDITION_LIMIT:.0e} (parameters {', '.join(self.weakest())} are "
                    "poorly determined together)"
                )
        out += [n for n in self.notes if n.startswith("!")]
        return [m.removeprefix("!") for m in out]

    def weakest(self) -> list[str]:
        """The parameters that dominate the least determined direction of the Jacobian (its
        smallest right singular vector, components above 0.25).

        Returns
        -------
        list of str
            At most four names.
        """
        return list(self.weak)

    def warn(self, stacklevel: int | None = None) -> None:
        """Emit one :class:`IdentifiabilityWarning` per finding.

        Parameters
        ----------
        stacklevel : int, default 3
            Passed to :func:`warnings.warn`.
        """
        level = caller_stacklevel() if stacklevel is None else stacklevel
        for message in self.warnings():
            warnings.warn(message, IdentifiabilityWarning, stacklevel=level)

    def lines(self) -> list[str]:
        """Readable lines for a summary.

        Returns
        -------
        list of str
            Condition number, bounds, correlations and notes.
        """
        out = []
        if math.isfinite(self.condition_number) or self.condition_number == float("inf"):
            out.append(
                f"condition number {self.condition_number:.3g} (column-normalised Jacobian, "
                f"limit {CONDITION_LIMIT:.0e})"
            )
        if self.near_bounds:
            out.append(
                "at or near bounds: " + ", ".join(f"{n} ({s})" for n, s in self.near_bounds.items())
            )
        if self.correlation:
            corr = np.asarray(self.correlation, dtype=float)
            off = np.abs(corr - np.diag(np.diag(corr)))
            if off.size > 1 and np.any(np.isfinite(off)):
                i, j = np.unravel_index(np.nanargmax(off), off.shape)
                out.append(
                    f"largest |correlation| {off[i, j]:.3f} ({self.names[i]} ~ {self.names[j]})"
                )
        out += [n for n in self.notes if not n.startswith("!")]
        out += [f"WARNING: {m}" for m in self.warnings()]
        return out

    def to_dict(self) -> dict[str, Any]:
        """The diagnostics as a JSON-ready dict, with the limits and the warnings.

        Returns
        -------
        dict
            Non-finite numbers as None.
        """
        return {
            "names": list(self.names),
            "correlation": [[_num(v) for v in row] for row in self.correlation],
            "condition_number": _num(self.condition_number),
            "condition_limit": CONDITION_LIMIT,
            "correlation_limit": CORRELATION_LIMIT,
            "near_bounds": dict(self.near_bounds),
            "bounds": {k: [float(a), float(b)] for k, (a, b) in self.bounds.items()},
            "correlated": [[a, b, float(r)] for a, b, r in self.correlated],
            "notes": [n.removeprefix("!") for n in self.notes],
            "warnings": self.warnings(),
            "jacobian": self.jacobian,
            "least_determined": list(self.weak),
        }


def _num(v) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else (None if math.isnan(v) else v)


# -- generic parameter vectors of a fitted model ---------------------------------------------


@dataclass
class Entry:
    """One identified scalar of a model's params: ``key`` (a param name), ``index`` (an
    element of a list param) or ``scale`` (the whole list multiplied by a common factor)."""

    label: str
    key: str
    index: int | None = None
    scale: bool = False
    also: tuple[str, ...] = ()  # params tied to ``key`` (set to the same value)


def entries_of(model, names: Sequence[str], scales: Sequence[str] = ()) -> list[Entry]:
    """Entries for ``names`` (lists expanded element-wise) and ``scales`` (lists whose common
    scale factor is identified, e.g. a threshold grid)."""
    params = model.params
    out = []
    for name in names:
        if " = " in name:  # tied params: "a = b"
            key, *others = name.split(" = ")
            out.append(Entry(name, key, also=tuple(others)))
            continue
        v = params[name]
        if isinstance(v, list):
            out += [Entry(f"{name}[{i}]", name, i) for i in range(len(v))]
        else:
            out.append(Entry(name, name))
    out += [Entry(f"{name} (scale)", name, scale=True) for name in scales]
    return out


def entries_from_labels(labels: Sequence[str]) -> list[Entry]:
    """The entries that :func:`entries_of` labelled ``labels`` (its inverse)."""
    out = []
    for label in labels:
        if " = " in label:
            key, *others = label.split(" = ")
            out.append(Entry(label, key, also=tuple(others)))
        elif label.endswith(" (scale)"):
            out.append(Entry(label, label.removesuffix(" (scale)"), scale=True))
        elif label.endswith("]") and "[" in label:
            key, index = label[:-1].rsplit("[", 1)
            out.append(Entry(label, key, int(index)))
        else:
            out.append(Entry(label, label))
    return out


def se_dict(model, entries: Sequence[Entry], se: np.ndarray) -> dict:
    """Standard errors in the shape of ``model.params``: a scale entry's error spread over its
    list in proportion (a common factor), list elements in place, scalars as they are."""
    params = model.params
    out: dict = {}
    for e, s in zip(entries, se, strict=True):
        if e.scale:
            v = np.asarray(params[e.key], dtype=float)
            ref = float(np.max(np.abs(v)))
            out[e.key] = (np.abs(v) * (float(s) / ref if ref > 0 else np.nan)).tolist()
        elif e.index is not None:  # an element not identified (held) has no error: NaN
            out.setdefault(e.key, [float("nan")] * len(params[e.key]))[e.index] = float(s)
        else:
            out[e.key] = float(s)
        for key in e.also:
            out[key] = float(s)
    return out


def vector_of(model, entries: Sequence[Entry]) -> np.ndarray:
    params = model.params
    out = []
    for e in entries:
        v = params[e.key]
        if e.scale:
            out.append(float(np.max(np.abs(v))))
        elif e.index is not None:
            out.append(float(v[e.index]))
        else:
            out.append(float(v))
    return np.array(out, dtype=float)


def with_vector(model, entries: Sequence[Entry], vec: np.ndarray):
    params = model.params
    changes: dict[str, Any] = {}
    for e, value in zip(entries, vec, strict=True):
        if e.scale:
            base = np.asarray(changes.get(e.key, params[e.key]), dtype=float)
            ref = float(np.max(np.abs(params[e.key])))
            changes[e.key] = (base * (value / ref if ref > 0 else 1.0)).tolist()
        elif e.index is not None:
            lst = list(changes.get(e.key, params[e.key]))
            lst[e.index] = float(value)
            changes[e.key] = lst
        else:
            changes[e.key] = float(value)
        for key in e.also:
            changes[key] = float(value)
    return model.with_params(**changes)


def fd_jacobian(
    simulate: Callable[[Any], np.ndarray],
    model,
    entries: Sequence[Entry],
    steps: np.ndarray | None = None,
) -> np.ndarray:
    """Central-difference Jacobian (N, k) of ``simulate(model)`` (the fitted samples) with
    respect to the entries; one-sided where a perturbed model is invalid or not finite."""
    v0 = vector_of(model, entries)
    if steps is None:
        typ = np.max(np.abs(v0)) if v0.size else 1.0
        steps = 1e-5 * np.maximum(np.abs(v0), 1e-3 * max(typ, 1e-12))
    mid = simulate(model)
    J = np.empty((mid.size, len(entries)))

    def run(vec):
        try:
            out = simulate(with_vector(model, entries, vec))
        except ValueError:
            return None
        return out if np.all(np.isfinite(out)) else None

    for i, h in enumerate(steps):
        up_v, down_v = v0.copy(), v0.copy()
        up_v[i] += h
        down_v[i] -= h
        up, down = run(up_v), run(down_v)
        if up is not None and down is not None:
            J[:, i] = (up - down) / (2 * h)
        elif up is not None:
            J[:, i] = (up - mid) / h
        elif down is not None:
            J[:, i] = (mid - down) / h
        else:
            J[:, i] = np.nan
    return J


RCOND = 1e-12  # singular values of the column-normalised J floored at RCOND * the largest


def inverse_gram(sv: np.ndarray, vt: np.ndarray) -> np.ndarray:
    """(Js'Js)^-1 from the SVD of the column-normalised Jacobian Js, with the singular values
    floored at RCOND times the largest: an unidentifiable direction gets a huge (not a
    discarded, as with a pseudo-inverse) variance, so its parameters show large standard
    errors and correlations near +-1."""
    s = np.maximum(sv, RCOND * (sv[0] if sv.size and sv[0] > 0 else 1.0))
    return (vt.T / s**2) @ vt


def covariance(J: np.ndarray, sse: float, n_fit: int) -> np.ndarray:
    """s^2 (J'J)^-1 with s^2 = SSE / (N - p) (columns normalised before inverting)."""
    k = J.shape[1]
    norms = np.linalg.norm(J, axis=0)
    norms = np.where(norms > 0, norms, 1.0)
    _, sv, vt = np.linalg.svd(J / norms, full_matrices=False)
    s2 = sse / max(n_fit - k, 1)
    return s2 * inverse_gram(sv, vt) / np.outer(norms, norms)


def linearised_se(J: np.ndarray, sse: float, n_fit: int) -> np.ndarray:
    """s^2 (J'J)^-1 standard errors, s^2 = SSE / (N - p); NaN if J is not finite. A
    parameter the data do not determine gets inf, never a small number: one the output does
    not depend on (a zero column), or one that dominates (component > 0.25) a direction
    whose singular value of the column-normalised J is below RCOND times the largest (an
    exactly collinear group, such as a constant regressor beside an offset)."""
    k = J.shape[1]
    if not np.all(np.isfinite(J)):
        return np.full(k, np.nan)
    se = np.sqrt(np.clip(np.diag(covariance(J, sse, n_fit)), 0.0, None))
    norms = np.linalg.norm(J, axis=0)
    se[~(norms > 0)] = np.inf
    if k and np.any(norms > 0):
        _, sv, vt = np.linalg.svd(J / np.where(norms > 0, norms, 1.0), full_matrices=False)
        for value, direction in zip(sv, vt, strict=True):
            if value <= RCOND * sv[0]:
                se[np.abs(direction) > 0.25] = np.inf
    return se


def undetermined_notes(errors: dict[str, Any]) -> list[str]:
    """A warning note ("!" first) naming the estimates whose standard error is inf (the data
    do not determine them, see :func:`linearised_se`); none when there are none.

    Parameters
    ----------
    errors : dict of str to float or list of float
        Standard errors by name.

    Returns
    -------
    list of str
        One note, or none.
    """
    names = [k for k, v in errors.items() if any(np.isposinf(np.asarray(v, dtype=float).ravel()))]
    if not names:
        return []
    return [
        f"!the data do not determine {', '.join(names)} (standard error inf): a constant or "
        "collinear regressor, or an effect the records never excite"
    ]


# -- bootstrap -------------------------------------------------------------------------------


def block_length(residual: np.ndarray) -> int:
    """Moving-block length: twice the residual's integrated autocorrelation time
    tau = 1 + 2 sum_k rho_k (Sokal's window: the sum stops at the first lag M >= 5 tau), and
    at least N^(1/3) (the classic rate for variance estimation); at most N/4. Blocks must
    span the correlation of the residual, or the bootstrap spread is too small (coloured
    noise, model error)."""
    e = np.asarray(residual, dtype=float)
    e = e - e.mean()
    n = e.size
    base = max(1, int(round(n ** (1.0 / 3.0))))
    if n < 4 or not np.any(e):
        return base
    f = np.fft.rfft(e, 2 * n)
    ac = np.fft.irfft(f * np.conj(f))[:n]
    ac = ac / ac[0]
    tau = 1.0 + 2.0 * np.cumsum(ac[1:])
    window = np.flatnonzero(np.arange(1, n) >= 5.0 * tau)
    t = float(tau[window[0]]) if window.size else float(tau[-1])
    return int(min(max(base, int(round(2.0 * max(t, 1.0)))), max(n // 4, 1)))


def moving_block_resample(
    residual: np.ndarray, segments: Sequence[int], block: int, rng: np.random.Generator
) -> np.ndarray:
    """A moving-block bootstrap resample of ``residual`` (concatenated fitted samples of the
    recordings, lengths ``segments``): each recording's residual is rebuilt from blocks of
    ``block`` consecutive samples drawn with replacement from the same recording."""
    out = np.empty_like(residual)
    start = 0
    for n in segments:
        e = residual[start : start + n]
        b = min(block, n)
        count = -(-n // b)
        starts = rng.integers(0, n - b + 1, size=count)
        idx = (starts[:, None] + np.arange(b)[None, :]).ravel()[:n]
        out[start : start + n] = e[idx]
        start += n
    return out


def bootstrap(
    draw: Callable[[np.random.Generator], np.ndarray | None], count: int, seed: int | None
) -> dict[str, Any]:
    """Re-fit ``count`` resamples: ``draw(rng)`` builds one resample, re-fits it and returns
    the estimate vector (or None if the re-fit failed). Returns the samples (count_ok, k),
    the standard errors (their standard deviation, ddof 1) and the number of failures."""
    if count < 2:
        raise ValueError(f"bootstrap must be at least 2 resamples (got {count})")
    rng = np.random.default_rng(seed)
    samples, failed = [], 0
    for _ in range(int(count)):
        est = draw(rng)
        if est is None or not np.all(np.isfinite(est)):
            failed += 1
            continue
        samples.append(np.asarray(est, dtype=float))
    if len(samples) < 2:
        raise ValueError(f"bootstrap: {failed} of {count} re-fits failed")
    S = np.vstack(samples)
    return {"samples": S, "se": S.std(axis=0, ddof=1), "failed": failed}


_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep


def caller_stacklevel() -> int:
    """The ``stacklevel`` that makes a warning raised by the caller of this function name the
    first frame outside the tendonsheath package (the user's call, however deep the steps)."""
    frame: FrameType | None = sys._getframe(1)
    level = 1
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        frame = frame.f_back
        level += 1
    return level


__all__ = [
    "BOUND_TOLERANCE",
    "CONDITION_LIMIT",
    "CORRELATION_LIMIT",
    "Diagnostics",
    "Entry",
    "IdentifiabilityWarning",
    "RCOND",
    "block_length",
    "bootstrap",
    "bound_side",
    "caller_stacklevel",
    "covariance",
    "entries_from_labels",
    "entries_of",
    "fd_jacobian",
    "inverse_gram",
    "linearised_se",
    "moving_block_resample",
    "se_dict",
    "undetermined_notes",
    "vector_of",
    "with_vector",
]
