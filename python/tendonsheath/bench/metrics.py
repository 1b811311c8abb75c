"""Tracking metrics of the bench (spec E), computed after a warm-up."""

from __future__ import annotations

import numpy as np


def dominant_period(t: np.ndarray, signal: np.ndarray) -> float:
    """Period (s) of the largest non-zero Fourier component of a uniformly sampled signal."""
    if t.size < 4:
        return float(t[-1] - t[0])
    dt = float(np.median(np.diff(t)))
    spectrum = np.abs(np.fft.rfft(signal - signal.mean()))
    spectrum[0] = 0.0
    k = int(np.argmax(spectrum))
    if k == 0 or spectrum[k] == 0.0:
        return float(t[-1] - t[0])
    return 1.0 / (k / (signal.size * dt))


def loop_width(x: np.ndarray, y: np.ndarray, points: int = 200) -> float:
    """Largest vertical gap between the rising and the falling branch of y against x.

    Parameters
    ----------
    x : numpy.ndarray of float
        The abscissa (e.g. the reference).
    y : numpy.ndarray of float
        The ordinate (e.g. the output), of x's length.
    points : int, default 200
        Grid points over the range both branches cover.

    Returns
    -------
    float
        The largest gap (unit of y); 0 when a branch is missing.
    """
    dx = np.gradient(x)
    up, down = dx > 0, dx < 0
    if up.sum() < 2 or down.sum() < 2:
        return 0.0
    lo = max(x[up].min(), x[down].min())
    hi = min(x[up].max(), x[down].max())
    if not hi > lo:
        return 0.0
    grid = np.linspace(lo, hi, points)
    ou, od = np.argsort(x[up]), np.argsort(x[down])
    yu = np.interp(grid, x[up][ou], y[up][ou])
    yd = np.interp(grid, x[down][od], y[down][od])
    return float(np.max(np.abs(yd - yu)))


def tracking_metrics(reference: np.ndarray, output: np.ndarray) -> dict[str, float]:
    """mse, rmse, max_abs (output units), percent_error and max_percent_error (of the
    reference's range, the measure of Lau et al. 2015) and the output-vs-reference loop width.

    Parameters
    ----------
    reference : numpy.ndarray of float
        The desired output.
    output : numpy.ndarray of float
        The output, of reference's length.

    Returns
    -------
    dict of str to float
        mse, rmse, max_abs, percent_error, max_percent_error and loop_width.
    """
    e = output - reference
    span = float(np.ptp(reference)) or 1.0
    mse = float(np.mean(e**2))
    return {
        "mse": mse,
        "rmse": float(np.sqrt(mse)),
        "max_abs": float(np.max(np.abs(e))),
        "percent_error": float(100.0 * np.mean(np.abs(e)) / span),
        "max_percent_error": float(100.0 * np.max(np.abs(e)) / span),
        "loop_width": loop_width(reference, output),
    }


__all__ = ["dominant_period", "loop_width", "tracking_metrics"]
