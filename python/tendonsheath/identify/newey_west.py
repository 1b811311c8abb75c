"""Newey-West (Bartlett kernel) standard errors of least-squares parameters, for residuals
stacked from independent recordings: the autocovariances are summed within each recording
only, so no lag pairs the end of one recording with the start of the next.

The bandwidth is a time when the recordings' sample periods are known: the residuals of a
drive are correlated over a time (the misfit repeats over each cycle, the encoder noise is
filtered over a time constant), not over a number of samples, so one lag in samples would
cover 2.5 times longer at 400 Hz than at 1 kHz. It is converted to each recording's lags with
that recording's own period."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .._util.typing import FloatArray
from .diagnostics import RCOND, inverse_gram


def _starts(n: int, blocks: Sequence[int] | None) -> list[tuple[int, int]]:
    """(start, stop) of each block of the n stacked rows (one block when None)."""
    sizes = [n] if blocks is None else [int(b) for b in blocks]
    if sum(sizes) != n or min(sizes) < 1:
        raise ValueError(f"blocks {sizes} do not split the {n} rows")
    edges = np.cumsum([0, *sizes])
    return [(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:], strict=True)]


def newey_west(
    jac: FloatArray,
    r: FloatArray,
    k: int,
    lags: int | None,
    blocks: Sequence[int] | None = None,
    periods: Sequence[float] | None = None,
    lag_s: float | None = None,
) -> tuple[FloatArray, list[int], float]:
    """Standard errors of the last k parameters: (J'J)^-1 S (J'J)^-1, S the Bartlett-weighted
    sum of the scores' autocovariances within each block of ``blocks`` (row counts of the
    independent recordings, in order; None: one).

    The bandwidth: ``lags`` samples in every block when given; else, with the blocks' sample
    ``periods`` (s), ``lag_s`` seconds (None: Andrews' AR(1) rule pooled in seconds,
    :func:`andrews_seconds`), ceil(lag_s / period) lags in each block; without periods,
    Andrews' rule in samples, shared. Returns (the k errors, each block's lags, the bandwidth
    in seconds: NaN without periods or with ``lags``)."""
    spans = _starts(jac.shape[0], blocks)
    if k == 0:
        return np.zeros(0), [0] * len(spans), math.nan
    scores = jac * r[:, None]
    seconds = math.nan
    if lags is not None:
        per_block = [int(lags)] * len(spans)
    elif periods is None:
        per_block = [andrews_lags(scores[:, -k:], spans)] * len(spans)
    else:
        seconds = andrews_seconds(scores[:, -k:], spans, periods) if lag_s is None else lag_s
        per_block = [
            int(min(b - a - 1, math.ceil(seconds / p)))
            for (a, b), p in zip(spans, periods, strict=True)
        ]
    s = scores.T @ scores
    for (a, b), lag in zip(spans, per_block, strict=True):
        g = scores[a:b]
        for ell in range(1, min(lag, b - a - 1) + 1):
            gamma = g[ell:].T @ g[:-ell]
            s += (1.0 - ell / (lag + 1.0)) * (gamma + gamma.T)
    bread, undetermined = _bread(jac)
    cov = bread @ s @ bread
    se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    se[undetermined] = np.inf
    return se[-k:], per_block, seconds


def _bread(jac: FloatArray) -> tuple[FloatArray, np.ndarray]:
    """(J'J)^-1 with the singular values of the column-normalised J floored (a pseudo-inverse
    would drop a direction the data do not determine and report a tiny error for it), and
    which parameters are undetermined: a zero column, or one that dominates (> 0.25) a
    direction whose singular value is below RCOND times the largest."""
    norms = np.linalg.norm(jac, axis=0)
    dead = ~(norms > 0)
    scale = np.where(dead, 1.0, norms)
    _, sv, vt = np.linalg.svd(jac / scale, full_matrices=False)
    bread = inverse_gram(sv, vt) / np.outer(scale, scale)
    for value, direction in zip(sv, vt, strict=True):
        if value <= RCOND * sv[0]:
            dead |= np.abs(direction) > 0.25
    return bread, dead


def _ar1_terms(g: FloatArray, spans: list[tuple[int, int]]) -> tuple[float, float] | None:
    """Andrews' (numerator, denominator) of one score column's AR(1) fit over the pairs of
    consecutive rows within the spans (in samples^2 of those spans' rate); None if constant."""
    head = np.concatenate([g[a : b - 1] for a, b in spans])
    tail = np.concatenate([g[a + 1 : b] for a, b in spans])
    denom = float(head @ head)
    if denom <= 0.0:
        return None
    rho = float(np.clip(tail @ head / denom, -0.999, 0.999))
    var = float(np.mean((tail - rho * head) ** 2))
    return (
        4 * rho**2 * var**2 / ((1 - rho) ** 6 * (1 + rho) ** 2),
        var**2 / (1 - rho) ** 4,
    )


def andrews_lags(scores: FloatArray, spans: list[tuple[int, int]] | None = None) -> int:
    """Andrews (1991) Bartlett bandwidth 1.1447 (alpha n)^(1/3), alpha from an AR(1) fit to
    each score column (weighted equally; the pairs of consecutive rows within each span), at
    most the longest span less one."""
    n = scores.shape[0]
    spans = [(0, n)] if spans is None else spans
    num = den = 0.0
    for g in scores.T:
        terms = _ar1_terms(g - g.mean(), spans)
        if terms is not None:
            num, den = num + terms[0], den + terms[1]
    alpha = num / den if den > 0 else 0.0
    longest = max(b - a for a, b in spans)
    return int(min(longest - 1, math.ceil(1.1447 * (alpha * n) ** (1.0 / 3.0))))


def andrews_seconds(
    scores: FloatArray, spans: list[tuple[int, int]], periods: Sequence[float]
) -> float:
    """Andrews' Bartlett bandwidth in seconds, pooled over recordings sampled at different
    periods: 1.1447 (alpha T)^(1/3), T the total duration and alpha (s^2) each recording's
    AR(1) alpha (samples^2, its own pairs of consecutive rows) times its period squared,
    weighted by its duration.

    Pooled rather than one bandwidth per recording: the scores' correlation time is the
    drive's, the same in every session, so every recording's pairs estimate it (a short
    recording's own AR(1) fit is noisy), and the bandwidth trades the bias and the variance
    of the one covariance summed over all of them, whose size is the total duration (Andrews'
    n^(1/3) in samples is (T / period)^(1/3): for one recording this is his rule exactly)."""
    total = sum((b - a) * p for (a, b), p in zip(spans, periods, strict=True))
    alpha = 0.0
    for (a, b), p in zip(spans, periods, strict=True):
        num = den = 0.0
        for g in scores.T:
            terms = _ar1_terms(g - g.mean(), [(a, b)]) if b - a > 1 else None
            if terms is not None:
                num, den = num + terms[0], den + terms[1]
        if den > 0:
            alpha += (b - a) * p / total * (num / den) * p**2
    return 1.1447 * (alpha * total) ** (1.0 / 3.0)


__all__ = ["andrews_lags", "andrews_seconds", "newey_west"]
