"""How well a model compensates: the command its inverse would send for a recorded output.

A model that predicts the output well can still compensate badly: its inverse amplifies what
the forward error hides (a flat branch, a slope near zero, an input range it never saw). The
offline inverse error runs the model's real-time inverse
(:class:`~tendonsheath.compensate.InverseFeedforward`) on a recording's output, taken as the
desired trajectory, and compares its commands with the input that really produced that output.

The recorded output is noisy, and an exact inverse turns noise at a reversal into jumps across
the dead zone that no robot would be asked for. The desired trajectory is therefore the
recorded output low-passed without phase lag (a second-order Butterworth, forward and back) at
ten times its dominant frequency (at most a quarter of the sample rate), and the inverse's
direction switch is smoothed over 3 % of that trajectory's peak rate (spec D.2: 2-5 %).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ..bench.metrics import dominant_period

if TYPE_CHECKING:
    from ..models import HysteresisModel

#: the desired trajectory's low-pass corner, in multiples of its dominant frequency
CUTOFF_HARMONICS = 10.0
#: the inverse's direction-switch speed, as a share of the trajectory's peak rate
SMOOTHING_SHARE = 0.03


def desired_from_record(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The recorded output as a desired trajectory: low-passed with no phase lag at
    CUTOFF_HARMONICS times its dominant frequency (at most a quarter of the sample rate).

    Parameters
    ----------
    t : numpy.ndarray of float
        Sample times (s), uniform.
    y : numpy.ndarray of float
        The recorded output.

    Returns
    -------
    numpy.ndarray of float
        The smoothed output (y itself when too short to filter).
    """
    from scipy.signal import butter, sosfiltfilt

    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    if y.size < 16:
        return y.copy()
    dt = float(np.median(np.diff(t)))
    fs = 1.0 / dt
    corner = min(CUTOFF_HARMONICS / dominant_period(t, y), 0.25 * fs)
    sos = butter(2, corner, fs=fs, output="sos")
    return sosfiltfilt(sos, y)


def offline_inverse(
    model: HysteresisModel, t: Any, y: Any, curve_angle: Any = None, load: Any = None
) -> tuple[np.ndarray, np.ndarray]:
    """The commands ``model``'s inverse sends for the recorded output y (see the module), and
    each cycle's status flags.

    Parameters
    ----------
    model : HysteresisModel
        Any model ``identify`` returns (its identified input range bounds the commands).
    t : array_like of float, or None
        Sample times (s); None: one sample per second of index (rate-independent models).
    y : array_like of float
        The recorded output.
    curve_angle : float, array_like of float or Route, optional
        The recording's curve angle or shape, for a model that follows the route.
    load : array_like of float, optional
        The recording's measured load, for a :class:`~tendonsheath.models.Loaded` model (its
        inverse is :class:`~tendonsheath.compensate.LoadCompensated`; no status flags: 0).

    Returns
    -------
    commands : numpy.ndarray of float
        The inverse's command at each sample.
    flags : numpy.ndarray of uint8
        Each cycle's :class:`~tendonsheath.Status`.
    """
    from ..compensate import InverseFeedforward

    y = np.asarray(y, dtype=float)
    ts = np.arange(y.size, dtype=float) if t is None else np.asarray(t, dtype=float)
    desired = desired_from_record(ts, y)
    rate = np.abs(np.diff(desired)) / np.diff(ts) if y.size > 1 else np.zeros(1)
    peak = float(np.max(rate)) if rate.size else 0.0
    smoothing = SMOOTHING_SHARE * peak if peak > 0 else 1.0
    from ..models import Loaded

    if isinstance(model, Loaded):
        from ..compensate import LoadCompensated

        if load is None:
            raise ValueError("a Loaded model's inverse needs the recording's measured load")
        u = LoadCompensated(model, smoothing=smoothing).command(ts, desired, load)
        return u.output, np.zeros(u.size, dtype=np.uint8)
    ff = InverseFeedforward(model, smoothing=smoothing)
    angle = _angle_argument(curve_angle, y.size)
    extra = angle if getattr(ff, "follows_route", False) and angle is not None else {}
    u = ff.command(ts, desired, **extra)
    return u.output, u.status


def _angle_argument(curve_angle: Any, n: int) -> dict[str, Any] | None:
    """command()'s keyword for the recording's curve angle or route (None without one)."""
    if curve_angle is None:
        return None
    if hasattr(curve_angle, "curve_angle"):  # a Route: the same shape all along
        return {"routes": lambda _t: curve_angle}
    values = np.asarray(curve_angle, dtype=float)
    return {"curve_angle": values if values.ndim else np.full(n, float(values))}


def inverse_rmse(commands: np.ndarray, x: np.ndarray) -> float:
    """Root-mean-square difference between an inverse's commands and the recorded input
    (NaN when there is none to compare).

    Parameters
    ----------
    commands : numpy.ndarray of float
        The inverse's commands.
    x : numpy.ndarray of float
        The inputs that really produced the output.

    Returns
    -------
    float
        The rmse, in input units.
    """
    e = np.asarray(commands, dtype=float) - np.asarray(x, dtype=float)
    return float(math.sqrt(np.mean(e * e))) if e.size else math.nan


__all__ = [
    "CUTOFF_HARMONICS",
    "SMOOTHING_SHARE",
    "desired_from_record",
    "inverse_rmse",
    "offline_inverse",
]
