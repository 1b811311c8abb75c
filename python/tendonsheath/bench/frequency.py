"""Frequency response of a closed loop from sine sweeps (Lau et al. 2015's bandwidth measure)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .run import run

if TYPE_CHECKING:
    import control  # python-control ships no types: its systems are Any to mypy

    from .._util.typing import ArrayLike
    from ..plant import ContinuumPlant, PullPullPlant
    from ..plant.sensor import Sensor
    from .run import Controller


@dataclass
class FrequencyResponse:
    """Per frequency (Hz): gain |Y/Y_d| in dB, phase (deg) and error magnitude |E|/|Y_d| of the
    fundamental; the bandwidths where the gain reaches -3 dB and where the error magnitude
    rises past twice its low-frequency level (NaN when not reached in the sweep).

    Parameters
    ----------
    frequencies : numpy.ndarray of float
        The sweep's frequencies (Hz).
    gain_db : numpy.ndarray of float
        |Y/Y_d| (dB) at each frequency.
    phase_deg : numpy.ndarray of float
        Phase of Y/Y_d (deg, unwrapped).
    error_magnitude : numpy.ndarray of float
        |E|/|Y_d| at each frequency.
    bandwidth_3db : float
        Frequency where the gain reaches -3 dB (Hz; NaN if not reached).
    bandwidth_error : float
        Frequency where the error magnitude rises past twice its low-frequency level (Hz;
        NaN if not reached).
    """

    frequencies: np.ndarray
    gain_db: np.ndarray
    phase_deg: np.ndarray
    error_magnitude: np.ndarray
    bandwidth_3db: float
    bandwidth_error: float

    def as_dict(self) -> dict:
        """The response as a JSON-ready dict (frequencies in Hz, lists of numbers).

        Returns
        -------
        dict
            frequencies_hz, gain_db, phase_deg, error_magnitude, bandwidth_3db_hz and
            bandwidth_error_hz.
        """
        return {
            "frequencies_hz": self.frequencies.tolist(),
            "gain_db": self.gain_db.tolist(),
            "phase_deg": self.phase_deg.tolist(),
            "error_magnitude": self.error_magnitude.tolist(),
            "bandwidth_3db_hz": self.bandwidth_3db,
            "bandwidth_error_hz": self.bandwidth_error,
        }

    def to_control(self, name: str | None = None) -> control.FrequencyResponseData:
        """The gain and phase as a ``control.FrequencyResponseData`` (omega = 2 pi f, rad/s).
        Needs python-control: ``pip install 'tendonsheath[control]'``.

        Parameters
        ----------
        name : str, optional
            The system's name.

        Returns
        -------
        control.FrequencyResponseData
            The measured response.
        """
        from ..control_interop import frequency_response_data

        return frequency_response_data(self.frequencies, self.gain_db, self.phase_deg, name)


def _fundamental(t: np.ndarray, signal: np.ndarray, f: float) -> complex:
    """Complex amplitude of the component at f (lock-in over whole cycles)."""
    return 2.0 * np.mean(signal * np.exp(-2j * np.pi * f * t))


def _first_crossing(f: np.ndarray, values: np.ndarray, level: float, above: bool) -> float:
    """Log-interpolated first frequency where values crosses level (NaN if never)."""
    hit = values >= level if above else values <= level
    if not hit.any():
        return float("nan")
    k = int(np.argmax(hit))
    if k == 0:
        return float(f[0])
    v0, v1 = values[k - 1], values[k]
    w = (level - v0) / (v1 - v0) if v1 != v0 else 1.0
    return float(np.exp(np.log(f[k - 1]) + w * (np.log(f[k]) - np.log(f[k - 1]))))


def frequency_response(
    plant: PullPullPlant | ContinuumPlant,
    controller: Controller,
    frequencies: ArrayLike | None = None,
    amplitude: float = 0.5,
    cycles: int = 3,
    rate: float = 1000.0,
    min_duration: float = 2.0,
    noise: Sensor | float | None = None,
) -> FrequencyResponse:
    """Sine sweep: at each frequency run the bench for ``cycles`` whole periods (at least
    ``min_duration`` s), discard the first period, and fit the fundamentals of the output and
    of the error. Default frequencies: 12 log-spaced from 0.05 to 2 Hz.

    Parameters
    ----------
    plant : PullPullPlant or ContinuumPlant
        The plant.
    controller : compensator or None
        As for :func:`tendonsheath.bench.run`.
    frequencies : array_like of float, optional
        The frequencies (Hz), positive and below rate / 2.
    amplitude : float, default 0.5
        Amplitude of the desired sine (rad).
    cycles : int, default 3
        Whole periods per frequency, >= 2 (the first is discarded).
    rate : float, default 1000.0
        The loop's rate (Hz).
    min_duration : float, default 2.0
        Shortest run per frequency (s).
    noise : Sensor or float, optional
        As for :func:`tendonsheath.bench.run`.

    Returns
    -------
    FrequencyResponse
        Gain, phase and error magnitude per frequency, and the two bandwidths.

    Raises
    ------
    ValueError
        Bad frequencies, cycles < 2 or a rate not > 0.
    """
    f = (
        np.logspace(np.log10(0.05), np.log10(2.0), 12)
        if frequencies is None
        else np.asarray(frequencies, dtype=float)
    )
    if f.ndim != 1 or f.size == 0 or np.any(~np.isfinite(f)) or np.any(f <= 0):
        raise ValueError("frequencies must be a non-empty 1-D array of positive numbers (Hz)")
    if cycles < 2:
        raise ValueError("cycles must be >= 2 (the first is discarded)")
    if not (math.isfinite(rate) and rate > 0):
        raise ValueError(f"rate must be a finite number of Hz > 0 (got {rate})")
    if np.any(f >= rate / 2):
        raise ValueError(
            f"frequencies must be below the Nyquist frequency rate / 2 = {rate / 2:g} Hz "
            f"(got {f.max():g} Hz)"
        )
    gains, phases, errors = [], [], []
    for fk in f:
        period = 1.0 / fk
        n_cycles = max(cycles, int(np.ceil(min_duration / period)))
        t = np.arange(0.0, n_cycles * period, 1.0 / rate)
        y_d = amplitude * np.sin(2 * np.pi * fk * t)
        result = run(plant, controller, t, y_d, noise=noise, warmup=period)
        keep = t >= period
        keep &= t < period * n_cycles - 0.5 / rate  # whole cycles only
        Yd = _fundamental(t[keep], y_d[keep], fk)
        Y = _fundamental(t[keep], result.output[keep], fk)
        E = _fundamental(t[keep], result.output[keep] - y_d[keep], fk)
        gains.append(20 * np.log10(abs(Y) / abs(Yd)))
        phases.append(np.degrees(np.angle(Y / Yd)))
        errors.append(abs(E) / abs(Yd))
    gain_db, phase_deg, err = np.array(gains), np.unwrap(np.radians(phases)), np.array(errors)
    low = float(np.median(err[: min(3, err.size)]))
    return FrequencyResponse(
        frequencies=f,
        gain_db=gain_db,
        phase_deg=np.degrees(phase_deg),
        error_magnitude=err,
        bandwidth_3db=_first_crossing(f, gain_db, -3.0, above=False),
        bandwidth_error=_first_crossing(f, err, max(2.0 * low, low + 0.05), above=True),
    )


__all__ = ["FrequencyResponse", "frequency_response"]
