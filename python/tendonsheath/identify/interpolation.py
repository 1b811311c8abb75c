"""Which input reconstruction between samples a record calls for, read from the input alone.

A HystereticOscillator integrates between samples, so it needs the input there. The sampled
input tells the cases apart:

- **held** (``"hold"``): a staircase: at least 40 % of the sample-to-sample steps are exactly
  zero (a command updated more slowly than it is sampled: a zero-order hold seen at a finer
  rate).
- **ramps** (``"linear"``): piecewise linear: at least 40 % of the second differences vanish
  (to 1e-9 of the range); linear interpolation is exact between its corners.
- **band-limited** (``"bandlimited"``): the energy the band-limited reconstruction cannot
  represent, the fraction of the input's energy above ``TOP_BAND`` of the sampling rate
  (:func:`tail_fraction`), is below a tenth of the mean-square error that linear
  interpolation would make on the rest (:func:`linear_error`, from the spectrum): a multisine,
  a sine sweep, filtered noise, sampled above their band, also with measurement noise up to a
  few per cent of the signal.
- otherwise (``"linear"``): energy up to the Nyquist frequency (white noise, steps at the
  sampling rate, a 1/f^2 spectrum): nothing between the samples is known better than the
  straight line.

The spectrum is the exact DFT of a record of whole periods, otherwise Welch's estimate with a
Blackman-Harris window (side lobes at -92 dB), so a record that starts and ends anywhere (a
sweep from rest) leaks no edge energy into the top band.
"""

from __future__ import annotations

import numpy as np

from .._util.sampling import is_periodic
from .._util.typing import ArrayLike

TOP_BAND = 0.4  # fraction of the sampling rate above which a band-limited input is empty
MARGIN = 0.1  # the tail must be below this fraction of linear interpolation's error
FLAT_FRACTION = 0.4  # smallest fraction of vanishing steps (hold) or second differences
MIN_SAMPLES = 64  # shorter records keep the linear reconstruction
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(16)


def spectrum(x: np.ndarray, periodic: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(frequencies in units of the sampling rate, power) of x with its mean removed: the
    exact DFT when x is whole periods, else Welch's estimate (Blackman-Harris window)."""
    from scipy.signal import welch

    x = np.asarray(x, dtype=float)
    x = x - x.mean()
    if periodic:
        return np.fft.rfftfreq(x.size), np.abs(np.fft.rfft(x)) ** 2
    nper = int(min(x.size, 4096))
    return welch(x, fs=1.0, window="blackmanharris", nperseg=nper, detrend="linear")


def linear_error(f: np.ndarray) -> np.ndarray:
    """Mean-square error of linear interpolation between the samples of a unit-power sine at
    frequency f (units of the sampling rate), averaged over its phase and the interval:
    about (2 pi f)^4 / 120 at low frequency."""
    s = 0.5 * (_NODES + 1.0)
    w = 0.5 * _WEIGHTS
    om = 2.0 * np.pi * np.asarray(f, dtype=float)[:, None]
    e = np.exp(1j * om * s) - (1.0 - s) - s * np.exp(1j * om)
    return (np.abs(e) ** 2) @ w


def tail_fraction(x, periodic: bool = False) -> float:
    """The fraction of x's energy (mean removed) above ``TOP_BAND`` of the sampling rate."""
    f, p = spectrum(x, periodic)
    total = float(p.sum())
    return float(p[f > TOP_BAND].sum()) / total if total > 0 else 0.0


def _flat(d: np.ndarray, tol: float) -> float:
    return float(np.mean(np.abs(d) <= tol)) if d.size else 0.0


def detect_input_interpolation(x: ArrayLike, periodic: bool = False) -> str:
    """ "hold", "bandlimited" or "linear" for the uniformly sampled input x (see the module
    docstring).

    Parameters
    ----------
    x : array_like of float, shape (n,)
        The input samples, uniformly sampled.
    periodic : bool, default False
        Whether x is a whole number of periods (its DFT is then exact).

    Returns
    -------
    str
        The input reconstruction that fits x.
    """
    x = np.asarray(x, dtype=float)
    if x.size < MIN_SAMPLES or not np.all(np.isfinite(x)) or np.ptp(x) == 0:
        return "linear"
    if _flat(np.diff(x), 0.0) >= FLAT_FRACTION:
        return "hold"
    if _flat(np.diff(x, 2), 1e-9 * float(np.ptp(x))) >= FLAT_FRACTION:
        return "linear"
    f, p = spectrum(x, periodic)
    total = float(p.sum())
    if not total > 0:
        return "linear"
    top = f > TOP_BAND
    tail = float(p[top].sum()) / total
    lin = float(p[~top] @ linear_error(f[~top])) / total
    return "bandlimited" if tail < MARGIN * lin else "linear"


def is_uniform(t, rtol: float = 1e-6) -> bool:
    """Whether the times t are uniformly spaced (the band-limited reconstruction needs it);
    False when there are none."""
    if t is None:
        return False
    d = np.diff(np.asarray(t, dtype=float).ravel())
    if d.size == 0:
        return False
    step = float(np.median(d))
    return step > 0 and float(np.max(np.abs(d - step))) <= rtol * step


def detect_for_recordings(recs, periodic: bool | None = None) -> tuple[str, str]:
    """The reconstruction for all recordings together and a note saying why: one that every
    uniformly sampled recording agrees on, else "linear". ``periodic``: whether the records
    are whole periods (None: detected by :func:`~tendonsheath.models.hysteretic_oscillator.
    is_periodic`)."""

    def whole(x):
        return is_periodic(x) if periodic is None else bool(periodic)

    found = {
        detect_input_interpolation(r.x, whole(r.x)) if is_uniform(r.t) else "linear" for r in recs
    }
    mode = found.pop() if len(found) == 1 else "linear"
    why = {
        "bandlimited": f"no energy above {TOP_BAND} of the sampling rate",
        "hold": "the input holds its value over runs of samples",
        "linear": "energy up to the Nyquist frequency, ramps, or non-uniform sampling",
    }[mode]
    return mode, f"input reconstruction {mode} detected ({why})"


__all__ = [
    "FLAT_FRACTION",
    "MARGIN",
    "MIN_SAMPLES",
    "TOP_BAND",
    "detect_for_recordings",
    "detect_input_interpolation",
    "is_uniform",
    "linear_error",
    "spectrum",
    "tail_fraction",
]
