"""Uniform sampling and periodic band-limited records: the helpers the plants' input
reconstruction, the HystereticOscillator and its identification share."""

from __future__ import annotations

import numpy as np


def uniform_step(t: np.ndarray, who: str, rtol: float = 1e-6) -> float:
    """The sample time of uniformly sampled times t; ValueError otherwise."""
    d = np.diff(np.asarray(t, dtype=float))
    if d.size == 0:
        raise ValueError(f"{who}: at least two samples are needed")
    dt = float(np.median(d))
    if not dt > 0 or np.max(np.abs(d - dt)) > rtol * dt:
        raise ValueError(
            f"{who}: band-limited reconstruction needs uniform sampling (steps from "
            f"{d.min():.6g} to {d.max():.6g}); resample the record or use "
            "input_interpolation='linear'"
        )
    return dt


def is_periodic(x: np.ndarray, band: float = 0.4, tol: float = 1e-10) -> bool:
    """True when the periodic extension of x is band-limited: its energy above ``band`` times
    the sampling rate is below ``tol`` of the total (a whole number of periods of a
    band-limited signal, e.g. a multisine, and no measurement noise)."""
    x = np.asarray(x, dtype=float)
    if x.size < 8:
        return False
    X = np.abs(np.fft.rfft(x - x.mean())) ** 2
    total = float(X.sum())
    if not total > 0:
        return True
    high = float(X[int(np.ceil(band * x.size)) :].sum())
    return high <= tol * total


def fft_upsample(x: np.ndarray, fine: int) -> np.ndarray:
    """Exact trigonometric interpolation of a periodic record on a grid ``fine`` times finer:
    out[k fine + i] = u(t_k + i dt / fine) (zero padding of the spectrum; the Nyquist bin of
    an even-length record is split between the positive and negative frequency)."""
    x = np.asarray(x, dtype=float)
    n = x.size
    if fine == 1:
        return x.copy()
    X = np.fft.rfft(x)
    Y = np.zeros(n * fine // 2 + 1, dtype=complex)
    Y[: X.size] = X
    if n % 2 == 0:
        Y[n // 2] *= 0.5
    return np.ascontiguousarray(np.fft.irfft(Y, n * fine) * fine)


__all__ = ["fft_upsample", "is_periodic", "uniform_step"]
