"""Newey-West (Bartlett kernel) standard errors of least-squares parameters, for residuals
stacked from independent recordings: the autocovariances are summed within each recording
only, so no lag pairs the end of one recording with the start of the next."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .._typing import FloatArray


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
) -> tuple[FloatArray, int]:
    """Standard errors of the last k parameters: (J'J)^-1 S (J'J)^-1, S the Bartlett-weighted
    sum of the scores' autocovariances up to ``lags`` (None: Andrews' AR(1) rule) within each
    block of ``blocks`` (row counts of the independent recordings, in order; None: one)."""
    if k == 0:
        return np.zeros(0), 0
    scores = jac * r[:, None]
    spans = _starts(scores.shape[0], blocks)
    lag = andrews_lags(scores[:, -k:], spans) if lags is None else int(lags)
    s = scores.T @ scores
    for a, b in spans:
        g = scores[a:b]
        for ell in range(1, min(lag, b - a - 1) + 1):
            gamma = g[ell:].T @ g[:-ell]
            s += (1.0 - ell / (lag + 1.0)) * (gamma + gamma.T)
    bread = np.linalg.pinv(jac.T @ jac)
    cov = bread @ s @ bread
    return np.sqrt(np.clip(np.diag(cov)[-k:], 0.0, None)), lag


def andrews_lags(scores: FloatArray, spans: list[tuple[int, int]] | None = None) -> int:
    """Andrews (1991) Bartlett bandwidth 1.1447 (alpha n)^(1/3), alpha from an AR(1) fit to
    each score column (weighted equally; the pairs of consecutive rows within each span), at
    most the longest span less one."""
    n = scores.shape[0]
    spans = [(0, n)] if spans is None else spans
    num = den = 0.0
    for g in scores.T:
        g = g - g.mean()
        head = np.concatenate([g[a : b - 1] for a, b in spans])
        tail = np.concatenate([g[a + 1 : b] for a, b in spans])
        denom = float(head @ head)
        if denom <= 0.0:
            continue
        rho = float(np.clip(tail @ head / denom, -0.999, 0.999))
        var = float(np.mean((tail - rho * head) ** 2))
        num += 4 * rho**2 * var**2 / ((1 - rho) ** 6 * (1 + rho) ** 2)
        den += var**2 / (1 - rho) ** 4
    alpha = num / den if den > 0 else 0.0
    longest = max(b - a for a, b in spans)
    return int(min(longest - 1, math.ceil(1.1447 * (alpha * n) ** (1.0 / 3.0))))
